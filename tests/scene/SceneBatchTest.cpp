// distanceBatch() and inCollisionBatch() (what the Python module's batched queries run) against Scene's own
// one-at-a-time queries: the same answers for any number of threads, warm or cold. The test names hold "Thread" so
// tests/sanitizers.sh runs them under ThreadSanitizer too.

#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/scene/SceneBatch.h"

using namespace meshgap;

namespace
{
    /** \brief Poses along a smooth motion through a world of boxes, so some collide and warm starts pay. */
    std::vector<Eigen::Isometry3d> motion(std::size_t count)
    {
        std::vector<Eigen::Isometry3d> poses;
        for (std::size_t i = 0; i < count; ++i)
        {
            const double s = double(i) / double(count);
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = Eigen::AngleAxisd(6.0 * s, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
            X.translation() = Eigen::Vector3d(-6.0 + 12.0 * s, 1.5 * std::sin(9.0 * s), 0.5 * std::cos(5.0 * s));
            poses.push_back(X);
        }
        return poses;
    }

    ScenePtr boxes()
    {
        Mesh world = test::transformed(test::box(0.5, 2, 1, 2), test::translation(-3, 0, 0));
        world = test::merged(world, test::transformed(test::box(1, 0.4, 1.5, 2), test::translation(0, 1.2, 0)));
        world = test::merged(world, test::transformed(test::box(0.3, 0.3, 0.3, 1), test::translation(3, -1, 0.5)));
        return Scene::fromMeshes(test::box(0.6, 0.3, 0.2, 2), world);
    }
}  // namespace

TEST(SceneBatch, ThreadsGiveTheOneThreadAnswersBlockByBlock)
{
    const ScenePtr scene = boxes();
    const std::vector<Eigen::Isometry3d> poses = motion(3 * SCENE_BATCH_BLOCK + 41);
    // The oracle: Scene::distance in order, a fresh warm start at each block's first pose.
    std::vector<SceneResult> expected(poses.size());
    SceneWarmStart warm;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        if (i % SCENE_BATCH_BLOCK == 0)
            warm = SceneWarmStart();
        scene->distance(poses[i], SceneRequest(), warm, expected[i]);
    }
    std::size_t colliding = 0;
    for (unsigned threads : {1u, 2u, 3u, 7u})
    {
        std::vector<SceneResult> got;
        distanceBatch(*scene, poses, SceneRequest(), true, threads, got);
        ASSERT_EQ(got.size(), poses.size());
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            EXPECT_EQ(got[i].distance, expected[i].distance) << threads << " threads, pose " << i;
            EXPECT_EQ(got[i].inCollision, expected[i].inCollision) << i;
            EXPECT_EQ(got[i].obstacle, expected[i].obstacle) << i;
            EXPECT_EQ(got[i].onA, expected[i].onA) << i;
            EXPECT_EQ(got[i].onB, expected[i].onB) << i;
            EXPECT_TRUE(got[i].certified) << i;
            colliding += threads == 1 && got[i].inCollision;
        }
    }
    EXPECT_GT(colliding, 0u);
    EXPECT_LT(colliding, poses.size() / 2);
}

TEST(SceneBatch, ColdThreadsGiveColdAnswersAndCollisionBatchesTheVerdicts)
{
    const ScenePtr scene = boxes();
    const std::vector<Eigen::Isometry3d> poses = motion(SCENE_BATCH_BLOCK + 9);
    std::vector<SceneResult> cold;
    distanceBatch(*scene, poses, SceneRequest(), false, 2, cold);
    std::vector<char> collide;
    inCollisionBatch(*scene, poses, 3, collide);
    ASSERT_EQ(collide.size(), poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        SceneWarmStart fresh;
        SceneResult r;
        scene->distance(poses[i], SceneRequest(), fresh, r);
        EXPECT_EQ(cold[i].distance, r.distance) << i;
        EXPECT_EQ(bool(collide[i]), scene->inCollision(poses[i])) << i;
        EXPECT_EQ(bool(collide[i]), r.inCollision) << i;
    }
}

TEST(SceneBatch, ThreadsZeroIsRefusedAndAnEmptyBatchIsEmpty)
{
    const ScenePtr scene = boxes();
    std::vector<SceneResult> results(3);
    EXPECT_THROW(distanceBatch(*scene, motion(4), SceneRequest(), true, 0, results), Exception);
    distanceBatch(*scene, {}, SceneRequest(), true, 4, results);
    EXPECT_TRUE(results.empty());
}
