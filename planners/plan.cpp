// meshgap_plan: plan a path for an OMPL.app-format problem with meshgap's clearance checker.
//
//   meshgap_plan --cfg problem.cfg [--planner rrtconnect] [--time 10] [--objective length|max_min_clearance]
//                [--mode certified|fast] [--seed N] [--out solution.path]
//
// Prints the outcome (solved exactly or approximately, path length, minimum clearance along the path's states,
// checker counters) and writes the path in OMPL's .path format (one state per line: x y z qx qy qz qw), which
// meshgap_distance --poses and OMPL.app read.

#include <boost/program_options.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"

namespace po = boost::program_options;
using namespace meshgap;

namespace
{
    int run(int argc, char **argv)
    {
        std::string cfg, planner = "rrtconnect", objective, mode = "certified", motion = "discrete", out;
        double time = 10.0;
        std::uint32_t seed = 1;
        po::options_description options("meshgap_plan --cfg FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help")("cfg", po::value(&cfg), "OMPL.app problem file (.cfg)")(
            "planner", po::value(&planner), "planner name (an unknown name lists the valid ones)")(
            "time", po::value(&time), "time limit in seconds")(
            "objective", po::value(&objective), "length or max_min_clearance (default: the cfg's, else length)")(
            "mode", po::value(&mode), "clearance: certified (exact) or fast (the paper's node distance)")(
            "motion", po::value(&motion),
            "motion validator: discrete (OMPL's, sampled) or clearance (conservative advancement, certified)")(
            "seed", po::value(&seed), "OMPL's random seed")("out", po::value(&out), "write the path here (.path)")(
            "quiet,q", "print warnings and errors only");
        po::variables_map vm;
        po::store(po::parse_command_line(argc, argv, options), vm);
        po::notify(vm);
        if (vm.count("help"))
        {
            std::cout << options << "\n";
            return 0;
        }
        if (vm.count("quiet"))
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        if (cfg.empty())
            throw Exception("command line", "--cfg FILE is required; see --help");
        if (mode != "certified" && mode != "fast")
            throw Exception("--mode", "'" + mode + "' is not certified or fast");
        if (motion != "discrete" && motion != "clearance")
            throw Exception("--motion", "'" + motion + "' is not discrete or clearance");
        if (motion == "clearance" && mode != "certified")
            throw Exception("--motion", "clearance needs --mode certified (it steps by exact clearance)");
        if (!(time > 0.0))
            throw Exception("--time", "must be positive");
        ompl::RNG::setSeed(seed);

        const ProblemConfig config = readProblemConfig(cfg);
        OmplProblem problem = setupProblem(config, mode == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                                         ClearanceChecker::Mode::FAST,
                                           objective);
        if (motion == "clearance")
            problem.setup->getSpaceInformation()->setMotionValidator(
                std::make_shared<ClearanceMotionValidator>(problem.setup->getSpaceInformation(), problem.checker));
        problem.setup->setPlanner(allocPlanner(planner, problem.setup->getSpaceInformation()));
        problem.setup->setup();
        OMPL_INFORM("%s: %zu obstacles, planner %s, objective %s, clearance %s", config.name.c_str(),
                    problem.scene->obstacles().size(), planner.c_str(), problem.objective.c_str(), mode.c_str());
        const ompl::base::PlannerStatus status = problem.setup->solve(time);
        const CheckerStats stats = problem.checker->stats();
        std::printf("problem        %s\nplanner        %s\nstatus         %s\n", config.name.c_str(), planner.c_str(),
                    status.asString().c_str());
        if (!problem.setup->haveSolutionPath())
        {
            std::printf("no path found within %g s\nvalidity calls %llu\nquery time     %.1f ms\n", time,
                        static_cast<unsigned long long>(stats.validityCalls), stats.seconds * 1e3);
            return 2;
        }
        ompl::geometric::PathGeometric &path = problem.setup->getSolutionPath();
        double minClearance = std::numeric_limits<double>::infinity();
        bool allValid = true;
        for (const ompl::base::State *s : path.getStates())
        {
            const SceneResult r = problem.checker->query(s);
            allValid = allValid && !r.inCollision;
            minClearance = std::min(minClearance, r.inCollision ? 0.0 : r.distance);
        }
        std::printf("exact solution %s\nstates         %zu\nlength         %.6g\nmin clearance  %.6g (%s, at the "
                    "path's states)\nstates valid   %s\nvalidity calls %llu\nclearance calls %llu\nquery time     "
                    "%.1f ms\n",
                    status == ompl::base::PlannerStatus::EXACT_SOLUTION ? "yes" : "no (approximate)",
                    path.getStateCount(), path.length(), minClearance,
                    mode == "certified" ? "exact" : "node distance", allValid ? "all" : "NO",
                    static_cast<unsigned long long>(stats.validityCalls),
                    static_cast<unsigned long long>(stats.clearanceCalls), stats.seconds * 1e3);
        if (!out.empty())
        {
            std::ofstream file(out);
            if (!file)
                throw Exception(out, "cannot open for writing");
            file.precision(17);  // full precision: the states must round-trip exactly
            path.printAsMatrix(file);
            if (!file)
                throw Exception(out, "write failed");
            std::printf("path written   %s\n", out.c_str());
        }
        return status == ompl::base::PlannerStatus::EXACT_SOLUTION ? 0 : 2;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
