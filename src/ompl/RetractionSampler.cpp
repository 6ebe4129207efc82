#include "meshgap/ompl/RetractionSampler.h"

#include <ompl/base/SpaceInformation.h>

#include <cmath>

#include "meshgap/ompl/ClearanceGradient.h"

namespace meshgap
{
    RetractionSampler::RetractionSampler(const ompl::base::SpaceInformation *si)
        : ompl::base::ValidStateSampler(si), sampler_(si->allocStateSampler())
    {
        name_ = "retraction";
        checker_ = std::dynamic_pointer_cast<const ClearanceChecker>(si->getStateValidityChecker());
        if (checker_ && checker_->mode() != ClearanceChecker::Mode::CERTIFIED)
            checker_.reset();
        if (!checker_)
            OMPL_WARN(
                "retraction: the validity checker is not a certified meshgap ClearanceChecker; sampling "
                "uniformly");
        work_ = si->allocState();
        params_.declareParam<double>(
            "free_probability", [this](double p) { setFreeProbability(p); }, [this] { return getFreeProbability(); });
        params_.declareParam<unsigned>(
            "retract_steps", [this](unsigned n) { setRetractSteps(n); }, [this] { return getRetractSteps(); });
        params_.declareParam<unsigned>(
            "medial_steps", [this](unsigned n) { setMedialSteps(n); }, [this] { return getMedialSteps(); });
    }

    RetractionSampler::~RetractionSampler()
    {
        si_->freeState(work_);
    }

    bool RetractionSampler::climb(ompl::base::State *state, double &value, double target)
    {
        const double L = checker_->scene().robot().radiusAboutOrigin();
        const std::size_t translations = gradient_.size() == 3 ? 2 : 3;
        double g2 = 0.0;  // the gradient's squared norm in clearanceGradient()'s metric
        for (std::size_t i = 0; i < gradient_.size(); ++i)
            g2 += i < translations ? gradient_[i] * gradient_[i] : gradient_[i] * gradient_[i] / (L * L);
        if (!(g2 > 1e-12))
            return false;
        // To first order the step of scale alpha raises the signed distance by alpha * g2.
        double alpha = target / g2;
        for (int trial = 0; trial < 5; ++trial, alpha *= 0.5)
        {
            ascentStep(gradient_, L, alpha, step_);
            applyTangentStep(*si_->getStateSpace(), state, step_.data(), work_);
            if (!si_->satisfiesBounds(work_))
                continue;
            const double v = checker_->clearance(work_);
            if (v > value)
            {
                si_->copyState(state, work_);
                value = v;
                return true;
            }
        }
        return false;
    }

    bool RetractionSampler::retract(ompl::base::State *state)
    {
        if (!checker_)
            return si_->isValid(state);
        if (checker_->isValid(state))
            return true;
        const double margin = 0.02 * checker_->scene().robot().radiusAboutOrigin();
        bool free = false;
        for (unsigned k = 0; k < retractSteps_ && !free; ++k)
        {
            ClearanceGradientInfo info;
            double value = clearanceGradient(*checker_, state, gradient_, ClearanceGradientOptions(), &info);
            if (!info.hasDirection)
                return false;  // a contact without depth: no direction to climb
            if (!climb(state, value, std::abs(value) + margin))
                return false;
            free = value > 0.0 && checker_->isValid(state);
        }
        if (!free)
            return false;
        // Centring: a few steps up the clearance, each aiming to raise it by about itself.
        for (unsigned k = 0; k < medialSteps_; ++k)
        {
            ClearanceGradientOptions options;
            ClearanceGradientInfo info;
            double value = clearanceGradient(*checker_, state, gradient_, options, &info);
            if (!info.hasDirection || !climb(state, value, value))
                break;
        }
        return checker_->isValid(state);  // every step of the centring rose from a free state; checked exactly
    }

    bool RetractionSampler::sample(ompl::base::State *state)
    {
        for (unsigned attempt = 0; attempt < attempts_; ++attempt)
        {
            sampler_->sampleUniform(state);
            if (checker_ ? checker_->isValid(state) : si_->isValid(state))
            {
                if (!checker_ || rng_.uniform01() < freeProbability_)
                    return true;
                continue;
            }
            if (checker_ && si_->satisfiesBounds(state) && retract(state))
                return true;
        }
        return false;
    }

    bool RetractionSampler::sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance)
    {
        for (unsigned attempt = 0; attempt < attempts_; ++attempt)
        {
            sampler_->sampleUniformNear(state, near, distance);
            if (checker_ ? checker_->isValid(state) : si_->isValid(state))
                return true;
        }
        // Every draw collided: the neighbourhood is (nearly) all obstacle. The last draw is retracted.
        return checker_ && si_->satisfiesBounds(state) && retract(state);
    }
}  // namespace meshgap
