// meshgap's max-min clearance objective against OMPL's own (the oracle: it queries every grid state): the same
// motion costs from fewer queries, and an invalid motion always negative.

#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/util/RandomNumbers.h>

#include "TestNote.h"
#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/Objectives.h"

using namespace meshgap;
namespace ob = ompl::base;

namespace
{
    // Four obstacles (boxes and a sphere, one a thin wall) and an L-shaped robot in a 12-wide box.
    struct World
    {
        ob::SpaceInformationPtr si;
        ScenePtr scene;
        std::shared_ptr<ClearanceChecker> checker;

        World()
        {
            Mesh world = test::merged(test::transformed(test::box(1, 1, 1, 2), test::translation(3, 0, 0)),
                                      test::transformed(test::icosphere(1.2, 2), test::translation(-3, 1, 0)));
            world = test::merged(world, test::transformed(test::box(4, 0.2, 2, 3), test::translation(0, -3, 0)));
            world = test::merged(world, test::transformed(test::box(0.3, 3, 3, 3), test::translation(0, 2.5, 1)));
            const Mesh robot = test::merged(test::box(0.8, 0.2, 0.2, 2),
                                            test::transformed(test::box(0.2, 0.6, 0.2, 2), test::translation(-0.6, 0.4, 0)));
            auto space = test::se3Space(6);
            si = std::make_shared<ob::SpaceInformation>(space);
            scene = Scene::fromMeshes(robot, world);
            checker = std::make_shared<ClearanceChecker>(si, scene);
            si->setStateValidityChecker(checker);
            si->setup();
        }

        /** \brief Random motions whose endpoints are free: as RRT* and PRM* ask for them (a motion from a tree
            state), up to \e range long. */
        std::vector<std::pair<ob::ScopedState<>, ob::ScopedState<>>> motions(int n, double range,
                                                                              bool oneRotation = false) const
        {
            ompl::RNG::setSeed(11);
            std::vector<std::pair<ob::ScopedState<>, ob::ScopedState<>>> out;
            ob::ScopedState<> a(si), b(si), toward(si);
            while (static_cast<int>(out.size()) < n)
            {
                a.random();
                toward.random();
                if (oneRotation)  // translations only, all at the identity rotation
                    for (ob::ScopedState<> *s : {&a, &toward})
                        (*s)->as<ob::SE3StateSpace::StateType>()->rotation().setIdentity();
                const double d = si->distance(a.get(), toward.get());
                si->getStateSpace()->interpolate(a.get(), toward.get(), std::min(1.0, range / d), b.get());
                if (checker->isValid(a.get()) && checker->isValid(b.get()))
                    out.emplace_back(a, b);
            }
            return out;
        }
    };
}  // namespace

TEST(MaxMinClearanceObjective, SameCostsAsOmplsObjectiveFromFewerQueries)
{
    World w;
    MaxMinClearanceObjective ours(w.si);
    ob::MaximizeMinClearanceObjective ompls(w.si);
    int free = 0, invalid = 0, interiorMinimum = 0;
    auto motions = w.motions(250, 6.0);
    for (auto &m : w.motions(100, 6.0, true))  // many states with one rotation: a cache keyed on it alone would fail
        motions.push_back(std::move(m));
    for (const auto &[a, b] : motions)
    {
        const double expected = ompls.motionCost(a.get(), b.get()).value();
        const double got = ours.motionCost(a.get(), b.get()).value();
        if (expected > 0.0)
        {
            ++free;
            // Both are the minimum over the same grid states, each an exact distance (to roundoff).
            ASSERT_NEAR(got, expected, 1e-9 * (1.0 + expected));
            interiorMinimum += expected < w.checker->clearance(b.get()) - 1e-9;
        }
        else
        {
            ++invalid;
            EXPECT_LE(got, 0.0);  // a grid state in collision: the motion costs a negative value, never a clearance
        }
    }
    EXPECT_GT(free, 50);
    EXPECT_GT(invalid, 50);
    EXPECT_GT(interiorMinimum, 20);  // the pruning had minima between the endpoints to find
    EXPECT_LT(ours.queriedStates(), ours.gridStates());
    test::Note() << "[          ] " << free << " free and " << invalid << " invalid motions: " << ours.queriedStates()
              << " states queried for " << ours.gridStates() << " grid states\n";
}

TEST(MaxMinClearanceObjective, FollowsTheCheckerInstalledNowAndIsOmplsWithAnyOther)
{
    // As a benchmark does: the objective is made with one checker, then others are installed in the space.
    World w;
    MaxMinClearanceObjective ours(w.si);
    ob::MaximizeMinClearanceObjective ompls(w.si);
    const auto motions = w.motions(40, 6.0);
    auto other = std::make_shared<ClearanceChecker>(w.si, w.scene);
    const auto fast = std::make_shared<ClearanceChecker>(w.si, w.scene,
                                                         ClearanceChecker::Mode::FAST);
    const ob::StateValidityCheckerPtr notMeshgap =
        std::make_shared<ob::AllValidStateValidityChecker>(w.si);  // clearance() is 0 everywhere
    for (const ob::StateValidityCheckerPtr &checker : {ob::StateValidityCheckerPtr(other),
                                                       ob::StateValidityCheckerPtr(fast), notMeshgap})
    {
        w.si->setStateValidityChecker(checker);
        const CheckerStats before = other->stats();
        // Fast mode's cold node searches are slow: a few motions show it is OMPL's objective there.
        const std::size_t count = checker == fast ? 3 : motions.size();
        for (std::size_t i = 0; i < count; ++i)
        {
            const auto &[a, b] = motions[i];
            const double expected = ompls.motionCost(a.get(), b.get()).value();
            const double got = ours.motionCost(a.get(), b.get()).value();
            if (expected > 0.0)
            {
                ASSERT_NEAR(got, expected, 1e-9 * (1.0 + expected));
            }
            else
            {
                EXPECT_LE(got, 0.0);
            }
        }
        // The installed meshgap checker answered (its own counters), not the one the objective was made with.
        if (checker == other)
        {
            EXPECT_GT(other->stats().clearanceCalls, before.clearanceCalls);
        }
    }
}
