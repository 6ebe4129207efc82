#ifndef MESHGAP_TESTS_THREAD_ALLOCATIONS_H
#define MESHGAP_TESTS_THREAD_ALLOCATIONS_H

// The counting allocator (CountingAllocator.h) with a per-thread count: include it in exactly one source file of an
// allocation-test executable, and read meshgap::test::threadAllocations() before and after the code under test.

#include <cstddef>

#include "alloc/CountingAllocator.h"

namespace meshgap::test
{
    /** \brief Allocations made by this thread so far (static TLS in the executable: reading it never allocates). */
    inline thread_local std::size_t threadAllocationCount = 0;

    inline std::size_t threadAllocations()
    {
        return threadAllocationCount;
    }
}  // namespace meshgap::test

void meshgapNoteAllocation()
{
    ++meshgap::test::threadAllocationCount;
}

#endif
