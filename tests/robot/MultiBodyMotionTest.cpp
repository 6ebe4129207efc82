// Certified motions for robots of free bodies (several rigid bodies in SE(2) and SE(3), a floating base, planar and
// floating joints): the displacement bounds against the vertices' real motion along OMPL's interpolation, a swap in
// which two bodies pass through each other between the states OMPL's discrete validator looks at, and planned paths
// checked densely by FCL.
#include <gtest/gtest.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/RobotProblem.h"
#include "robot/TestTree.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace
    {
        ob::RealVectorBounds box3(double x, double y, double z)
        {
            ob::RealVectorBounds b(3);
            b.setLow(0, -x);
            b.setLow(1, -y);
            b.setLow(2, -z);
            b.setHigh(0, x);
            b.setHigh(1, y);
            b.setHigh(2, z);
            return b;
        }

        /** \brief A random state of \e robot: each free body's pose within 3 of the origin, a uniform rotation
            (SE(3)) or yaw (SE(2)); joint values from \e joints. */
        std::vector<double> randomState(const RobotModel &robot, std::mt19937 &rng,
                                        const std::function<double(std::size_t)> &joints)
        {
            std::uniform_real_distribution<double> u(-1.0, 1.0);
            std::normal_distribution<double> n;
            std::vector<double> q(robot.dimension());
            for (std::size_t k = 0; k < q.size(); ++k)
                q[k] = joints(k);
            for (std::size_t f = 0; f < robot.frames().size(); ++f)
            {
                const FrameMotion m = robot.frameMotion(f);
                if (m.kind == FrameMotion::Kind::SE2)
                {
                    q[m.variable] = 3 * u(rng);
                    q[m.variable + 1] = 2 * u(rng);
                    q[m.variable + 2] = M_PI * u(rng);
                }
                else if (m.kind == FrameMotion::Kind::SE3)
                {
                    const Eigen::Quaterniond r = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
                    const double v[7] = {3 * u(rng), 2 * u(rng), 2 * u(rng), r.x(), r.y(), r.z(), r.w()};
                    std::copy(v, v + 7, q.begin() + static_cast<long>(m.variable));
                }
            }
            return q;
        }

        /** \brief How far any vertex of link \e link moved from the poses (\e framesA, \e linksA) to (\e framesB,
            \e linksB), in frame \e c (the world for NONE). */
        double largestMove(const RobotModel &robot, std::size_t link, std::size_t c,
                           const std::vector<Eigen::Isometry3d> &framesA, const std::vector<Eigen::Isometry3d> &linksA,
                           const std::vector<Eigen::Isometry3d> &framesB, const std::vector<Eigen::Isometry3d> &linksB)
        {
            const Eigen::Isometry3d XA = c == RobotModel::NONE ? linksA[link] : framesA[c].inverse() * linksA[link];
            const Eigen::Isometry3d XB = c == RobotModel::NONE ? linksB[link] : framesB[c].inverse() * linksB[link];
            double most = 0.0;
            for (const Eigen::Vector3d &v : robot.links()[link].body->surface().vertices)
                most = std::max(most, (XB * v - XA * v).norm());
            return most;
        }

        /** \brief Random motions of \e robot along OMPL's interpolation in its space, every vertex at 200 states
            each: at fraction t no vertex of a link is further than t times the link's bound from where it started,
            and no two links of a checked pair, in their nearest common frame (the world for two bodies), moved more
            than t times the pair's bound together. Returns the largest ratio of a real move to its bound. */
        double checkBounds(const RobotModel &robot, const std::function<double(std::size_t)> &joints, unsigned seed)
        {
            const MotionBound bound(robot);
            const ob::StateSpacePtr space = robotStateSpace(robot, box3(4, 4, 4));
            std::mt19937 rng(seed);
            ob::State *sa = space->allocState(), *sb = space->allocState(), *s = space->allocState();
            std::vector<double> moves, q;
            std::vector<Eigen::Isometry3d> framesA, linksA, framesQ, linksQ;
            double tightest = 0.0;
            auto moved = [&](std::size_t link, std::size_t c)
            { return largestMove(robot, link, c, framesA, linksA, framesQ, linksQ); };
            for (int trial = 0; trial < test::scaled(40); ++trial)
            {
                // Through OMPL's states, so that a and b are what the space holds (yaw wrapped, unit quaternions).
                robotStateFromVector(*space, randomState(robot, rng, joints), sa);
                robotStateFromVector(*space, randomState(robot, rng, joints), sb);
                std::vector<double> a, b;
                robotStateToVector(*space, sa, a);
                robotStateToVector(*space, sb, b);
                bound.linkDisplacements(a, b, moves);
                robot.linkPoses(a.data(), a.size(), framesA, linksA);
                for (int step = 1; step <= 200 && !::testing::Test::HasFailure(); ++step)
                {
                    const double t = step / 200.0;
                    space->interpolate(sa, sb, t, s);
                    robotStateToVector(*space, s, q);
                    robot.linkPoses(q.data(), q.size(), framesQ, linksQ);
                    for (std::size_t i = 0; i < robot.links().size(); ++i)
                    {
                        const double real = moved(i, RobotModel::NONE);
                        EXPECT_LE(real, t * moves[i] + 1e-9) << robot.links()[i].name << " trial " << trial;
                        tightest = std::max(tightest, real / (t * moves[i]));
                    }
                    for (const auto &[first, second] : robot.selfPairs())
                    {
                        const std::size_t c =
                            test::commonFrame(robot, robot.links()[first].frame, robot.links()[second].frame);
                        const double real = moved(first, c) + moved(second, c);
                        const double pair = bound.pairDisplacement(first, second, a, b);
                        EXPECT_LE(real, t * pair + 1e-9)
                            << robot.links()[first].name << " " << robot.links()[second].name << " trial " << trial;
                        EXPECT_LE(pair, moves[first] + moves[second] + 1e-12);
                        if (c == RobotModel::NONE)  // two bodies: both bounds, added
                        {
                            EXPECT_NEAR(pair, moves[first] + moves[second], 1e-12);
                        }
                    }
                }
            }
            space->freeState(sa);
            space->freeState(sb);
            space->freeState(s);
            return tightest;
        }

        /** \brief Random pieces of random motions of \e robot (middle state, half-length 0.5, 0.1 or 0.01 of the
            motion): no vertex of a link is further from where it is at the middle than MotionBound::pieceBounds()
            says, at 100 states of the piece, no checked pair moved more in its nearest common frame than
            pairBound(), nor in any split's frame than pairSplitBound() (MotionBound::splitFrame()); each bound is at
            most the piece's share of the whole motion's crude bound. Returns the mean ratio of the piece bound to
            that share (how much tighter it is). */
        double checkPieceBounds(const RobotModel &robot, const std::function<double(std::size_t)> &joints,
                                unsigned seed)
        {
            const MotionBound bound(robot);
            const ob::StateSpacePtr space = robotStateSpace(robot, box3(4, 4, 4));
            std::mt19937 rng(seed);
            std::uniform_real_distribution<double> unit(0.0, 1.0);
            ob::State *sa = space->allocState(), *sb = space->allocState(), *s = space->allocState();
            std::vector<double> a, b, q, moves, sums;
            std::vector<Eigen::Isometry3d> framesM, linksM, framesQ, linksQ;
            MotionBound::Motion motion;
            double ratio = 0.0;
            int ratios = 0;
            auto moved = [&](std::size_t link, std::size_t c)
            { return largestMove(robot, link, c, framesM, linksM, framesQ, linksQ); };
            for (int trial = 0; trial < test::scaled(60) && !::testing::Test::HasFailure(); ++trial)
            {
                robotStateFromVector(*space, randomState(robot, rng, joints), sa);
                robotStateFromVector(*space, randomState(robot, rng, joints), sb);
                robotStateToVector(*space, sa, a);
                robotStateToVector(*space, sb, b);
                bound.linkDisplacements(a, b, moves);
                bound.motion(a, b, motion);
                const double half = std::vector<double>{0.5, 0.1, 0.01}[trial % 3];
                const double middle = half + (1.0 - 2.0 * half) * unit(rng);
                space->interpolate(sa, sb, middle, s);
                robotStateToVector(*space, s, q);
                robot.linkPoses(q.data(), q.size(), framesM, linksM);
                // Every other trial bounds a random half of the links only (the others' sums left as they were,
                // NaN here): the brute force below checks the links bounded.
                std::vector<unsigned char> only(robot.links().size(), 1);
                if (trial % 2 == 1)
                    for (unsigned char &o : only)
                        o = unit(rng) < 0.5 ? 1 : 0;
                sums.assign(sums.size(), std::numeric_limits<double>::quiet_NaN());
                bound.pieceBounds(motion, framesM, linksM, half, sums, &only);
                for (std::size_t i = 0; i < robot.links().size(); ++i)
                    EXPECT_EQ(std::isnan(bound.linkBound(i, sums)), !only[i] && !sums.empty())
                        << robot.links()[i].name << " " << trial;
                for (int step = 0; step <= 100; ++step)
                {
                    space->interpolate(sa, sb, middle - half + 2.0 * half * step / 100.0, s);
                    robotStateToVector(*space, s, q);
                    robot.linkPoses(q.data(), q.size(), framesQ, linksQ);
                    for (std::size_t i = 0; i < robot.links().size(); ++i)
                    {
                        if (!only[i])
                            continue;
                        const double piece = bound.linkBound(i, sums);
                        EXPECT_LE(moved(i, RobotModel::NONE), piece + 1e-9) << robot.links()[i].name << " " << trial;
                        EXPECT_LE(piece, half * moves[i] * (1 + 1e-9) + 1e-12);
                        if (step == 0 && moves[i] > 0)
                        {
                            ratio += piece / (half * moves[i]);
                            ++ratios;
                        }
                    }
                    for (const auto &[first, second] : robot.selfPairs())
                    {
                        if (!only[first] || !only[second])
                            continue;
                        const std::size_t c =
                            test::commonFrame(robot, robot.links()[first].frame, robot.links()[second].frame);
                        const auto terms = bound.pairTerms(first, second);
                        const double piece = bound.pairBound(first, second, terms, sums);
                        EXPECT_LE(moved(first, c) + moved(second, c), piece + 1e-9)
                            << robot.links()[first].name << " " << robot.links()[second].name << " " << trial;
                        // Every split of the joints between them: the two links' moves in the frame between.
                        for (std::size_t split = 0; split < bound.pairSplits(first, second, terms); ++split)
                        {
                            const std::size_t f = bound.splitFrame(first, second, terms, split);
                            const double part =
                                bound.pairSplitBound(first, second, terms, split, sums, motion, half, framesM, linksM);
                            EXPECT_LE(moved(first, f) + moved(second, f), part + 1e-9)
                                << robot.links()[first].name << " " << robot.links()[second].name << " split "
                                << split << " trial " << trial;
                        }
                        EXPECT_LE(bound.pairPieceBound(first, second, terms, sums, motion, half, framesM, linksM), piece);
                    }
                }
            }
            space->freeState(sa);
            space->freeState(sb);
            space->freeState(s);
            return ratios ? ratio / ratios : 0.0;
        }

        /** \brief Three bodies, one in SE(2) and two in SE(3), none centred on its frame's origin, and a payload
            on the second. */
        MultiBodyRobotPtr threeBodies()
        {
            auto robot = std::make_shared<MultiBodyRobot>(std::vector<MultiBodyRobot::Part>{
                {"flat", Body::build(test::transformed(test::box(0.3, 0.1, 0.05), test::translation(0.5, 0, 0))),
                 RigidSpace::SE2},
                {"bar", Body::build(test::transformed(test::box(0.6, 0.05, 0.05), test::translation(0.2, 0.1, 0))),
                 RigidSpace::SE3},
                {"ball", Body::build(test::transformed(test::icosphere(0.2, 1), test::translation(0, 0, 0.3))),
                 RigidSpace::SE3}});
            robot->attach("payload", test::box(0.1, 0.1, 0.1), "bar", test::translation(0.0, 0.8, 0.0));
            return robot;
        }

        /** \brief Two plates 4 cm thick (\e space: SE(2) or SE(3)) among no obstacle but a far cube, in a box 8 by
            4 by 4: the swap_se2 setting, with nothing between the bodies. */
        struct PlateSwap
        {
            std::shared_ptr<RobotScene> scene;
            ob::SpaceInformationPtr si;

            explicit PlateSwap(RigidSpace space)
            {
                const BodyConstPtr plate = Body::build(test::box(0.02, 0.5, 0.5));
                auto robot = std::make_shared<MultiBodyRobot>(
                    std::vector<MultiBodyRobot::Part>{{"a", plate, space}, {"b", plate, space}});
                scene = std::make_shared<RobotScene>(
                    robot, std::vector<BodyConstPtr>{
                               Body::build(test::transformed(test::box(0.5, 0.5, 0.5), test::translation(20, 20, 0)))});
                si = std::make_shared<ob::SpaceInformation>(robotStateSpace(*robot, box3(4, 2, 2)));
                si->setStateValidityChecker(std::make_shared<RobotChecker>(si, scene));
                si->setup();  // OMPL's default resolution: 1 % of the extent
            }

            /** \brief Plate a from x = -3 to 3, plate b from 3 + shift to -3 + shift, at heights ya and yb. */
            void motion(double shift, double ya, double yb, ob::State *s1, ob::State *s2) const
            {
                auto pose = [&](double xa, double xb)
                {
                    if (si->getStateDimension() == 6)
                        return std::vector<double>{xa, ya, 0, xb, yb, 0};
                    return std::vector<double>{xa, ya, 0, 0, 0, 0, 1, xb, yb, 0, 0, 0, 0, 1};
                };
                robotStateFromVector(*si->getStateSpace(), pose(-3, 3 + shift), s1);
                robotStateFromVector(*si->getStateSpace(), pose(3, -3 + shift), s2);
            }
        };

        void passThrough(RigidSpace space)
        {
            const PlateSwap swap(space);
            const ob::SpaceInformationPtr &si = swap.si;
            ob::State *s1 = si->allocState(), *s2 = si->allocState(), *s = si->allocState();
            // OMPL's discrete validator looks at k / n of the motion. The plates meet where a's x equals b's,
            // -3 + 6t = 3 + shift - 6t: put that halfway between two of those states, t = (n/2 + 1/2) / n.
            swap.motion(0.0, 0.0, 0.0, s1, s2);
            const unsigned n = si->getStateSpace()->validSegmentCount(s1, s2);
            const double crossing = (n / 2 + 0.5) / n, shift = 12.0 * crossing - 6.0;
            swap.motion(shift, 0.0, 0.0, s1, s2);
            ASSERT_EQ(si->getStateSpace()->validSegmentCount(s1, s2), n);
            ASSERT_TRUE(si->isValid(s1));
            ASSERT_TRUE(si->isValid(s2));
            // The oracle: at the crossing the plates overlap (the exact test), and they do not at OMPL's states.
            si->getStateSpace()->interpolate(s1, s2, crossing, s);
            EXPECT_FALSE(si->isValid(s));
            ob::DiscreteMotionValidator discrete(si);
            EXPECT_TRUE(discrete.checkMotion(s1, s2)) << n << " segments: OMPL's validator should miss the crossing";
            const RobotMotionValidator certified(si, swap.scene, swap.scene->robot());
            EXPECT_FALSE(certified.checkMotion(s1, s2));
            // The same swap with the plates at different heights (1 apart): free, and certified free.
            swap.motion(shift, -1.0, 1.0, s1, s2);
            EXPECT_TRUE(certified.checkMotion(s1, s2));
            test::Note() << n << " segments of OMPL's discrete check; the plates cross at t = " << crossing;
            si->freeState(s1);
            si->freeState(s2);
            si->freeState(s);
        }
    }  // namespace

    TEST(MultiBodyMotion, DisplacementBoundHoldsForSeveralBodies)
    {
        const MultiBodyRobotPtr robot = threeBodies();
        ASSERT_EQ(robot->selfPairs().size(), 5u);  // the payload is allowed against its own body only
        const double tightest = checkBounds(
            *robot, [](std::size_t) { return 0.0; }, 3);
        test::Note() << "largest displacement / bound " << tightest;
        EXPECT_GT(tightest, 0.3);  // a bound, not a wild one
        test::Note() << "piece bound / crude share, mean " << checkPieceBounds(*robot, [](std::size_t) { return 0.0; }, 4);
    }

    TEST(MultiBodyMotion, DisplacementBoundHoldsForAFloatingBase)
    {
        UrdfOptions options;
        options.floatingBase = true;
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF, options);
        robot->attach("payload", test::box(0.03, 0.02, 0.01), "tool", test::translation(0.0, 0.0, 0.04));
        // tree.urdf's joint values after the base's seven numbers: wrist_roll (continuous), shoulder, extend,
        // spin (continuous), tilt, within their limits.
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const double scale[5] = {1.5, 2.5, 0.2, 1.5, 1.0}, centre[5] = {0, 0, 0.1, 0, 0};
        const double tightest = checkBounds(
            *robot, [&](std::size_t k) { return k < 7 ? 0.0 : centre[k - 7] + scale[k - 7] * u(rng); }, 7);
        test::Note() << "largest displacement / bound " << tightest;
        EXPECT_GT(tightest, 0.2);
        test::Note() << "piece bound / crude share, mean "
                     << checkPieceBounds(
                            *robot, [&](std::size_t k) { return k < 7 ? 0.0 : centre[k - 7] + scale[k - 7] * u(rng); },
                            8);
    }

    TEST(MultiBodyMotion, PieceBoundHoldsForAFixedTree)
    {
        // tree.urdf on a fixed base, carrying a payload: the bound a certified arm motion is proven with.
        const UrdfRobotPtr robot = test::treeWithPayload();
        std::mt19937 rng(6);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const double scale[5] = {1.5, 2.5, 0.2, 1.5, 1.0}, centre[5] = {0, 0, 0.1, 0, 0};
        const double ratio = checkPieceBounds(
            *robot, [&](std::size_t k) { return centre[k] + scale[k] * u(rng); }, 9);
        test::Note() << "piece bound / crude share, mean " << ratio;
        EXPECT_LT(ratio, 1.0);  // tighter than the crude bound on average, or it would not be worth its price
    }

    TEST(MultiBodyMotion, DisplacementBoundHoldsForPlanarAndFloatingJoints)
    {
        // mobile.urdf: a planar base carrying a revolute arm, a floating drone, a planar slider normal to x; the
        // shoulder (state number 3) within its limits.
        const UrdfRobotPtr robot = UrdfRobot::load(test::MOBILE_URDF);
        std::mt19937 rng(6);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const double tightest = checkBounds(
            *robot, [&](std::size_t k) { return k == 3 ? u(rng) : 0.0; }, 9);
        test::Note() << "largest displacement / bound " << tightest;
        EXPECT_GT(tightest, 0.2);
    }

    TEST(MultiBodyMotion, BodiesPassingThroughEachOtherAreRefusedInSE2)
    {
        passThrough(RigidSpace::SE2);
    }

    TEST(MultiBodyMotion, BodiesPassingThroughEachOtherAreRefusedInSE3)
    {
        passThrough(RigidSpace::SE3);
    }

    namespace
    {
        /** \brief RRTConnect on \e map with the certified validator at OMPL's default resolution, \e runs times;
            every path it returns checked at states at most 1e-4 of the volume's diagonal apart along OMPL's
            interpolation: FCL pair by pair (each body against each obstacle, the bodies against each other) where
            built with it, and the exact test. */
        void planAndCheckDensely(const std::string &map, int runs)
        {
            const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/" + map + "/" + map + ".cfg";
            const RobotProblem p = readRobotProblem(cfg);
            ASSERT_TRUE(p.volume && p.goal);
            const auto scene = std::make_shared<RobotScene>(p.robot, p.obstacles);
            ob::RealVectorBounds bounds(3);
            for (int k = 0; k < 3; ++k)
            {
                bounds.setLow(k, p.volume->min()[k]);
                bounds.setHigh(k, p.volume->max()[k]);
            }
            const double step = 1e-4 * (p.volume->max() - p.volume->min()).norm();
#ifdef MESHGAP_HAVE_FCL
            std::vector<std::shared_ptr<test::FclModel>> links, obstacles;
            for (const RobotLink &link : scene->links())
                links.push_back(test::fclModel(link.body->surface()));
            for (const BodyConstPtr &o : scene->obstacles())
                obstacles.push_back(test::fclModel(o->surface()));
#endif
            std::size_t checked = 0;
            for (int run = 0; run < runs; ++run)
            {
                og::SimpleSetup setup(robotStateSpace(*p.robot, bounds));
                const ob::SpaceInformationPtr si = setup.getSpaceInformation();
                setup.setStateValidityChecker(std::make_shared<RobotChecker>(si, scene));
                const auto validator = std::make_shared<RobotMotionValidator>(si, scene, *p.robot);
                si->setMotionValidator(validator);
                ob::ScopedState<> start(si), goal(si);
                robotStateFromVector(*si->getStateSpace(), p.start, start.get());
                robotStateFromVector(*si->getStateSpace(), *p.goal, goal.get());
                setup.setStartAndGoalStates(start, goal);
                setup.setPlanner(std::make_shared<og::RRTConnect>(si));
                ASSERT_EQ(setup.solve(30.0), ob::PlannerStatus::EXACT_SOLUTION) << map << " run " << run;
                const og::PathGeometric &path = setup.getSolutionPath();
                for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                    ASSERT_TRUE(validator->checkMotion(path.getState(i), path.getState(i + 1)));
                ob::State *s = si->allocState();
                std::vector<double> q;
#ifdef MESHGAP_HAVE_FCL
                std::vector<Eigen::Isometry3d> frames, poses;
#endif
                RobotWarmStart warm;
                for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                {
                    const auto n = static_cast<std::size_t>(
                                       std::ceil(si->distance(path.getState(i), path.getState(i + 1)) / step)) +
                                   1;
                    for (std::size_t k = 0; k <= n; ++k, ++checked)
                    {
                        si->getStateSpace()->interpolate(path.getState(i), path.getState(i + 1), double(k) / n, s);
                        robotStateToVector(*si->getStateSpace(), s, q);
                        ASSERT_FALSE(scene->inCollision(q.data(), q.size(), warm)) << map << " motion " << i;
#ifdef MESHGAP_HAVE_FCL
                        p.robot->linkPoses(q.data(), q.size(), frames, poses);
                        for (std::size_t l = 0; l < links.size(); ++l)
                            for (const auto &o : obstacles)
                                ASSERT_FALSE(test::fclCollide(o, links[l], poses[l])) << map << " motion " << i;
                        for (const auto &[x, y] : scene->selfPairs())
                            ASSERT_FALSE(test::fclCollide(links[x], links[y], poses[x].inverse() * poses[y]))
                                << map << " motion " << i << ": bodies " << x << " and " << y << " pass through";
#endif
                    }
                }
                si->freeState(s);
            }
            test::Note() << runs << " paths, " << checked << " states checked densely";
        }
    }  // namespace

    TEST(MultiBodyMotion, PlannedSwapPathsAreFreeWhenCheckedDensely)
    {
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        planAndCheckDensely("swap_se2", test::scaled(3));
        planAndCheckDensely("swap_se3", test::scaled(3));
    }
}  // namespace meshgap
