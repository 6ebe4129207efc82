#ifndef MESHGAP_THREAD_INSTANCES_H
#define MESHGAP_THREAD_INSTANCES_H

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace meshgap
{
    /** \brief A number no other object of the process gets: the key of an object's per-thread state
        (threadInstanceFor()), never its address, which a later object could reuse. */
    inline std::uint64_t newInstanceId()
    {
        static std::atomic<std::uint64_t> next{1};
        return next.fetch_add(1, std::memory_order_relaxed);
    }

    namespace detail
    {
        template <typename T>
        std::unordered_map<std::uint64_t, T> &threadInstances()
        {
            thread_local std::unordered_map<std::uint64_t, T> instances;
            return instances;
        }
    }  // namespace detail

    /** \brief The calling thread's \e T for the object numbered \e id (newInstanceId()), made from \e args at its
        first use on this thread and kept from call to call (a checker's warm start and working arrays). A thread
        keeps the instances of its last \e Kept objects: when another arrives, the oldest object's (the smallest id)
        goes, so that a process making object after object (a benchmark's runs, a loop in Python) does not grow
        without bound; an object whose instance went starts afresh. The reference returned stays valid until this
        thread asks for an instance it does not hold while \e Kept are held (that drops the oldest object's): a
        caller holding one must not ask for another object's meanwhile (no checker calls another checker). */
    template <typename T, std::size_t Kept, typename... Args>
    T &threadInstanceFor(std::uint64_t id, Args &&...args)
    {
        static_assert(Kept > 0, "keep at least one instance");
        std::unordered_map<std::uint64_t, T> &instances = detail::threadInstances<T>();
        const auto found = instances.find(id);
        if (found != instances.end())
            return found->second;
        if (instances.size() >= Kept)
            instances.erase(std::min_element(instances.begin(), instances.end(),
                                             [](const auto &a, const auto &b) { return a.first < b.first; }));
        return instances.try_emplace(id, std::forward<Args>(args)...).first->second;
    }
}  // namespace meshgap

#endif
