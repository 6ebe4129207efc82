#ifndef MESHGAP_THREAD_COUNTERS_H
#define MESHGAP_THREAD_COUNTERS_H

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace meshgap
{
    namespace detail
    {
        /** \brief A small number for the calling thread, handed out in the order threads first ask (0, 1, 2, ...). */
        inline std::size_t threadOrdinal()
        {
            static std::atomic<std::size_t> next{0};
            thread_local const std::size_t ordinal = next.fetch_add(1, std::memory_order_relaxed);
            return ordinal;
        }
    }  // namespace detail

    /** \brief \e N counters that many threads add to and any thread reads as sums. Each thread adds to a shard of
        its own, one cache line per shard, so threads sharing a checker do not pass one cache line back and forth
        on every query (with one shared set of atomic counters, two threads sharing a checker ran at about half the
        rate of two processes). Threads take the shards in turn; past SHARDS threads, two may share one (the
        additions stay exact: they are atomic). A sum read while threads add is a snapshot of no particular
        instant, as with one atomic per counter. */
    template <std::size_t N>
    class ThreadCounters
    {
    public:
        /** \brief Add \e value to counter \e k (k < N). */
        void add(std::size_t k, std::uint64_t value)
        {
            shards_[detail::threadOrdinal() % SHARDS].values[k].fetch_add(value, std::memory_order_relaxed);
        }
        /** \brief Counter \e k summed over every thread's shard. */
        std::uint64_t sum(std::size_t k) const
        {
            std::uint64_t total = 0;
            for (const Shard &s : shards_)
                total += s.values[k].load(std::memory_order_relaxed);
            return total;
        }

        static constexpr std::size_t SHARDS = 32;

    private:
        struct alignas(64) Shard
        {
            std::array<std::atomic<std::uint64_t>, N> values{};
        };
        std::array<Shard, SHARDS> shards_{};
    };
}  // namespace meshgap

#endif
