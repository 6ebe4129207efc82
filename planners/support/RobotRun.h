#ifndef MESHGAP_PLANNERS_SUPPORT_ROBOT_RUN_H
#define MESHGAP_PLANNERS_SUPPORT_ROBOT_RUN_H

// meshgap_plan and meshgap_distance on a robot problem (RobotProblem: a URDF robot, its payload, or several bodies):
// the OMPL setup (robotStateSpace(), RobotChecker, RobotMotionValidator proving the answer of a sampled search,
// CertifiedAnswerPlanner, for every kind of robot), the run's summary and path file, and the per-state whole-robot
// answers meshgap_distance prints.

#include <memory>
#include <ompl/base/PlannerStatus.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ostream>
#include <string>

#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/robot/RobotProblem.h"
#include "support/DenseClearance.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief A planning run on a robot problem. */
        struct RobotPlanRun
        {
            RobotProblem problem;
            RobotSceneConstPtr scene;
            ompl::geometric::SimpleSetupPtr setup;
            std::shared_ptr<RobotChecker> checker;
            /** \brief The certified motion validator (every robot, unless --motion discrete); null when
                OMPL's discrete one checks motions. */
            std::shared_ptr<RobotMotionValidator> motion;
            /** \brief With the certified validator, the planner: a sampled search, its answer certified. */
            std::shared_ptr<CertifiedAnswerPlanner> answer;
            /** \brief The objective planned for: --objective, else the problem's, else length. */
            std::string objective{"length"};
            ompl::base::PlannerStatus status;
            bool exact = false, havePath = false;
            /** \brief --optimize clearance could not run on the planner's path (the summary says why). */
            bool optimizeFailed = false;
            /** \brief With a path: the exact minimum clearance over the dense path, the pair that attains it, and
                whether every dense state is free; with --optimize, the same of the planner's path before it. */
            double minClearance = 0.0, minClearanceBefore = 0.0;
            std::string limitingPair, limitingPairBefore;
            bool denseFree = false;
            /** \brief The dense path and its clearance (every link's too with --report); null without a path. */
            std::unique_ptr<DenseClearance> dense;
            std::string summary;
        };

        /** \brief Set up the planner on \e problem (o.cfg's, or o.moveit's files', readToolProblem()); throws
            meshgap::Exception naming the option that does not apply to robot problems, a problem without a goal (or,
            for rigid bodies, a volume), and a start or goal out of bounds or in collision (the pair and its
            distance). */
        std::unique_ptr<RobotPlanRun> setUpRobotPlan(const PlanOptions &o, RobotProblem problem);

        /** \brief Solve (then, with --optimize clearance, raise the path's clearance: ClearancePathOptimizer on the
            whole robot's clearance, every motion it makes certified), then the summary: the path's length, cost
            and the exact minimum clearance over it densely interpolated (o.dense states per validity-check
            segment) with the pair that attains it (before and after the optimiser when it ran), and the checker's
            and validator's counts. */
        void solveRobotPlan(RobotPlanRun &run, const PlanOptions &o);

        /** \brief Write the summary (o.summaryFile), the path (o.out: one state a line, the numbers of
            start.joints, or of the bodies' states one after the other) and the HTML report (o.report: every link
            along the path, as meshgap_report writes it). */
        void writeRobotPlanFiles(const RobotPlanRun &run, const PlanOptions &o, std::ostream &log);

        /** \brief The first columns of meshgap_distance --poses on a robot problem, one row per state (index from
            0): the whole robot's exact signed clearance, whether it is in collision, whether certified, the pair
            that attains it (link, and other_link for two links or obstacle, the obstacle's index, for a link
            against the world; the other one empty), its witness points (world frame); then clearance_LINK, each
            link's clearance, in the order of the robot's links. */
        inline constexpr const char *ROBOT_CSV_COLUMNS =
            "index,distance,in_collision,certified,link,other_link,obstacle,witness_link_x,witness_link_y,"
            "witness_link_z,witness_other_x,witness_other_y,witness_other_z";

        /** \brief How meshgap_distance answers a problem (robotDistance()). */
        struct RobotDistanceOptions
        {
            bool json{false};   ///< JSON instead of text or CSV: one object, or an array with states
            bool cold{false};   ///< no warm start: a cold query at every state
            bool depth{true};   ///< in collision, the penetration depth (RobotRequest::computeDepth)
        };

        /** \brief meshgap_distance on the problem \e p (any kind: a single body is a robot of one link): at the start
            (\e stateText empty and \e statesFile empty) or at the state \e stateText, a text block of the whole
            robot's exact signed clearance, the pair that attains it (a link and an obstacle, or two links), its
            witnesses and every link's clearance; at every state of \e statesFile (one a line, as a .path of the
            problem), the same as CSV (ROBOT_CSV_COLUMNS), and the time per query (median, mean) on stderr; with
            options.json, JSON objects of the same fields and the time. One warm start is carried from state to
            state unless options.cold. Throws meshgap::Exception naming file:line for a state of the wrong dimension
            or a malformed number. */
        void robotDistance(const RobotProblem &p, const std::string &stateText, const std::string &statesFile,
                           const RobotDistanceOptions &options, std::ostream &out);
    }  // namespace cli
}  // namespace meshgap

#endif
