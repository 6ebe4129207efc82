// meshgap_plan: plan a path for an OMPL.app-format problem (SE(3), or SE(2) for a 2D cfg) with meshgap's clearance
// checker.
//
//   meshgap_plan --cfg problem.cfg [--planner rrtconnect] [--time 10] [--objective NAME [--weight W]]
//                [--checker certified|fast] [--motion discrete|clearance] [--seed N] [--out solution.path]
//                [--clearance-csv clearance.csv] [--summary summary.txt] [--export-glb scene.glb [--export-states N]]
//                [--report plan.html] [--optimize clearance [--optimize-time S] [--optimize-rounds N]]
//                [--sampler NAME]
//
// While it plans, one progress line a second goes to stderr (elapsed time, validity checks, the planner's best cost
// when it reports one). Then it prints a summary (solved, exact or approximate, planning time, path length, cost, the
// exact minimum clearance along the densely interpolated path, checker counters), writes the path in OMPL's .path
// format (one state per line: x y z qx qy qz qw, or x y theta), which meshgap_distance --poses and OMPL.app read, the
// exact clearance along the dense path as CSV, and the scene (world, the robot at N states along the path, the
// closest-point segment at each) as a glTF 2.0 binary file for any 3D viewer. Exit status: 0 exact solution, 2
// approximate or none (or --optimize could not certify the path), 1 bad input (including a start or goal in
// collision: the message says which, the obstacle and the distance). --optimize clearance runs the
// ClearancePathOptimizer on the planner's path (its uncertified motions repaired first) before any of this.
//
// On a control problem (a "control" key: kinematic_car, dynamic_car, blimp, quadrotor) it plans with OMPL's control
// planners (kpiece, the default, rrt, est, pdst, sst) over the model's propagated motions (support/ControlRun.h); the
// .path holds the states one propagation step apart, as OMPL.app writes a control path.
//
// A robot problem (robot.urdf, or robot.1, robot.2, ...: meshgap/robot/RobotProblem.h) is planned by the same run in
// the robot's joint space: exact whole-robot checks, every motion of the answer proven by the certified motion
// validator, for every kind of robot (a sampled search, its path certified: CertifiedAnswerPlanner; OMPL's discrete
// validator with --motion discrete); the .path holds one state a line, the numbers of start.joints, and the clearance
// CSV a column per state number; --checker fast is a single body's.
//
// Its options are support/PlanOptions.h's table (the Python module's plan() takes the same ones as keywords), and a
// run is support/PlanRun.h's, one for every kind of geometric problem (plan() makes the same one): the progress line,
// --optimize (OptimizeOption.h), the dense path's exact clearance (support/DenseClearance.h), the summary and the
// files it writes (support/PlanOutputs.h, support/PlanReport.h). What depends on the problem's kind (the checker, the
// motion validator, the planner around the search, the summary lines that speak of them) is chosen from the problem in
// one place, support/PlanChecks.h.

#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>
#include <ompl/util/RandomNumbers.h>
#include <type_traits>
#include <variant>

#include "CliMain.h"
#include "support/ControlRun.h"
#include "support/MoveItOptions.h"
#include "support/PlanOptions.h"
#include "support/PlanRun.h"

namespace po = boost::program_options;
using namespace meshgap;
using namespace meshgap::cli;

namespace
{
    /** \brief The flag of a row of support/PlanOptions.h's table, bound to its field of \e o. */
    void declareOption(po::options_description &options, const PlanOption &row, PlanOptions &o)
    {
        const std::string flag = row.name + (row.letter ? std::string(",") + row.letter : std::string());
        std::visit(
            [&](auto field)
            {
                using T = std::remove_reference_t<decltype(o.*field)>;
                if constexpr (std::is_same_v<T, bool>)
                    options.add_options()(flag.c_str(), row.help.c_str());  // a switch: set by parseOptions()
                else
                    options.add_options()(flag.c_str(), po::value<T>(&(o.*field)), row.help.c_str());
            },
            row.field);
    }

    /** \brief Parse and check the command line; false after --help. */
    bool parseOptions(int argc, char **argv, PlanOptions &o)
    {
        po::options_description options("meshgap_plan --cfg FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help");
        for (const PlanOption &row : planOptionTable())
            declareOption(options, row, o);
        addMoveItOptions(options, o.moveit);
        po::options_description all;
        all.add(options);
        addRenamedOptions(all, {{"mode", "--checker certified|fast"}});
        po::variables_map vm;
        if (!parseCommandLine(argc, argv, all, vm, nullptr, &options))
            return false;
        for (const PlanOption &row : planOptionTable())
        {
            if (vm.count(row.name))
                o.given.insert(row.name);
            if (const auto *field = std::get_if<bool PlanOptions::*>(&row.field))
                o.*(*field) = vm.count(row.name) > 0;
        }
        checkPlanOptions(o);
        return true;
    }

    /** \brief A control problem (a "control" key): support/ControlRun.h. */
    int runControl(const PlanOptions &o, ProblemConfig config)
    {
        const std::unique_ptr<ControlPlanRun> p = setUpControlPlan(o, std::move(config));
        OMPL_INFORM("%s: control %s, %zu obstacles, planner %s", p->config.name.c_str(), p->config.control.c_str(),
                    p->problem.scene->obstacles().size(), p->planner.c_str());
        solveControlPlan(*p, o);
        std::cout << p->summary;
        writeControlPlanFiles(*p, o, std::cout);
        if (!p->havePath)
        {
            std::fprintf(stderr, "no path found within %g s\n", o.time);
            return 2;
        }
        return p->exact ? 0 : 2;
    }

    int run(int argc, char **argv)
    {
        PlanOptions o;
        if (!parseOptions(argc, argv, o))
            return 0;
        ompl::RNG::setSeed(o.seed);
        Problem problem = readToolProblem(o.cfg, o.moveit);
        if (isControlProblem(problem))
            return runControl(o, std::move(*problem.rigidBody));
        const std::unique_ptr<PlanRun> p = setUpPlan(o, std::move(problem));
        OMPL_INFORM("%s: %s, %zu state numbers, %zu obstacles, planner %s, objective %s, clearance %s, motion %s",
                    p->checks->settings().name.c_str(), p->scene->robot().description().c_str(),
                    p->scene->robot().dimension(), p->scene->obstacles().size(), o.planner.c_str(),
                    p->objective.c_str(), o.checker.c_str(), p->motion.c_str());
        solvePlan(*p, o);
        std::cout << p->summary;
        writePlanFiles(*p, o, std::cout);
        if (!p->havePath)
        {
            std::fprintf(stderr, "no path found within %g s\n", o.time);
            return 2;
        }
        return p->exact && !p->optimizeFailed ? 0 : 2;
    }
}  // namespace

int main(int argc, char **argv)
{
    return runMain(argc, argv, run);
}
