// The OMPL checker: exact validity (never valid in collision), honest specs, certified clearance equal to the
// brute-force minimum over obstacles, fast mode with a named solver a pure function of the state, fast mode's default
// (warm-fast, warm-started per thread) never below the exact clearance with the exact verdict, and thread safety.

#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>
#include <iostream>
#include <limits>
#include <thread>

#include "TestNote.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/ompl/ClearanceChecker.h"

using namespace meshgap;
namespace ob = ompl::base;

namespace
{
    // A world of several separate parts and an L-shaped (concave) robot.
    struct Fixture
    {
        Mesh world, robot;
        ScenePtr scene;
        ob::SpaceInformationPtr si;

        Fixture()
        {
            world = test::merged(test::merged(test::transformed(test::box(1, 1, 1, 2), test::translation(3, 0, 0)),
                                              test::transformed(test::icosphere(1.2, 2), test::translation(-3, 1, 0))),
                                 test::transformed(test::box(4, 0.3, 2, 3), test::translation(0, -3, 0)));
            robot = test::merged(test::box(0.8, 0.2, 0.2, 2), test::transformed(test::box(0.2, 0.6, 0.2, 2), test::translation(-0.6, 0.4, 0)));
            scene = Scene::fromMeshes(robot, world);
            auto space = test::se3Space(5);
            si = std::make_shared<ob::SpaceInformation>(space);
        }

        std::vector<ob::ScopedState<ob::SE3StateSpace>> randomStates(int n) const
        {
            ompl::RNG::setSeed(7);
            std::vector<ob::ScopedState<ob::SE3StateSpace>> states;
            for (int i = 0; i < n; ++i)
            {
                states.emplace_back(si->getStateSpace());
                states.back().random();
            }
            return states;
        }
    };
}  // namespace

TEST(ClearanceChecker, SpecsSayWhatTheClearanceIs)
{
    Fixture f;
    ClearanceChecker certified(f.si, f.scene, ClearanceChecker::Mode::CERTIFIED);
    ClearanceChecker fast(f.si, f.scene, ClearanceChecker::Mode::FAST);
    EXPECT_EQ(certified.getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::EXACT);
    EXPECT_EQ(fast.getSpecs().clearanceComputationType, ob::StateValidityCheckerSpecs::APPROXIMATE);
    EXPECT_TRUE(certified.getSpecs().hasValidDirectionComputation);
}

#ifdef MESHGAP_HAVE_FCL
TEST(ClearanceChecker, NeverValidInCollisionAndClearanceIsTheExactMinimum)
{
    Fixture f;
    ClearanceChecker checker(f.si, f.scene);
    const auto fw = test::fclModel(f.world), fr = test::fclModel(f.robot);
    int colliding = 0, free = 0;
    for (const auto &s : f.randomStates(400))
    {
        const Eigen::Isometry3d X = poseFromState(*f.si->getStateSpace(), s.get());
        const bool hit = test::fclCollide(fw, fr, X);
        ASSERT_EQ(checker.isValid(s.get()), !hit) << X.matrix();
        double dist = -1.0;
        EXPECT_EQ(checker.isValid(s.get(), dist), !hit);
        if (hit)
        {
            ++colliding;
            EXPECT_LE(checker.clearance(s.get()), 0.0);  // signed: a penetration depth, or 0 where none is computed
            EXPECT_LE(dist, 0.0);
            continue;
        }
        ++free;
        const double exact = test::fclDistance(fw, fr, X);
        EXPECT_NEAR(checker.clearance(s.get()), exact, 1e-9 * (1 + exact));
        EXPECT_NEAR(dist, exact, 1e-9 * (1 + exact));
    }
    EXPECT_GT(colliding, 20);
    EXPECT_GT(free, 20);
}
#endif

#ifdef MESHGAP_HAVE_FCL
// clearance(state, validState, available): from colliding and nearly colliding states, a proposed state is free (FCL),
// within bounds, keeps the rotation, and is clearer than the state it came from.
TEST(ClearanceChecker, ValidStateAwayFromTheNearestObstacleIsFreeAndClearer)
{
    Fixture f;
    ClearanceChecker checker(f.si, f.scene);
    const auto fw = test::fclModel(f.world), fr = test::fclModel(f.robot);
    ob::ScopedState<ob::SE3StateSpace> away(f.si->getStateSpace());
    int colliding = 0, near = 0, collidingFixed = 0, nearFixed = 0;
    for (const auto &s : f.randomStates(600))
    {
        const Eigen::Isometry3d X = poseFromState(*f.si->getStateSpace(), s.get());
        const bool hit = test::fclCollide(fw, fr, X);
        const double before = hit ? 0.0 : test::fclDistance(fw, fr, X);
        if (!hit && before > 0.3)
            continue;  // only colliding and nearly colliding states
        bool available = false;
        const double c = checker.clearance(s.get(), away.get(), available);
        EXPECT_EQ(c <= 0.0, hit);
        (hit ? colliding : near)++;
        if (!available)
            continue;
        (hit ? collidingFixed : nearFixed)++;
        const Eigen::Isometry3d Y = poseFromState(*f.si->getStateSpace(), away.get());
        ASSERT_TRUE(f.si->satisfiesBounds(away.get()));
        ASSERT_FALSE(test::fclCollide(fw, fr, Y)) << X.matrix() << "\n->\n" << Y.matrix();
        EXPECT_GT(test::fclDistance(fw, fr, Y), before);
        EXPECT_TRUE(Y.linear().isApprox(X.linear(), 1e-12));
    }
    EXPECT_GT(colliding, 20);
    EXPECT_GT(near, 10);
    // The direction is useful, not just safe: most states get a valid state (measured: see the counts).
    EXPECT_GT(nearFixed, near * 8 / 10) << nearFixed << " of " << near;
    EXPECT_GT(collidingFixed, colliding / 3) << collidingFixed << " of " << colliding;
    test::Note() << "valid state away: " << collidingFixed << " of " << colliding << " colliding, " << nearFixed << " of "
              << near << " near\n";
}
#endif

TEST(ClearanceChecker, OutOfBoundsIsInvalid)
{
    Fixture f;
    ClearanceChecker checker(f.si, f.scene);
    ob::ScopedState<ob::SE3StateSpace> s(f.si->getStateSpace());
    s->setXYZ(4.5, 4.5, 4.5);
    s->rotation().setIdentity();
    EXPECT_TRUE(checker.isValid(s.get()));
    s->setX(6.0);
    EXPECT_FALSE(checker.isValid(s.get()));
}

TEST(ClearanceChecker, FastModeIsAPureFunctionOfTheStateAndNeverBelowExact)
{
    Fixture f;
    ClearanceChecker fast(f.si, f.scene, ClearanceChecker::Mode::FAST, "comb-GA-wl"), exact(f.si, f.scene);
    const auto states = f.randomStates(60);
    std::vector<double> first;
    for (const auto &s : states)
        first.push_back(fast.clearance(s.get()));
    for (std::size_t i = states.size(); i-- > 0;)  // again, in the other order
        EXPECT_EQ(fast.clearance(states[i].get()), first[i]);
    for (std::size_t i = 0; i < states.size(); ++i)
        EXPECT_GE(first[i], exact.clearance(states[i].get()) - 1e-12);
}

TEST(ClearanceChecker, ThreadsGiveTheSingleThreadedAnswers)
{
    // One checker per mode, queried from 8 threads at once, each visiting the states in its own interleaved order
    // (strides coprime to the state count), validity and clearance mixed: every answer equals the single-threaded
    // one bit for bit. Warm starts are per thread, so a thread's history never leaks into another's answer.
    constexpr int THREADS = 8, ROUNDS = 2;
    Fixture f;
    const auto states = f.randomStates(101);
    for (const ClearanceChecker::Mode mode : {ClearanceChecker::Mode::CERTIFIED, ClearanceChecker::Mode::FAST})
    {
        const bool fast = mode == ClearanceChecker::Mode::FAST;
        // Fast mode with the paper's solver, which is a pure function of the state (warm-fast's answers depend on
        // the thread's history: WarmFastAlongPathsInThreads below).
        ClearanceChecker checker(f.si, f.scene, mode, "comb-GA-wl");
        // Fast clearance runs comb-GA-wl per obstacle pair: fewer states keep the test short.
        const std::size_t n = fast ? 23 : states.size();
        std::vector<double> expected(n);
        std::vector<char> expectedValid(n);
        {
            ClearanceChecker reference(f.si, f.scene, mode, "comb-GA-wl");
            for (std::size_t i = 0; i < n; ++i)
            {
                expected[i] = reference.clearance(states[i].get());
                expectedValid[i] = reference.isValid(states[i].get());
            }
        }
        std::vector<std::vector<double>> got(THREADS, std::vector<double>(n));
        std::vector<std::vector<char>> gotValid(THREADS, std::vector<char>(n));
        std::vector<std::thread> threads;
        for (int t = 0; t < THREADS; ++t)
            threads.emplace_back([&, t] {
                static const std::size_t strides[THREADS] = {1, 2, 3, 4, 5, 6, 7, 8};
                for (int round = 0; round < ROUNDS; ++round)
                    for (std::size_t k = 0; k < n; ++k)
                    {
                        // n is prime, so every stride visits every state once per round.
                        const std::size_t i = (k * strides[t] + static_cast<std::size_t>(round * 17 + t)) % n;
                        if ((k + static_cast<std::size_t>(t)) % 2 == 0)
                        {
                            got[t][i] = checker.clearance(states[i].get());
                            gotValid[t][i] = checker.isValid(states[i].get());
                        }
                        else
                        {
                            // isValid(state, d) asks no depth: in collision d is CONTACT_DISTANCE, the verdict.
                            double d = 0.0;
                            gotValid[t][i] = checker.isValid(states[i].get(), d);
                            got[t][i] = d == CONTACT_DISTANCE && expected[i] < 0.0 ? expected[i] : d;
                        }
                    }
            });
        for (std::thread &t : threads)
            t.join();
        int collisions = 0;
        for (std::size_t i = 0; i < n; ++i)
            collisions += !expectedValid[i];
        if (!fast)
        {
            EXPECT_GT(collisions, 0) << "no state collides: the verdicts went untested";
        }
        for (int t = 0; t < THREADS; ++t)
            for (std::size_t i = 0; i < n; ++i)
            {
                EXPECT_EQ(got[t][i], expected[i]) << (fast ? "fast" : "certified") << " thread " << t << " state " << i;
                EXPECT_EQ(gotValid[t][i], expectedValid[i]) << "thread " << t << " state " << i;
            }
        // Every call counted once, whichever thread made it (the counters are per thread, summed by stats()).
        std::size_t clearanceCalls = 0;
        for (int t = 0; t < THREADS; ++t)
            for (std::size_t k = 0; k < n; ++k)
                clearanceCalls += (k + static_cast<std::size_t>(t)) % 2 == 0 ? ROUNDS : 0;
        const CheckerStats stats = checker.stats();
        EXPECT_EQ(stats.clearanceCalls, clearanceCalls);
        EXPECT_EQ(stats.validityCalls, n * THREADS * ROUNDS);
    }
}

namespace
{
    // Runs of nearby states: OMPL's interpolation between consecutive random states, \e steps per segment.
    std::vector<ob::ScopedState<ob::SE3StateSpace>> pathStates(const Fixture &f, int segments, int steps)
    {
        const auto ends = f.randomStates(segments + 1);
        std::vector<ob::ScopedState<ob::SE3StateSpace>> states;
        for (int k = 0; k < segments; ++k)
            for (int i = 0; i < steps; ++i)
            {
                states.emplace_back(f.si->getStateSpace());
                f.si->getStateSpace()->interpolate(ends[k].get(), ends[k + 1].get(), double(i) / steps,
                                                   states.back().get());
            }
        return states;
    }
}  // namespace

// Fast mode's default solver is warm-fast (the same answers as naming it), each answer at or above the certified
// (exact) clearance and the distance between its own witness points, the verdict exact, and along runs of nearby
// states most answers the exact clearance itself (the surface descent reaches the closest triangles).
TEST(ClearanceChecker, FastModeDefaultsToWarmFastNeverBelowExact)
{
    Fixture f;
    const auto states = pathStates(f, 6, 40);
    ClearanceChecker fast(f.si, f.scene, ClearanceChecker::Mode::FAST),
        named(f.si, f.scene, ClearanceChecker::Mode::FAST, "warm-fast"), exact(f.si, f.scene);
    int free = 0, atExact = 0, colliding = 0;
    for (const auto &s : states)
    {
        const SceneResult r = fast.query(s.get());
        ASSERT_EQ(r.distance, named.clearance(s.get()));
        const SceneResult e = exact.query(s.get());
        ASSERT_EQ(fast.isValid(s.get()), exact.isValid(s.get()));
        ASSERT_EQ(r.inCollision, e.inCollision);
        EXPECT_EQ(r.certified, r.fellBack && e.certified);  // a run's start falls back to the exact query
        if (e.inCollision)
        {
            ++colliding;
            EXPECT_LE(r.distance, 0.0);
            continue;
        }
        ++free;
        EXPECT_GE(r.distance, e.distance - 1e-12);
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-9 * (1.0 + r.distance));
        atExact += r.distance <= e.distance + 1e-9 * (1.0 + e.distance);
    }
    EXPECT_GT(free, 60);
    EXPECT_GT(colliding, 0) << "no state collides: the verdicts went untested";
    EXPECT_GE(2 * atExact, free) << atExact << " of " << free << " free states at the exact clearance";
    test::Note() << "warm-fast at the exact clearance at " << atExact << " of " << free << " free states\n";
}

// Threads each walking the runs with one warm-fast checker: every answer at or above the exact one, every verdict
// exact (a thread's warm start is its own).
TEST(ClearanceChecker, WarmFastAlongPathsInThreads)
{
    constexpr int THREADS = 4;
    Fixture f;
    const auto states = pathStates(f, 4, 30);
    std::vector<double> exactDistance;
    std::vector<char> exactValid;
    {
        ClearanceChecker exact(f.si, f.scene);
        for (const auto &s : states)
        {
            exactDistance.push_back(exact.clearance(s.get()));
            exactValid.push_back(exact.isValid(s.get()));
        }
    }
    ClearanceChecker fast(f.si, f.scene, ClearanceChecker::Mode::FAST);
    std::vector<std::vector<double>> got(THREADS, std::vector<double>(states.size()));
    std::vector<std::vector<char>> gotValid(THREADS, std::vector<char>(states.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < THREADS; ++t)
        threads.emplace_back([&, t] {
            // Thread t walks the runs forwards (even t) or backwards (odd t).
            for (std::size_t k = 0; k < states.size(); ++k)
            {
                const std::size_t i = t % 2 == 0 ? k : states.size() - 1 - k;
                got[t][i] = fast.clearance(states[i].get());
                gotValid[t][i] = fast.isValid(states[i].get());
            }
        });
    for (std::thread &t : threads)
        t.join();
    for (int t = 0; t < THREADS; ++t)
        for (std::size_t i = 0; i < states.size(); ++i)
        {
            EXPECT_EQ(gotValid[t][i], exactValid[i]) << "thread " << t << " state " << i;
            if (exactValid[i])
            {
                EXPECT_GE(got[t][i], exactDistance[i] - 1e-12) << "thread " << t << " state " << i;
            }
            else
            {
                EXPECT_LE(got[t][i], 0.0) << "thread " << t << " state " << i;
            }
        }
}
