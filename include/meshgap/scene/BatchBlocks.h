#ifndef MESHGAP_SCENE_BATCH_BLOCKS_H
#define MESHGAP_SCENE_BATCH_BLOCKS_H

#include <algorithm>
#include <atomic>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "meshgap/Exception.h"

namespace meshgap
{
    /** \brief Run \e work(block, run) for every block in [0, blocks) on at most \e threads threads (the calling
        thread one of them; \e run numbers the thread, from 0), each taking the next block not yet taken, so the
        threads finish together however the cost varies along the batch; rethrow the first exception once all have
        stopped. Throws meshgap::Exception when \e threads is 0. The batches of Scene (SceneBatch.h) and of
        RobotScene (RobotBatch.h) share it. */
    template <typename Work>
    void forEachBatchBlock(std::size_t blocks, unsigned threads, Work work)
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
}  // namespace meshgap

#endif
