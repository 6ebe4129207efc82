#ifndef MESHGAP_FLAT_INDEX_SET_H
#define MESHGAP_FLAT_INDEX_SET_H

#include <cstdint>
#include <vector>

namespace meshgap
{
    /** \brief A set of indices into the caller's array of keys, by open addressing: one flat array of slots (a power
        of two, at most half full, so probe sequences stay short), linear probing, each slot holding an index and the
        high half of its key's hash (its tag: most unequal keys are told apart without reading them, and the slot
        is the tag's leading bits, so the table grows by the tags alone). It starts small and doubles as it fills:
        when many keys are equal (a welded mesh has a sixth as many positions as corners) the slots stay few and in
        cache. No allocation per key, no erase. The caller hashes (equal keys must have equal hashes; the high 32
        bits are used) and compares. */
    class FlatIndexSet
    {
    public:
        /** \brief Room for \e expected keys before the first doubling. */
        explicit FlatIndexSet(std::size_t expected = 0)
        {
            bits_ = 4;
            while ((std::size_t(1) << bits_) < 2 * expected && bits_ < 32)
                ++bits_;
            slots_.assign(std::size_t(1) << bits_, Slot{0u, EMPTY});
        }

        /** \brief The index of the first inserted key equal to the one at \e index (\e equal(i): whether the key at
            i is), whose hash is \e hash; if there is none, \e index is inserted and returned. */
        template <class Equal>
        std::uint32_t findOrInsert(std::uint64_t hash, std::uint32_t index, const Equal &equal)
        {
            const auto tag = static_cast<std::uint32_t>(hash >> 32);
            const std::size_t mask = slots_.size() - 1;
            for (std::size_t s = home(tag);; s = (s + 1) & mask)
            {
                Slot &slot = slots_[s];
                if (slot.index == EMPTY)
                {
                    slot = Slot{tag, index};
                    if (2 * ++size_ > slots_.size() && bits_ < 32)
                        grow();
                    return index;
                }
                if (slot.tag == tag && equal(slot.index))
                    return slot.index;
            }
        }

    private:
        static constexpr std::uint32_t EMPTY = UINT32_MAX;
        struct Slot
        {
            std::uint32_t tag, index;
        };

        std::size_t home(std::uint32_t tag) const { return tag >> (32 - bits_); }

        /** \brief Twice the slots, each entry moved to its new home by its tag. */
        void grow()
        {
            std::vector<Slot> old(std::size_t(1) << ++bits_, Slot{0u, EMPTY});
            old.swap(slots_);
            const std::size_t mask = slots_.size() - 1;
            for (const Slot &slot : old)
                if (slot.index != EMPTY)
                {
                    std::size_t s = home(slot.tag);
                    while (slots_[s].index != EMPTY)
                        s = (s + 1) & mask;
                    slots_[s] = slot;
                }
        }

        std::vector<Slot> slots_;
        unsigned bits_{4};
        std::size_t size_{0};
    };
}  // namespace meshgap

#endif
