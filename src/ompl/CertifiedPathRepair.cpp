#include "meshgap/ompl/CertifiedPathRepair.h"

#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/ompl/MotionValidatorFactory.h"

namespace meshgap
{
    namespace ob = ompl::base;
    namespace og = ompl::geometric;

    CertifiedPathRepair::CertifiedPathRepair(const ob::SpaceInformationPtr &si, ClearanceFieldPtr checker)
        : si_(si), checker_(std::move(checker))
    {
        if (!checker_)
            throw Exception("CertifiedPathRepair", "no checker");
        if (!checker_->certified())
            throw Exception("CertifiedPathRepair", "needs a checker in CERTIFIED mode (exact clearance)");
        checker_->gradientDimension();  // throws for spaces the checker has no gradient in
        validator_ = allocCertifiedMotionValidator(si_, checker_);
    }

    void CertifiedPathRepair::validateStates(const og::PathGeometric &path) const
    {
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            if (!si_->satisfiesBounds(path.getState(i)))
                throw Exception("CertifiedPathRepair",
                                "state " + std::to_string(i) + " of the input path is out of bounds");
            if (!checker_->isValid(path.getState(i)))
                throw Exception("CertifiedPathRepair",
                                "state " + std::to_string(i) + " of the input path is in collision");
        }
    }

    void CertifiedPathRepair::freeFrom(std::vector<ob::State *> &states, std::size_t first) const
    {
        for (std::size_t k = first; k < states.size(); ++k)
            si_->freeState(states[k]);
        states.resize(std::min(first, states.size()));
    }

    double CertifiedPathRepair::pushOut(ob::State *s, double target, const ob::PlannerTerminationCondition &ptc)
    {
        const double L = checker_->lengthScale();
        double c = checker_->clearance(s);
        std::vector<double> gradient, step;
        ob::State *candidate = si_->allocState();
        // The first trial step moves the robot about as far as the clearance has to rise.
        double alpha = std::max(target - c, 1e-3 * L);
        for (unsigned k = 0; k < MAX_PUSH_STEPS && c < target && !ptc(); ++k)
        {
            ClearanceGradientOptions options;
            options.tieTolerance = 0.05 * std::abs(c) + 1e-9 * (1.0 + L);
            options.probes = c > 0.0 ? 3 : 0;
            ClearanceGradientInfo info;
            checker_->gradient(s, gradient, options, &info);
            const double g2 = checker_->gradientNorm2(gradient);
            if (!info.hasDirection || !(g2 > 1e-12))
                break;
            bool stepped = false;
            for (int trial = 0; trial < 8 && !stepped; ++trial, alpha *= 0.5)
            {
                checker_->ascentStep(gradient, alpha / std::sqrt(g2), step);
                checker_->applyStep(s, step.data(), candidate);
                if (!si_->satisfiesBounds(candidate))
                    continue;
                const double cc = checker_->clearance(candidate);
                if (cc > c)
                {
                    si_->copyState(s, candidate);
                    c = cc;
                    stepped = true;
                    alpha *= 4.0;  // doubled once the loop halves it
                }
            }
            if (!stepped)
                break;
        }
        si_->freeState(candidate);
        return c;
    }

    bool CertifiedPathRepair::bisect(const ob::State *a, double ca, const ob::State *b, double cb, unsigned depth,
                                     std::vector<ob::State *> &out, const ob::PlannerTerminationCondition &ptc)
    {
        if (validator_->checkMotion(a, b))
            return true;
        if (depth == 0 || ptc())
            return false;
        ob::State *middle = si_->allocState();
        si_->getStateSpace()->interpolate(a, b, 0.5, middle);
        const double cm = pushOut(middle, std::min(ca, cb), ptc);
        const std::size_t mark = out.size();
        if (cm > 0.0 && si_->satisfiesBounds(middle) && checker_->isValid(middle) &&
            bisect(a, ca, middle, cm, depth - 1, out, ptc))
        {
            out.push_back(middle);
            if (bisect(middle, cm, b, cb, depth - 1, out, ptc))
                return true;
            freeFrom(out, mark);  // the middle with them
            return false;
        }
        freeFrom(out, mark);
        si_->freeState(middle);
        return false;
    }

    bool CertifiedPathRepair::replan(const ob::State *a, const ob::State *b, std::vector<ob::State *> &out,
                                     const ob::PlannerTerminationCondition &ptc)
    {
        if (!replanSi_)
        {
            replanSi_ = std::make_shared<ob::SpaceInformation>(si_->getStateSpace());
            replanSi_->setStateValidityChecker(std::dynamic_pointer_cast<ob::StateValidityChecker>(checker_));
            replanSi_->setMotionValidator(allocCertifiedMotionValidator(replanSi_, checker_));
            replanSi_->setStateValidityCheckingResolution(si_->getStateValidityCheckingResolution());
            replanSi_->setup();
        }
        auto pdef = std::make_shared<ob::ProblemDefinition>(replanSi_);
        pdef->setStartAndGoalStates(a, b);
        auto planner = std::make_shared<og::RRTConnect>(replanSi_);
        planner->setProblemDefinition(pdef);
        planner->setup();
        if (planner->solve(ptc) != ob::PlannerStatus::EXACT_SOLUTION)
            return false;
        auto &path = *pdef->getSolutionPath()->as<og::PathGeometric>();
        og::PathSimplifier(replanSi_).reduceVertices(path);
        const std::size_t n = path.getStateCount();
        // The planner's path runs from copies of a and b; each motion is checked again so that what is inserted
        // is certified whatever the planner did.
        if (n < 2 || si_->distance(path.getState(0), a) != 0.0 || si_->distance(path.getState(n - 1), b) != 0.0)
            return false;
        for (std::size_t k = 0; k + 1 < n; ++k)
            if (!validator_->checkMotion(path.getState(k), path.getState(k + 1)))
                return false;
        for (std::size_t k = 1; k + 1 < n; ++k)
            out.push_back(si_->cloneState(path.getState(k)));
        return true;
    }

    bool CertifiedPathRepair::repair(og::PathGeometric &path, const ob::PlannerTerminationCondition &ptc)
    {
        const auto start = std::chrono::steady_clock::now();
        stats_ = Stats();
        validateStates(path);
        std::vector<ob::State *> &states = path.getStates();
        std::vector<ob::State *> repaired, between;
        repaired.reserve(states.size());
        for (std::size_t i = 0; i + 1 < states.size(); ++i)
        {
            repaired.push_back(states[i]);
            if (validator_->checkMotion(states[i], states[i + 1]))
                continue;
            ++stats_.refused;
            between.clear();
            const double ca = checker_->clearance(states[i]), cb = checker_->clearance(states[i + 1]);
            if (bisect(states[i], ca, states[i + 1], cb, maxDepth_, between, ptc))
                ++stats_.bisected;
            else if (replan_ && replan(states[i], states[i + 1], between, ptc))
                ++stats_.replanned;
            else
            {
                // Free what was inserted so far; the path keeps its own states.
                for (ob::State *s : repaired)
                    if (std::find(states.begin(), states.end(), s) == states.end())
                        si_->freeState(s);
                stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                throw Exception("CertifiedPathRepair",
                                "motion " + std::to_string(i) + "→" + std::to_string(i + 1) +
                                    " of the input path is refused by the certified clearance motion validator, "
                                    "and neither bisection nor replanning found a certified detour in the time given");
            }
            repaired.insert(repaired.end(), between.begin(), between.end());
            stats_.inserted += static_cast<unsigned>(between.size());
        }
        if (!states.empty())
            repaired.push_back(states.back());
        states.swap(repaired);
        stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats_.inserted > 0;
    }
}  // namespace meshgap
