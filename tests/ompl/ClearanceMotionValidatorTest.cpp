// The clearance motion validator never accepts a motion that collides (checked densely at 1/1000 of each motion
// with the exact collision test), and how it compares with OMPL's DiscreteMotionValidator.

#include <gtest/gtest.h>

#include <cstdio>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"

using namespace meshgap;
namespace ob = ompl::base;

TEST(ClearanceMotionValidator, NeverAcceptsAMotionThatCollides)
{
    // Thin walls and posts (easy to jump over between discrete samples) and an L-shaped robot.
    const Mesh world = test::merged(test::merged(test::transformed(test::box(0.05, 2.0, 2.0, 2), test::translation(0, 0, 0)),
                                                 test::transformed(test::box(0.1, 0.1, 2.0, 1), test::translation(-2, 1.5, 0))),
                                    test::transformed(test::box(2.0, 0.05, 2.0, 2), test::translation(0, -2.5, 0)));
    const Mesh robot = test::merged(test::box(0.5, 0.1, 0.1, 1), test::transformed(test::box(0.1, 0.4, 0.1, 1), test::translation(-0.4, 0.3, 0)));
    const ScenePtr scene = Scene::fromMeshes(robot, world);
    auto space = test::se3Space(4);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<ClearanceChecker>(si, scene);
    si->setStateValidityChecker(checker);
    si->setup();
    ClearanceMotionValidator validator(si, checker);
    ob::DiscreteMotionValidator discrete(si);

    ompl::RNG::setSeed(11);
    ob::ScopedState<ob::SE3StateSpace> s1(space), s2(space), s(space);
    int motions = 0, accepted = 0, rejectedFree = 0, discreteMisses = 0, refusedByProbes = 0;
    std::uint64_t discreteChecks = 0, queries = 0, probes = 0;
    while (motions < 1500)
    {
        s1.random();
        if (!checker->isValid(s1.get()))
            continue;
        s2.random();
        // Mostly short motions (as planners make), some long ones.
        if (motions % 4 != 0)
            space->interpolate(s1.get(), s2.get(), 0.15, s2.get());
        ++motions;
        // Dense exact check at 1/1000 of the motion: the oracle.
        bool collides = false;
        for (int k = 0; k <= 1000 && !collides; ++k)
        {
            space->interpolate(s1.get(), s2.get(), k / 1000.0, s.get());
            collides = scene->inCollision(poseFromState(*space, s.get()));
        }
        const std::uint64_t queriesBefore = validator.queries(), probesBefore = validator.probes();
        const bool ok = validator.checkMotion(s1.get(), s2.get());
        ASSERT_FALSE(ok && collides) << "motion " << motions << " accepted but collides";
        queries += validator.queries() - queriesBefore;
        probes += validator.probes() - probesBefore;
        refusedByProbes += !ok && validator.queries() == queriesBefore;
        accepted += ok;
        rejectedFree += !ok && !collides;
        const std::uint64_t callsBefore = checker->stats().validityCalls;
        const bool discreteOk = discrete.checkMotion(s1.get(), s2.get());
        discreteChecks += checker->stats().validityCalls - callsBefore;
        discreteMisses += discreteOk && collides;
        // lastValid: the state reported is collision-free and lies on the motion.
        // The lastValid version advances without probing first: the probes must not change the answer.
        std::pair<ob::State *, double> last(s.get(), -1.0);
        const bool advanced = validator.checkMotion(s1.get(), s2.get(), last);
        ASSERT_EQ(advanced, ok) << "motion " << motions;
        if (!advanced)
        {
            EXPECT_GE(last.second, 0.0);
            EXPECT_LT(last.second, 1.0);
            EXPECT_TRUE(checker->isValid(s.get()));
        }
    }
    std::printf("motions %d: accepted %d, refused though free %d, refused by a probe %d; clearance queries %llu and "
                "probes %llu vs discrete state checks %llu; collisions the discrete validator missed: %d\n",
                motions, accepted, rejectedFree, refusedByProbes, static_cast<unsigned long long>(queries),
                static_cast<unsigned long long>(probes), static_cast<unsigned long long>(discreteChecks),
                discreteMisses);
    EXPECT_GT(accepted, 300);        // it does certify motions, not just refuse them
    EXPECT_GT(refusedByProbes, 100);  // and the probes refuse colliding ones before any advancing
}

TEST(ClearanceMotionValidator, NeedsACertifiedChecker)
{
    auto space = test::se3Space(1);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    const ScenePtr scene = Scene::fromMeshes(test::box(0.1, 0.1, 0.1, 1), test::transformed(test::box(0.1, 0.1, 0.1, 1), test::translation(1, 0, 0)));
    auto fast = std::make_shared<ClearanceChecker>(si, scene, ClearanceChecker::Mode::FAST);
    EXPECT_THROW(ClearanceMotionValidator(si, fast), std::exception);
}

TEST(ClearanceMotionValidator, TheAdvanceQueryGivesTheFullQuerysVerdictAndFreeClearanceWithoutTheDepth)
{
    // What the advance asks (ClearanceChecker::query with computeDepth false) against the full query, at random
    // states (seeded) around a thick box: the same verdict, the same distance where free, and in collision the
    // verdict alone (no depth computed: CONTACT_DISTANCE, NOT_COMPUTED) where the full query measures a depth.
    const ScenePtr scene = Scene::fromMeshes(test::box(0.4, 0.3, 0.2, 2), test::box(1.0, 1.0, 1.0, 2));
    auto space = test::se3Space(2);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<ClearanceChecker>(si, scene);
    si->setStateValidityChecker(checker);
    si->setup();
    SceneRequest verdict;
    verdict.computeDepth = false;
    ob::ScopedState<ob::SE3StateSpace> s(space);
    int colliding = 0, free = 0;
    for (int i = 0; i < 300; ++i)
    {
        // Seeded: the same states in any test order.
        stateFromPose(*space, test::randomPose(500 + i, 1.6), s.get());
        const SceneResult full = checker->query(s.get()), quick = checker->query(s.get(), verdict);
        ASSERT_EQ(quick.inCollision, full.inCollision) << i;
        if (full.inCollision)
        {
            ++colliding;
            EXPECT_NE(full.penetration, Penetration::NOT_COMPUTED) << i;
            EXPECT_EQ(quick.penetration, Penetration::NOT_COMPUTED) << i;
            EXPECT_EQ(quick.distance, CONTACT_DISTANCE) << i;
        }
        else
        {
            ++free;
            EXPECT_EQ(quick.distance, full.distance) << i;
        }
    }
    EXPECT_GT(colliding, 20);
    EXPECT_GT(free, 20);
}
