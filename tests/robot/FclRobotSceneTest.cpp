// FclRobotScene, the FCL peer as MoveIt uses FCL (broad-phase managers, primitives as FCL's shapes): on the same
// triangles its verdict and least distance are FCL's pair by pair over the pairs the scene checks (allowed pairs
// left out); with the true primitive solids it brackets meshgap's exact answer on the same solids; threads
// get the same answers. On maps/arm_fixture and a MotionBenchMaker UR5 problem (../shared/data/mbm, skipped when
// absent), random states of fixed seeds. A single body (a robot of one link, rigidBodyProblem()) answers as OMPL.app's
// FCL checker does: its mesh against the whole world as one BVHModel.
#include <gtest/gtest.h>

#ifdef MESHGAP_HAVE_FCL
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <thread>
#include <unistd.h>

#include "FclRobotScene.h"
#include "FclOracle.h"
#include "TestScale.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/scene/RobotMesh.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        /** \brief Uniform states within the joint limits (continuous joints in [-pi, pi]). */
        std::vector<std::vector<double>> randomStates(const UrdfRobot &robot, std::size_t count, std::uint32_t seed)
        {
            std::mt19937 rng(seed);
            std::vector<std::vector<double>> states;
            for (std::size_t n = 0; n < count; ++n)
            {
                std::vector<double> q;
                for (std::size_t k = 0; k < robot.dimension(); ++k)
                {
                    const double lo = std::isfinite(robot.stateLower(k)) ? robot.stateLower(k) : -M_PI;
                    const double hi = std::isfinite(robot.stateUpper(k)) ? robot.stateUpper(k) : M_PI;
                    q.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
                }
                states.push_back(q);
            }
            return states;
        }

        /** \brief FCL pair by pair over the pairs \e scene checks, on the bodies' surfaces: the verdict and the
            least distance (at least 0). */
        struct PairByPair
        {
            explicit PairByPair(const RobotScene &scene) : scene_(scene)
            {
                for (const RobotLink &link : scene.links())
                    links_.push_back(test::fclModel(link.body->surface()));
                for (const BodyConstPtr &o : scene.obstacles())
                    obstacles_.push_back(test::fclModel(o->surface()));
            }

            /** \brief Every pair's collide; when none collides, every pair's distance (in collision 0). */
            void answer(const std::vector<Eigen::Isometry3d> &X, bool &hit, double &least) const
            {
                hit = false;
                least = std::numeric_limits<double>::infinity();
                for (bool distance : {false, true})
                {
                    auto pair = [&](const std::shared_ptr<test::FclModel> &a, const Eigen::Isometry3d &Xa,
                                    const std::shared_ptr<test::FclModel> &b, const Eigen::Isometry3d &Xb)
                    {
                        if (distance)
                            least = std::min(least, std::max(0.0, test::fclDistance(a, b, Xa.inverse() * Xb)));
                        else
                            hit = hit || test::fclCollide(a, b, Xa.inverse() * Xb);
                    };
                    for (std::size_t i = 0; i < links_.size(); ++i)
                        for (std::size_t o : scene_.linkObstacles(i))
                            pair(obstacles_[o], Eigen::Isometry3d::Identity(), links_[i], X[i]);
                    for (const LinkPair &p : scene_.selfPairs())
                        pair(links_[p.first], X[p.first], links_[p.second], X[p.second]);
                    if (hit)
                    {
                        least = 0.0;
                        return;
                    }
                }
            }

        private:
            const RobotScene &scene_;
            std::vector<std::shared_ptr<test::FclModel>> links_, obstacles_;
        };

        struct FclSceneTally
        {
            std::size_t states{0}, colliding{0}, free{0};
        };

        /** \brief FclRobotScene on the surfaces answers as FCL pair by pair: the same verdict, the same least
            distance. */
        void expectPairByPair(const RobotScenePtr &scene, const std::vector<std::vector<double>> &states,
                              FclSceneTally &tally)
        {
            const FclRobotScene fcl(scene, false);
            EXPECT_EQ(fcl.numLinkObjects(), scene->links().size());
            const PairByPair oracle(*scene);
            for (const std::vector<double> &q : states)
            {
                const std::vector<Eigen::Isometry3d> X = scene->robot().linkPoses(q);
                bool hit = false;
                double least = 0.0;
                oracle.answer(X, hit, least);
                ++tally.states;
                (hit ? tally.colliding : tally.free) += 1;
                ASSERT_EQ(fcl.inCollision(X), hit) << "state " << tally.states;
                const double d = fcl.distance(X);
                EXPECT_NEAR(d, least, 1e-12 * std::max(1.0, least)) << "state " << tally.states;
                EXPECT_EQ(hit, d == 0.0) << "state " << tally.states << ": distance " << d;
                // Asked below a bound: the least distance when nearer, else the bound.
                for (const double factor : {0.5, 0.999, 1.001, 2.0})
                {
                    const double below = factor * least;
                    EXPECT_NEAR(fcl.distance(X, below), std::min(least, below), 1e-12 * std::max(1.0, least))
                        << "state " << tally.states << ", below " << below;
                }
            }
        }

        /** \brief How far a circumscribed mesh of \e body's primitives reaches beyond them at most (sphereMesh()'s
            bound, the largest of cylinderMesh()'s, coneMesh()'s and its own, at \e segments). */
        double excessOf(const Body &body, unsigned segments)
        {
            double excess = 0.0;
            const double factor = 1.0 / std::pow(std::cos(M_PI / segments), 2) - 1.0;
            for (const Primitive &p : body.primitives())
                if (p.kind != Primitive::Kind::BOX)
                    excess = std::max(excess, factor * p.size.x());
            return excess;
        }

        /** \brief FclRobotScene on the true solids against meshgap's exact answer, on the true solids too
            (refineExact(), 5): the verdicts agree wherever meshgap's distance is clear of FCL's GJK tolerance, FCL's
            distance is at least meshgap's (less that tolerance) and above it by at most the meshes' excess (both
            bodies of a pair, FCL's GJK stopping short). And the solids are seen, not their circumscribed meshes:
            FclRobotScene on the meshes (no primitives) is never farther than meshgap; returns how many states it
            puts strictly nearer. */
        std::size_t expectBracketsMeshgap(const RobotScenePtr &scene, const std::vector<std::vector<double>> &states,
                                          unsigned segments)
        {
            const FclRobotScene fcl(scene, true), meshes(scene, false);
            double excess = 0.0;
            for (const RobotLink &link : scene->links())
                excess = std::max(excess, excessOf(*link.body, segments));
            for (const BodyConstPtr &o : scene->obstacles())
                excess = std::max(excess, excessOf(*o, segments));
            const double gjk = 1e-6;  // FCL's GJK on primitives answers to its tolerance
            std::size_t nearer = 0;
            RobotWarmStart warm;
            RobotResult result;
            for (std::size_t n = 0; n < states.size(); ++n)
            {
                const std::vector<double> &q = states[n];
                const std::vector<Eigen::Isometry3d> X = scene->robot().linkPoses(q);
                scene->distance(q.data(), q.size(), RobotRequest(), warm, result);
                const bool hit = fcl.inCollision(X);
                const double d = fcl.distance(X), ours = std::max(0.0, result.distance);
                EXPECT_NEAR(fcl.distance(X, 0.5 * d), 0.5 * d, 1e-12) << "state " << n;
                EXPECT_NEAR(fcl.distance(X, 2.0 * d), d, 1e-12) << "state " << n;
                if (result.distance > gjk)
                {
                    EXPECT_FALSE(hit) << "state " << n << ": meshgap " << result.distance;
                }
                if (hit)
                {
                    EXPECT_LE(result.distance, gjk) << "state " << n;
                }
                EXPECT_GE(d, ours - gjk) << "state " << n;
                EXPECT_LE(d, ours + 2.0 * excess + gjk) << "state " << n;
                const double onMeshes = std::max(0.0, meshes.distance(X));
                EXPECT_LE(onMeshes, ours + 1e-9) << "state " << n;
                nearer += onMeshes < ours - 1e-9 ? 1 : 0;
            }
            return nearer;
        }

        RobotProblem armFixture()
        {
            return readRobotProblem(std::string(MESHGAP_SOURCE_DIR) + "/maps/arm_fixture/arm_fixture.cfg");
        }

        std::vector<std::vector<double>> armStates(const RobotProblem &problem, std::size_t count, std::uint32_t seed)
        {
            std::vector<std::vector<double>> states =
                randomStates(static_cast<const UrdfRobot &>(*problem.robot), count, seed);
            states.push_back(problem.start);
            states.push_back(*problem.goal);
            return states;
        }
    }  // namespace

    TEST(FclRobotScene, ArmFixtureMatchesFclPairByPairAllowedPairsLeftOut)
    {
        const RobotProblem problem = armFixture();
        const std::vector<std::vector<double>> states = armStates(problem, 400, 11);
        FclSceneTally tally;
        expectPairByPair(std::make_shared<RobotScene>(problem.robot, problem.obstacles), states, tally);
        // A collision matrix that allows every link against the first obstacle: those pairs are never asked.
        std::vector<LinkPair> allowed;
        for (std::size_t i = 0; i < problem.robot->links().size(); ++i)
            allowed.emplace_back(i, 0);
        expectPairByPair(std::make_shared<RobotScene>(problem.robot, problem.obstacles, allowed), states, tally);
        EXPECT_GT(tally.colliding, 50u);
        EXPECT_GT(tally.free, 50u);
    }

    TEST(FclRobotScene, ArmFixtureTrueSolidsBracketMeshgapsAnswer)
    {
        const RobotProblem problem = armFixture();
        const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles);
        // The arm's links are URDF cylinders and boxes (one link two cylinders); the payload and the world meshes.
        std::size_t solids = 0;
        for (const RobotLink &link : scene->links())
            solids += link.body->primitives().size();
        EXPECT_GE(solids, 5u);
        EXPECT_TRUE(scene->obstacles()[0]->primitives().empty());
        const FclRobotScene fcl(scene);
        EXPECT_EQ(fcl.numLinkObjects(), solids + 1);  // the payload is one mesh
        const std::size_t nearer = expectBracketsMeshgap(scene, armStates(problem, 400, 12), 32);
        EXPECT_GT(nearer, 10u);  // the true cylinders are seen: their prisms are nearer
    }

    TEST(FclRobotScene, SingleBodyAnswersAsFclOnTheWholeWorld)
    {
        // The benchmark's FCL peer of a single body: the one-link robot's mesh against the world's connected parts in
        // the obstacles' manager. The oracle: OMPL.app's FCL checker, the centred robot mesh against the whole world
        // as one BVHModel, placed by the same state. slotted_wall's world is one part, handshake's six.
        std::size_t parts = 0;
        for (const char *map : {"slotted_wall", "handshake"})
        {
            const ProblemConfig config = readProblemConfig(std::string(MESHGAP_SOURCE_DIR) + "/maps/" + map + "/" +
                                                           map + ".cfg");
            const RobotProblem problem = rigidBodyProblem(config);
            const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles);
            const FclRobotScene fcl(scene);
            ASSERT_EQ(fcl.numLinkObjects(), 1u) << map;
            parts += fcl.numObstacleObjects();
            const auto robot = test::fclModel(loadRobotMesh(config.robot, config.planar));
            const auto world = test::fclModel(loadMesh(config.world));
            // States about the start (a twentieth of the volume's diagonal) and anywhere in it, random rotations.
            const double spread = 0.05 * config.volume->diagonal().norm();
            std::mt19937 rng(17);
            std::normal_distribution<double> near(0.0, 1.0);
            FclSceneTally tally;
            for (std::size_t n = 0; n < 300; ++n)
            {
                Eigen::Vector3d t = config.start.translation();
                t += spread * Eigen::Vector3d(near(rng), near(rng), near(rng));
                if (n % 4 == 0)
                    for (int k = 0; k < 3; ++k)
                        t[k] = std::uniform_real_distribution<double>(config.volume->min()[k],
                                                                      config.volume->max()[k])(rng);
                const Eigen::Quaterniond q =
                    Eigen::Quaterniond(near(rng), near(rng), near(rng), near(rng)).normalized();
                const std::vector<double> state = {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
                const std::vector<Eigen::Isometry3d> X = problem.robot->linkPoses(state);
                const bool hit = test::fclCollide(world, robot, X[0]);
                EXPECT_EQ(fcl.inCollision(X), hit) << map << " state " << n;
                const double expected = hit ? 0.0 : std::max(0.0, test::fclDistance(world, robot, X[0]));
                EXPECT_NEAR(fcl.distance(X), expected, 1e-9 * std::max(1.0, expected)) << map << " state " << n;
                (hit ? tally.colliding : tally.free) += 1;
            }
            EXPECT_GT(tally.colliding, 30u) << map;
            EXPECT_GT(tally.free, 30u) << map;
        }
        EXPECT_EQ(parts, 7u);  // the world in parts, against the oracle's one model
    }

    TEST(FclRobotScene, ThreadsGetTheSameAnswers)
    {
        const RobotProblem problem = armFixture();
        const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles);
        const FclRobotScene fcl(scene);
        const std::vector<std::vector<double>> states = armStates(problem, 200, 13);
        std::vector<double> expected;
        std::vector<char> expectedHit;
        for (const std::vector<double> &q : states)
        {
            expected.push_back(fcl.distance(scene->robot().linkPoses(q)));
            expectedHit.push_back(fcl.inCollision(scene->robot().linkPoses(q)) ? 1 : 0);
        }
        std::vector<std::size_t> wrong(3, 0);
        std::vector<std::thread> threads;
        for (std::size_t t = 0; t < wrong.size(); ++t)
            threads.emplace_back(
                [&, t]
                {
                    for (int round = 0; round < 3; ++round)
                        for (std::size_t n = 0; n < states.size(); ++n)
                        {
                            const std::vector<Eigen::Isometry3d> X = scene->robot().linkPoses(states[n]);
                            wrong[t] += fcl.distance(X) != expected[n] ? 1 : 0;
                            wrong[t] += fcl.inCollision(X) != (expectedHit[n] != 0) ? 1 : 0;
                        }
                });
        for (std::thread &thread : threads)
            thread.join();
        for (std::size_t t = 0; t < wrong.size(); ++t)
            EXPECT_EQ(wrong[t], 0u) << "thread " << t;
    }

    TEST(FclRobotScene, Ur5BookshelfMatchesFclPairByPairAndBracketsMeshgap)
    {
        const fs::path folder = fs::path(MESHGAP_SHARED_DATA_DIR) / "mbm" / "ur5";
        if (!fs::exists(folder / "problems.tar.bz2") || !fs::exists(folder / "ur5.urdf"))
            GTEST_SKIP() << "MotionBenchMaker's UR5 problems are not in " << folder.string();
        const fs::path dir = fs::temp_directory_path() / ("meshgap_fcl_mbm_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        const std::string inside = "problems/bookshelf_small_ur5/";
        const std::string command = "tar -xjf '" + (folder / "problems.tar.bz2").string() + "' -C '" + dir.string() +
                                    "' " + inside + "scene0001.yaml " + inside + "request0001.yaml";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        MoveItFiles files;
        files.urdf = (folder / "ur5.urdf").string();
        files.srdf = (folder / "ur5.srdf").string();
        files.scene = (dir / inside / "scene0001.yaml").string();
        files.request = (dir / inside / "request0001.yaml").string();
        files.packagePath = {folder.string()};
        const RobotProblem problem = readMoveItProblem(files);
        fs::remove_all(dir);
        std::size_t cylinders = 0;
        for (const BodyConstPtr &o : problem.obstacles)
            for (const Primitive &p : o->primitives())
                cylinders += p.kind == Primitive::Kind::CYLINDER ? 1 : 0;
        EXPECT_GT(cylinders, 0u);
        const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles, problem.allowedObstacles);
        // FCL's distance between the UR5's meshes costs a large part of a second a state: a few states.
        const std::vector<std::vector<double>> states =
            armStates(problem, static_cast<std::size_t>(test::scaled(12, 8)), 14);
        FclSceneTally tally;
        expectPairByPair(scene, states, tally);
        EXPECT_GE(tally.colliding, 2u);
        EXPECT_GE(tally.free, 2u);  // the start and the goal, at least
        expectBracketsMeshgap(scene, states, files.segments);
    }
}  // namespace meshgap
#endif
