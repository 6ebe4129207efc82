#ifndef MESHGAP_CACHE_ALIGNED_H
#define MESHGAP_CACHE_ALIGNED_H

#include <cstddef>

namespace meshgap
{
    /** \brief How far apart two threads' data must start so that they never write the same cache line: a line is
        64 bytes on x86-64 and most ARM cores, and Intel's spatial prefetcher fetches lines in pairs, so two. */
    constexpr std::size_t FALSE_SHARING_BYTES = 128;

    /** \brief A \e T on cache lines of its own: in an array of them, one per thread (a batch's warm starts), a thread
        writing its element never writes a line another thread's element lies on. */
    template <typename T>
    struct alignas(FALSE_SHARING_BYTES) CacheAligned
    {
        T value;
    };
}  // namespace meshgap

#endif
