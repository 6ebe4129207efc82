// meshgap_report: turn a problem (any kind: one rigid body, a URDF robot, several bodies) and a path for it into one
// self-contained HTML report, as meshgap_plan --report writes after planning. A single body is a robot of one link
// (rigidBodyProblem()), so every kind takes one route: the path has one state a line (x y z qx qy qz qw, or x y theta
// for a 2D problem, for a single body; the numbers of start.joints, or the bodies' poses one after the other, for a
// robot), and the report draws every link along it, with each link's clearance when there are several.
//
//   meshgap_report --cfg problem.cfg --path solution.path --out report.html [--dense 4] [-q]
//
// The path (OMPL's .path format) is interpolated with --dense
// states per OMPL validity-check segment and the exact clearance computed at each state, as meshgap_plan does; the
// report shows the scene with the robot along it (a slider), the closest-point segment, clearance against arc length
// and a summary table (see planners/support/PlanReport.h). Exit status 0; 2 when the path collides with the world
// (or the robot with itself) at some dense state: the report is written, showing where, and one "warning: ..." line
// on stderr says so; 1 with one error line for bad input (nothing is written then).

#include <boost/program_options.hpp>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/robot/RobotProblem.h"
#include "support/MoveItOptions.h"
#include "support/PathFile.h"
#include "support/PlanReport.h"

namespace po = boost::program_options;
using namespace meshgap;

namespace
{
    /** \brief The exit status: 0 for a free path; 2, with a warning on stderr, when \e collisions of the \e states
        dense states collide. */
    int pathVerdict(std::size_t collisions, std::size_t states, double least, const std::string &pathFile)
    {
        if (collisions == 0)
            return 0;
        std::fprintf(stderr,
                     "warning: %s: the path collides at %zu of its %zu dense states (min clearance %g); the report "
                     "shows where\n",
                     pathFile.c_str(), collisions, states, least);
        return 2;
    }

    /** \brief The report of \e pathFile on \e problem (any kind: a single body is a robot of one link): every link
        along the path, the whole robot's clearance and each link's. */
    int report(const RobotProblem &problem, const std::string &pathFile, const std::string &out, unsigned dense)
    {
        const RobotScene scene(problem.robot, problem.obstacles, problem.allowedObstacles);
        const std::vector<std::vector<double>> states = readRobotPathFile(pathFile, *problem.robot);
        const ompl::geometric::PathGeometric path =
            robotPath(reportSpaceInformation(*problem.robot, problem.volume, states), states);
        std::ostringstream length;
        length.precision(6);
        length << path.length();
        PlanReportData data =
            reportFromDense(scene, denseClearance(path, scene, dense),
                           {{"problem", problem.name + " (" + problem.robot->description() + ", " +
                                            std::to_string(scene.links().size()) + " link" +
                                            (scene.links().size() == 1 ? "" : "s") + ", " +
                                            std::to_string(problem.robot->dimension()) + " state numbers)"},
                            {"path", pathFile},
                            {"states", std::to_string(states.size())},
                            {"length", length.str()}});
        data.summary[2].second += " (dense: " + std::to_string(data.clearance.size()) + ")";
        writePlanReport(scene, data, out);
        const double least = *std::min_element(data.clearance.begin(), data.clearance.end());
        std::printf("report written  %s (%zu dense states, %zu link%s, min clearance %g)\n", out.c_str(),
                    data.clearance.size(), scene.links().size(), scene.links().size() == 1 ? "" : "s", least);
        std::size_t collisions = 0;
        for (char c : data.inCollision)
            collisions += c != 0;
        return pathVerdict(collisions, data.clearance.size(), least, pathFile);
    }

    int run(int argc, char **argv)
    {
        std::string cfg, pathFile, out;
        MoveItFiles moveit;
        unsigned dense = 4;
        po::options_description options("meshgap_report --cfg FILE --path FILE --out FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help")("cfg", po::value(&cfg), "OMPL.app problem file (.cfg)")(
            "path", po::value(&pathFile), "the path (.path: one state a line)")(
            "out", po::value(&out), "write the HTML report here")(
            "dense", po::value(&dense), "states per OMPL validity-check segment of the dense path (default 4)")(
            "quiet,q", "print errors only, and the warning of a colliding path (no log, no mesh warnings)");
        cli::addMoveItOptions(options, moveit);
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, options, vm))
            return 0;
        if ((cfg.empty() && moveit.urdf.empty()) || pathFile.empty() || out.empty())
            throw Exception("command line", "--cfg FILE (or --urdf with --scene and --request), --path FILE and "
                                            "--out FILE are required; see --help");
        if (dense < 1)
            throw Exception("--dense", "must be at least 1");

        return report(cli::readToolRobotProblem(cfg, moveit), pathFile, out, dense);
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
