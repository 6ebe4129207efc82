// The clearance path optimiser: over many seeds its output is never less clear than its input (measured the same
// way), every motion it accepts into a path is free by a dense exact collision check, it reaches the analytic
// optimum in a corridor, it is repeatable with a seed, and it refuses an invalid input path with a clear error
// (repair off: CertifiedPathRepairTest tests the repair of refused motions).

#include <gtest/gtest.h>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include <filesystem>
#include <tuple>

#include "TestMeshes.h"
#include "TestScale.h"
#include "TestSpaces.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceOptimizingPlanner.h"
#include "meshgap/ompl/ClearancePathOptimizer.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    /** \brief RRTConnect returns at its first exact solution: this limit only ends a search that fails anyway, so
        a busy machine cannot change a verdict. */
    constexpr double SOLVE_LIMIT = 300.0;

    /** \brief The optimiser's rounds (setMaxRounds()) end it, not the clock: the same result on any machine. */
    const ob::PlannerTerminationCondition UNTIL_ROUNDS_END = ob::plannerNonTerminatingCondition();

    /** \brief An SE(3) problem on \e scene in the box [-4, 4]^3, the clearance checker and validator installed. */
    struct PathProblem
    {
        og::SimpleSetupPtr setup;
        ClearanceCheckerPtr checker;
    };

    PathProblem makeProblem(const ScenePtr &scene, double extent = 4.0)
    {
        auto space = test::se3Space(extent);
        PathProblem p;
        p.setup = std::make_shared<og::SimpleSetup>(space);
        const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
        p.checker = std::make_shared<ClearanceChecker>(si, scene);
        p.setup->setStateValidityChecker(p.checker);
        si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si, p.checker));
        return p;
    }

    /** \brief Number of the states at 1/steps of the motion a -> b that collide (exact test). */
    int denseCollisions(const ob::SpaceInformation &si, const Scene &scene, const ob::State *a, const ob::State *b,
                        int steps)
    {
        ob::State *s = si.allocState();
        int collisions = 0;
        for (int k = 0; k <= steps; ++k)
        {
            si.getStateSpace()->interpolate(a, b, static_cast<double>(k) / steps, s);
            collisions += scene.inCollision(poseFromState(*si.getStateSpace(), s));
        }
        si.freeState(s);
        return collisions;
    }

    /** \brief Thin walls with a slot and a post, and an L-shaped robot (the validator test's scene). */
    ScenePtr slotScene()
    {
        const Mesh world =
            test::merged(test::merged(test::transformed(test::box(0.05, 1.2, 2.0, 2), test::translation(0, 1.6, 0)),
                                      test::transformed(test::box(0.05, 1.2, 2.0, 2), test::translation(0, -1.6, 0))),
                         test::transformed(test::box(0.2, 0.2, 2.0, 1), test::translation(-2, 0.5, 0)));
        const Mesh robot =
            test::merged(test::box(0.3, 0.08, 0.08, 1),
                         test::transformed(test::box(0.08, 0.25, 0.08, 1), test::translation(-0.22, 0.17, 0)));
        return Scene::fromMeshes(robot, world);
    }
}  // namespace

TEST(ClearancePathOptimizer, NeverLessClearAndEveryAcceptedMotionIsFree)
{
    const ScenePtr scene = slotScene();
    int raised = 0;
    const int seeds = test::scaled(10, 4);  // raw and simplified inputs either way
    for (int seed = 1; seed <= seeds; ++seed)
    {
        PathProblem p = makeProblem(scene);
        const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
        ob::ScopedState<ob::SE3StateSpace> start(si->getStateSpace()), goal(si->getStateSpace());
        start->setXYZ(-3, -0.5, 0.3);
        start->rotation().setIdentity();
        goal->setXYZ(3, 0.5, -0.3);
        goal->rotation().setAxisAngle(0, 0, 1, 1.0);
        p.setup->setStartAndGoalStates(start, goal);
        p.setup->setPlanner(std::make_shared<og::RRTConnect>(si));
        ompl::RNG::setSeed(seed);
        ASSERT_EQ(p.setup->solve(SOLVE_LIMIT), ob::PlannerStatus::EXACT_SOLUTION) << "seed " << seed;
        if (seed % 2 == 0)
            p.setup->simplifySolution();  // both raw and simplified inputs
        og::PathGeometric path = p.setup->getSolutionPath();

        ClearancePathOptimizer optimizer(si, p.checker);
        optimizer.setMaxRounds(6);
        optimizer.setSeed(static_cast<unsigned long>(seed));
        int accepted = 0;
        optimizer.setAcceptedMotionCallback(
            [&](const ob::State *a, const ob::State *b)
            {
                ++accepted;
                EXPECT_EQ(denseCollisions(*si, *scene, a, b, 200), 0)
                    << "seed " << seed << ": accepted a colliding motion";
            });
        const og::PathGeometric input = path;
        const double before = optimizer.minClearance(input);
        optimizer.optimize(path, UNTIL_ROUNDS_END);
        const double after = optimizer.minClearance(path);
        EXPECT_GE(after, before * (1.0 - 1e-12)) << "seed " << seed;
        EXPECT_NEAR(optimizer.lastStats().minClearanceBefore, before, 1e-9 * (1.0 + before)) << "seed " << seed;
        EXPECT_LE(path.length(), 3.0 * input.length() * (1.0 + 1e-12)) << "seed " << seed;
        raised += after > before + 1e-6;
        EXPECT_GT(accepted, 0) << "seed " << seed;
        // The result: same ends, every state valid, every motion free at a fine step.
        ASSERT_GE(path.getStateCount(), 2u);
        EXPECT_EQ(si->distance(path.getState(0), input.getState(0)), 0.0);
        EXPECT_EQ(si->distance(path.getState(path.getStateCount() - 1), input.getState(input.getStateCount() - 1)),
                  0.0);
        for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
            EXPECT_EQ(denseCollisions(*si, *scene, path.getState(i), path.getState(i + 1), 200), 0) << "seed " << seed;
    }
    // Not a tautology: the planner's paths graze the slot and the post; the optimiser must find room.
    EXPECT_GE(raised, seeds - 2);
}

TEST(ClearancePathOptimizer, ReachesTheMiddleOfACorridor)
{
    // Walls with faces at y = -1 and y = 1, an octahedron of radius 0.5: at the start and goal (centred, unrotated)
    // the clearance is exactly 0.5, which bounds the path's minimum; a path bent towards one wall has 0.1.
    Mesh octahedron;
    octahedron.vertices = {{0.5, 0, 0}, {-0.5, 0, 0}, {0, 0.5, 0}, {0, -0.5, 0}, {0, 0, 0.5}, {0, 0, -0.5}};
    octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    const Mesh walls = test::merged(test::transformed(test::box(4.0, 0.5, 2.0, 2), test::translation(0, 1.5, 0)),
                                    test::transformed(test::box(4.0, 0.5, 2.0, 2), test::translation(0, -1.5, 0)));
    PathProblem p = makeProblem(Scene::fromMeshes(octahedron, walls));
    const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
    si->setup();
    og::PathGeometric path(si);
    ob::ScopedState<ob::SE3StateSpace> s(si->getStateSpace());
    s->rotation().setIdentity();
    for (const auto &xy : {std::pair<double, double>{-3, 0}, {-1, 0.35}, {0, 0.4}, {1, 0.35}, {3, 0}})
    {
        s->setXYZ(xy.first, xy.second, 0);
        path.append(s.get());
    }
    for (bool shortcut : {false, true})
    {
        og::PathGeometric work = path;
        ClearancePathOptimizer optimizer(si, p.checker);
        optimizer.setShortcut(shortcut);
        optimizer.setMaxRounds(200);
        const double before = optimizer.minClearance(work);
        EXPECT_NEAR(before, 0.1, 1e-3);
        EXPECT_TRUE(optimizer.optimize(work, UNTIL_ROUNDS_END));
        const double after = optimizer.minClearance(work);
        EXPECT_GE(after, 0.49) << "shortcut " << shortcut;
        EXPECT_LE(after, 0.5 + 1e-9) << "shortcut " << shortcut;
        EXPECT_LE(work.length(), 3.0 * path.length());
    }
}

TEST(ClearancePathOptimizer, RepeatableWithASeed)
{
    const ScenePtr scene = slotScene();
    PathProblem p = makeProblem(scene);
    const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
    ob::ScopedState<ob::SE3StateSpace> start(si->getStateSpace()), goal(si->getStateSpace());
    start->setXYZ(-3, -0.5, 0.3);
    start->rotation().setIdentity();
    goal->setXYZ(3, 0.5, -0.3);
    goal->rotation().setIdentity();
    p.setup->setStartAndGoalStates(start, goal);
    p.setup->setPlanner(std::make_shared<og::RRTConnect>(si));
    ompl::RNG::setSeed(3);
    ASSERT_EQ(p.setup->solve(SOLVE_LIMIT), ob::PlannerStatus::EXACT_SOLUTION);
    const og::PathGeometric input = p.setup->getSolutionPath();
    std::vector<og::PathGeometric> results;
    for (int run = 0; run < 2; ++run)
    {
        og::PathGeometric path = input;
        ClearancePathOptimizer optimizer(si, p.checker);
        optimizer.setMaxRounds(8);
        optimizer.setSeed(42);
        optimizer.optimize(path, UNTIL_ROUNDS_END);
        results.push_back(path);
    }
    ASSERT_EQ(results[0].getStateCount(), results[1].getStateCount());
    for (std::size_t i = 0; i < results[0].getStateCount(); ++i)
        EXPECT_LT(si->distance(results[0].getState(i), results[1].getState(i)), 1e-9) << i;
}

TEST(ClearancePathOptimizer, RefusesAnInvalidInputPath)
{
    PathProblem p = makeProblem(slotScene());
    const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
    si->setup();
    ClearancePathOptimizer optimizer(si, p.checker);
    optimizer.setRepair(false);  // refused motions throw (CertifiedPathRepairTest covers their repair)
    ob::ScopedState<ob::SE3StateSpace> s(si->getStateSpace());
    s->rotation().setIdentity();
    // Through the wall at x = 0 (y = 2 is inside its upper half): the motion collides, both ends are free.
    og::PathGeometric through(si);
    s->setXYZ(-1, 2, 0);
    through.append(s.get());
    s->setXYZ(1, 2, 0);
    through.append(s.get());
    try
    {
        optimizer.optimize(through);
        ADD_FAILURE() << "no exception for a colliding motion";
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("motion from state 0 to 1"), std::string::npos) << e.what();
    }
    // A state in collision.
    og::PathGeometric inside(si);
    s->setXYZ(-1, 2, 0);
    inside.append(s.get());
    s->setXYZ(0, 2, 0);
    inside.append(s.get());
    try
    {
        optimizer.optimize(inside);
        ADD_FAILURE() << "no exception for a state in collision";
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("state 1 of the input path is in collision"), std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(optimizer.params().setParam("max_length_factor", "2"));
    EXPECT_EQ(optimizer.getMaxLengthFactor(), 2.0);
}

TEST(ClearancePathOptimizer, NeverLessClearOnSlottedWall)
{
    const fs::path cfg = fs::path(MESHGAP_SOURCE_DIR) / "maps" / "slotted_wall" / "slotted_wall.cfg";
    for (int seed = 1; seed <= test::scaled(3); ++seed)
    {
        OmplProblem problem = setupProblem(readProblemConfig(cfg.string()), ClearanceChecker::Mode::CERTIFIED);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si, problem.checker));
        problem.setup->setPlanner(std::make_shared<og::RRTConnect>(si));
        ompl::RNG::setSeed(seed);
        ASSERT_EQ(problem.setup->solve(SOLVE_LIMIT), ob::PlannerStatus::EXACT_SOLUTION) << "seed " << seed;
        problem.setup->simplifySolution();
        og::PathGeometric path = problem.setup->getSolutionPath();
        ClearancePathOptimizer optimizer(si, problem.checker);
        optimizer.setMaxRounds(3);
        int bad = 0;
        optimizer.setAcceptedMotionCallback([&](const ob::State *a, const ob::State *b)
                                            { bad += denseCollisions(*si, *problem.scene, a, b, 100) > 0; });
        const double before = optimizer.minClearance(path);
        optimizer.optimize(path, UNTIL_ROUNDS_END);
        EXPECT_GE(optimizer.minClearance(path), before * (1.0 - 1e-12)) << "seed " << seed;
        EXPECT_EQ(bad, 0) << "seed " << seed;
    }
}

TEST(ClearancePathOptimizer, RrtConnectPlusOptIsOnePlanner)
{
    // allocPlanner("rrtconnect+opt"): RRTConnect, then the optimiser in the same solve(); its path is the
    // optimised one (certified motions, at least as clear as RRTConnect's), and with a FAST checker it is left alone.
    const ScenePtr scene = slotScene();
    for (const ClearanceChecker::Mode mode : {ClearanceChecker::Mode::CERTIFIED, ClearanceChecker::Mode::FAST})
    {
        PathProblem p = makeProblem(scene);
        const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
        if (mode == ClearanceChecker::Mode::FAST)
        {
            p.checker = std::make_shared<ClearanceChecker>(si, scene, mode);
            p.setup->setStateValidityChecker(p.checker);
            si->setMotionValidator(std::make_shared<ob::DiscreteMotionValidator>(si));
        }
        ob::ScopedState<ob::SE3StateSpace> start(si->getStateSpace()), goal(si->getStateSpace());
        start->setXYZ(-3, -0.5, 0.3);
        start->rotation().setIdentity();
        goal->setXYZ(3, 0.5, -0.3);
        goal->rotation().setIdentity();
        p.setup->setStartAndGoalStates(start, goal);
        const ob::PlannerPtr planner = allocPlanner("rrtconnect+opt", si);
        ASSERT_TRUE(planner->params().setParam("optimize_time", "1"));
        p.setup->setPlanner(planner);
        ASSERT_EQ(p.setup->solve(SOLVE_LIMIT), ob::PlannerStatus::EXACT_SOLUTION);
        const auto &stats = std::static_pointer_cast<ClearanceOptimizingPlanner>(planner)->lastStats();
        const og::PathGeometric &path = p.setup->getSolutionPath();
        if (mode == ClearanceChecker::Mode::FAST)
        {
            EXPECT_EQ(stats.rounds, 0u) << "not optimised without a certified checker";
            continue;
        }
        EXPECT_GE(stats.minClearanceAfter, stats.minClearanceBefore);
        EXPECT_EQ(stats.statesAfter, path.getStateCount());
        EXPECT_NEAR(stats.lengthAfter, path.length(), 1e-9 * path.length());
        for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
            EXPECT_EQ(denseCollisions(*si, *scene, path.getState(i), path.getState(i + 1), 100), 0);
    }
}

TEST(ClearancePathOptimizer, ReachesTheMiddleOfACorridorInSe2)
{
    // The corridor of ReachesTheMiddleOfACorridor, in the plane: SE(2) states (x, y, yaw), the robot at z = 0.
    Mesh octahedron;
    octahedron.vertices = {{0.5, 0, 0}, {-0.5, 0, 0}, {0, 0.5, 0}, {0, -0.5, 0}, {0, 0, 0.5}, {0, 0, -0.5}};
    octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    const Mesh walls = test::merged(test::transformed(test::box(4.0, 0.5, 2.0, 2), test::translation(0, 1.5, 0)),
                                    test::transformed(test::box(4.0, 0.5, 2.0, 2), test::translation(0, -1.5, 0)));
    auto space = std::make_shared<ob::SE2StateSpace>();
    ob::RealVectorBounds bounds(2);
    bounds.setLow(-4);
    bounds.setHigh(4);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(octahedron, walls));
    si->setStateValidityChecker(checker);
    si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si, checker));
    si->setup();
    og::PathGeometric path(si);
    ob::ScopedState<ob::SE2StateSpace> s(space);
    for (const auto &[x, y, yaw] :
         {std::tuple<double, double, double>{-3, 0, 0}, {-1, 0.35, 0.3}, {0, 0.4, -0.4}, {1, 0.35, 0.2}, {3, 0, 0}})
    {
        s->setXY(x, y);
        s->setYaw(yaw);
        path.append(s.get());
    }
    ClearancePathOptimizer optimizer(si, checker);
    optimizer.setShortcut(false);
    optimizer.setMaxRounds(200);
    int bad = 0;
    optimizer.setAcceptedMotionCallback([&](const ob::State *a, const ob::State *b)
                                        { bad += denseCollisions(*si, checker->scene(), a, b, 100) > 0; });
    const double before = optimizer.minClearance(path);
    EXPECT_LT(before, 0.2);
    EXPECT_TRUE(optimizer.optimize(path, UNTIL_ROUNDS_END));
    const double after = optimizer.minClearance(path);
    EXPECT_GE(after, 0.49);
    EXPECT_LE(after, 0.5 + 1e-9);  // the ends' clearance
    EXPECT_EQ(bad, 0);
}
