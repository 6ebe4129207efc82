// No query path allocates once warmed up on a thread: Scene::distance() in every mode (certified cold and warm,
// fast, collision-only, in collision with penetration depth, fast with on-demand mesh distances),
// Scene::inCollision(), ClearanceMotionValidator::checkMotion() with its checker, and ClearanceChecker's queries on
// threads sharing one checker. This executable replaces the global operator new / new[] and malloc / calloc /
// realloc and counts, per thread, every allocation; each mode runs its queries once to warm up, then once more
// counted, and the second pass must allocate nothing (and give the same answers). Not built under sanitizers (they
// replace the allocator themselves).

#include <gtest/gtest.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "TestMeshes.h"
#include "alloc/ThreadAllocations.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/scene/Scene.h"

namespace meshgap
{
    namespace
    {
        /** \brief 24 boxes of a few sizes on a 6 x 4 grid (spacing 1), one obstacle each: more than one R-tree leaf
            (16 entries), so the broad phase walks inner nodes too. */
        Mesh world()
        {
            Mesh all;
            for (int i = 0; i < 6; ++i)
                for (int j = 0; j < 4; ++j)
                {
                    const double h = 0.15 + 0.02 * ((i + 2 * j) % 3);
                    const Mesh part = test::transformed(test::box(h, h, 1.2 * h, 2), test::translation(i, j, 0.0));
                    all = all.triangles.empty() ? part : test::merged(all, part);
                }
            all.source = "alloc::world";
            return all;
        }

        ScenePtr makeScene(bool onDemand)
        {
            BodyOptions options;
            options.gridSize = 0;  // the meshes as they are: small graphs, quick fast-mode queries
            if (onDemand)
                options.distances.memoryBudgetBytes = 0;  // every body beyond the dense budget
            return Scene::fromMeshes(test::icosphere(0.25, 2), world(), options);
        }

        /** \brief The robot along a row of boxes at height \e y (0.5: between rows, free; 0.1: in collision with the
            boxes it passes), turning as it goes. */
        std::vector<Eigen::Isometry3d> motion(double y, int count = 24)
        {
            std::vector<Eigen::Isometry3d> poses;
            for (int k = 0; k < count; ++k)
            {
                Eigen::Isometry3d X = test::translation(-0.5 + 0.25 * k, y, 0.05 * (k % 3));
                X.linear() = Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
                poses.push_back(X);
            }
            return poses;
        }

        struct Answer
        {
            double distance;
            std::size_t obstacle;
            bool inCollision;
            bool operator==(const Answer &o) const
            {
                return std::memcmp(&distance, &o.distance, sizeof distance) == 0 && obstacle == o.obstacle &&
                       inCollision == o.inCollision;
            }
        };

        /** \brief Runs \e query over \e poses twice (warm-up, then counted) with one warm start carried through
            (no warm start at all if \e cold); returns the allocations of the second pass and checks that both
            passes gave the same answers. */
        std::size_t allocationsAfterWarmUp(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses,
                                           const SceneRequest &request, bool cold, std::size_t &collisions)
        {
            std::vector<Answer> first, second;
            first.reserve(poses.size());
            second.reserve(poses.size());
            std::size_t counted = 0;
            collisions = 0;
            // The warm start is the caller's: it warms up with the thread, and each pass starts it afresh (reset()
            // keeps its memory). A cold query takes none.
            SceneWarmStart warm;
            for (int pass = 0; pass < 2; ++pass)
            {
                std::vector<Answer> &answers = pass == 0 ? first : second;
                warm.reset();
                SceneResult result;
                for (const Eigen::Isometry3d &X : poses)
                {
                    const std::size_t before = test::threadAllocations();
                    if (cold)
                        scene.distance(X, request, result);
                    else
                        scene.distance(X, request, warm, result);
                    counted += pass == 1 ? test::threadAllocations() - before : 0;
                    answers.push_back({result.distance, result.obstacle, result.inCollision});
                    collisions += pass == 1 && result.inCollision;
                }
            }
            EXPECT_TRUE(first == second) << "the counted pass gave other answers than the warm-up pass";
            return counted;
        }

        SceneRequest exact(double stopBelow = -1.0)
        {
            SceneRequest r;
            r.stopBelow = stopBelow;
            return r;
        }

        SceneRequest fast(double stopBelow = -1.0)
        {
            SceneRequest r;
            r.exact = false;
            r.stopBelow = stopBelow;
            r.seed = 7;
            return r;
        }

        /** \brief Fast mode with warm-fast, the checker's default fast solver (a warm start per obstacle). */
        SceneRequest warmFast(double stopBelow = -1.0)
        {
            SceneRequest r = fast(stopBelow);
            r.solver = "warm-fast";
            return r;
        }

        class QueryAllocations : public ::testing::Test
        {
        protected:
            static void SetUpTestSuite()
            {
                dense_ = makeScene(false);
                onDemand_ = makeScene(true);
                ASSERT_TRUE(dense_->robot().distances().isDense());
                ASSERT_FALSE(onDemand_->robot().distances().isDense());
                ASSERT_FALSE(onDemand_->obstacles()[0]->distances().isDense());
                ASSERT_GT(dense_->obstacles().size(), 16u);
            }

            static void TearDownTestSuite()
            {
                dense_.reset();
                onDemand_.reset();
            }

            /** \brief Expects no allocation after warm-up, and (if \e collide) collisions on the way, else none. */
            static void check(const Scene &scene, const SceneRequest &request, bool cold, bool collide)
            {
                std::size_t collisions = 0;
                const std::vector<Eigen::Isometry3d> poses = motion(collide ? 0.1 : 0.5);
                EXPECT_EQ(allocationsAfterWarmUp(scene, poses, request, cold, collisions), 0u)
                    << "allocations over " << poses.size() << " queries";
                if (collide)
                    EXPECT_GT(collisions, 0u);
                else
                    EXPECT_EQ(collisions, 0u);
            }

            static ScenePtr dense_, onDemand_;
        };

        ScenePtr QueryAllocations::dense_, QueryAllocations::onDemand_;

        TEST_F(QueryAllocations, CertifiedCold)
        {
            check(*dense_, exact(), true, false);
        }

        TEST_F(QueryAllocations, CertifiedWarm)
        {
            check(*dense_, exact(), false, false);
        }

        TEST_F(QueryAllocations, CertifiedEarlyStop)
        {
            check(*dense_, exact(0.1), false, false);
        }

        TEST_F(QueryAllocations, CollisionOnly)
        {
            check(*dense_, exact(0.0), false, false);
            check(*dense_, exact(0.0), false, true);
        }

        TEST_F(QueryAllocations, InCollisionWithDepth)
        {
            check(*dense_, exact(), false, true);
            check(*dense_, exact(), true, true);
            check(*dense_, fast(), false, true);
        }

        TEST_F(QueryAllocations, InCollisionWithDepthAlongAStretch)
        {
            // Small steps through one box, in collision at every pose: the warm start carries the pair's deepest node
            // from pose to pose (PenetrationWarmStart), and allocates nothing once warmed up.
            std::vector<Eigen::Isometry3d> poses;
            for (int k = 0; k < 40; ++k)
            {
                Eigen::Isometry3d X = test::translation(0.3 - 0.015 * k, 0.02, 0.01);
                X.linear() =
                    Eigen::AngleAxisd(0.02 * k, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
                poses.push_back(X);
            }
            std::size_t collisions = 0;
            EXPECT_EQ(allocationsAfterWarmUp(*dense_, poses, exact(), false, collisions), 0u);
            EXPECT_EQ(collisions, poses.size());
        }

        TEST_F(QueryAllocations, InCollisionVerdict)
        {
            const std::vector<Eigen::Isometry3d> poses = motion(0.1);
            std::size_t counted = 0, collisions = 0;
            for (int pass = 0; pass < 2; ++pass)
                for (const Eigen::Isometry3d &X : poses)
                {
                    const std::size_t before = test::threadAllocations();
                    const bool hit = dense_->inCollision(X);
                    counted += pass == 1 ? test::threadAllocations() - before : 0;
                    collisions += pass == 1 && hit;
                }
            EXPECT_EQ(counted, 0u);
            EXPECT_GT(collisions, 0u);
        }

        TEST_F(QueryAllocations, InCollisionVerdictCarriedFromPoseToPose)
        {
            // The collision fronts grow on the first pass; the second allocates nothing. Small steps (a front is
            // written only along a run of nearby poses), grazing the boxes of the row: in collision at some of them.
            std::vector<Eigen::Isometry3d> poses;
            for (int k = 0; k < 300; ++k)
            {
                Eigen::Isometry3d X = test::translation(-0.5 + 0.02 * k, 0.4, 0.0);
                X.linear() =
                    Eigen::AngleAxisd(0.01 * k, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
                poses.push_back(X);
            }
            SceneWarmStart warm;
            std::size_t counted = 0, collisions = 0;
            for (int pass = 0; pass < 2; ++pass)
                for (const Eigen::Isometry3d &X : poses)
                {
                    const std::size_t before = test::threadAllocations();
                    const bool hit = dense_->inCollision(X, warm);
                    counted += pass == 1 ? test::threadAllocations() - before : 0;
                    collisions += pass == 1 && hit;
                    ASSERT_EQ(hit, dense_->inCollision(X));
                }
            EXPECT_EQ(counted, 0u);
            EXPECT_GT(collisions, 0u);
            std::size_t kept = 0;
            for (const ExactWarmStart &pair : warm.pairs)
                kept += pair.collision.reused;
            EXPECT_GT(kept, 0u);  // fronts were written and used
        }

        TEST_F(QueryAllocations, Fast)
        {
            check(*dense_, fast(), false, false);
            check(*dense_, fast(), true, false);
            check(*dense_, fast(0.0), false, true);
        }

        TEST_F(QueryAllocations, FastOnDemandDistances)
        {
            check(*onDemand_, fast(), false, false);
            check(*onDemand_, fast(), true, false);
        }

        TEST_F(QueryAllocations, WarmFast)
        {
            check(*dense_, warmFast(), false, false);
            check(*dense_, warmFast(), false, true);
            check(*onDemand_, warmFast(), false, false);
        }

        TEST_F(QueryAllocations, CertifiedOnDemandDistances)
        {
            check(*onDemand_, exact(), true, false);
            check(*onDemand_, exact(), false, false);
        }

        TEST_F(QueryAllocations, CertifiedMotions)
        {
            namespace ob = ompl::base;
            auto space = std::make_shared<ob::SE3StateSpace>();
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-2.0);
            bounds.setHigh(7.0);
            space->setBounds(bounds);
            const auto si = std::make_shared<ob::SpaceInformation>(space);
            const auto checker = std::make_shared<ClearanceChecker>(si, dense_);
            si->setStateValidityChecker(checker);
            const auto validator = std::make_shared<ClearanceMotionValidator>(si, checker);
            si->setMotionValidator(validator);
            si->setup();
            // Motions between the rows (free) and through the boxes (refused), each pose to the next. The checker's
            // warm start is its own and carries over from pass to pass (its certificates grow to the largest front
            // they hold), so the path runs a few times before the counted pass.
            constexpr int PASSES = 4;
            std::vector<Eigen::Isometry3d> poses = motion(0.5), through = motion(0.1);
            poses.insert(poses.end(), through.begin(), through.end());
            ob::State *a = si->allocState(), *b = si->allocState();
            std::vector<bool> first, second;
            std::size_t counted = 0;
            for (int pass = 0; pass < PASSES; ++pass)
                for (std::size_t k = 0; k + 1 < poses.size(); ++k)
                {
                    stateFromPose(*space, poses[k], a);
                    stateFromPose(*space, poses[k + 1], b);
                    const std::size_t before = test::threadAllocations();
                    const bool free = validator->checkMotion(a, b);
                    counted += pass == PASSES - 1 ? test::threadAllocations() - before : 0;
                    if (pass == 0 || pass == PASSES - 1)
                        (pass == 0 ? first : second).push_back(free);
                }
            si->freeState(a);
            si->freeState(b);
            EXPECT_EQ(first, second);
            EXPECT_NE(std::count(second.begin(), second.end(), true), 0);
            EXPECT_NE(std::count(second.begin(), second.end(), false), 0);
            EXPECT_EQ(counted, 0u);
        }

        /** \brief Every query of a checker (\e checkers: certified and fast), asked at each of \e states in turn. */
        void askEverything(const std::vector<const ClearanceChecker *> &checkers,
                           const std::vector<ompl::base::State *> &states, std::vector<double> &answers)
        {
            answers.clear();
            for (const ompl::base::State *s : states)
                for (const ClearanceChecker *c : checkers)
                {
                    double d = 0.0;
                    answers.push_back(c->isValid(s) ? 1.0 : 0.0);
                    answers.push_back(c->isValid(s, d) ? d : -1.0);
                    answers.push_back(c->clearance(s));
                    answers.push_back(c->clearanceOrContact(s));
                    answers.push_back(c->clearanceBelow(s, 0.2));
                }
        }

        TEST_F(QueryAllocations, CheckerSharedByThreads)
        {
            // ClearanceChecker's queries (validity, clearance, early stops; certified and fast) from two threads
            // sharing one checker per mode: once a thread has walked the states twice (its warm starts, scratch
            // arrays and counter shard made), a third walk allocates nothing on either thread. The states run along a
            // row of boxes in small steps (warm starts carried), half of them in collision, at every thread's pace.
            auto space = std::make_shared<ompl::base::SE3StateSpace>();
            ompl::base::RealVectorBounds bounds(3);
            bounds.setLow(-2.0);
            bounds.setHigh(7.0);
            space->setBounds(bounds);
            auto si = std::make_shared<ompl::base::SpaceInformation>(space);
            const ClearanceChecker certified(si, dense_, ClearanceChecker::Mode::CERTIFIED);
            const ClearanceChecker fastChecker(si, dense_, ClearanceChecker::Mode::FAST);
            std::vector<ompl::base::State *> states;
            for (const double y : {0.5, 0.1})
                for (int k = 0; k < 60; ++k)
                {
                    Eigen::Isometry3d X = test::translation(-0.5 + 0.05 * k, y, 0.0);
                    X.linear() =
                        Eigen::AngleAxisd(0.02 * k, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
                    states.push_back(si->allocState());
                    stateFromPose(*space, X, states.back());
                }
            const std::vector<const ClearanceChecker *> checkers{&certified, &fastChecker};
            constexpr int THREADS = 2;
            std::size_t first[THREADS] = {0, 0}, counted[THREADS] = {0, 0}, collisions[THREADS] = {0, 0};
            std::vector<double> answers[THREADS][3];
            std::vector<std::thread> threads;
            for (int t = 0; t < THREADS; ++t)
                threads.emplace_back([&, t] {
                    for (int pass = 0; pass < 3; ++pass)
                    {
                        answers[t][pass].reserve(10 * states.size());
                        const std::size_t before = test::threadAllocations();
                        askEverything(checkers, states, answers[t][pass]);
                        (pass == 0 ? first[t] : counted[t]) = test::threadAllocations() - before;
                    }
                    for (std::size_t i = 0; i < answers[t][2].size(); i += 10)
                        collisions[t] += answers[t][2][i] == 0.0;
                });
            for (std::thread &thread : threads)
                thread.join();
            for (int t = 0; t < THREADS; ++t)
            {
                EXPECT_GT(first[t], 0u) << "thread " << t << ": the first walk's allocations went uncounted";
                EXPECT_EQ(counted[t], 0u) << "thread " << t << ": allocations over " << states.size() << " states";
                EXPECT_GT(collisions[t], 0u) << "thread " << t;
                EXPECT_LT(collisions[t], states.size()) << "thread " << t;
                // The certified verdicts and complete answers do not depend on the history (early stops in collision
                // may meet another obstacle first).
                for (std::size_t i = 0; i < answers[t][2].size(); i += 10)
                    for (const std::size_t k : {i, i + 1, i + 2})
                        EXPECT_EQ(answers[t][2][k], answers[0][0][k]) << "thread " << t << " answer " << k;
            }
            for (ompl::base::State *s : states)
                si->freeState(s);
        }
    }  // namespace

    TEST(ThreadAllocations, CountsEveryAllocationOfThisThread)
    {
        // The counter the tests above rely on: a query that allocates must be seen.
        const std::size_t before = test::threadAllocations();
        auto *vector = new std::vector<double>(100);
        const std::size_t after = test::threadAllocations();
        delete vector;
        EXPECT_EQ(after - before, 2u);  // the vector object, then its buffer
    }
}  // namespace meshgap

int main(int argc, char **argv)
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
