#ifndef MESHGAP_OMPL_OBJECTIVES_H
#define MESHGAP_OMPL_OBJECTIVES_H

#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/StateCostIntegralObjective.h>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/ThreadCounters.h"
#include "meshgap/ompl/StatePool.h"

namespace meshgap
{
    class ClearanceField;

    /** \brief Settings of the objectives allocObjective() makes. */
    struct ObjectiveOptions
    {
        /** \brief Weight w of the clearance term of "weighted" (length + w * integral of 1/clearance). The integral
            is unitless (length over clearance), so w is a length: at clearance w a piece of path costs twice its
            length. 0 (the default) means one tenth of the robot's radius about its origin when the space's validity
            checker is a meshgap ClearanceChecker (the scene's own scale), else 1. */
        double weight{0.0};
        /** \brief Clearances at or below this count as this in "clearance"'s 1/clearance (so a grazing or colliding
            state costs 1/minClearance, large but finite, rather than infinity or a negative cost). */
        double minClearance{1e-9};
    };

    /**
       @anchor mgClearanceObjective
       @par Short description
       OMPL's integral of 1/clearance along the path, as OMPL's OptimalPlanning demo defines ClearanceObjective: a
       StateCostIntegralObjective (with motion cost interpolation) whose state cost is 1/clearance, the clearance
       from the space's validity checker (signed: at or below minClearance the cost is 1/minClearance). Paths that
       stay far from obstacles cost less; unlike the max-min objective it trades clearance along the whole path.
    */
    class ClearanceObjective : public ompl::base::StateCostIntegralObjective
    {
    public:
        explicit ClearanceObjective(const ompl::base::SpaceInformationPtr &si, double minClearance = 1e-9);
        ompl::base::Cost stateCost(const ompl::base::State *s) const override;

    private:
        double minClearance_;
    };

    /**
       @anchor mgMaxMinClearanceObjective
       @par Short description
       OMPL's MaximizeMinClearanceObjective, the same costs from fewer clearance queries. A motion's cost is, as in
       OMPL's MinimaxObjective, the smallest clearance over the states at j / n of the way (n = validSegmentCount(),
       j = 1 .. n-1) and its end s2 (not s1: a path does not count its start); here a state of that grid is queried
       only if it could lower the minimum found so far, and then only asked whether it does. Clearance is
       1-Lipschitz in the robot's displacement, and sweepBound() bounds the displacement, so the known clearances
       bound the states around them from below; the grid states are visited best-first by that bound (Piyavskii's
       rule), and the search ends when the lowest bound left is at or above the minimum found: the unvisited states
       cannot change it. Each query is ClearanceField::clearanceBelow(state, minimum so far): the exact clearance
       if lower, else a proof that it is not, which the scene finds cheaply by pruning everything farther. More
       savings:
       - the clearances of motion endpoints (tree states, met again and again by RRT* and PRM*) are kept in a
         small per-thread cache keyed by the state's numbers;
       - a motion with a state in collision costs that state's negative value as soon as it is found, without
         its depth (ClearanceField::clearanceOrContact()) and without querying the rest: OMPL's would cost it the
         most negative sample; either way the motion is invalid, and its exact cost is never used.
       The space's validity checker is asked as a ClearanceField: one rigid body's ClearanceChecker, or a robot's
       RobotChecker (the whole robot: every link, payloads, self pairs; sweep() is then the largest displacement
       bound over the pairs, and the cache is keyed by the state's numbers). With a validity checker that is not a
       certified ClearanceField (a ClearanceChecker in FAST mode: its node distance is not
       Lipschitz, the node search may miss the closest pair) it is OMPL's objective unchanged. The checker
       is the space's at each call, so a benchmark that installs another checker gets its costs from that one.
    */
    class MaxMinClearanceObjective : public ompl::base::MaximizeMinClearanceObjective
    {
    public:
        explicit MaxMinClearanceObjective(const ompl::base::SpaceInformationPtr &si);
        ompl::base::Cost motionCost(const ompl::base::State *s1, const ompl::base::State *s2) const override;

        /** \brief Grid states OMPL's objective would have queried, and states this one did query (cache misses
            and grid states), over all threads. */
        std::uint64_t gridStates() const { return counts_.sum(GRID_STATES); }
        std::uint64_t queriedStates() const { return counts_.sum(QUERIED); }

    private:
        /** \brief The clearance of \e s (clearanceOrContact()), from this thread's cache if \e checker gave it
            recently. */
        double cachedClearance(const ClearanceField &checker, const ompl::base::State *s) const;

        enum Count : std::size_t
        {
            GRID_STATES,
            QUERIED,
            COUNTS
        };
        mutable StatePool states_;  ///< the working state of each thread costing a motion
        mutable ThreadCounters<COUNTS> counts_;  ///< per thread: threads sharing the objective share no cache line
    };

    /** \brief The objective names allocObjective() knows: length, clearance, max_min_clearance, weighted. */
    std::vector<std::string> objectiveNames();

    /** \brief A new optimization objective by name:
        - "length": path length (PathLengthOptimizationObjective);
        - "clearance": the integral of 1/clearance (ClearanceObjective);
        - "max_min_clearance": maximise the smallest clearance along the path (MaxMinClearanceObjective: OMPL's
          MaximizeMinClearanceObjective, computed with fewer queries);
        - "weighted": length + w * clearance (MultiOptimizationObjective; w is ObjectiveOptions::weight).
        The clearance objectives ask \e si's validity checker for clearance(). Throws meshgap::Exception listing the
        valid names for an unknown one. */
    ompl::base::OptimizationObjectivePtr allocObjective(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ObjectiveOptions &options = ObjectiveOptions());
}  // namespace meshgap

#endif
