// Whole-robot answers: the one-body robot against today's Scene (the same answers), and robots of many bodies (two
// rigid bodies, the test tree, the fanuc arm carrying a concave payload) pair by pair against FCL on the same meshes
// at the same poses; the pruned query against the every-pair one, warm against cold, threads against one thread.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <thread>

#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/RigidBodyRobot.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/scene/Scene.h"
#include "support/Shapes.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "robot/TestTree.h"

namespace meshgap
{
    namespace
    {
        /** \brief A C-shaped plate (concave), \e size across, opening towards +x, \e size / 4 thick, centred. */
        Mesh cShapeFixture(double size)
        {
            const double w = size, t = size / 4;
            const Polygon2d outer = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, w - t}, {w, w - t}, {w, w}, {0, w}};
            Mesh m = makeExtrusion(outer, {}, t, size / 3);
            transformMesh(m, test::translation(-w / 2, -w / 2, -t / 2));
            return m;
        }

        Eigen::Isometry3d robotScenePose(const Eigen::Matrix3d &R, const Eigen::Vector3d &p)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = R;
            X.translation() = p;
            return X;
        }

        /** \brief Obstacles scaled to a robot's reach \e r about the point \e at: a concave fixture (a C), a
            pillar and a plate. Nothing in it is fitted to one robot. */
        std::vector<BodyConstPtr> world(double r, const Eigen::Vector3d &at)
        {
            Mesh fixture = cShapeFixture(0.5 * r);
            transformMesh(fixture,
                          robotScenePose(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(),
                                         at + Eigen::Vector3d(0.55 * r, 0.0, 0.3 * r)));
            Mesh pillar = makeBox(Eigen::Vector3d(0.15 * r, 0.15 * r, 0.8 * r), 0.2 * r);
            transformMesh(pillar, test::translation(at.x() - 0.4 * r, at.y() + 0.5 * r, at.z() + 0.4 * r));
            Mesh plate = makeBox(Eigen::Vector3d(0.4 * r, 0.6 * r, 0.03 * r), 0.2 * r);
            transformMesh(plate, test::translation(at.x() + 0.5 * r, at.y() - 0.4 * r, at.z() + 0.2 * r));
            std::vector<BodyConstPtr> bodies;
            for (Mesh *m : {&fixture, &pillar, &plate})
                bodies.push_back(Body::build(*m));
            return bodies;
        }

        /** \brief The largest distance from the world origin of any link's surface over \e states. */
        double reach(const RobotModel &robot, const std::vector<double> &state)
        {
            double r = 0.0;
            const std::vector<Eigen::Isometry3d> poses = robot.linkPoses(state);
            for (std::size_t i = 0; i < poses.size(); ++i)
                for (const Eigen::Vector3d &v : robot.links()[i].body->surface().vertices)
                    r = std::max(r, (poses[i] * v).norm());
            return r;
        }

        /** \brief Uniform states within the joint limits (continuous joints in [-pi, pi]). */
        std::vector<std::vector<double>> randomJointStates(const UrdfRobot &robot, std::size_t count,
                                                           std::uint32_t seed)
        {
            std::mt19937 rng(seed);
            std::vector<std::vector<double>> states;
            for (std::size_t n = 0; n < count; ++n)
            {
                std::vector<double> q;
                for (std::size_t i = 0; i < robot.dimension(); ++i)
                {
                    const double lo = std::isfinite(robot.stateLower(i)) ? robot.stateLower(i) : -M_PI;
                    const double hi = std::isfinite(robot.stateUpper(i)) ? robot.stateUpper(i) : M_PI;
                    q.push_back(std::uniform_real_distribution<double>(lo, hi)(rng));
                }
                states.push_back(q);
            }
            return states;
        }

        /** \brief What comparing with FCL saw. */
        struct FclTally
        {
            std::size_t states{0}, pairs{0}, colliding{0}, free{0}, contained{0}, selfColliding{0};
            double worstRelative{0.0};
        };

#ifdef MESHGAP_HAVE_FCL
        /** \brief True when a vertex of one body lies inside the other, closed, one (containment, which FCL's
            surface test cannot see): brute-force winding numbers. */
        bool contained(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
        {
            return (b.isClosed() && containsPoint(b, X_AB.inverse() * a.surface().vertices[0])) ||
                   (a.isClosed() && containsPoint(a, X_AB * b.surface().vertices[0]));
        }

        /** \brief One pair's answer against FCL's: the same verdict (a containment FCL misses, checked by
            winding numbers, aside), the same distance within 1e-8 relative when free. */
        void expectPairMatches(const RobotPairAnswer &answer, bool fclHit, double fclDistance, bool containment,
                               FclTally &tally, const std::string &what)
        {
            ASSERT_EQ(answer.status, RobotPairAnswer::Status::EXACT) << what;
            ++tally.pairs;
            const bool ours = answer.distance < 0.0;
            if (ours && !fclHit && containment)
            {
                ++tally.contained;
                return;
            }
            ASSERT_EQ(ours, fclHit) << what << ": ours " << answer.distance << ", FCL " << fclDistance;
            if (fclHit)
            {
                ++tally.colliding;
                return;
            }
            ++tally.free;
            const double relative = std::abs(answer.distance - fclDistance) / std::max(fclDistance, 1e-300);
            tally.worstRelative = std::max(tally.worstRelative, relative);
            EXPECT_LE(relative, 1e-8) << what << ": ours " << answer.distance << ", FCL " << fclDistance;
        }

        /** \brief Every pair of \e scene at every state against FCL on the same meshes at the same poses. */
        void compareWithFcl(const RobotScene &scene, const std::vector<std::vector<double>> &states, FclTally &tally)
        {
            std::vector<std::shared_ptr<test::FclModel>> links, obstacles;
            for (const RobotLink &link : scene.links())
                links.push_back(test::fclModel(link.body->surface()));
            for (const BodyConstPtr &o : scene.obstacles())
                obstacles.push_back(test::fclModel(o->surface()));
            RobotRequest request;
            request.everyPair = true;
            RobotWarmStart warm;
            RobotResult result;
            for (const std::vector<double> &q : states)
            {
                ++tally.states;
                scene.distance(q.data(), q.size(), request, warm, result);
                ASSERT_TRUE(result.certified);
                const std::vector<Eigen::Isometry3d> poses = scene.robot().linkPoses(q);
                double least = std::numeric_limits<double>::infinity();
                for (std::size_t i = 0; i < links.size(); ++i)
                {
                    bool hit = false, inside = false;
                    double d = std::numeric_limits<double>::infinity();
                    for (std::size_t k = 0; k < obstacles.size(); ++k)
                    {
                        hit = hit || test::fclCollide(obstacles[k], links[i], poses[i]);
                        d = std::min(d, test::fclDistance(obstacles[k], links[i], poses[i]));
                        inside = inside || contained(*scene.obstacles()[k], *scene.links()[i].body, poses[i]);
                    }
                    expectPairMatches(result.pairs[i], hit, d, inside, tally, "link " + scene.links()[i].name);
                    least = std::min(least, result.pairs[i].distance);
                }
                for (std::size_t p = 0; p < scene.selfPairs().size(); ++p)
                {
                    const auto [a, b] = scene.selfPairs()[p];
                    const Eigen::Isometry3d X_AB = poses[a].inverse() * poses[b];
                    const bool hit = test::fclCollide(links[a], links[b], X_AB);
                    tally.selfColliding += hit ? 1 : 0;
                    const RobotPairAnswer &answer = result.pairs[scene.links().size() + p];
                    expectPairMatches(answer, hit, test::fclDistance(links[a], links[b], X_AB),
                                      contained(*scene.links()[a].body, *scene.links()[b].body, X_AB), tally,
                                      scene.links()[a].name + " vs " + scene.links()[b].name);
                    least = std::min(least, answer.distance);
                }
                EXPECT_EQ(result.distance, least);
                if (::testing::Test::HasFatalFailure())
                    return;
            }
        }
#endif

        /** \brief The pruned query gives the every-pair query's minimum, pair and verdict, warm along the run as
            cold; inCollision() agrees with the sign. */
        void expectPrunedMatchesEveryPair(const RobotScene &scene, const std::vector<std::vector<double>> &states)
        {
            RobotRequest every, pruned;
            every.everyPair = true;
            RobotWarmStart warm, collisionWarm;
            RobotResult full, fast, cold;
            for (const std::vector<double> &q : states)
            {
                scene.distance(q, every, full);
                scene.distance(q.data(), q.size(), pruned, warm, fast);
                scene.distance(q, pruned, cold);
                EXPECT_EQ(fast.distance, full.distance);
                EXPECT_EQ(cold.distance, full.distance);
                EXPECT_EQ(fast.inCollision, full.inCollision);
                EXPECT_TRUE(fast.certified);
                EXPECT_EQ(fast.selfPair, full.selfPair);
                EXPECT_EQ(fast.link, full.link);
                EXPECT_EQ(fast.other, full.other);
                EXPECT_EQ(scene.inCollision(q.data(), q.size(), collisionWarm), full.distance < 0.0);
                for (std::size_t i = 0; i < fast.linkClearance.size(); ++i)
                    EXPECT_LE(fast.linkClearance[i], full.linkClearance[i] + 1e-12);
                // A stop below a positive value reports a distance at or below it exactly when the true one is.
                RobotRequest stop;
                stop.stopBelow = 0.05 * std::abs(full.distance);
                RobotResult early;
                scene.distance(q, stop, early);
                EXPECT_EQ(early.distance <= stop.stopBelow, full.distance <= stop.stopBelow);
            }
        }

        std::string fanucFolder()
        {
            return std::string(MESHGAP_SHARED_DATA_DIR) + "/robots";
        }
    }  // namespace

    TEST(RobotScene, OneRigidBodyGivesTodaysSceneAnswers)
    {
        const BodyConstPtr robotBody = Body::build(cShapeFixture(1.0));
        // Lowered so that the plane z = 0, where an SE(2) robot moves, cuts every obstacle.
        const std::vector<BodyConstPtr> obstacles = world(2.0, Eigen::Vector3d(0.0, 0.0, -0.5));
        const Scene scene(robotBody, obstacles);
        for (RigidSpace space : {RigidSpace::SE3, RigidSpace::SE2})
        {
            const auto robot = std::make_shared<RigidBodyRobot>(robotBody, space);
            const RobotScene robotScene(robot, obstacles);
            ASSERT_TRUE(robotScene.selfPairs().empty());
            std::mt19937 rng(3);
            std::uniform_real_distribution<double> u(-2.0, 2.0);
            std::normal_distribution<double> g;
            SceneWarmStart sceneWarm;
            RobotWarmStart robotWarm;
            std::vector<double> state = space == RigidSpace::SE3 ? std::vector<double>{0, 0, 0, 0, 0, 0, 1}
                                                                 : std::vector<double>{0, 0, 0};
            std::size_t colliding = 0;
            for (int n = 0; n < 300; ++n)
            {
                // A random walk, so that the warm starts carry over.
                for (std::size_t k = 0; k < state.size(); ++k)
                    state[k] = n % 50 == 0 ? (k < 3 ? u(rng) : g(rng)) : state[k] + 0.05 * g(rng);
                const Eigen::Isometry3d X = rigidPose(space, state.data());
                SceneResult expected;
                scene.distance(X, SceneRequest(), sceneWarm, expected);
                RobotResult got;
                robotScene.distance(state.data(), state.size(), RobotRequest(), robotWarm, got);
                ASSERT_EQ(got.distance, expected.distance) << n;
                EXPECT_EQ(got.other, expected.obstacle);
                EXPECT_EQ(got.onA, expected.onA);
                EXPECT_EQ(got.onB, expected.onB);
                EXPECT_EQ(got.inCollision, expected.inCollision);
                EXPECT_EQ(got.certified, expected.certified);
                EXPECT_EQ(got.linkClearance[0], expected.distance);
                EXPECT_EQ(robotScene.inCollision(state.data(), state.size(), robotWarm), scene.inCollision(X));
                colliding += expected.inCollision ? 1 : 0;
            }
            EXPECT_GT(colliding, 10u);
            EXPECT_LT(colliding, 290u);
        }
    }

    TEST(RobotScene, TwoRigidBodiesMatchFclPairByPair)
    {
#ifndef MESHGAP_HAVE_FCL
        GTEST_SKIP() << "FCL not found: no oracle";
#else
        Mesh plain = test::box(0.3, 0.2, 0.1);
        const auto robot = std::make_shared<MultiBodyRobot>(std::vector<MultiBodyRobot::Part>{
            {"c", Body::build(cShapeFixture(1.0)), RigidSpace::SE3}, {"box", Body::build(plain), RigidSpace::SE2}});
        ASSERT_EQ(robot->dimension(), 10u);
        const RobotScene scene(robot, world(2.0, Eigen::Vector3d::Zero()));
        ASSERT_EQ(scene.selfPairs().size(), 1u);
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-1.5, 1.5);
        std::normal_distribution<double> g;
        std::vector<std::vector<double>> states;
        for (int n = 0; n < 400; ++n)
            states.push_back({u(rng), u(rng), u(rng), g(rng), g(rng), g(rng), g(rng), u(rng), u(rng), 2 * u(rng)});
        FclTally tally;
        compareWithFcl(scene, states, tally);
        test::Note() << tally.pairs << " pairs: " << tally.colliding << " colliding, " << tally.free << " free, "
                     << tally.contained << " contained; worst relative " << tally.worstRelative;
        EXPECT_GT(tally.selfColliding, 5u);
        EXPECT_GT(tally.free, 100u);
        expectPrunedMatchesEveryPair(scene, std::vector<std::vector<double>>(states.begin(), states.begin() + 100));
#endif
    }

    TEST(RobotScene, TestTreeMatchesFclPairByPair)
    {
#ifndef MESHGAP_HAVE_FCL
        GTEST_SKIP() << "FCL not found: no oracle";
#else
        UrdfOptions options;
        options.solids = false;  // the oracle is FCL on the same triangles
        const UrdfRobotPtr robot = UrdfRobot::load(
            std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/meshgap_test_description/urdf/tree.urdf", options);
        Mesh payload = cShapeFixture(0.1);
        robot->attach("payload", payload, "tool", test::translation(0.0, 0.0, 0.05));
        const std::vector<std::vector<double>> states = randomJointStates(*robot, test::scaled(300, 40), 5);
        const RobotScene scene(robot, world(reach(*robot, std::vector<double>(5, 0.0)), Eigen::Vector3d::Zero()));
        FclTally tally;
        compareWithFcl(scene, states, tally);
        test::Note() << tally.pairs << " pairs: " << tally.colliding << " colliding (" << tally.selfColliding
                     << " self), " << tally.free << " free, " << tally.contained << " contained; worst relative "
                     << tally.worstRelative;
        EXPECT_GT(tally.colliding, 10u);
        expectPrunedMatchesEveryPair(
            scene, std::vector<std::vector<double>>(states.begin(), states.begin() + test::scaled(100)));
#endif
    }

    TEST(RobotScene, FanucCarryingAConcavePayloadMatchesFclPairByPair)
    {
#ifndef MESHGAP_HAVE_FCL
        GTEST_SKIP() << "FCL not found: no oracle";
#else
        const std::string folder = fanucFolder();
        const std::string urdf = folder + "/moveit_resources_fanuc_description/urdf/fanuc.urdf";
        const std::string srdf = folder + "/moveit_resources_fanuc_moveit_config/config/fanuc.srdf";
        if (!std::filesystem::exists(urdf) || !std::filesystem::exists(srdf))
            GTEST_SKIP() << "the fanuc arm is not in " << folder << " (see ../shared/data/robots/README.md)";
        UrdfOptions options;
        options.packagePath = {folder};
        const UrdfRobotPtr robot = UrdfRobot::load(urdf, options);
        readSrdf(*robot, srdf);
        const std::vector<double> zero(robot->dimension(), 0.0);
        const double r = reach(*robot, zero);
        robot->attach("payload", cShapeFixture(0.15 * r), "tool0", test::translation(0.0, 0.0, 0.1 * r));
        // MESHGAP_ROBOT_STATES sets the count (10,000 for the full check; 1,000 by default, 40 under test::scale() < 1:
        // each state is every pair's exact distance and FCL's).
        const char *count = std::getenv("MESHGAP_ROBOT_STATES");
        const std::vector<std::vector<double>> states =
            randomJointStates(*robot, count ? std::strtoul(count, nullptr, 10) : test::scaledAtMost(1000, 40), 17);
        const RobotScene scene(robot, world(r, Eigen::Vector3d::Zero()));
        FclTally tally;
        compareWithFcl(scene, states, tally);
        test::Note() << tally.states << " states, " << tally.pairs << " pairs: " << tally.colliding << " colliding ("
                     << tally.selfColliding << " self), " << tally.free << " free, " << tally.contained
                     << " contained; worst relative " << tally.worstRelative;
        EXPECT_GT(tally.selfColliding, 0u);
        EXPECT_GT(tally.colliding, 0u);
        const auto pruned = std::min<std::ptrdiff_t>(test::scaled(100), static_cast<std::ptrdiff_t>(states.size()));
        expectPrunedMatchesEveryPair(scene, std::vector<std::vector<double>>(states.begin(), states.begin() + pruned));
#endif
    }

    TEST(RobotScene, PairQuestionsAgreeWithEveryPairsExactAnswer)
    {
        // pairApart(k, m) says "more than m apart" exactly when pair k's exact distance (every pair answered) is
        // above m, and pairCollides(k) when it is negative; margins drawn around each pair's own distance.
        const UrdfRobotPtr robot = test::treeWithPayload();
        const RobotScene scene(robot, test::postsAroundTree());
        std::mt19937 rng(23);
        std::uniform_real_distribution<double> u(-1.0, 1.0), factor(0.5, 1.5);
        RobotRequest every;
        every.everyPair = true;
        RobotWarmStart warm;
        RobotResult exact;
        std::size_t apart = 0, within = 0, colliding = 0;
        for (int trial = 0; trial < test::scaled(300, 100); ++trial)
        {
            const std::vector<double> q = {3 * u(rng), 2.5 * u(rng), 0.05 + 0.05 * u(rng), 3 * u(rng), u(rng)};
            scene.distance(q, every, exact);
            scene.place(q.data(), q.size(), warm);
            for (std::size_t k = 0; k < scene.numPairs(); ++k)
            {
                const double d = exact.pairs[k].distance;
                if (std::isinf(d))
                    continue;  // a pair the query left out
                const double margin = d > 0.0 ? d * factor(rng) : 0.01 * factor(rng);
                if (std::abs(margin - d) < 1e-9 * (1.0 + std::abs(d)))
                    continue;  // too close to call either way
                const bool says = scene.pairApart(k, margin, warm);
                EXPECT_EQ(says, d > margin) << "trial " << trial << ", pair " << k << ": " << d << " vs " << margin;
                EXPECT_EQ(scene.pairCollides(k, warm), d < 0.0) << "trial " << trial << ", pair " << k;
                (says ? apart : within)++;
                colliding += d < 0.0;
            }
        }
        test::Note() << apart << " apart, " << within << " within their margin, " << colliding << " colliding";
        EXPECT_GT(apart, 100u);
        EXPECT_GT(within, 100u);
        EXPECT_GT(colliding, 0u);
    }

    TEST(RobotScene, RequestIsADistanceRequestWithTheSameDefaults)
    {
        const RobotRequest request;
        const DistanceRequest &base = request;
        EXPECT_EQ(base.stopBelow, -1.0);
        EXPECT_EQ(base.upperBound, std::numeric_limits<double>::infinity());
        EXPECT_TRUE(base.computeDepth);
        EXPECT_EQ(base.maxTests, 0u);
        EXPECT_FALSE(base.outerBoundFirst);
        EXPECT_FALSE(request.everyPair);
        EXPECT_TRUE(request.selfCollision);
    }

    TEST(RobotScene, OuterBoundsFirstChangeNoAnswer)
    {
        // RobotRequest::outerBoundFirst reaches every pair's question (links against the obstacles, self pairs) and
        // changes its cost only: bounded queries, pruned and every pair, give the same answers bit for bit.
        const UrdfRobotPtr robot = test::treeWithPayload();
        const RobotScene scene(robot, test::postsAroundTree());
        std::mt19937 rng(29);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        std::size_t below = 0, atLeast = 0;
        for (int trial = 0; trial < test::scaled(200, 50); ++trial)
        {
            const std::vector<double> q = {3 * u(rng), 2.5 * u(rng), 0.05 + 0.05 * u(rng), 3 * u(rng), u(rng)};
            for (int variant = 0; variant < 4; ++variant)
            {
                const bool everyPair = variant & 1;
                RobotRequest plain;
                plain.everyPair = everyPair;
                plain.selfCollision = variant & 2;  // without self pairs, more answers lie beyond the bound
                plain.upperBound = 0.05;
                RobotRequest outer = plain;
                outer.outerBoundFirst = true;
                RobotResult expected, got;
                scene.distance(q, plain, expected);
                scene.distance(q, outer, got);
                const std::string where = "trial " + std::to_string(trial) + ", variant " + std::to_string(variant);
                EXPECT_EQ(got.distance, expected.distance) << where;
                EXPECT_EQ(got.atLeast, expected.atLeast) << where;
                EXPECT_EQ(got.certified, expected.certified) << where;
                EXPECT_EQ(got.inCollision, expected.inCollision) << where;
                EXPECT_EQ(got.selfPair, expected.selfPair) << where;
                EXPECT_EQ(got.link, expected.link) << where;
                EXPECT_EQ(got.other, expected.other) << where;
                EXPECT_EQ(got.onA, expected.onA) << where;
                EXPECT_EQ(got.onB, expected.onB) << where;
                ASSERT_EQ(got.pairs.size(), expected.pairs.size());
                for (std::size_t k = 0; k < got.pairs.size(); ++k)
                {
                    EXPECT_EQ(got.pairs[k].status, expected.pairs[k].status) << where << ", pair " << k;
                    EXPECT_EQ(got.pairs[k].distance, expected.pairs[k].distance) << where << ", pair " << k;
                }
                (expected.atLeast ? atLeast : below)++;
            }
        }
        // Both kinds of answer are compared, several times each (800 answers: 22 at least the bound; 200 under the
        // sanitizers' scale: 8).
        test::Note() << below << " answers below the bound, " << atLeast << " at least it";
        EXPECT_GT(below, 4u);
        EXPECT_GT(atLeast, 4u);
    }

    TEST(RobotScene, ThreadsWithTheirOwnWarmStartsGiveTheSameAnswers)
    {
        const UrdfRobotPtr robot =
            UrdfRobot::load(std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/meshgap_test_description/urdf/tree.urdf");
        const RobotScene scene(robot, world(reach(*robot, std::vector<double>(5, 0.0)), Eigen::Vector3d::Zero()));
        const std::vector<std::vector<double>> states = randomJointStates(*robot, 200, 9);
        std::vector<double> expected;
        for (const auto &q : states)
        {
            RobotResult r;
            scene.distance(q, RobotRequest(), r);
            expected.push_back(r.distance);
        }
        std::vector<std::vector<double>> got(2);
        std::vector<std::thread> threads;
        for (std::size_t t = 0; t < 2; ++t)
            threads.emplace_back(
                [&, t]
                {
                    RobotWarmStart warm;
                    RobotResult r;
                    for (const auto &q : states)
                    {
                        scene.distance(q.data(), q.size(), RobotRequest(), warm, r);
                        got[t].push_back(r.distance);
                    }
                });
        for (std::thread &t : threads)
            t.join();
        EXPECT_EQ(got[0], expected);
        EXPECT_EQ(got[1], expected);
    }

    TEST(RobotScene, BadQueriesGetOneClearErrorEach)
    {
        const auto robot = std::make_shared<RigidBodyRobot>(Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE2);
        const RobotScene scene(robot, world(1.0, Eigen::Vector3d::Zero()));
        RobotResult result;
        try
        {
            scene.distance(std::vector<double>{1.0, 2.0}, RobotRequest(), result);
            FAIL() << "a state of the wrong dimension was accepted";
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find("a state of 2 numbers, where this robot has 3"), std::string::npos)
                << e.what();
        }
        RobotRequest request;
        request.upperBound = 0.0;
        EXPECT_THROW(scene.distance(std::vector<double>{1.0, 2.0, 0.0}, request, result), Exception);
    }
}  // namespace meshgap
