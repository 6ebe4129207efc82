#ifndef MESHGAP_TESTS_COUNTING_ALLOCATOR_H
#define MESHGAP_TESTS_COUNTING_ALLOCATOR_H

// Replaces the global allocation functions (malloc, calloc, realloc, operator new and new[] in every form, and the
// matching operator delete) with glibc's own, calling meshgapNoteAllocation() once per allocation. Include it in
// exactly one source file of an executable, which defines meshgapNoteAllocation() (it must not allocate). Used by
// tests/alloc and bench/scaling.cpp; not for sanitizer builds, which replace the allocator themselves.

#include <cstddef>
#include <cstdlib>
#include <new>

/** \brief Called for every allocation, before it is made; defined by the executable. */
void meshgapNoteAllocation();

extern "C" void *__libc_malloc(std::size_t);
extern "C" void *__libc_calloc(std::size_t, std::size_t);
extern "C" void *__libc_realloc(void *, std::size_t);
extern "C" void *__libc_memalign(std::size_t, std::size_t);

namespace meshgap_counting_allocator
{
    inline void *counted(std::size_t size, std::size_t align = 0)
    {
        meshgapNoteAllocation();
        void *p = align > alignof(std::max_align_t) ? __libc_memalign(align, size ? size : 1)
                                                    : __libc_malloc(size ? size : 1);
        if (!p)
            throw std::bad_alloc();
        return p;
    }
}  // namespace meshgap_counting_allocator

extern "C" void *malloc(std::size_t size)
{
    meshgapNoteAllocation();
    return __libc_malloc(size);
}
extern "C" void *calloc(std::size_t n, std::size_t size)
{
    meshgapNoteAllocation();
    return __libc_calloc(n, size);
}
extern "C" void *realloc(void *p, std::size_t size)
{
    meshgapNoteAllocation();
    return __libc_realloc(p, size);
}
void *operator new(std::size_t size)
{
    return meshgap_counting_allocator::counted(size);
}
void *operator new[](std::size_t size)
{
    return meshgap_counting_allocator::counted(size);
}
void *operator new(std::size_t size, std::align_val_t a)
{
    return meshgap_counting_allocator::counted(size, static_cast<std::size_t>(a));
}
void *operator new[](std::size_t size, std::align_val_t a)
{
    return meshgap_counting_allocator::counted(size, static_cast<std::size_t>(a));
}
void operator delete(void *p) noexcept
{
    std::free(p);
}
void operator delete[](void *p) noexcept
{
    std::free(p);
}
void operator delete(void *p, std::size_t) noexcept
{
    std::free(p);
}
void operator delete[](void *p, std::size_t) noexcept
{
    std::free(p);
}
void operator delete(void *p, std::align_val_t) noexcept
{
    std::free(p);
}
void operator delete[](void *p, std::align_val_t) noexcept
{
    std::free(p);
}
void operator delete(void *p, std::size_t, std::align_val_t) noexcept
{
    std::free(p);
}
void operator delete[](void *p, std::size_t, std::align_val_t) noexcept
{
    std::free(p);
}

#endif
