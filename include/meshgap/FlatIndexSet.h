#ifndef MESHGAP_FLAT_INDEX_SET_H
#define MESHGAP_FLAT_INDEX_SET_H

#include <cstdint>
#include <vector>

namespace meshgap
{
    /** \brief A set of indices into the caller's array of keys, by open addressing: one flat array of slots (a power
        of two, at most half full, so probe sequences stay short), linear probing from the hash's low bits, each slot
        holding an index and the high half of its key's hash (most unequal keys are told apart without reading
        them). Sized once for at most \e keys insertions; no allocation per key, no erase. The caller hashes (equal
        keys must have equal hashes) and compares. */
    class FlatIndexSet
    {
    public:
        explicit FlatIndexSet(std::size_t keys)
        {
            std::size_t capacity = 16;
            while (capacity < 2 * keys)
                capacity *= 2;
            slots_.assign(capacity, Slot{0u, EMPTY});
            mask_ = capacity - 1;
        }

        /** \brief The index of the first inserted key equal to the one at \e index (\e equal(i): whether the key at
            i is), whose hash is \e hash; if there is none, \e index is inserted and returned. */
        template <class Equal>
        std::uint32_t findOrInsert(std::uint64_t hash, std::uint32_t index, const Equal &equal)
        {
            const auto tag = static_cast<std::uint32_t>(hash >> 32);
            for (std::size_t s = hash & mask_;; s = (s + 1) & mask_)
            {
                Slot &slot = slots_[s];
                if (slot.index == EMPTY)
                {
                    slot = Slot{tag, index};
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
        std::vector<Slot> slots_;
        std::size_t mask_{0};
    };
}  // namespace meshgap

#endif
