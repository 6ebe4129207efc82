#ifndef MESHGAP_OMPL_STATE_POOL_H
#define MESHGAP_OMPL_STATE_POOL_H

#include <ompl/base/StateSpace.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <utility>

namespace meshgap
{
    /** \brief Working states of one state space for the threads that use an object at once (a motion validator,
        an objective): a Lease takes a kept state, or allocates one when every kept state is in use, and gives it
        back when it ends. A thread that has warmed up allocates nothing, and threads do not wait for each other
        (no lock: each kept state sits in an atomic slot). States beyond the slots are freed on return. */
    class StatePool
    {
    public:
        explicit StatePool(ompl::base::StateSpacePtr space) : space_(std::move(space))
        {
            for (std::atomic<ompl::base::State *> &slot : slots_)
                slot.store(nullptr, std::memory_order_relaxed);
        }
        ~StatePool()
        {
            for (std::atomic<ompl::base::State *> &slot : slots_)
                if (ompl::base::State *s = slot.exchange(nullptr))
                    space_->freeState(s);
        }
        StatePool(const StatePool &) = delete;
        StatePool &operator=(const StatePool &) = delete;

        /** \brief One state of the pool's space, the caller's until the lease ends. */
        class Lease
        {
        public:
            explicit Lease(StatePool &pool) : pool_(pool), state_(pool.take()) {}
            ~Lease() { pool_.give(state_); }
            Lease(const Lease &) = delete;
            Lease &operator=(const Lease &) = delete;

            ompl::base::State *get() const { return state_; }

        private:
            StatePool &pool_;
            ompl::base::State *state_;
        };

    private:
        /** \brief Enough for OMPL's parallel planners and Python's thread pools on the machines we know; more
            threads at once still work, allocating each time. */
        static constexpr std::size_t SLOTS = 32;

        ompl::base::State *take()
        {
            for (std::atomic<ompl::base::State *> &slot : slots_)
                if (slot.load(std::memory_order_relaxed) != nullptr)
                    if (ompl::base::State *s = slot.exchange(nullptr, std::memory_order_acquire))
                        return s;
            return space_->allocState();
        }

        void give(ompl::base::State *s)
        {
            for (std::atomic<ompl::base::State *> &slot : slots_)
            {
                ompl::base::State *empty = nullptr;
                if (slot.load(std::memory_order_relaxed) == nullptr &&
                    slot.compare_exchange_strong(empty, s, std::memory_order_release, std::memory_order_relaxed))
                    return;
            }
            space_->freeState(s);
        }

        ompl::base::StateSpacePtr space_;
        std::array<std::atomic<ompl::base::State *>, SLOTS> slots_;
    };
}  // namespace meshgap

#endif
