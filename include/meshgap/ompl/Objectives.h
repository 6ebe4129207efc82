#ifndef MESHGAP_OMPL_OBJECTIVES_H
#define MESHGAP_OMPL_OBJECTIVES_H

#include <ompl/base/objectives/StateCostIntegralObjective.h>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"

namespace meshgap
{
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

    /** \brief The objective names allocObjective() knows: length, clearance, max_min_clearance, weighted. */
    std::vector<std::string> objectiveNames();

    /** \brief A new optimization objective by name:
        - "length": path length (PathLengthOptimizationObjective);
        - "clearance": the integral of 1/clearance (ClearanceObjective);
        - "max_min_clearance": maximise the smallest clearance along the path (MaximizeMinClearanceObjective);
        - "weighted": length + w * clearance (MultiOptimizationObjective; w is ObjectiveOptions::weight).
        The clearance objectives ask \e si's validity checker for clearance(). Throws meshgap::Exception listing the
        valid names for an unknown one. */
    ompl::base::OptimizationObjectivePtr allocObjective(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ObjectiveOptions &options = ObjectiveOptions());
}  // namespace meshgap

#endif
