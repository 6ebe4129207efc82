#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_RUN_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_RUN_H

// One planning run as meshgap_plan makes it, shared by meshgap_plan and the Python module's plan(): the problem set
// up from PlanOptions (checker, sampler, motion validator, planner and its parameters), solve, --optimize, the dense
// clearance, the summary text and the files the options ask for.

#include <memory>
#include <ompl/base/PlannerStatus.h>
#include <ostream>
#include <string>

#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/ProblemConfig.h"
#include "support/DenseClearance.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief A planning run: the problem, what the planner found, the dense path's exact clearance and the
            summary. */
        struct PlanRun
        {
            ProblemConfig config;
            OmplProblem problem;
            /** \brief The body as a robot of one link against the problem's obstacles (its body and obstacles the
                scene's): the dense path's clearance and the report, as for every kind of problem. */
            RobotSceneConstPtr robotScene;
            std::shared_ptr<ClearanceMotionValidator> cmv;
            ompl::base::PlannerStatus status;
            bool exact = false, havePath = false;
            bool optimizeFailed = false;  ///< --optimize could not certify the planner's path (left as it was)
            /** \brief The dense path and its clearance; null without a path. */
            std::unique_ptr<DenseClearance> dense;
            /** \brief meshgap_plan's summary: "key" padded to 16 columns, then the value, one per line. */
            std::string summary;
        };

        /** \brief The planner \e o names, with its --param values (and Python's params); throws meshgap::Exception
            naming the option at fault. */
        ompl::base::PlannerPtr allocPlanPlanner(const PlanOptions &o, const ompl::base::SpaceInformationPtr &si);

        /** \brief Load the single-body problem \e config (o.cfg's, readToolProblem()) and set up the planner as \e o
            says (OMPL's seed is the caller's to set first); throws meshgap::Exception naming the option or file at
            fault. */
        std::unique_ptr<PlanRun> setUpPlan(const PlanOptions &o, ProblemConfig config);

        /** \brief Solve (with the progress line on stderr unless o.quiet), optimise the path if o.optimize asks, then
            the dense clearance and the summary. */
        void solvePlan(PlanRun &run, const PlanOptions &o);

        /** \brief Write the files \e o asks for (summary, scene, report; the path and the clearance CSV when there
            is a path), saying each on \e log ("path written    FILE"). */
        void writePlanFiles(const PlanRun &run, const PlanOptions &o, std::ostream &log);
    }  // namespace cli
}  // namespace meshgap

#endif
