#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "meshgap/ThreadCounters.h"

using namespace meshgap;

// Sums over threads are exact, with more threads than shards too (two threads then share a shard).
TEST(ThreadCounters, SumsEveryThreadsAdditionsExactly)
{
    for (const std::size_t threads : {std::size_t{1}, std::size_t{3}, ThreadCounters<2>::SHARDS + 5})
    {
        ThreadCounters<2> counters;
        std::vector<std::thread> workers;
        for (std::size_t t = 0; t < threads; ++t)
            workers.emplace_back([&counters, t] {
                for (std::uint64_t i = 0; i < 2000; ++i)
                {
                    counters.add(0, 1);
                    counters.add(1, t + 1);
                }
            });
        for (std::thread &w : workers)
            w.join();
        EXPECT_EQ(counters.sum(0), 2000u * threads) << threads << " threads";
        EXPECT_EQ(counters.sum(1), 2000u * threads * (threads + 1) / 2) << threads << " threads";
    }
}

// One shard per cache line: threads adding to different shards never write the same line.
TEST(ThreadCounters, ShardsAreCacheLinesApart)
{
    EXPECT_GE(alignof(ThreadCounters<1>), 64u);
    EXPECT_EQ(sizeof(ThreadCounters<1>), 64u * ThreadCounters<1>::SHARDS);
    EXPECT_EQ(sizeof(ThreadCounters<9>), 128u * ThreadCounters<9>::SHARDS);
}
