#ifndef MESHGAP_PLANNERS_SUPPORT_CONTROL_RUN_H
#define MESHGAP_PLANNERS_SUPPORT_CONTROL_RUN_H

// meshgap_plan on a control problem (an OMPL.app .cfg with a "control" key): OMPL's control planners over the
// model's space (meshgap/ompl/ControlModels.h), the certified ClearanceChecker as validity checker, the summary and
// the path as OMPL.app writes a control path (its states, one propagation step apart, in OMPL's matrix format).

#include <memory>
#include <ompl/base/Planner.h>
#include <ompl/base/PlannerStatus.h>
#include <ompl/control/SpaceInformation.h>
#include <string>
#include <vector>

#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/scene/ProblemConfig.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief A control planning run: the problem, what the planner found, the summary. */
        struct ControlPlanRun
        {
            ProblemConfig config;
            OmplControlProblem problem;
            std::string planner;
            ompl::base::PlannerStatus status;
            bool exact = false, havePath = false;
            std::string summary;
            /** \brief With a path: its states one propagation step apart (each the state's reals, as --out writes
                them), its duration, its distance to the goal (0 when exact) and the least certified clearance over
                those states. */
            std::vector<std::vector<double>> states;
            double duration = 0.0, goalDistance = 0.0, minClearance = 0.0;
        };

        /** \brief Whether \e problem is a control problem (a single body's .cfg with a "control" key), planned by this
            run rather than the geometric one (support/PlanRun.h). */
        inline bool isControlProblem(const Problem &problem)
        {
            return problem.rigidBody && !problem.rigidBody->control.empty();
        }

        /** \brief The control planners meshgap_plan runs: kpiece, rrt, est, pdst, sst. */
        const std::vector<std::string> &controlPlannerNames();

        /** \brief OMPL's control planner named \e name (one of controlPlannerNames(), any case) on \e si; throws
            meshgap::Exception naming "WHERE NAME" (\e where: the option that gave it) and listing the valid names
            for another name. */
        ompl::base::PlannerPtr allocControlPlanner(const std::string &name,
                                                   const ompl::control::SpaceInformationPtr &si,
                                                   const std::string &where = "--planner");

        /** \brief Set up \e config (a control problem) as \e o says: the planner (kpiece unless --planner names one
            of controlPlannerNames(); --param as for a geometric problem), the checker (--checker), the seed. Throws
            meshgap::Exception naming the option at fault, including an option that applies to geometric problems
            only (--objective, --motion clearance, --optimize, --sampler, --export-glb, --report, --clearance-csv). */
        std::unique_ptr<ControlPlanRun> setUpControlPlan(const PlanOptions &o, ProblemConfig config);

        /** \brief Solve for o.time seconds (progress line unless o.quiet), then the summary: status, solved (yes
            (exact), approximate or no), the distance to the goal, the path's states and duration, and the least
            certified clearance over its states. */
        void solveControlPlan(ControlPlanRun &run, const PlanOptions &o);

        /** \brief Write --summary and, with a path, --out: the path's states one propagation step apart
            (PathControl::interpolate(), then asGeometric()), one per line, at full precision. */
        void writeControlPlanFiles(const ControlPlanRun &run, const PlanOptions &o, std::ostream &log);
    }  // namespace cli
}  // namespace meshgap

#endif
