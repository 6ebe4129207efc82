// No whole-robot query allocates once warmed up on a thread: RobotScene::distance() (pruned, every pair, with an
// early stop, in collision) and RobotScene::inCollision(), for a kinematic tree carrying a payload among obstacles,
// along a joint-space path, and RobotMotionValidator::checkMotion() along its motions. The global allocation
// functions are replaced and counted per thread (as QueryAllocations.cpp does); each mode runs the path once to warm
// up, then once more counted, and the second pass must allocate nothing and give the same answers. Not built under
// sanitizers.

#include <gtest/gtest.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "TestMeshes.h"
#include "robot/TestTree.h"
#include "alloc/ThreadAllocations.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/UrdfRobot.h"

namespace meshgap
{
    namespace
    {
        class RobotQueryAllocations : public ::testing::Test
        {
        protected:
            static void SetUpTestSuite()
            {
                const UrdfRobotPtr robot = test::treeWithPayload();
                // Boxes around the arm's sweep: the path passes near and through them.
                const std::vector<BodyConstPtr> obstacles = test::postsAroundTree();
                scene_ = std::make_shared<RobotScene>(robot, obstacles);
            }
            static void TearDownTestSuite() { scene_.reset(); }

            /** \brief A joint-space path of small steps: the shoulder sweeps a full turn, the others swing. */
            static std::vector<std::vector<double>> path()
            {
                std::vector<std::vector<double>> states;
                for (int k = 0; k < 120; ++k)
                {
                    const double t = k / 120.0;
                    states.push_back({3 * t, -2.5 + 5 * t, 0.1 + 0.2 * std::sin(6 * t), 4 * t, std::sin(9 * t)});  // within the limits
                }
                return states;
            }

            /** \brief Allocations of the second pass of \e request along path(); the passes' answers must agree, and
                the path must meet collisions and free states both. */
            static std::size_t allocationsAfterWarmUp(const RobotRequest &request)
            {
                const std::vector<std::vector<double>> states = path();
                std::vector<double> first, second;
                first.reserve(states.size());
                second.reserve(states.size());
                RobotWarmStart warm;
                RobotResult result;
                std::size_t counted = 0, collisions = 0;
                for (int pass = 0; pass < 2; ++pass)
                {
                    warm.reset();
                    for (const std::vector<double> &q : states)
                    {
                        const std::size_t before = test::threadAllocations();
                        scene_->distance(q.data(), q.size(), request, warm, result);
                        counted += pass == 1 ? test::threadAllocations() - before : 0;
                        (pass == 0 ? first : second).push_back(result.distance);
                        collisions += pass == 1 && result.inCollision;
                    }
                }
                EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
                EXPECT_GT(collisions, 0u);
                EXPECT_LT(collisions, states.size());
                return counted;
            }

            static RobotScenePtr scene_;
        };

        RobotScenePtr RobotQueryAllocations::scene_;

        TEST_F(RobotQueryAllocations, Pruned)
        {
            EXPECT_EQ(allocationsAfterWarmUp(RobotRequest()), 0u);
        }

        TEST_F(RobotQueryAllocations, EveryPair)
        {
            RobotRequest request;
            request.everyPair = true;
            EXPECT_EQ(allocationsAfterWarmUp(request), 0u);
        }

        TEST_F(RobotQueryAllocations, EarlyStop)
        {
            RobotRequest request;
            request.stopBelow = 0.01;
            EXPECT_EQ(allocationsAfterWarmUp(request), 0u);
        }

        TEST_F(RobotQueryAllocations, CollisionVerdict)
        {
            const std::vector<std::vector<double>> states = path();
            RobotWarmStart warm;
            std::size_t counted = 0, collisions = 0;
            for (int pass = 0; pass < 2; ++pass)
            {
                warm.reset();  // each pass starts afresh, with the memory the first one grew
                for (const std::vector<double> &q : states)
                {
                    const std::size_t before = test::threadAllocations();
                    const bool hit = scene_->inCollision(q.data(), q.size(), warm);
                    counted += pass == 1 ? test::threadAllocations() - before : 0;
                    collisions += pass == 1 && hit;
                }
            }
            EXPECT_EQ(counted, 0u);
            EXPECT_GT(collisions, 0u);
        }

        TEST_F(RobotQueryAllocations, MotionValidator)
        {
            namespace ob = ompl::base;
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-1.0);
            bounds.setHigh(1.0);
            const auto si = std::make_shared<ob::SpaceInformation>(robotStateSpace(scene_->robot(), bounds));
            si->setStateValidityChecker([](const ob::State *) { return true; });
            const auto validator = std::make_shared<RobotMotionValidator>(si, scene_, scene_->robot());
            si->setMotionValidator(validator);
            si->setup();
            const std::vector<std::vector<double>> states = path();
            ob::State *a = si->allocState(), *b = si->allocState();
            std::vector<bool> first, second;
            std::size_t counted = 0;
            for (int pass = 0; pass < 2; ++pass)
                for (std::size_t k = 0; k + 3 < states.size(); k += 3)
                {
                    robotStateFromVector(*si->getStateSpace(), states[k], a);
                    robotStateFromVector(*si->getStateSpace(), states[k + 3], b);
                    const std::size_t before = test::threadAllocations();
                    const bool free = validator->checkMotion(a, b);
                    counted += pass == 1 ? test::threadAllocations() - before : 0;
                    (pass == 0 ? first : second).push_back(free);
                }
            si->freeState(a);
            si->freeState(b);
            EXPECT_EQ(first, second);
            // The path meets the posts: some motions are proven free, some refused.
            EXPECT_NE(std::count(second.begin(), second.end(), true), 0);
            EXPECT_NE(std::count(second.begin(), second.end(), false), 0);
            EXPECT_EQ(counted, 0u);
        }
    }  // namespace
}  // namespace meshgap

int main(int argc, char **argv)
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
