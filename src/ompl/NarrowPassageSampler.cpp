#include "meshgap/ompl/NarrowPassageSampler.h"

#include <ompl/base/SpaceInformation.h>

#include "meshgap/ompl/ClearanceGradient.h"

namespace meshgap
{
    NarrowPassageSampler::NarrowPassageSampler(const ompl::base::SpaceInformation *si)
        : ompl::base::ValidStateSampler(si), sampler_(si->allocStateSampler())
    {
        name_ = "narrow_passage";
        checker_ = std::dynamic_pointer_cast<const ClearanceChecker>(si->getStateValidityChecker());
        if (checker_ && checker_->mode() != ClearanceChecker::Mode::CERTIFIED)
            checker_.reset();
        if (!checker_)
            OMPL_WARN(
                "narrow_passage: the validity checker is not a certified meshgap ClearanceChecker; sampling "
                "uniformly");
        work_ = si->allocState();
        params_.declareParam<double>(
            "free_probability", [this](double p) { setFreeProbability(p); }, [this] { return getFreeProbability(); });
        params_.declareParam<unsigned>(
            "medial_steps", [this](unsigned n) { setMedialSteps(n); }, [this] { return getMedialSteps(); });
    }

    NarrowPassageSampler::~NarrowPassageSampler()
    {
        si_->freeState(work_);
    }

    bool NarrowPassageSampler::accept(ompl::base::State *state, bool local)
    {
        if (!checker_)
            return si_->isValid(state);
        const double narrow = narrowClearance_ > 0.0 ? narrowClearance_ : checker_->scene().robot().radiusAboutOrigin();
        double clearance;
        if (checker_->isValid(state))  // exact collision test first: a few microseconds, no distance
        {
            // A tree planner's local sample, or one of the free states kept anyway: free is enough.
            if (local || rng_.uniform01() < freeProbability_)
                return true;
            // Otherwise kept only in a thin free space: near an obstacle (a bounded query, cheap far from all)...
            clearance = checker_->clearanceBelow(state, narrow);
            if (!(clearance < narrow))
                return false;
        }
        else
        {
            if (!si_->satisfiesBounds(state))
                return false;
            // Out along the penetration direction (validStateAway() returns only a valid state).
            const SceneResult r = checker_->query(state);
            if (!checker_->validStateAway(state, r, work_))
                return false;
            si_->copyState(state, work_);
            if (local)
                return true;  // pushed out of the obstacle, and kept near where it was asked for
            clearance = checker_->clearanceBelow(state, narrow);
            if (!(clearance < narrow))
                return rng_.uniform01() < freeProbability_;
        }
        // ... and still near one in the middle of the free space around it: a narrow passage.
        return centre(state, clearance) < narrow;
    }

    double NarrowPassageSampler::centre(ompl::base::State *state, double clearance)
    {
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        const double L = checker_->scene().robot().radiusAboutOrigin();
        for (unsigned k = 0; k < medialSteps_; ++k)
        {
            ClearanceGradientOptions options;
            options.tieTolerance = 0.05 * clearance;
            ClearanceGradientInfo info;
            clearanceGradient(*checker_, state, gradient_, options, &info);
            double g2 = 0.0;
            for (std::size_t i = 0; i < gradient_.size(); ++i)
                g2 += i < (gradient_.size() == 3 ? 2u : 3u) ? gradient_[i] * gradient_[i]
                                                            : gradient_[i] * gradient_[i] / (L * L);
            if (!info.hasDirection || !(g2 > 1e-12))
                break;
            // A first step of about the clearance itself, halved until the clearance rises.
            double alpha = clearance / std::sqrt(g2);
            bool moved = false;
            for (int trial = 0; trial < 5 && !moved; ++trial, alpha *= 0.5)
            {
                ascentStep(gradient_, L, alpha, step_);
                applyTangentStep(space, state, step_.data(), work_);
                if (!si_->satisfiesBounds(work_))
                    continue;
                const double c = checker_->clearance(work_);
                if (c > clearance)
                {
                    si_->copyState(state, work_);
                    clearance = c;
                    moved = true;
                }
            }
            if (!moved)
                break;
        }
        return clearance;
    }

    bool NarrowPassageSampler::sample(ompl::base::State *state)
    {
        for (unsigned attempt = 0; attempt < attempts_; ++attempt)
        {
            sampler_->sampleUniform(state);
            if (accept(state, false))
                return true;
        }
        return false;
    }

    bool NarrowPassageSampler::sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance)
    {
        // Free draws first, as the uniform sampler makes them: a collision test each, no bias where the
        // neighbourhood is open (a tree planner's expansion there is as fast as with uniform sampling).
        for (unsigned attempt = 0; attempt < attempts_; ++attempt)
        {
            sampler_->sampleUniformNear(state, near, distance);
            if (checker_ ? checker_->isValid(state) : si_->isValid(state))
                return true;
        }
        // Every draw collided, where uniform sampling gives up: the neighbourhood is (nearly) all obstacle, e.g.
        // the inside of a passage. The last draw is pushed out along its penetration direction.
        return checker_ && accept(state, true);
    }
}  // namespace meshgap
