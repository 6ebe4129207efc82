// RobotScene's collision verdict (inCollision(), pairCollides()) and its broad phase: boxGap() is a lower bound of
// two boxes' exact distance (the library's GJK on the boxes as solids); the verdict is the exact distance query's
// (RobotScene::distance(), another code path: each link's Scene, refineExact()) at every state and pair by pair, on
// the test tree among solid boxes (a link inside a box, a box inside a link, a corner through a face) and on
// MotionBenchMaker's UR5 problems (../shared/data/mbm, skipped when absent), whose states no FCL finds colliding
// where meshgap finds them free. Random states of fixed seeds, and the two states on either side of the verdict's
// boundary, bisected to within 1e-7 of each other.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>

#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/Primitives.h"
#include "meshgap/robot/RobotScene.h"
#include "robot/TestTree.h"

#ifdef MESHGAP_HAVE_FCL
#include "FclRobotScene.h"
#endif

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        Eigen::Matrix3d verdictRandomRotation(std::mt19937 &rng)
        {
            std::normal_distribution<double> n(0.0, 1.0);
            return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
        }

        /** \brief A solid box obstacle (its mesh and the box primitive) of \e size, placed by \e pose. */
        BodyConstPtr solidBox(const Eigen::Vector3d &size, const Eigen::Isometry3d &pose)
        {
            Mesh mesh = boxMesh(size);
            for (Eigen::Vector3d &v : mesh.vertices)
                v = pose * v;
            Primitive p;
            p.kind = Primitive::Kind::BOX;
            p.size = size;
            p.pose = pose;
            return Body::build(std::move(mesh), {p});
        }

        Eigen::Isometry3d at(double x, double y, double z, const Eigen::Matrix3d &R = Eigen::Matrix3d::Identity())
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = R;
            X.translation() = Eigen::Vector3d(x, y, z);
            return X;
        }

        /** \brief How the verdict compared with the exact query over a set of states. */
        struct VerdictTally
        {
            std::size_t states{0}, colliding{0}, free{0}, pairs{0}, pairsColliding{0};
        };

        /** \brief inCollision() and every pairCollides() against the exact distance query at \e q (every pair
            answered exactly: its sign is the pair's verdict). States within \e grazing of a contact are not
            called either way. */
        void expectVerdictIsExact(const RobotScene &scene, const std::vector<double> &q, RobotWarmStart &warm,
                                  VerdictTally &tally, double grazing = 1e-9, bool pairByPair = true)
        {
            RobotRequest every;
            every.everyPair = pairByPair;
            every.computeDepth = false;
            RobotResult exact;
            scene.distance(q, every, exact);
            if (!exact.inCollision && exact.distance < grazing)
                return;
            const bool says = scene.inCollision(q.data(), q.size(), warm);
            ++tally.states;
            (exact.inCollision ? tally.colliding : tally.free) += 1;
            EXPECT_EQ(says, exact.inCollision) << "state " << tally.states << ": exact distance " << exact.distance;
            if (!pairByPair)
                return;
            scene.place(q.data(), q.size(), warm);
            for (std::size_t k = 0; k < scene.numPairs(); ++k)
            {
                const RobotPairAnswer &a = exact.pairs[k];
                if (a.status == RobotPairAnswer::Status::NOT_CHECKED || (a.distance > 0.0 && a.distance < grazing))
                    continue;
                const bool hit = a.status == RobotPairAnswer::Status::EXACT && a.distance <= 0.0;
                ++tally.pairs;
                tally.pairsColliding += hit ? 1 : 0;
                EXPECT_EQ(scene.pairCollides(k, warm), hit)
                    << "state " << tally.states << ", pair " << k << ": exact distance " << a.distance;
            }
        }

        /** \brief Two states within \e tolerance (in joint values) of each other on either side of the verdict's
            boundary between a free state and a colliding one, {free, colliding} as inCollision() says (bisection by
            the verdict under test: the exact query then checks both sides where the verdict changes its mind, which
            catches an error on either side of a contact at two exact queries per contact). */
        std::pair<std::vector<double>, std::vector<double>> nearContact(const RobotScene &scene,
                                                                        std::vector<double> free,
                                                                        std::vector<double> hit, double tolerance)
        {
            RobotWarmStart warm;
            for (int step = 0; step < 60; ++step)
            {
                double gap = 0.0;
                std::vector<double> middle(free.size());
                for (std::size_t k = 0; k < free.size(); ++k)
                {
                    middle[k] = 0.5 * (free[k] + hit[k]);
                    gap = std::max(gap, std::abs(free[k] - hit[k]));
                }
                if (gap < tolerance)
                    break;
                (scene.inCollision(middle.data(), middle.size(), warm) ? hit : free) = middle;
            }
            return {free, hit};
        }
    }  // namespace

    TEST(RobotSceneVerdict, BoxGapIsALowerBoundOfTheBoxesDistance)
    {
        // Against GJK on the two boxes as solids (primitiveGap(), exact for polytopes): never above it, 0 or less
        // when they overlap, and tight (to 1e-9) for boxes apart along a face normal of one of them.
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> size(0.01, 0.5), offset(-0.8, 0.8);
        std::size_t apart = 0, overlapping = 0, proven = 0;
        for (int trial = 0; trial < 3000; ++trial)
        {
            WorldBox a{Eigen::Vector3d(offset(rng), offset(rng), offset(rng)), verdictRandomRotation(rng),
                       Eigen::Vector3d(size(rng), size(rng), size(rng))};
            WorldBox b{Eigen::Vector3d(offset(rng), offset(rng), offset(rng)), verdictRandomRotation(rng),
                       Eigen::Vector3d(size(rng), size(rng), size(rng))};
            Primitive pa, pb;
            pa.size = 2.0 * a.half;
            pb.size = 2.0 * b.half;
            Eigen::Isometry3d Xa = at(a.center.x(), a.center.y(), a.center.z(), a.axes);
            Eigen::Isometry3d Xb = at(b.center.x(), b.center.y(), b.center.z(), b.axes);
            const SolidGap exact = primitiveGap(pa, Xa, pb, Xb);
            const double gap = boxGap(a, b);
            EXPECT_LE(gap, exact.upper + 1e-12) << "trial " << trial;
            if (exact.distance == 0.0)
            {
                EXPECT_LE(gap, 0.0) << "trial " << trial;
                ++overlapping;
            }
            else
                ++apart;
            proven += gap > 0.0 ? 1 : 0;
        }
        EXPECT_GT(overlapping, 300u);
        EXPECT_GT(apart, 300u);
        EXPECT_GT(proven, apart / 2);  // the bound proves most separated pairs apart
        // Face to face: tight.
        const WorldBox a{Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.1, 0.2, 0.3)};
        const WorldBox b{Eigen::Vector3d(0.35, 0.05, 0.0), Eigen::Matrix3d::Identity(),
                         Eigen::Vector3d(0.05, 0.05, 0.05)};
        EXPECT_NEAR(boxGap(a, b), 0.2, 1e-8);
    }

    TEST(RobotSceneVerdict, SolidBoxesAnsweredAsTheSolidsTheyAre)
    {
        // The test tree among boxes given as solids (a box primitive with its mesh): a large slab the arm reaches
        // into (links inside it, corners through its faces), small cubes it can swallow (a cube inside a closed
        // link), rotated boxes. Every verdict and every pair's verdict is the exact query's, on random states and
        // on states bisected to within 1e-7 rad of a contact.
        const UrdfRobotPtr robot = test::treeWithPayload();
        std::vector<BodyConstPtr> obstacles = {
            solidBox(Eigen::Vector3d(0.5, 1.2, 0.1), at(0.6, 0.0, 0.05)),
            solidBox(Eigen::Vector3d(0.01, 0.01, 0.01), at(0.3, 0.0, 0.3)),
            solidBox(
                Eigen::Vector3d(0.3, 0.05, 0.4),
                at(-0.35, 0.3, 0.3, Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix())),
            solidBox(Eigen::Vector3d(0.02, 0.3, 0.02), at(0.1, -0.35, 0.45))};
        const RobotScene scene(robot, obstacles);
        std::mt19937 rng(31);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        RobotWarmStart warm;
        VerdictTally tally, near;
        std::vector<std::vector<double>> free, hit;
        for (int trial = 0; trial < test::scaled(400, 120); ++trial)
        {
            const std::vector<double> q = {3 * u(rng), 2.5 * u(rng), 0.05 + 0.05 * u(rng), 3 * u(rng), u(rng)};
            expectVerdictIsExact(scene, q, warm, tally);
            RobotResult r;
            scene.distance(q, RobotRequest(), r);
            (r.inCollision ? hit : free).push_back(q);
        }
        for (std::size_t n = 0; n < std::min(free.size(), hit.size()) && n < 60; ++n)
        {
            const auto [justFree, justHit] = nearContact(scene, free[n], hit[n], 1e-7);
            expectVerdictIsExact(scene, justFree, warm, near, 1e-12);
            expectVerdictIsExact(scene, justHit, warm, near, 1e-12);
        }
        test::Note() << tally.states << " states (" << tally.colliding << " colliding), " << tally.pairs << " pairs ("
                     << tally.pairsColliding << " colliding); " << near.states << " near a contact";
        EXPECT_GT(tally.colliding, 50u);
        EXPECT_GT(tally.free, 50u);
        EXPECT_GT(near.colliding, 15u);  // both sides of the contacts checked
        EXPECT_GT(near.free, 15u);
    }

    TEST(RobotSceneVerdict, Ur5ProblemsVerdictIsExactAndFclFindsNoCollisionWhereItSaysFree)
    {
        const fs::path folder = fs::path(MESHGAP_SHARED_DATA_DIR) / "mbm" / "ur5";
        if (!fs::exists(folder / "problems.tar.bz2") || !fs::exists(folder / "ur5.urdf"))
            GTEST_SKIP() << "MotionBenchMaker's UR5 problems are not in " << folder.string();
        const fs::path dir = fs::temp_directory_path() / ("meshgap_verdict_mbm_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        // One of the four scenes under test::scale() < 1 (each costs its robot's load and its exact queries anew).
        std::vector<std::string> scenarios = {"table_pick_ur5", "box_ur5", "bookshelf_small_ur5", "cage_ur5"};
        scenarios.resize(static_cast<std::size_t>(test::scaled(4)));
        std::string command = "tar -xjf '" + (folder / "problems.tar.bz2").string() + "' -C '" + dir.string() + "'";
        for (const std::string &s : scenarios)
            command += " problems/" + s + "/scene0001.yaml problems/" + s + "/request0001.yaml";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::ostringstream seen;
        for (const std::string &s : scenarios)
        {
            MoveItFiles files;
            files.urdf = (folder / "ur5.urdf").string();
            files.srdf = (folder / "ur5.srdf").string();
            files.scene = (dir / "problems" / s / "scene0001.yaml").string();
            files.request = (dir / "problems" / s / "request0001.yaml").string();
            files.packagePath = {folder.string()};
            const RobotProblem problem = readMoveItProblem(files);
            const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles, problem.allowedObstacles);
#ifdef MESHGAP_HAVE_FCL
            const FclRobotScene fcl(scene, true);
#endif
            std::mt19937 rng(5);
            RobotWarmStart warm;
            VerdictTally tally, near;
            std::vector<std::vector<double>> free, hit;
            const std::size_t n = problem.robot->dimension();
            for (int trial = 0; trial < test::scaled(150, 30); ++trial)
            {
                // Uniform within the limits, and between the start and goal (near the obstacles the problem is about).
                std::vector<double> q(n);
                const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
                for (std::size_t k = 0; k < n; ++k)
                {
                    const double lo = std::max(problem.robot->stateLower(k), -M_PI);
                    const double hi = std::min(problem.robot->stateUpper(k), M_PI);
                    q[k] = trial % 2 == 0 ? std::uniform_real_distribution<double>(lo, hi)(rng)
                                          : (1 - t) * problem.start[k] + t * (*problem.goal)[k] +
                                                std::normal_distribution<double>(0.0, 0.3)(rng);
                    q[k] = std::min(std::max(q[k], lo), hi);
                }
                expectVerdictIsExact(*scene, q, warm, tally, 1e-9, trial % 5 == 0);
                const bool says = scene->inCollision(q.data(), q.size(), warm);
                (says ? hit : free).push_back(q);
#ifdef MESHGAP_HAVE_FCL
                if (!says)
                {
                    EXPECT_FALSE(fcl.inCollision(scene->robot().linkPoses(q))) << s << ", state " << trial;
                }
#endif
            }
            const auto contacts = static_cast<std::size_t>(test::scaled(15, 6));
            for (std::size_t m = 0; m < std::min(free.size(), hit.size()) && m < contacts; ++m)
            {
                const auto [justFree, justHit] = nearContact(*scene, free[m], hit[m], 1e-7);
                expectVerdictIsExact(*scene, justFree, warm, near, 1e-12, false);
                expectVerdictIsExact(*scene, justHit, warm, near, 1e-12, false);
            }
            seen << s << ": " << tally.states << " states (" << tally.colliding << " colliding), " << tally.pairs
                 << " pairs (" << tally.pairsColliding << " colliding); " << near.states << " near a contact ("
                 << near.colliding << " colliding). ";
            EXPECT_GT(tally.colliding, 5u) << s;
            EXPECT_GT(tally.free, 5u) << s;
            EXPECT_GT(near.colliding, 3u) << s;
            EXPECT_GT(near.free, 3u) << s;
        }
        test::Note() << seen.str();
        fs::remove_all(dir);
    }
}  // namespace meshgap
