// A path file checked against its problem, as bench/optimize_defaults.sh reads it: is every motion certified (the
// ClearanceMotionValidator accepts it), is the densely interpolated path free by FCL (the peer, when built with it)
// and by meshgap's exact test, and its least clearance by both.
//
//   build/bench/meshgap_bench_path_check [--cfg maps/twisted/twisted.cfg] [--path FILE] [--steps 20]
//
// Without --path, the path is the cfg's start and goal (one straight motion).
//
// One line on stdout: "states N motions M certified K fcl_free yes|no|n/a fcl_min D exact_free yes|no exact_min D"
// (D over the states at 1/steps of every motion). The path is OMPL's .path format: x y z qx qy qz qw, or x y theta
// for a planar problem.

#include <ompl/util/Console.h>

#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "CliMain.h"
#include "FclOracle.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace ob = ompl::base;

namespace
{
    /** \brief The path file's states (7 numbers a line for SE(3), 3 for SE(2)) in \e space's states. */
    std::vector<ob::State *> readStates(const std::string &file, const ob::SpaceInformation &si, bool planar)
    {
        std::ifstream in(file);
        if (!in)
            throw Exception(file, "cannot open");
        std::vector<ob::State *> states;
        std::string line;
        for (int number = 1; std::getline(in, line); ++number)
        {
            std::istringstream words(line);
            std::vector<double> v;
            for (double x; words >> x;)
                v.push_back(x);
            if (v.empty() || line[0] == '#')
                continue;
            if (v.size() != (planar ? 3u : 7u))
                throw Exception(file + ":" + std::to_string(number), planar ? "expected x y theta" :
                                                                              "expected x y z qx qy qz qw");
            ob::State *s = si.allocState();
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            if (planar)
            {
                X.linear() = Eigen::AngleAxisd(v[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
                X.translation() = Eigen::Vector3d(v[0], v[1], 0.0);
            }
            else
            {
                X.linear() = Eigen::Quaterniond(v[6], v[3], v[4], v[5]).normalized().toRotationMatrix();
                X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
            }
            stateFromPose(*si.getStateSpace(), X, s);
            states.push_back(s);
        }
        if (states.size() < 2)
            throw Exception(file, "fewer than two states");
        return states;
    }

    int run(int argc, char **argv)
    {
        std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/twisted/twisted.cfg", path;
        int steps = 20;
        namespace po = boost::program_options;
        po::options_description cli("meshgap_bench_path_check");
        cli.add_options()("help,h", "print this help")("cfg", po::value(&cfg), "OMPL.app problem (.cfg)")(
            "path", po::value(&path), "the path (.path: x y z qx qy qz qw, or x y theta; default: the cfg's start and goal)")(
            "steps", po::value(&steps), "states checked per motion (default 20)");
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, cli, vm))
            return 0;
        if (steps < 1)
            throw Exception("--steps", "must be at least 1");
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        const ProblemConfig config = readProblemConfig(cfg);
        OmplProblem problem = setupProblem(config, ClearanceChecker::Mode::CERTIFIED);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        si->setup();
        std::vector<ob::State *> states;
        if (!path.empty())
            states = readStates(path, *si, config.planar);
        else
            for (const Eigen::Isometry3d &X : {config.start, *config.goal})
            {
                states.push_back(si->allocState());
                stateFromPose(*si->getStateSpace(), X, states.back());
            }
        ClearanceMotionValidator validator(si, problem.checker);
#ifdef MESHGAP_HAVE_FCL
        const auto fw = test::fclModel(loadMesh(config.world)),
                   fr = test::fclModel(loadRobotMesh(config.robot, config.planar));
#endif
        int certified = 0, fclHits = 0, exactHits = 0;
        double fclMin = std::numeric_limits<double>::infinity(), exactMin = fclMin;
        ob::State *s = si->allocState();
        for (std::size_t i = 0; i + 1 < states.size(); ++i)
        {
            certified += validator.checkMotion(states[i], states[i + 1]);
            for (int k = 0; k <= steps; ++k)
            {
                si->getStateSpace()->interpolate(states[i], states[i + 1], static_cast<double>(k) / steps, s);
                const double c = problem.checker->clearance(s);
                exactMin = std::min(exactMin, c);
                exactHits += !problem.checker->isValid(s);
#ifdef MESHGAP_HAVE_FCL
                const Eigen::Isometry3d X = poseFromState(*si->getStateSpace(), s);
                fclHits += test::fclCollide(fw, fr, X);
                fclMin = std::min(fclMin, test::fclDistance(fw, fr, X));
#endif
            }
        }
        si->freeState(s);
        for (ob::State *state : states)
            si->freeState(state);
#ifdef MESHGAP_HAVE_FCL
        const std::string fclFree = fclHits == 0 ? "yes" : "no";
#else
        const std::string fclFree = "n/a";
#endif
        std::printf("states %zu motions %zu certified %d fcl_free %s fcl_min %.6g exact_free %s exact_min %.6g\n",
                    states.size(), states.size() - 1, certified, fclFree.c_str(), fclMin,
                    exactHits == 0 ? "yes" : "no", exactMin);
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
