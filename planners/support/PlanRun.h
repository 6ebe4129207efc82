#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_RUN_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_RUN_H

// One planning run as meshgap_plan makes it, shared by meshgap_plan and the Python module's plan(), for every kind of
// geometric problem (a single body is a robot of one link; control problems: support/ControlRun.h): the problem set
// up from PlanOptions, solve (with the progress line), --optimize, the exact clearance over the dense path, the
// summary text and the files the options ask for (the path, the clearance CSV, the summary, the scene, the report).
// What depends on the problem's kind (the checker, the motion validator, the planner around the search, the summary
// lines that speak of them) is the run's PlanChecks, made in one place (support/PlanChecks.h).

#include <memory>
#include <ompl/base/PlannerStatus.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ostream>
#include <string>
#include <vector>

#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "support/DenseClearance.h"
#include "support/PlanChecks.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief A planning run: the problem, what the planner found, the dense path's exact clearance and the
            summary. */
        struct PlanRun
        {
            /** \brief What depends on the problem's kind: planChecks(). */
            std::unique_ptr<PlanChecks> checks;
            ompl::geometric::SimpleSetupPtr setup;
            /** \brief The robot (a single body: one link) against the problem's obstacles: the dense path's
                clearance, the scene export and the report. */
            RobotSceneConstPtr scene;
            /** \brief The start and (when there is one) the goal, as the robot's state numbers. */
            std::vector<std::vector<double>> ends;
            /** \brief The objective planned for (--objective, else the problem's, else length) and the motion check
                (--motion, or the kind's default). */
            std::string objective, motion;
            ompl::base::PlannerStatus status;
            bool exact = false, havePath = false;
            bool optimizeFailed = false;  ///< --optimize could not certify the planner's path (left as it was)
            /** \brief The dense path and its clearance (every link's too with --report); null without a path. */
            std::unique_ptr<DenseClearance> dense;
            /** \brief With --optimize and a path: the planner's path's, before the optimiser. */
            std::unique_ptr<DenseClearance> before;
            /** \brief meshgap_plan's summary: "key" padded to 16 columns, then the value, one per line. */
            std::string summary;
        };

        /** \brief The planner \e o names, with its --param values (and Python's params); throws meshgap::Exception
            naming the option at fault. */
        ompl::base::PlannerPtr allocPlanPlanner(const PlanOptions &o, const ompl::base::SpaceInformationPtr &si);

        /** \brief Set up the planner on \e problem (o.cfg's, or o.moveit's files', readToolProblem(); not a control
            problem) as \e o says (OMPL's seed is the caller's to set first); throws meshgap::Exception naming the
            option or file at fault. */
        std::unique_ptr<PlanRun> setUpPlan(const PlanOptions &o, Problem problem);

        /** \brief Solve (with the progress line on stderr unless o.quiet, when the checker counts its checks), then
            with a path and --optimize clearance raise its clearance (ClearancePathOptimizer, its motions certified),
            then the summary: the path's length, cost and exact minimum clearance over it densely interpolated
            (o.dense states per validity-check segment), and the checker's and validator's counts. */
        void solvePlan(PlanRun &run, const PlanOptions &o);

        /** \brief Write the files \e o asks for (summary, scene, report; the path and the clearance CSV when there
            is a path), saying each on \e log ("path written    FILE"). */
        void writePlanFiles(const PlanRun &run, const PlanOptions &o, std::ostream &log);
    }  // namespace cli
}  // namespace meshgap

#endif
