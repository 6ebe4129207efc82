#include <gtest/gtest.h>

#include <set>
#include <thread>
#include <vector>

#include "meshgap/ThreadInstances.h"

using namespace meshgap;

namespace
{
    /** \brief An instance that counts how many are alive, and says which id and which construction it is. */
    struct Tracked
    {
        explicit Tracked(int t) : tag(t) { ++alive; }
        ~Tracked() { --alive; }
        Tracked(const Tracked &) = delete;
        Tracked &operator=(const Tracked &) = delete;
        int tag;
        int uses{0};
        static thread_local int alive;
    };
    thread_local int Tracked::alive = 0;
}  // namespace

// Ids are unique, also when threads take them at once.
TEST(ThreadInstances, IdsAreUniqueAcrossThreads)
{
    std::vector<std::vector<std::uint64_t>> taken(4);
    std::vector<std::thread> workers;
    for (auto &ids : taken)
        workers.emplace_back([&ids] {
            for (int i = 0; i < 1000; ++i)
                ids.push_back(newInstanceId());
        });
    for (std::thread &w : workers)
        w.join();
    std::set<std::uint64_t> all;
    for (const auto &ids : taken)
        all.insert(ids.begin(), ids.end());
    EXPECT_EQ(all.size(), 4000u);
}

// An instance is kept from call to call; a thread holds at most Kept of them, the oldest objects' going first, and an
// object whose instance went gets a fresh one; another thread has instances of its own.
TEST(ThreadInstances, KeepsTheLastObjectsInstancesPerThread)
{
    constexpr std::size_t KEPT = 3;
    std::vector<std::uint64_t> ids;
    for (int k = 0; k < 6; ++k)
        ids.push_back(newInstanceId());
    const int aliveBefore = Tracked::alive;
    const auto use = [](std::uint64_t id, int tag) -> Tracked & { return threadInstanceFor<Tracked, KEPT>(id, tag); };
    Tracked &first = use(ids[0], 100);
    first.uses = 7;
    EXPECT_EQ(&use(ids[0], 999), &first);  // kept: the arguments are not used again
    EXPECT_EQ(use(ids[0], 999).tag, 100);
    for (std::size_t k = 1; k < ids.size(); ++k)
        use(ids[k], 100 + static_cast<int>(k)).uses = 1;
    EXPECT_EQ(Tracked::alive - aliveBefore, static_cast<int>(KEPT));  // bounded
    // The newest three are kept as they were...
    for (std::size_t k = ids.size() - KEPT; k < ids.size(); ++k)
    {
        const Tracked &t = use(ids[k], -1);
        EXPECT_EQ(t.tag, 100 + static_cast<int>(k));
        EXPECT_EQ(t.uses, 1);
    }
    // ... the first went, and comes back afresh (and pushes out the oldest kept one).
    const Tracked &again = use(ids[0], 5);
    EXPECT_EQ(again.tag, 5);
    EXPECT_EQ(again.uses, 0);
    EXPECT_EQ(Tracked::alive - aliveBefore, static_cast<int>(KEPT));

    int otherTag = 0, otherUses = -1;
    std::thread other([&] {
        const Tracked &t = use(ids.back(), 42);
        otherTag = t.tag;
        otherUses = t.uses;
    });
    other.join();
    EXPECT_EQ(otherTag, 42);
    EXPECT_EQ(otherUses, 0);
}
