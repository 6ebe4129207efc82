#include "meshgap/robot/RobotBatch.h"

#include <algorithm>

#include "meshgap/scene/BatchBlocks.h"

namespace meshgap
{
    void robotDistanceBatch(const RobotScene &scene, const double *states, std::size_t count,
                            const RobotRequest &request, unsigned threads, std::vector<RobotResult> &results)
    {
        results.resize(count);
        const std::size_t dof = scene.robot().dimension(), blocks = (count + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        std::vector<RobotWarmStart> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                          [&](std::size_t b, std::size_t run)
                          {
                              RobotWarmStart &start = starts[run];
                              start.reset();  // ties between pairs aside, answers never depend on it; still afresh
                              for (std::size_t i = b * SCENE_BATCH_BLOCK;
                                   i < std::min(count, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                                  scene.distance(states + i * dof, dof, request, start, results[i]);
                          });
    }

    void robotInCollisionBatch(const RobotScene &scene, const double *states, std::size_t count, bool selfCollision,
                               unsigned threads, std::vector<char> &results)
    {
        results.assign(count, 0);
        const std::size_t dof = scene.robot().dimension(), blocks = (count + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        std::vector<RobotWarmStart> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                          [&](std::size_t b, std::size_t run)
                          {
                              for (std::size_t i = b * SCENE_BATCH_BLOCK;
                                   i < std::min(count, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                                  results[i] = scene.inCollision(states + i * dof, dof, starts[run], selfCollision) ?
                                                   1 :
                                                   0;
                          });
    }
}  // namespace meshgap
