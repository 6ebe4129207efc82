#ifndef MESHGAP_OMPL_PROBLEM_SETUP_H
#define MESHGAP_OMPL_PROBLEM_SETUP_H

#include <ompl/control/SimpleSetup.h>
#include <ompl/geometric/SimpleSetup.h>

#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/scene/ProblemConfig.h"

namespace meshgap
{
    /** \brief An OMPL problem built from an OMPL.app .cfg, in OMPL.app's conventions: an SE(3) space bounded by the
        cfg's volume, or for a planar cfg (ProblemConfig::planar) an SE(2) space bounded by its x/y volume with the
        robot moving in the plane z = 0 of the world; the robot loaded and centred as OMPL.app does (by its centre
        c, or for a planar problem by (c.x, c.y, 0)), so its state is its pose; the world split into its connected
        parts as obstacles; a ClearanceChecker in \e mode; and the cfg's start and goal. The objective is made by
        allocObjective() from \e objective or, when empty, the cfg's own objective key (default: length), with
        \e objectiveOptions; the cfg's objective.threshold, if any, is its cost threshold. Throws meshgap::Exception
        for a cfg without a volume or goal, an unknown objective, or a start or goal out of bounds or in collision
        (the message says which, the obstacle hit, where, and the signed distance). */
    struct OmplProblem
    {
        ompl::geometric::SimpleSetupPtr setup;
        ClearanceCheckerPtr checker;
        ScenePtr scene;
        std::string objective;
    };

    OmplProblem setupProblem(const ProblemConfig &config, ClearanceChecker::Mode mode, const std::string &objective = "",
                             const BodyOptions &bodies = BodyOptions(),
                             const ObjectiveOptions &objectiveOptions = ObjectiveOptions());

    /** \brief A control problem (an OMPL.app .cfg with a "control" key) in OMPL.app's conventions: the model's
        space information (controlSpaceInformation(), its pose bounded by the cfg's volume), the scene as
        setupProblem() loads it, a ClearanceChecker in \e mode as the validity checker (it reads the pose part of the
        state), and the cfg's start and goal poses with zero velocities. The goal threshold is OMPL's default, as in
        OMPL.app: control planners mostly end with an approximate solution. Throws meshgap::Exception as
        setupProblem() does, for a cfg without a control key, and for a model not modelled (naming the file). */
    struct OmplControlProblem
    {
        ompl::control::SimpleSetupPtr setup;
        ClearanceCheckerPtr checker;
        ScenePtr scene;
    };

    OmplControlProblem setupControlProblem(const ProblemConfig &config, ClearanceChecker::Mode mode,
                                           const BodyOptions &bodies = BodyOptions());
}  // namespace meshgap

#endif
