// Certified joint-space motions on maps/arm_fixture (the arm carrying its C-shaped payload by the fixture's window):
// every motion the certified motion validator accepts, checked at steps of at most 1e-4 rad by the exact collision
// test (every link against the fixture, every self pair, containment included), must be free. The count of accepted
// motions is MESHGAP_ARM_MOTIONS (default 300, a few seconds; bench/robots.md records a run of 10,000).
#include <gtest/gtest.h>

#include <ompl/base/SpaceInformation.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/UrdfRobot.h"
#include "TestNote.h"
#include "TestScale.h"

namespace ob = ompl::base;

namespace meshgap
{
    TEST(ArmMotionSampling, CertifiedMotionsAreFreeAtEveryTenThousandthOfARadian)
    {
        const char *env = std::getenv("MESHGAP_ARM_MOTIONS");
        const long wanted = env ? std::atol(env) : test::scaled(300);  // 300 by default, scaled by test::scale()
        ASSERT_GT(wanted, 0) << "MESHGAP_ARM_MOTIONS must be a positive count";
        const RobotProblem p = readRobotProblem(std::string(MESHGAP_SOURCE_DIR) + "/maps/arm_fixture/arm_fixture.cfg");
        const auto scene = std::make_shared<RobotScene>(p.robot, p.obstacles);
        const auto &urdf = dynamic_cast<const UrdfRobot &>(*p.robot);
        ob::RealVectorBounds bounds(3);
        bounds.setLow(-1);
        bounds.setHigh(1);
        auto si = std::make_shared<ob::SpaceInformation>(robotStateSpace(urdf, bounds));
        si->setStateValidityChecker(std::make_shared<RobotChecker>(si, scene));
        const auto validator = std::make_shared<RobotMotionValidator>(si, scene, urdf);
        si->setMotionValidator(validator);
        si->setup();

        // Start states facing the fixture (yaw within 0.6 rad of it), within every joint's limits, near contact;
        // motions of up to 0.25 rad per joint from there.
        std::mt19937 rng(11);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const std::vector<double> half = {0.6, 2.0, 2.5, 2.0};
        ob::State *a = si->allocState(), *b = si->allocState();
        RobotWarmStart warm;
        RobotRequest near;
        near.upperBound = 0.05;
        RobotResult result;
        long accepted = 0, rejected = 0, colliding = 0, states = 0;
        std::vector<double> qa(4), qb(4), q(4);
        while (accepted < wanted)
        {
            for (std::size_t k = 0; k < 4; ++k)
            {
                qa[k] = half[k] * u(rng);
                qb[k] = std::clamp(qa[k] + 0.25 * u(rng), -half[k], half[k]);
            }
            // Only motions that start near contact (some pair within 0.05) say much: most of the joint space is
            // far from the fixture.
            scene->distance(qa.data(), 4, near, warm, result);
            if (result.inCollision || result.atLeast || scene->inCollision(qb.data(), 4, warm))
                continue;
            robotStateFromVector(*si->getStateSpace(), qa, a);
            robotStateFromVector(*si->getStateSpace(), qb, b);
            if (!validator->checkMotion(a, b))
            {
                ++rejected;
                continue;
            }
            ++accepted;
            double largest = 0.0;
            for (std::size_t k = 0; k < 4; ++k)
                largest = std::max(largest, std::abs(qb[k] - qa[k]));
            const auto n = static_cast<long>(std::ceil(largest / 1e-4));
            for (long s = 0; s <= n; ++s)
            {
                for (std::size_t k = 0; k < 4; ++k)
                    q[k] = qa[k] + (qb[k] - qa[k]) * static_cast<double>(s) / n;
                colliding += scene->inCollision(q.data(), 4, warm);
            }
            states += n + 1;
        }
        si->freeState(a);
        si->freeState(b);
        EXPECT_EQ(colliding, 0);
        test::Note() << accepted << " certified motions (" << rejected << " rejected), " << states
                     << " states checked at <= 1e-4 rad, " << colliding << " colliding";
    }
}  // namespace meshgap
