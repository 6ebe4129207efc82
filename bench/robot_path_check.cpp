// A robot problem's path checked by FCL 0.7, pair by pair: every link against every obstacle and every self pair the
// robot checks, the same meshes at the same link poses, at states interpolated densely along each motion (OMPL's
// interpolation in the problem's state space, at most --step of the space's extent apart). Prints the states
// checked, those FCL finds colliding, and FCL's least distance, then how many of the path's motions the certified
// RobotMotionValidator proves free; exit status 0 when no state collides, 3 otherwise.
//
//   build/bench/meshgap_bench_robot_path_check --cfg maps/swap_se3/swap_se3.cfg --path solution.path [--step 1e-4]

#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <ompl/util/Console.h>
#include <sstream>

#include "CliMain.h"
#include "FclOracle.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "support/PathFile.h"

using namespace meshgap;
namespace po = boost::program_options;
namespace ob = ompl::base;

int main(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "error: built without FCL, the oracle\n");
    return 1;
#else
    return cli::runMain(argc, argv, [](int ac, char **av) {
        std::string cfg, pathFile;
        double step = 1e-4;
        po::options_description options("meshgap_bench_robot_path_check --cfg F --path P [--step S]");
        options.add_options()("help,h", "print this help")("cfg", po::value(&cfg)->required(), "robot problem")(
            "path", po::value(&pathFile)->required(), "path file (one state a line)")(
            "step", po::value(&step), "largest step between checked states, a fraction of the space's extent");
        po::variables_map vm;
        if (!cli::parseCommandLine(ac, av, options, vm))
            return 0;
        ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
        const RobotProblem p = readRobotProblem(cfg);
        const auto scenePtr = std::make_shared<RobotScene>(p.robot, p.obstacles, p.allowedObstacles);
        const RobotScene &scene = *scenePtr;
        ob::RealVectorBounds bounds(3);
        bounds.setLow(-1e3);
        bounds.setHigh(1e3);
        const ob::StateSpacePtr space = robotStateSpace(*p.robot, bounds);
        std::vector<std::shared_ptr<test::FclModel>> links, obstacles;
        for (const RobotLink &link : scene.links())
            links.push_back(test::fclModel(link.body->surface()));
        for (const BodyConstPtr &o : scene.obstacles())
            obstacles.push_back(test::fclModel(o->surface()));
        const auto states = readRobotPathFile(pathFile, *p.robot);
        const double extent = p.volume ? (p.volume->max() - p.volume->min()).norm() : space->getMaximumExtent();
        ob::State *a = space->allocState(), *b = space->allocState(), *s = space->allocState();
        std::vector<double> q;
        std::vector<Eigen::Isometry3d> frames, poses;
        std::size_t checked = 0, colliding = 0;
        double least = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i + 1 < states.size(); ++i)
        {
            robotStateFromVector(*space, states[i], a);
            robotStateFromVector(*space, states[i + 1], b);
            const auto n = static_cast<std::size_t>(std::ceil(space->distance(a, b) / (step * extent))) + 1;
            for (std::size_t k = (i == 0 ? 0 : 1); k <= n; ++k)
            {
                space->interpolate(a, b, static_cast<double>(k) / n, s);
                robotStateToVector(*space, s, q);
                p.robot->linkPoses(q.data(), q.size(), frames, poses);
                bool hit = false;
                for (std::size_t l = 0; l < links.size(); ++l)
                    for (std::size_t o : scene.linkObstacles(l))
                        hit = hit || test::fclCollide(obstacles[o], links[l], poses[l]);
                for (const auto &[x, y] : scene.selfPairs())
                    hit = hit || test::fclCollide(links[x], links[y], poses[x].inverse() * poses[y]);
                colliding += hit;
                ++checked;
                if (k == n || k == 0)  // FCL's distance at the path's own states
                    for (std::size_t l = 0; l < links.size(); ++l)
                        for (const auto &o : obstacles)
                            least = std::min(least, test::fclDistance(o, links[l], poses[l]));
            }
        }
        space->freeState(a);
        space->freeState(b);
        space->freeState(s);
        // The path's motions, each asked of the certified validator anew.
        auto si = std::make_shared<ob::SpaceInformation>(space);
        si->setStateValidityChecker(std::make_shared<RobotChecker>(si, scenePtr));
        si->setup();
        const RobotMotionValidator validator(si, scenePtr, *p.robot);
        ob::State *m1 = si->allocState(), *m2 = si->allocState();
        std::size_t certified = 0;
        for (std::size_t i = 0; i + 1 < states.size(); ++i)
        {
            robotStateFromVector(*space, states[i], m1);
            robotStateFromVector(*space, states[i + 1], m2);
            certified += validator.checkMotion(m1, m2);
        }
        si->freeState(m1);
        si->freeState(m2);
        std::printf("%s: %zu states checked (step %g of %g), %zu colliding by FCL, FCL's least link-obstacle "
                    "distance at the path's states %.6g, %zu of %zu motions certified\n",
                    pathFile.c_str(), checked, step, extent, colliding, least, certified,
                    states.empty() ? std::size_t(0) : states.size() - 1);
        return colliding == 0 ? 0 : 3;
    });
#endif
}
