#include "meshgap/ompl/Objectives.h"

#include <ompl/base/OptimizationObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/ClearanceField.h"

namespace meshgap
{
    ClearanceObjective::ClearanceObjective(const ompl::base::SpaceInformationPtr &si, double minClearance)
      : ompl::base::StateCostIntegralObjective(si, true), minClearance_(minClearance)
    {
        if (!(minClearance_ > 0.0))
            throw Exception("ClearanceObjective", "minClearance must be positive");
        description_ = "Integral of 1/clearance";
    }

    ompl::base::Cost ClearanceObjective::stateCost(const ompl::base::State *s) const
    {
        return ompl::base::Cost(1.0 / std::max(si_->getStateValidityChecker()->clearance(s), minClearance_));
    }

    namespace
    {
        /** \brief One remembered clearance: the checker that answered (its id), the state (its numbers, as
            StateSpace::copyToReals() gives them) and the answer. */
        struct CachedClearance
        {
            std::uint64_t checker{0};  ///< 0: empty
            std::vector<double> pose;
            double clearance;
        };

        /** \brief This thread's cache, direct-mapped, shared by all objectives and checkers (each entry says which
            checker answered: a checker's clearance is a function of the state alone). */
        constexpr std::size_t CACHE_SIZE = 4096;
        std::vector<CachedClearance> &threadCache()
        {
            thread_local std::vector<CachedClearance> cache(CACHE_SIZE);
            return cache;
        }

        std::size_t slotOf(std::uint64_t checker, const std::vector<double> &pose)
        {
            std::uint64_t h = 1469598103934665603ull ^ checker;
            for (double x : pose)
            {
                std::uint64_t bits;
                std::memcpy(&bits, &x, sizeof bits);
                h = (h ^ bits) * 1099511628211ull;
            }
            return static_cast<std::size_t>(h ^ (h >> 29)) & (CACHE_SIZE - 1);
        }

        /** \brief A stretch of OMPL's grid between two grid states i < j whose clearances are known to be at least
            ci and cj, with no state queried in between. Clearance is 1-Lipschitz in the robot's displacement and a
            grid step displaces no robot point by more than \e step, so a state k in between is at least
            max(ci - step (k - i), cj - step (j - k)) clear; \e bound is the lowest of that over the stretch (where
            the two slopes cross). */
        struct Gap
        {
            int i, j;
            double ci, cj, bound;
        };

        Gap makeGap(int i, int j, double ci, double cj, double step)
        {
            // Lowest where the slopes cross (the grid states there are no lower).
            return {i, j, ci, cj, 0.5 * (ci + cj - step * (j - i))};
        }
    }  // namespace

    MaxMinClearanceObjective::MaxMinClearanceObjective(const ompl::base::SpaceInformationPtr &si)
      : ompl::base::MaximizeMinClearanceObjective(si), states_(si->getStateSpace())
    {
    }

    double MaxMinClearanceObjective::cachedClearance(const ClearanceField &checker, const ompl::base::State *s) const
    {
        thread_local std::vector<double> pose;
        si_->getStateSpace()->copyToReals(pose, s);
        CachedClearance &slot = threadCache()[slotOf(checker.fieldId(), pose)];
        if (slot.checker == checker.fieldId() && slot.pose == pose)
            return slot.clearance;
        counts_.add(QUERIED, 1);
        slot.checker = checker.fieldId();
        slot.pose.assign(pose.begin(), pose.end());
        slot.clearance = checker.clearanceOrContact(s);
        return slot.clearance;
    }

    ompl::base::Cost MaxMinClearanceObjective::motionCost(const ompl::base::State *s1,
                                                          const ompl::base::State *s2) const
    {
        // The space's checker now (a benchmark may install another one after the objective was made). Only an exact
        // clearance is 1-Lipschitz: a fast-mode answer (the node search's best find) need not be.
        const auto *checker = dynamic_cast<const ClearanceField *>(si_->getStateValidityChecker().get());
        if (checker == nullptr || !checker->certified())
            return ompl::base::MaximizeMinClearanceObjective::motionCost(s1, s2);
        // As OMPL's, the minimum is over the grid states after s1 and s2 itself (s1 is the previous motion's end, or
        // a start, whose cost the path does not count); s1's clearance only bounds its neighbours.
        const double c2 = cachedClearance(*checker, s2);
        if (!(c2 > 0.0))
            return ompl::base::Cost(c2);
        const double c1 = cachedClearance(*checker, s1);
        double lowest = c2;
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        const int n = static_cast<int>(space.validSegmentCount(s1, s2));
        if (n < 2)
            return ompl::base::Cost(lowest);
        counts_.add(GRID_STATES, n - 1);
        const double step = checker->sweep(s1, s2) / n;
        if (!(step > 0.0))
            return ompl::base::Cost(lowest);  // every grid state is s1's pose

        // Best-first over the stretches of grid between queried states, lowest bound first, until the lowest bound
        // left is at or above the lowest clearance found: nothing unqueried can be lower. In a stretch, the states
        // its ends already prove at least that clear are skipped; of the rest, [l, r], the middle one is queried,
        // and the stretch split there. A query only asks whether the state is clearer than the lowest so far
        // (clearanceBelow(state, lowest)): a proof that it is stops the search early and is cheap, and an answer
        // below comes back exact, the new lowest. (Measured on cubicles, RRT* 5 s: asking more, enough to also prove
        // a stretch of neighbours at least as clear, answered exactly far more often and grew a tree about 1.6 times
        // smaller; bench/README.md.) A state in collision ends the search: the motion is invalid.
        thread_local std::vector<Gap> gaps;  // a heap, lowest bound on top
        const auto higher = [](const Gap &a, const Gap &b) { return a.bound > b.bound; };
        gaps.clear();
        gaps.push_back(makeGap(0, n, c1, c2, step));
        const StatePool::Lease lease(states_);
        ompl::base::State *state = lease.get();
        while (!gaps.empty() && gaps.front().bound < lowest)
        {
            std::pop_heap(gaps.begin(), gaps.end(), higher);
            const Gap g = gaps.back();
            gaps.pop_back();
            // The grid states of (i, j) that neither end proves at least `lowest` clear.
            // (s1's clearance may be below the lowest: it proves nothing then.)
            const auto steps = [&](double c) { return static_cast<int>(std::clamp((c - lowest) / step, 0.0, 1.0 * n)); };
            const int l = g.i + 1 + steps(g.ci), r = g.j - 1 - steps(g.cj);
            if (l > r)
                continue;
            const int k = l + (r - l) / 2;
            space.interpolate(s1, s2, static_cast<double>(k) / n, state);
            counts_.add(QUERIED, 1);
            const double c = checker->clearanceBelow(state, lowest);
            if (!(c > 0.0))
            {
                lowest = c;  // in collision: the motion is invalid, whatever the rest
                break;
            }
            lowest = std::min(lowest, c);
            if (k - g.i > 1)
            {
                gaps.push_back(makeGap(g.i, k, g.ci, c, step));
                std::push_heap(gaps.begin(), gaps.end(), higher);
            }
            if (g.j - k > 1)
            {
                gaps.push_back(makeGap(k, g.j, c, g.cj, step));
                std::push_heap(gaps.begin(), gaps.end(), higher);
            }
        }
        return ompl::base::Cost(lowest);
    }

    std::vector<std::string> objectiveNames()
    {
        return {"length", "clearance", "max_min_clearance", "weighted"};
    }

    ompl::base::OptimizationObjectivePtr allocObjective(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ObjectiveOptions &options)
    {
        namespace ob = ompl::base;
        if (name == "length")
            return std::make_shared<ob::PathLengthOptimizationObjective>(si);
        if (name == "clearance")
            return std::make_shared<ClearanceObjective>(si, options.minClearance);
        if (name == "max_min_clearance")
            return std::make_shared<MaxMinClearanceObjective>(si);
        if (name == "weighted")
        {
            double weight = options.weight;
            if (weight == 0.0)
            {
                const auto *checker = dynamic_cast<const ClearanceField *>(si->getStateValidityChecker().get());
                weight = checker != nullptr ? 0.1 * checker->lengthScale() : 1.0;
            }
            if (!(weight > 0.0) || !std::isfinite(weight))
                throw Exception("objective", "the weight of 'weighted' must be positive and finite");
            auto multi = std::make_shared<ob::MultiOptimizationObjective>(si);
            multi->addObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si), 1.0);
            multi->addObjective(std::make_shared<ClearanceObjective>(si, options.minClearance), weight);
            multi->lock();
            return multi;
        }
        std::string valid;
        for (const std::string &n : objectiveNames())
            valid += (valid.empty() ? "" : ", ") + n;
        throw Exception("objective", "unknown objective " + quote(name) + "; valid names: " + valid);
    }
}  // namespace meshgap
