// The robot's OMPL side: the joint-space state space (its layout, bounds and the state <-> numbers map), the
// validity checker against RobotScene, and RRTConnect planning with it on the test tree.
#include <gtest/gtest.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <array>
#include <random>
#include <thread>

#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/UrdfRobot.h"
#include "TestMeshes.h"
#include "robot/TestTree.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace
    {
        ob::RealVectorBounds cube(double half)
        {
            ob::RealVectorBounds b(3);
            b.setLow(-half);
            b.setHigh(half);
            return b;
        }

    }  // namespace

    TEST(RobotOmpl, JointSpaceFollowsTheStateLayout)
    {
        UrdfOptions options;
        options.floatingBase = true;
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF, options);
        const ob::StateSpacePtr space = robotStateSpace(*robot, cube(2.0));
        const auto *compound = space->as<ob::CompoundStateSpace>();
        // SE(3), then wrist_roll (continuous), shoulder + extend (bounded), spin (continuous), tilt (bounded).
        ASSERT_EQ(compound->getSubspaceCount(), 5u);
        EXPECT_NE(dynamic_cast<ob::SE3StateSpace *>(compound->getSubspace(0).get()), nullptr);
        EXPECT_NE(dynamic_cast<ob::SO2StateSpace *>(compound->getSubspace(1).get()), nullptr);
        const auto *bounded = dynamic_cast<ob::RealVectorStateSpace *>(compound->getSubspace(2).get());
        ASSERT_NE(bounded, nullptr);
        ASSERT_EQ(bounded->getDimension(), 2u);
        EXPECT_EQ(bounded->getBounds().low, (std::vector<double>{-2.5, -0.1}));   // the file's limits
        EXPECT_EQ(bounded->getBounds().high, (std::vector<double>{2.5, 0.3}));
        EXPECT_NE(dynamic_cast<ob::SO2StateSpace *>(compound->getSubspace(3).get()), nullptr);
        EXPECT_EQ(space->as<ob::CompoundStateSpace>()->getSubspace(4)->getDimension(), 1u);

        // Numbers -> state -> numbers, and the link poses of both agree.
        const std::vector<double> values = {0.1, -0.2, 0.3, 0.0, 0.6, 0.0, 0.8, 0.4, 1.0, 0.2, -2.0, 0.5};
        ob::State *state = space->allocState();
        robotStateFromVector(*space, values, state);
        std::vector<double> back;
        robotStateToVector(*space, state, back);
        EXPECT_EQ(back, values);
        space->freeState(state);
        EXPECT_THROW(robotStateFromVector(*space, std::vector<double>(11, 0.0), state), Exception);

        const auto two = std::make_shared<MultiBodyRobot>(std::vector<MultiBodyRobot::Part>{
            {"a", Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE2},
            {"b", Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE3}});
        EXPECT_EQ(robotStateSpace(*two, cube(1.0))->as<ob::CompoundStateSpace>()->getSubspaceCount(), 2u);
    }

    TEST(RobotOmpl, CheckerGivesTheRobotScenesAnswers)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF);
        const auto scene = std::make_shared<RobotScene>(robot, test::postsAroundTree());
        auto si = std::make_shared<ob::SpaceInformation>(robotStateSpace(*robot, cube(1.0)));
        const auto checker = std::make_shared<RobotChecker>(si, scene);
        si->setStateValidityChecker(checker);
        si->setup();
        ompl::RNG::setSeed(5);
        ob::StateSamplerPtr sampler = si->allocStateSampler();
        ob::State *state = si->allocState();
        std::vector<double> q;
        std::size_t invalid = 0;
        for (int n = 0; n < 300; ++n)
        {
            sampler->sampleUniform(state);
            robotStateToVector(*si->getStateSpace(), state, q);
            RobotResult expected;
            scene->distance(q, RobotRequest(), expected);
            EXPECT_EQ(checker->clearance(state), expected.distance);
            EXPECT_EQ(checker->isValid(state), !(expected.distance < 0.0));
            invalid += checker->isValid(state) ? 0 : 1;
        }
        si->freeState(state);
        EXPECT_GT(invalid, 10u);
        EXPECT_LT(invalid, 290u);
    }

    TEST(RobotOmpl, ThreadsSharingACheckerGiveTheSingleThreadedAnswers)
    {
        // One RobotChecker queried from 4 threads at once, each visiting the states in its own order (strides
        // coprime to the state count) and asking validity, clearance and the bounded clearances: every answer equals
        // a single-threaded checker's bit for bit (a thread's warm start and working arrays are its own).
        constexpr int THREADS = 4;
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF);
        const auto scene = std::make_shared<RobotScene>(robot, test::postsAroundTree());
        auto si = std::make_shared<ob::SpaceInformation>(robotStateSpace(*robot, cube(1.0)));
        const auto shared = std::make_shared<RobotChecker>(si, scene);
        si->setStateValidityChecker(shared);
        si->setup();
        ompl::RNG::setSeed(5);
        ob::StateSamplerPtr sampler = si->allocStateSampler();
        constexpr std::size_t N = 61;  // prime: every stride visits every state
        std::vector<ob::State *> states(N);
        for (ob::State *&state : states)
        {
            state = si->allocState();
            sampler->sampleUniform(state);
        }
        auto answers = [&si](const RobotChecker &checker, const ob::State *state) {
            return std::array<double, 4>{checker.isValid(state) ? 1.0 : 0.0, checker.clearance(state),
                                         checker.clearanceOrContact(state), checker.clearanceBelow(state, 0.05)};
        };
        std::vector<std::array<double, 4>> expected(N);
        {
            const RobotChecker reference(si, scene);
            for (std::size_t i = 0; i < N; ++i)
                expected[i] = answers(reference, states[i]);
        }
        std::vector<std::vector<std::array<double, 4>>> got(THREADS, std::vector<std::array<double, 4>>(N));
        std::vector<std::thread> threads;
        for (int t = 0; t < THREADS; ++t)
            threads.emplace_back([&, t] {
                for (std::size_t k = 0; k < N; ++k)
                {
                    const std::size_t i = (k * static_cast<std::size_t>(2 * t + 1) + static_cast<std::size_t>(t)) % N;
                    got[t][i] = answers(*shared, states[i]);
                }
            });
        for (std::thread &thread : threads)
            thread.join();
        std::size_t invalid = 0;
        for (std::size_t i = 0; i < N; ++i)
            invalid += expected[i][0] == 0.0;
        EXPECT_GT(invalid, 0u) << "no state collides: the verdicts went untested";
        EXPECT_LT(invalid, N);
        for (int t = 0; t < THREADS; ++t)
            for (std::size_t i = 0; i < N; ++i)
                for (int k = 0; k < 4; ++k)
                    EXPECT_EQ(got[t][i][k], expected[i][k]) << "thread " << t << " state " << i << " answer " << k;
        for (ob::State *state : states)
            si->freeState(state);
    }

    /** \brief RRTConnect on the tree among boxes; with \e certified, RobotMotionValidator validates the motions
        and the whole path is checked densely. */
    static void planTreeAroundTheBoxes(bool certified)
    {
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF);
        // Boxes up to the arm's shoulder: the upper links pass over them, the lower ones must not swing into them.
        const auto scene = std::make_shared<RobotScene>(robot, test::postsAroundTree(0.45));
        og::SimpleSetup setup(robotStateSpace(*robot, cube(1.0)));
        setup.setStateValidityChecker(std::make_shared<RobotChecker>(setup.getSpaceInformation(), scene));
        if (certified)
            setup.getSpaceInformation()->setMotionValidator(
                std::make_shared<RobotMotionValidator>(setup.getSpaceInformation(), scene, *robot));
        // Free states with the shoulder on either side of the boxes, found by a fixed-seed search.
        std::mt19937 rng(2);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        auto freeState = [&](double shoulder)
        {
            for (;;)
            {
                const std::vector<double> q = {u(rng), shoulder + 0.3 * u(rng), 0.1 + 0.2 * u(rng), u(rng), u(rng)};
                RobotResult r;
                scene->distance(q, RobotRequest(), r);
                if (r.distance > 0.01)
                    return q;
            }
        };
        ob::ScopedState<> start(setup.getStateSpace()), goal(setup.getStateSpace());
        robotStateFromVector(*setup.getStateSpace(), freeState(-2.0), start.get());
        robotStateFromVector(*setup.getStateSpace(), freeState(2.0), goal.get());
        setup.setStartAndGoalStates(start, goal);
        setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
        ompl::RNG::setSeed(3);
        setup.setup();
        ASSERT_TRUE(setup.getSpaceInformation()->isValid(start.get()));
        ASSERT_TRUE(setup.getSpaceInformation()->isValid(goal.get()));
        // RRTConnect stops at its first solution: the limit only bounds a run that could not find one, so that a
        // slow machine (a sanitizer build, a loaded core) never fails the test by the clock.
        ASSERT_EQ(setup.solve(300.0), ob::PlannerStatus::EXACT_SOLUTION);
        og::PathGeometric path = setup.getSolutionPath();
        EXPECT_TRUE(path.check());
        if (certified)
            path.interpolate(static_cast<unsigned int>(std::ceil(path.length() / 1e-3)) + 1);
        // Every waypoint is free, by a whole-robot query of its own; with the certified validator, every state of
        // the path at steps of 1e-3 (OMPL's discrete validator only samples at its resolution: it may miss a
        // collision between samples, so its path is checked at its waypoints only).
        // A warm start carried along (the answer is the cold one, Scene's contract): the dense states are close.
        std::vector<double> q;
        RobotWarmStart warm;
        RobotResult r;
        for (ob::State *s : path.getStates())
        {
            robotStateToVector(*setup.getStateSpace(), s, q);
            scene->distance(q.data(), q.size(), RobotRequest(), warm, r);
            EXPECT_GE(r.distance, 0.0);
        }
    }

    TEST(RobotOmpl, RrtConnectPlansTheTreeAroundTheBoxes)
    {
        planTreeAroundTheBoxes(false);
    }

    TEST(RobotOmpl, RrtConnectWithCertifiedMotionsGivesADenselyFreePath)
    {
        planTreeAroundTheBoxes(true);
    }
}  // namespace meshgap
