#include "meshgap/scene/SceneBatch.h"

#include <algorithm>
#include <exception>
#include <string>
#include <thread>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        /** \brief Run \e work(firstBlock, endBlock) over \e blocks blocks split into at most \e threads contiguous
            runs, the first on the calling thread; rethrow the first exception once all have stopped. */
        template <typename Work>
        void splitBlocks(std::size_t blocks, unsigned threads, Work work)
        {
            if (threads < 1)
                throw Exception("threads", "must be at least 1, not " + std::to_string(threads));
            const std::size_t runs = std::max<std::size_t>(1, std::min<std::size_t>(threads, blocks));
            std::vector<std::exception_ptr> errors(runs);
            auto runOne = [&](std::size_t k) {
                try
                {
                    work(k * blocks / runs, (k + 1) * blocks / runs);
                }
                catch (...)
                {
                    errors[k] = std::current_exception();
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
        splitBlocks(blocks, threads, [&](std::size_t firstBlock, std::size_t endBlock) {
            for (std::size_t b = firstBlock; b < endBlock; ++b)
            {
                SceneWarmStart start;
                for (std::size_t i = b * SCENE_BATCH_BLOCK; i < std::min(n, (b + 1) * SCENE_BATCH_BLOCK); ++i)
                {
                    if (!warm)
                        start = SceneWarmStart();
                    scene.distance(poses[i], request, start, results[i]);
                }
            }
        });
    }

    void inCollisionBatch(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, unsigned threads,
                          std::vector<char> &results)
    {
        results.assign(poses.size(), 0);
        const std::size_t n = poses.size(), blocks = (n + SCENE_BATCH_BLOCK - 1) / SCENE_BATCH_BLOCK;
        splitBlocks(blocks, threads, [&](std::size_t firstBlock, std::size_t endBlock) {
            for (std::size_t i = firstBlock * SCENE_BATCH_BLOCK; i < std::min(n, endBlock * SCENE_BATCH_BLOCK); ++i)
                results[i] = scene.inCollision(poses[i]) ? 1 : 0;
        });
    }
}  // namespace meshgap
