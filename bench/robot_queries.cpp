// Whole-robot checks along joint-space paths against FCL 0.7 on the same pairs (every link against every obstacle,
// every self pair the SRDF leaves), the same meshes at the same link poses: the minimum signed distance (meshgap:
// RobotScene::distance(), pruned, warm from state to state, and cold; FCL two ways: every pair's distance, the least
// kept, and as MoveIt uses it, FclRobotScene's broad-phase managers) and the collision verdict (meshgap:
// RobotScene::inCollision(), warm; FCL: collide pair by pair, stopping at the first hit, and FclRobotScene). The robot is a URDF (the fanuc arm of ../shared/data/robots by default) carrying a C-shaped payload,
// among a C-shaped fixture, a pillar and a plate scaled to its reach; paths join random states within the joint
// limits in steps of --step radians (the largest joint change). CPU time per state, best of --repeat passes.
//
//   build/bench/meshgap_bench_robot_queries [--urdf F --srdf F --package-path DIR] [--paths 20] [--step 0.01]
//                                           [--repeat 3] [--seed 1] [--attach LINK (tool0)]

#include <algorithm>
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <ompl/util/Console.h>
#include <random>

#include "CliMain.h"
#include "FclOracle.h"
#include "FclRobotScene.h"
#include "TestMeshes.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "support/Shapes.h"

using namespace meshgap;
namespace po = boost::program_options;

namespace
{
    /** \brief A C-shaped plate \e size across, opening towards +x, size / 4 thick, centred. */
    Mesh cShape(double size)
    {
        const double w = size, t = size / 4;
        const Polygon2d outer = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, w - t}, {w, w - t}, {w, w}, {0, w}};
        Mesh m = makeExtrusion(outer, {}, t, size / 3);
        transformMesh(m, test::translation(-w / 2, -w / 2, -t / 2));
        return m;
    }

    /** \brief A C fixture, a pillar and a plate scaled to the reach \e r. */
    std::vector<BodyConstPtr> world(double r)
    {
        Mesh fixture = cShape(0.5 * r);
        Eigen::Isometry3d X = test::translation(0.55 * r, 0.0, 0.3 * r);
        X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
        transformMesh(fixture, X);
        Mesh pillar = makeBox(Eigen::Vector3d(0.15 * r, 0.15 * r, 0.8 * r), 0.2 * r);
        transformMesh(pillar, test::translation(-0.4 * r, 0.5 * r, 0.4 * r));
        Mesh plate = makeBox(Eigen::Vector3d(0.4 * r, 0.6 * r, 0.03 * r), 0.2 * r);
        transformMesh(plate, test::translation(0.5 * r, -0.4 * r, 0.2 * r));
        return {Body::build(fixture), Body::build(pillar), Body::build(plate)};
    }

    /** \brief States along \e paths straight joint-space segments between random states, \e step apart. */
    std::vector<std::vector<double>> pathStates(const UrdfRobot &robot, unsigned paths, double step, unsigned seed)
    {
        std::mt19937 rng(seed);
        auto random = [&]
        {
            std::vector<double> q;
            for (std::size_t i = 0; i < robot.dimension(); ++i)
            {
                const double lo = robot.stateLower(i), hi = robot.stateUpper(i);
                q.push_back(std::uniform_real_distribution<double>(std::isfinite(lo) ? lo : -M_PI,
                                                                   std::isfinite(hi) ? hi : M_PI)(rng));
            }
            return q;
        };
        std::vector<std::vector<double>> states;
        for (unsigned p = 0; p < paths; ++p)
        {
            const std::vector<double> a = random(), b = random();
            double longest = 0.0;
            for (std::size_t k = 0; k < a.size(); ++k)
                longest = std::max(longest, std::abs(b[k] - a[k]));
            const auto n = static_cast<std::size_t>(std::ceil(longest / step));
            for (std::size_t i = 0; i <= n; ++i)
            {
                std::vector<double> q(a.size());
                for (std::size_t k = 0; k < a.size(); ++k)
                    q[k] = a[k] + (b[k] - a[k]) * double(i) / double(std::max<std::size_t>(n, 1));
                states.push_back(q);
            }
        }
        return states;
    }

    /** \brief CPU microseconds per state of \e pass over \e count states, best of \e repeat. */
    double microseconds(unsigned repeat, std::size_t count, const std::function<void()> &pass)
    {
        double best = std::numeric_limits<double>::infinity();
        for (unsigned r = 0; r < repeat; ++r)
        {
            const std::clock_t start = std::clock();
            pass();
            best = std::min(best, double(std::clock() - start) / CLOCKS_PER_SEC / double(count) * 1e6);
        }
        return best;
    }
}  // namespace

static int run(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "error: built without FCL, the peer\n");
    return 1;
#else
    const std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/robots";
    std::string urdf = data + "/moveit_resources_fanuc_description/urdf/fanuc.urdf";
    std::string srdf = data + "/moveit_resources_fanuc_moveit_config/config/fanuc.srdf", packagePath = data;
    std::string attachTo = "tool0";
    unsigned paths = 20, repeat = 3, seed = 1;
    double step = 0.01;
    po::options_description options("meshgap_bench_robot_queries [options]");
    options.add_options()("help,h", "print this help")(
        "urdf", po::value(&urdf), ("the robot (default: " + urdf + ")").c_str())(
        "srdf", po::value(&srdf), "its allowed pairs (default: the fanuc's SRDF; empty: none)")(
        "package-path", po::value(&packagePath), ("package:// search folder (default: " + data + ")").c_str())(
        "paths", po::value(&paths), "joint-space paths between random states (default 20)")(
        "step", po::value(&step), "largest joint change between states, radians (default 0.01)")(
        "repeat", po::value(&repeat), "passes; the best is kept (default 3)")(
        "seed", po::value(&seed), "seed of the random states (default 1)")(
        "attach", po::value(&attachTo), "link carrying the C-shaped payload (default tool0)");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, options, vm))
        return 0;
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);

    UrdfOptions urdfOptions;
    urdfOptions.packagePath = {packagePath};
    const UrdfRobotPtr robot = UrdfRobot::load(urdf, urdfOptions);
    if (!srdf.empty())
        readSrdf(*robot, srdf);
    double r = 0.0;
    const std::vector<Eigen::Isometry3d> zero = robot->linkPoses(std::vector<double>(robot->dimension(), 0.0));
    for (std::size_t i = 0; i < zero.size(); ++i)
        for (const Eigen::Vector3d &v : robot->links()[i].body->surface().vertices)
            r = std::max(r, (zero[i] * v).norm());
    robot->attach("payload", cShape(0.15 * r), attachTo, test::translation(0.0, 0.0, 0.1 * r));
    const auto shared = std::make_shared<const RobotScene>(robot, world(r));
    const RobotScene &scene = *shared;
    const FclRobotScene broad(shared, false);  // the same meshes: the fanuc's links and the payload are meshes
    const std::vector<std::vector<double>> states = pathStates(*robot, paths, step, seed);

    std::vector<std::shared_ptr<test::FclModel>> links, obstacles;
    for (const RobotLink &link : scene.links())
        links.push_back(test::fclModel(link.body->surface()));
    for (const BodyConstPtr &o : scene.obstacles())
        obstacles.push_back(test::fclModel(o->surface()));
    std::vector<Eigen::Isometry3d> frames, poses;

    // The answers, checked against each other first.
    std::size_t colliding = 0, disagreements = 0, broadDisagreements = 0;
    std::vector<double> fclDistances;
    auto fclState = [&](const std::vector<double> &q, bool collisionOnly, double &least)
    {
        robot->linkPoses(q.data(), q.size(), frames, poses);
        least = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < links.size(); ++i)
            for (const auto &o : obstacles)
            {
                if (collisionOnly && test::fclCollide(o, links[i], poses[i]))
                    return true;
                if (!collisionOnly)
                    least = std::min(least, test::fclDistance(o, links[i], poses[i]));
            }
        for (const auto &[a, b] : scene.selfPairs())
        {
            const Eigen::Isometry3d X_AB = poses[a].inverse() * poses[b];
            if (collisionOnly && test::fclCollide(links[a], links[b], X_AB))
                return true;
            if (!collisionOnly)
                least = std::min(least, test::fclDistance(links[a], links[b], X_AB));
        }
        return false;
    };
    {
        RobotWarmStart warm;
        RobotResult result;
        for (const std::vector<double> &q : states)
        {
            double ignored;
            const bool hit = fclState(q, true, ignored);
            colliding += hit ? 1 : 0;
            scene.distance(q.data(), q.size(), RobotRequest(), warm, result);
            disagreements += (result.distance < 0.0) != hit ? 1 : 0;  // containment (FCL cannot see it) counts here
            // The broad phase answers as the pairs do (the least distance to rounding: FCL gets world poses there,
            // each pair's relative pose here).
            double least;
            fclState(q, false, least);
            least = std::max(0.0, least);
            broadDisagreements += broad.inCollision(poses) != hit ||
                                  std::abs(broad.distance(poses) - least) > 1e-9 * std::max(1.0, least);
        }
    }

    double sink = 0.0;
    const double fclDistance = microseconds(repeat, states.size(), [&] {
        for (const auto &q : states)
        {
            double least;
            fclState(q, false, least);
            sink += least;
        }
    });
    const double fclCollide = microseconds(repeat, states.size(), [&] {
        for (const auto &q : states)
        {
            double ignored;
            sink += fclState(q, true, ignored) ? 1 : 0;
        }
    });
    auto broadPass = [&](bool collisionOnly)
    {
        return microseconds(repeat, states.size(), [&] {
            for (const auto &q : states)
            {
                robot->linkPoses(q.data(), q.size(), frames, poses);
                sink += collisionOnly ? (broad.inCollision(poses) ? 1.0 : 0.0) : broad.distance(poses);
            }
        });
    };
    const double broadDistance = broadPass(false), broadCollide = broadPass(true);
    auto meshgapDistance = [&](bool warmStart)
    {
        return microseconds(repeat, states.size(), [&] {
            RobotWarmStart warm;
            RobotResult result;
            for (const auto &q : states)
            {
                if (!warmStart)
                    warm.reset();
                scene.distance(q.data(), q.size(), RobotRequest(), warm, result);
                sink += result.distance;
            }
        });
    };
    const double warmDistance = meshgapDistance(true), coldDistance = meshgapDistance(false);
    const double warmCollide = microseconds(repeat, states.size(), [&] {
        RobotWarmStart warm;
        for (const auto &q : states)
            sink += scene.inCollision(q.data(), q.size(), warm) ? 1 : 0;
    });

    std::size_t triangles = 0;
    for (const RobotLink &link : scene.links())
        triangles += link.body->surface().triangles.size();
    std::printf("robot %s: %zu links (%zu triangles), %zu self pairs, %zu obstacles; %zu states on %u paths "
                "(step %.3g), %zu colliding (FCL), %zu verdicts differing, %zu broad-phase answers differing\n",
                robot->name().c_str(), scene.links().size(), triangles, scene.selfPairs().size(),
                scene.obstacles().size(), states.size(), paths, step, colliding, disagreements, broadDisagreements);
    std::printf("| | FCL distance, every pair | FCL distance, broad phase | meshgap cold | meshgap warm | "
                "FCL collide, every pair | FCL collide, broad phase | meshgap collision, warm |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    std::printf("| us/state | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n", fclDistance, broadDistance,
                coldDistance, warmDistance, fclCollide, broadCollide, warmCollide);
    std::printf("| ratio to FCL's broad phase | %.3f | 1 | %.3f | %.3f | %.3f | 1 | %.3f |\n",
                fclDistance / broadDistance, coldDistance / broadDistance, warmDistance / broadDistance,
                fclCollide / broadCollide, warmCollide / broadCollide);
    std::printf("(checksum %.6g)\n", sink);
    return 0;
#endif
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
