#include "meshgap/robot/RobotBatch.h"

#include <algorithm>

#include "meshgap/Exception.h"
#include "meshgap/CacheAligned.h"
#include "meshgap/scene/BatchBlocks.h"

namespace meshgap
{
    namespace
    {
        /** \brief Run \e f on state \e i; a meshgap::Exception it throws (a state outside the joint limits, say)
            is rethrown naming the state's row in the batch. */
        template <typename F>
        void atRow(std::size_t i, F &&f)
        {
            try
            {
                f();
            }
            catch (const Exception &e)
            {
                throw Exception("states[" + std::to_string(i) + "]", e.what());
            }
        }
    }  // namespace

    void robotDistanceBatch(const RobotScene &scene, const double *states, std::size_t count,
                            const RobotRequest &request, unsigned threads, std::vector<RobotResult> &results)
    {
        results.resize(count);
        const std::size_t dof = scene.robot().dimension(), blocks = (count + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        // One warm start per thread, each on cache lines of its own: written at every query, never falsely shared.
        std::vector<CacheAligned<RobotWarmStart>> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                          [&](std::size_t b, std::size_t run)
                          {
                              RobotWarmStart &start = starts[run].value;
                              start.reset();  // ties between pairs aside, answers never depend on it; still afresh
                              for (std::size_t i = b * SCENE_BATCH_BLOCK;
                                   i < std::min(count, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                                  atRow(i, [&] { scene.distance(states + i * dof, dof, request, start, results[i]); });
                          });
    }

    void robotInCollisionBatch(const RobotScene &scene, const double *states, std::size_t count, bool selfCollision,
                               unsigned threads, std::vector<char> &results)
    {
        results.assign(count, 0);
        const std::size_t dof = scene.robot().dimension(), blocks = (count + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        std::vector<CacheAligned<RobotWarmStart>> starts(std::max(1u, threads));
        forEachBatchBlock(blocks, threads,
                          [&](std::size_t b, std::size_t run)
                          {
                              for (std::size_t i = b * SCENE_BATCH_BLOCK;
                                   i < std::min(count, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                                  atRow(i,
                                        [&]
                                        {
                                            RobotWarmStart &start = starts[run].value;
                                            results[i] = scene.inCollision(states + i * dof, dof, start, selfCollision);
                                        });
                          });
    }
}  // namespace meshgap
