// The OMPL checker: exact validity (never valid in collision), honest specs, certified clearance equal to the
// brute-force minimum over obstacles, a fast mode that is a pure function of the state, and thread safety.

#include <gtest/gtest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>
#include <thread>

#include "FclOracle.h"
#include "TestMeshes.h"
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
            auto space = std::make_shared<ob::SE3StateSpace>();
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-5);
            bounds.setHigh(5);
            space->setBounds(bounds);
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
            EXPECT_EQ(checker.clearance(s.get()), 0.0);
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
    ClearanceChecker fast(f.si, f.scene, ClearanceChecker::Mode::FAST), exact(f.si, f.scene);
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
    Fixture f;
    ClearanceChecker checker(f.si, f.scene);
    const auto states = f.randomStates(120);
    std::vector<double> expected;
    std::vector<char> expectedValid;
    for (const auto &s : states)
    {
        expected.push_back(checker.clearance(s.get()));
        expectedValid.push_back(checker.isValid(s.get()));
    }
    std::vector<std::vector<double>> got(4, std::vector<double>(states.size()));
    std::vector<std::vector<char>> gotValid(4, std::vector<char>(states.size()));
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int round = 0; round < 3; ++round)
                for (std::size_t k = 0; k < states.size(); ++k)
                {
                    // Interleaved orders: strides coprime to the state count visit every state once per round.
                    static const std::size_t strides[4] = {1, 7, 11, 13};
                    const std::size_t i = (k * strides[t] + round * 17) % states.size();
                    got[t][i] = checker.clearance(states[i].get());
                    gotValid[t][i] = checker.isValid(states[i].get());
                }
        });
    for (std::thread &t : threads)
        t.join();
    for (int t = 0; t < 4; ++t)
        for (std::size_t i = 0; i < states.size(); ++i)
        {
            EXPECT_EQ(got[t][i], expected[i]) << "thread " << t << " state " << i;
            EXPECT_EQ(gotValid[t][i], expectedValid[i]);
        }
    const CheckerStats stats = checker.stats();
    EXPECT_EQ(stats.clearanceCalls, states.size() * 13);
}
