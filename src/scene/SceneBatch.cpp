#include "meshgap/scene/SceneBatch.h"

#include <algorithm>

#include "meshgap/CacheAligned.h"
#include "meshgap/scene/BatchBlocks.h"

namespace meshgap
{
    void distanceBatch(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, const SceneRequest &request,
                       bool warm, unsigned threads, std::vector<SceneResult> &results)
    {
        results.assign(poses.size(), SceneResult());
        const std::size_t n = poses.size(), blocks = (n + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        // A complete exact answer does not depend on the warm start (canonical ties: bit for bit the cold one), so a
        // thread carries its warm start from block to block; any other answer (fast mode, an early stop, no depth:
        // which colliding obstacle is met first) starts
        // each block afresh, so that it depends on the block alone, never on which thread took which block.
        const bool carry = request.exact && request.stopBelow < 0.0 && request.computeDepth;
        // One warm start per thread, each on cache lines of its own: written at every query, never falsely shared.
        std::vector<CacheAligned<SceneWarmStart>> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                     [&](std::size_t b, std::size_t run)
                     {
                         SceneWarmStart &start = starts[run].value;
                         if (!carry)
                             start.reset();
                         for (std::size_t i = b * SCENE_BATCH_BLOCK; i < std::min(n, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                         {
                             if (warm)
                                 scene.distance(poses[i], request, start, results[i]);
                             else
                                 scene.distance(poses[i], request, results[i]);  // a cold query: no warm start
                         }
                     });
    }

    void inCollisionBatch(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, unsigned threads,
                          std::vector<char> &results)
    {
        results.assign(poses.size(), 0);
        const std::size_t n = poses.size(), blocks = (n + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        // The verdict does not depend on the warm start: each thread carries its own (collision fronts) across
        // the blocks it takes, which pays along a trajectory and costs next to nothing between unrelated poses.
        std::vector<CacheAligned<SceneWarmStart>> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                     [&](std::size_t b, std::size_t run)
                     {
                         for (std::size_t i = b * SCENE_BATCH_BLOCK; i < std::min(n, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                             results[i] = scene.inCollision(poses[i], starts[run].value) ? 1 : 0;
                     });
    }
}  // namespace meshgap
