#ifndef MESHGAP_THREAD_SCRATCH_H
#define MESHGAP_THREAD_SCRATCH_H

namespace meshgap
{
    /** \brief The calling thread's instance of \e T (a query's working arrays) for the lifetime of this object:
        reused from query to query with its capacity kept, so a warmed-up thread allocates nothing. The caller
        empties what it needs emptied. A nested use on the same thread (while another ThreadScratch<T> is alive
        there) gets a fresh T of its own rather than the one in use. */
    template <typename T>
    class ThreadScratch
    {
    public:
        ThreadScratch() : slot_(threadSlot()), nested_(slot_.busy) { slot_.busy = true; }
        ~ThreadScratch()
        {
            if (!nested_)
                slot_.busy = false;
        }
        ThreadScratch(const ThreadScratch &) = delete;
        ThreadScratch &operator=(const ThreadScratch &) = delete;

        T &get() { return nested_ ? own_ : slot_.value; }

    private:
        struct Slot
        {
            T value;
            bool busy{false};
        };

        static Slot &threadSlot()
        {
            thread_local Slot slot;
            return slot;
        }

        Slot &slot_;
        bool nested_;
        T own_;
    };
}  // namespace meshgap

#endif
