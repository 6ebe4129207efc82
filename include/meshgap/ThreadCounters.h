#ifndef MESHGAP_THREAD_COUNTERS_H
#define MESHGAP_THREAD_COUNTERS_H

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "meshgap/CacheAligned.h"

namespace meshgap
{
    namespace detail
    {
        /** \brief How many threads at once may hold a shard of their own in every ThreadCounters. */
        constexpr std::size_t OWN_COUNTER_SHARDS = 32;

        /** \brief The calling thread's shard of every ThreadCounters: one that no other living thread holds, taken at
            the thread's first addition and given back when the thread ends (a later thread takes it over, with the
            counts in it), or OWN_COUNTER_SHARDS (the shared shard) while every one is held. */
        class CounterShard
        {
        public:
            static std::size_t ofThisThread()
            {
                thread_local const CounterShard shard;
                return shard.index_;
            }

            CounterShard(const CounterShard &) = delete;
            CounterShard &operator=(const CounterShard &) = delete;

        private:
            CounterShard() : index_(take()) {}
            ~CounterShard()
            {
                // Release: this thread's last additions happen before the next holder's first.
                if (index_ < OWN_COUNTER_SHARDS)
                    held()[index_].store(false, std::memory_order_release);
            }

            static std::array<std::atomic<bool>, OWN_COUNTER_SHARDS> &held()
            {
                static std::array<std::atomic<bool>, OWN_COUNTER_SHARDS> flags{};
                return flags;
            }

            static std::size_t take()
            {
                for (std::size_t k = 0; k < OWN_COUNTER_SHARDS; ++k)
                {
                    bool free = false;
                    if (held()[k].compare_exchange_strong(free, true, std::memory_order_acquire))
                        return k;
                }
                return OWN_COUNTER_SHARDS;
            }

            std::size_t index_;
        };
    }  // namespace detail

    /** \brief \e N counters that many threads add to and any thread reads as sums. Each thread adds to a shard that
        no other living thread writes, on cache lines of its own, with a plain load and store (no atomic
        read-modify-write, no line passed between cores): threads sharing a checker share nothing on a query's path.
        Past OWN_COUNTER_SHARDS living threads, the others add to one shared shard, atomically (the sums stay exact).
        A sum read while threads add is a snapshot of no particular instant, as with one atomic per counter. */
    template <std::size_t N>
    class ThreadCounters
    {
    public:
        /** \brief Add \e value to counter \e k (k < N). */
        void add(std::size_t k, std::uint64_t value)
        {
            const std::size_t s = detail::CounterShard::ofThisThread();
            std::atomic<std::uint64_t> &c = shards_[s].values[k];
            if (s < detail::OWN_COUNTER_SHARDS)  // this thread's alone: no other writer
                c.store(c.load(std::memory_order_relaxed) + value, std::memory_order_relaxed);
            else
                c.fetch_add(value, std::memory_order_relaxed);
        }
        /** \brief Counter \e k summed over every shard. */
        std::uint64_t sum(std::size_t k) const
        {
            std::uint64_t total = 0;
            for (const Shard &s : shards_)
                total += s.values[k].load(std::memory_order_relaxed);
            return total;
        }

        /** \brief Shards: one per thread up to OWN_COUNTER_SHARDS living threads, and the shared one. */
        static constexpr std::size_t SHARDS = detail::OWN_COUNTER_SHARDS + 1;

    private:
        struct alignas(FALSE_SHARING_BYTES) Shard
        {
            std::array<std::atomic<std::uint64_t>, N> values{};
        };
        std::array<Shard, SHARDS> shards_{};
    };
}  // namespace meshgap

#endif
