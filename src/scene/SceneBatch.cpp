#include "meshgap/scene/SceneBatch.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <string>
#include <thread>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        /** \brief Run \e work(block, run) for every block in [0, blocks) on at most \e threads threads (the calling
            thread one of them; \e run numbers the thread, from 0), each taking the next block not yet taken, so the
           threads finish together however the cost varies along the batch; rethrow the first exception once all have
           stopped. */
        template <typename Work>
        void forEachBlock(std::size_t blocks, unsigned threads, Work work)
        {
            if (threads < 1)
                throw Exception("threads", "must be at least 1, not " + std::to_string(threads));
            const std::size_t runs = std::max<std::size_t>(1, std::min<std::size_t>(threads, blocks));
            std::atomic<std::size_t> next{0};
            std::vector<std::exception_ptr> errors(runs);
            auto runOne = [&](std::size_t k)
            {
                try
                {
                    for (std::size_t b = next++; b < blocks; b = next++)
                        work(b, k);
                }
                catch (...)
                {
                    errors[k] = std::current_exception();
                    next = blocks;  // the others stop after their current block
                }
            };
            std::vector<std::thread> pool;
            pool.reserve(runs - 1);
            for (std::size_t k = 1; k < runs; ++k)
                pool.emplace_back(runOne, k);
            runOne(0);
            for (std::thread &t : pool)
                t.join();
            for (const std::exception_ptr &e : errors)
                if (e)
                    std::rethrow_exception(e);
        }
    }  // namespace

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
        std::vector<SceneWarmStart> starts(std::max(1u, threads));
        forEachBlock(blocks, threads,
                     [&](std::size_t b, std::size_t run)
                     {
                         SceneWarmStart &start = starts[run];
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
        std::vector<SceneWarmStart> starts(std::max(1u, threads));
        forEachBlock(blocks, threads,
                     [&](std::size_t b, std::size_t run)
                     {
                         for (std::size_t i = b * SCENE_BATCH_BLOCK; i < std::min(n, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                             results[i] = scene.inCollision(poses[i], starts[run]) ? 1 : 0;
                     });
    }
}  // namespace meshgap
