// Repairing a path whose motions the certified motion validator refuses, as a planner with OMPL's sampled validator
// returns them: a motion clipping the edge of a thin plate and one passing through its middle, both between free
// states that a sampled check at eighths of the motion finds free. The repaired path's every motion is certified by
// a fresh validator and free by a dense exact check (and by FCL), and the optimiser then raises its minimum
// clearance; a motion into an enclosed state cannot be repaired and the error names it.

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <array>
#include <string>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/CertifiedPathRepair.h"
#include "meshgap/ompl/ClearancePathOptimizer.h"

using namespace meshgap;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace
{
    /** \brief A plate 0.02 thick (x in [-0.01, 0.01], y and z in [-1, 1]) and a 0.1 x 0.2 x 0.2 box robot, in SE(3)
        or SE(2) (the robot in the plane z = 0), bounds [-4, 4]; optionally a closed box of six thin walls around
        (2.5, 2.5, 0), inner half-size 0.4. */
    struct PlateProblem
    {
        Mesh world, robot;
        ScenePtr scene;
        ob::SpaceInformationPtr si;
        ClearanceCheckerPtr checker;

        PlateProblem(bool planar, bool enclosure)
        {
            world = test::box(0.01, 1.0, 1.0, 2);
            if (enclosure)
                for (int axis = 0; axis < 3; ++axis)
                    for (double side : {-1.0, 1.0})
                    {
                        std::array<double, 3> half{0.43, 0.43, 0.43}, at{2.5, 2.5, 0.0};
                        half[axis] = 0.015;
                        at[axis] += side * 0.415;
                        world = test::merged(world, test::transformed(test::box(half[0], half[1], half[2], 1),
                                                                      test::translation(at[0], at[1], at[2])));
                    }
            robot = test::box(0.05, 0.1, 0.1, 1);
            scene = Scene::fromMeshes(robot, world);
            ob::StateSpacePtr space;
            if (planar)
            {
                auto se2 = std::make_shared<ob::SE2StateSpace>();
                ob::RealVectorBounds bounds(2);
                bounds.setLow(-4);
                bounds.setHigh(4);
                se2->setBounds(bounds);
                space = se2;
            }
            else
                space = test::se3Space(4.0);
            si = std::make_shared<ob::SpaceInformation>(space);
            checker = std::make_shared<ClearanceChecker>(si, scene);
            si->setStateValidityChecker(checker);
            si->setup();
        }

        /** \brief The path through (x, y) points at z = 0, yaw 0 / identity rotation. */
        og::PathGeometric path(const std::vector<std::array<double, 2>> &points) const
        {
            og::PathGeometric p(si);
            ob::State *s = si->allocState();
            for (const auto &xy : points)
            {
                if (si->getStateSpace()->getType() == ob::STATE_SPACE_SE2)
                {
                    auto *se2 = s->as<ob::SE2StateSpace::StateType>();
                    se2->setXY(xy[0], xy[1]);
                    se2->setYaw(0.0);
                }
                else
                {
                    auto *se3 = s->as<ob::SE3StateSpace::StateType>();
                    se3->setXYZ(xy[0], xy[1], 0.0);
                    se3->rotation().setIdentity();
                }
                p.append(s);
            }
            si->freeState(s);
            return p;
        }

        /** \brief States of motion a -> b that collide, at 1/steps of it, by the scene's exact test. */
        int denseCollisions(const ob::State *a, const ob::State *b, int steps) const
        {
            ob::State *s = si->allocState();
            int collisions = 0;
            for (int k = 0; k <= steps; ++k)
            {
                si->getStateSpace()->interpolate(a, b, static_cast<double>(k) / steps, s);
                collisions += scene->inCollision(poseFromState(*si->getStateSpace(), s));
            }
            si->freeState(s);
            return collisions;
        }

        /** \brief What OMPL's sampled validator would check with 8 segments: the states at k / 8 all free. */
        bool eighthsFree(const ob::State *a, const ob::State *b) const
        {
            ob::State *s = si->allocState();
            bool free = true;
            for (int k = 0; k <= 8; ++k)
            {
                si->getStateSpace()->interpolate(a, b, k / 8.0, s);
                free = free && checker->isValid(s);
            }
            si->freeState(s);
            return free;
        }

        /** \brief Every motion certified by a fresh validator, and free at 1/400 of it by the exact test and by
            FCL; reports which fails. */
        void expectCertifiedAndFree(const og::PathGeometric &p, const std::string &what) const
        {
            ClearanceMotionValidator validator(si, checker);
#ifdef MESHGAP_HAVE_FCL
            const auto fw = test::fclModel(world), fr = test::fclModel(robot);
#endif
            ob::State *s = si->allocState();
            for (std::size_t i = 0; i + 1 < p.getStateCount(); ++i)
            {
                EXPECT_TRUE(validator.checkMotion(p.getState(i), p.getState(i + 1))) << what << ": motion " << i;
                EXPECT_EQ(denseCollisions(p.getState(i), p.getState(i + 1), 400), 0) << what << ": motion " << i;
#ifdef MESHGAP_HAVE_FCL
                int fclHits = 0;
                for (int k = 0; k <= 400; ++k)
                {
                    si->getStateSpace()->interpolate(p.getState(i), p.getState(i + 1), k / 400.0, s);
                    fclHits += test::fclCollide(fw, fr, poseFromState(*si->getStateSpace(), s));
                }
                EXPECT_EQ(fclHits, 0) << what << ": motion " << i << " (FCL)";
#endif
            }
            si->freeState(s);
        }
    };

    const ob::PlannerTerminationCondition NEVER = ob::plannerNonTerminatingCondition();
}  // namespace

TEST(CertifiedPathRepair, BisectsAMotionClippingAThinPlatesEdge)
{
    for (bool planar : {false, true})
    {
        const std::string what = planar ? "SE(2)" : "SE(3)";
        PlateProblem problem(planar, false);
        // The robot (y in [0.98, 1.18] at y = 1.08) clips the plate's edge (y <= 1) by 0.02 for |x| < 0.06; the
        // states at eighths of the motion (x = -1.1 + 0.25 k) miss it.
        const og::PathGeometric input = problem.path({{-1.1, 1.08}, {0.9, 1.08}});
        ASSERT_TRUE(problem.eighthsFree(input.getState(0), input.getState(1))) << what;
        ASSERT_GT(problem.denseCollisions(input.getState(0), input.getState(1), 400), 0) << what;
        ClearanceMotionValidator validator(problem.si, problem.checker);
        ASSERT_FALSE(validator.checkMotion(input.getState(0), input.getState(1))) << what;

        og::PathGeometric repaired = input;
        CertifiedPathRepair repair(problem.si, problem.checker);
        repair.setReplan(false);  // bisection alone
        EXPECT_TRUE(repair.repair(repaired, NEVER)) << what;
        EXPECT_EQ(repair.lastStats().refused, 1u) << what;
        EXPECT_EQ(repair.lastStats().bisected, 1u) << what;
        EXPECT_EQ(repair.lastStats().inserted + 2, repaired.getStateCount()) << what;
        EXPECT_EQ(problem.si->distance(repaired.getState(0), input.getState(0)), 0.0) << what;
        EXPECT_EQ(problem.si->distance(repaired.getState(repaired.getStateCount() - 1), input.getState(1)), 0.0);
        problem.expectCertifiedAndFree(repaired, what + " repaired");

        // The optimiser repairs the same way, then raises the repaired path's minimum clearance.
        og::PathGeometric optimised = input;
        ClearancePathOptimizer optimizer(problem.si, problem.checker);
        optimizer.setMaxRounds(30);
        optimizer.setTimeLimit(120.0);  // the rounds end it
        const double repairedClearance = optimizer.minClearance(repaired);
        optimizer.optimize(optimised);
        EXPECT_EQ(optimizer.lastStats().repair.bisected, 1u) << what;
        EXPECT_NEAR(optimizer.lastStats().minClearanceBefore, repairedClearance, 1e-9) << what;
        problem.expectCertifiedAndFree(optimised, what + " optimised");
        const double after = optimizer.minClearance(optimised);
        EXPECT_GT(after, repairedClearance + 0.05) << what << ": from " << repairedClearance;
    }
}

TEST(CertifiedPathRepair, ReplansAMotionThroughAThinPlate)
{
    for (bool planar : {false, true})
    {
        const std::string what = planar ? "SE(2)" : "SE(3)";
        PlateProblem problem(planar, false);
        // Straight through the plate's middle: no push of a middle state gets round it, the replanning must.
        const og::PathGeometric input = problem.path({{-2.0, -2.0}, {-1.1, 0.0}, {0.9, 0.0}, {2.0, 1.5}});
        ASSERT_TRUE(problem.eighthsFree(input.getState(1), input.getState(2))) << what;
        ASSERT_GT(problem.denseCollisions(input.getState(1), input.getState(2), 400), 0) << what;

        og::PathGeometric repaired = input;
        CertifiedPathRepair repair(problem.si, problem.checker);
        EXPECT_TRUE(repair.repair(repaired, ob::timedPlannerTerminationCondition(60.0))) << what;
        EXPECT_EQ(repair.lastStats().refused, 1u) << what;
        EXPECT_EQ(repair.lastStats().replanned, 1u) << what
                                                    << ": pushing a middle state out along the plate's "
                                                       "normal never gets round it";
        problem.expectCertifiedAndFree(repaired, what + " repaired");
        // The other motions are kept: the input's states are all in the repaired path, in order.
        std::size_t next = 0;
        for (std::size_t k = 0; k < repaired.getStateCount() && next < input.getStateCount(); ++k)
            next += problem.si->distance(repaired.getState(k), input.getState(next)) == 0.0;
        EXPECT_EQ(next, input.getStateCount()) << what;

        og::PathGeometric optimised = input;
        ClearancePathOptimizer optimizer(problem.si, problem.checker);
        optimizer.setMaxRounds(30);
        optimizer.setTimeLimit(120.0);
        optimizer.optimize(optimised);
        EXPECT_EQ(optimizer.lastStats().repair.refused, 1u) << what;
        problem.expectCertifiedAndFree(optimised, what + " optimised");
        EXPECT_GT(optimizer.minClearance(optimised), optimizer.lastStats().minClearanceBefore + 0.05) << what;
        EXPECT_GT(optimizer.lastStats().minClearanceAfter, optimizer.lastStats().minClearanceBefore) << what;
    }
}

TEST(CertifiedPathRepair, NamesTheMotionItCannotRepair)
{
    PlateProblem problem(false, true);
    // State 2 is free, inside a closed box: no certified motion reaches it.
    const og::PathGeometric input = problem.path({{-2.0, -2.0}, {1.5, -1.0}, {2.5, 2.5}});
    ASSERT_TRUE(problem.checker->isValid(input.getState(2)));
    og::PathGeometric path = input;
    ClearancePathOptimizer optimizer(problem.si, problem.checker);
    optimizer.setTimeLimit(1.0);
    try
    {
        optimizer.optimize(path);
        ADD_FAILURE() << "no exception for a motion into a closed box";
    }
    catch (const Exception &e)
    {
        const std::string message = e.what();
        EXPECT_NE(message.find("motion 1→2 "), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
    ASSERT_EQ(path.getStateCount(), input.getStateCount()) << "the path is left as it was";
    for (std::size_t i = 0; i < input.getStateCount(); ++i)
        EXPECT_EQ(problem.si->distance(path.getState(i), input.getState(i)), 0.0);

    // With repair off, the refused motion throws at once, as before.
    optimizer.setRepair(false);
    try
    {
        optimizer.optimize(path);
        ADD_FAILURE() << "no exception with repair off";
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("motion from state 1 to 2"), std::string::npos) << e.what();
    }
}
