#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "meshgap/CacheAligned.h"
#include "meshgap/ThreadCounters.h"

using namespace meshgap;

namespace
{
    /** \brief Runs \e work on \e threads threads that all live until every one has finished its work, so that all of
        them hold a counter shard at once. */
    template <typename Work>
    void runAllAlive(std::size_t threads, Work work)
    {
        std::mutex mutex;
        std::condition_variable done;
        std::size_t finished = 0;
        std::vector<std::thread> workers;
        for (std::size_t t = 0; t < threads; ++t)
            workers.emplace_back([&, t] {
                work(t);
                std::unique_lock<std::mutex> lock(mutex);
                if (++finished == threads)
                    done.notify_all();
                done.wait(lock, [&] { return finished == threads; });
            });
        for (std::thread &w : workers)
            w.join();
    }
}  // namespace

// Sums over threads are exact, with more threads alive at once than own shards too (the rest share one, atomically).
TEST(ThreadCounters, SumsEveryThreadsAdditionsExactly)
{
    for (const std::size_t threads : {std::size_t{1}, std::size_t{3}, detail::OWN_COUNTER_SHARDS + 5})
    {
        ThreadCounters<2> counters;
        runAllAlive(threads, [&counters](std::size_t t) {
            for (std::uint64_t i = 0; i < 2000; ++i)
            {
                counters.add(0, 1);
                counters.add(1, t + 1);
            }
        });
        EXPECT_EQ(counters.sum(0), 2000u * threads) << threads << " threads";
        EXPECT_EQ(counters.sum(1), 2000u * threads * (threads + 1) / 2) << threads << " threads";
    }
}

// Threads alive at once hold different shards (past the own ones, the shared one); a thread that ends gives its
// shard back, so threads made one after the other (a thread per batch) never run out, and the counts written in a
// shard stay in the sums when another thread takes it over.
TEST(ThreadCounters, LivingThreadsHoldShardsOfTheirOwnAndGiveThemBack)
{
    const std::size_t threads = detail::OWN_COUNTER_SHARDS + 3;
    const std::size_t mainShard = detail::CounterShard::ofThisThread();  // the test's own thread holds one too
    std::vector<std::size_t> shards(threads);
    runAllAlive(threads, [&shards](std::size_t t) { shards[t] = detail::CounterShard::ofThisThread(); });
    std::set<std::size_t> own;
    std::size_t shared = 0;
    for (const std::size_t s : shards)
    {
        if (s == detail::OWN_COUNTER_SHARDS)
            ++shared;
        else
            EXPECT_TRUE(own.insert(s).second) << "two living threads hold shard " << s;
        EXPECT_TRUE(s == detail::OWN_COUNTER_SHARDS || s != mainShard) << "a thread holds the test's own shard";
    }
    EXPECT_EQ(own.size() + shared, threads);
    EXPECT_GE(shared, 3u);

    ThreadCounters<1> counters;
    for (int k = 0; k < 3 * static_cast<int>(detail::OWN_COUNTER_SHARDS); ++k)
    {
        std::size_t shard = 0;
        std::thread([&] {
            shard = detail::CounterShard::ofThisThread();
            counters.add(0, 1);
        }).join();
        EXPECT_LT(shard, detail::OWN_COUNTER_SHARDS) << "thread " << k << " found no shard given back";
    }
    EXPECT_EQ(counters.sum(0), 3u * detail::OWN_COUNTER_SHARDS);
}

// One shard per pair of cache lines: threads adding to different shards never write the same line.
TEST(ThreadCounters, ShardsAreCacheLinesApart)
{
    EXPECT_GE(alignof(ThreadCounters<1>), FALSE_SHARING_BYTES);
    EXPECT_EQ(sizeof(ThreadCounters<1>), FALSE_SHARING_BYTES * ThreadCounters<1>::SHARDS);
    EXPECT_EQ(sizeof(ThreadCounters<17>), 2 * FALSE_SHARING_BYTES * ThreadCounters<17>::SHARDS);
}

// Per-thread objects in one array (a batch's warm starts) each on lines of their own, whatever their size.
TEST(ThreadCounters, CacheAlignedElementsShareNoLine)
{
    struct Odd
    {
        char bytes[336];  // a warm start's size: not a multiple of a line
    };
    std::vector<CacheAligned<Odd>> perThread(3);
    for (const CacheAligned<Odd> &e : perThread)
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(&e) % FALSE_SHARING_BYTES, 0u);
    EXPECT_EQ(sizeof(CacheAligned<Odd>) % FALSE_SHARING_BYTES, 0u);
    EXPECT_GE(sizeof(CacheAligned<Odd>), sizeof(Odd));
}
