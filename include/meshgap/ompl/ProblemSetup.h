#ifndef MESHGAP_OMPL_PROBLEM_SETUP_H
#define MESHGAP_OMPL_PROBLEM_SETUP_H

#include <ompl/geometric/SimpleSetup.h>

#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/scene/ProblemConfig.h"

namespace meshgap
{
    /** \brief An OMPL problem built from an OMPL.app .cfg, in OMPL.app's conventions: an SE(3) space bounded by the
        cfg's volume, the robot loaded and centred as OMPL.app does (its state is its pose), the world split into
        its connected parts as obstacles, a ClearanceChecker in \e mode, and the cfg's start and goal. The
        objective is "length" (path length) or "max_min_clearance" (OMPL's MaximizeMinClearanceObjective), from
        \e objective or, when empty, the cfg's own objective key (default: length). Throws meshgap::Exception for a
        cfg without a volume, an unknown objective, or a start or goal that is out of bounds or in collision. */
    struct OmplProblem
    {
        ompl::geometric::SimpleSetupPtr setup;
        ClearanceCheckerPtr checker;
        ScenePtr scene;
        std::string objective;
    };

    OmplProblem setupProblem(const ProblemConfig &config, ClearanceChecker::Mode mode, const std::string &objective = "",
                             const BodyOptions &bodies = BodyOptions());
}  // namespace meshgap

#endif
