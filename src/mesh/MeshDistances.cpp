#include "meshgap/mesh/MeshDistances.h"

#include <ompl/util/Console.h>

#include <algorithm>
#include <atomic>
#include <boost/graph/detail/d_ary_heap.hpp>
#include <boost/property_map/property_map.hpp>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <mutex>
#include <new>
#include <thread>
#include <utility>

#include "meshgap/Exception.h"
#include "meshgap/mesh/DistanceCache.h"

/* Both strategies run the very same Dijkstra (DijkstraCore::run()): the loop of Boost.Graph's
   dijkstra_shortest_paths_no_color_map_no_init, over SurfaceGraph's CSR arrays in their edge order, with Boost's
   4-ary indirect heap (boost::d_ary_heap_indirect) on raw-pointer distance and index-in-heap arrays. The dense
   table runs it to the end from every source; an on-demand query runs it from the first argument and stops when the
   target is settled or the next node to settle lies beyond the radius. Up to that point both perform the same heap
   operations on the same values, and a settled node's distance and predecessor never change afterwards (weights
   are >= 0, relaxation needs a strict decrease), so answers agree bit for bit, ties included.

   The loop is ours rather than Boost.Graph's function because that function can only be stopped early by throwing
   from its visitor (an allocation and an unwind per search), and it builds its heap, a std::vector, afresh on every
   call; ours stops by returning and keeps the heap's storage in the caller's buffer. Its operations (pop, the
   examine test, relaxation, push or decrease-key) are Boost's, in Boost's order, so the searches, and with them
   every distance and predecessor, are those the Boost.Graph call gave.

   Keeping an on-demand query proportional to the region it searches, and free of allocations once a thread has
   warmed up: the distance array lives in a per-thread workspace that stays at +inf except for the nodes a search
   touched, which are recorded and reset afterwards; the index-in-heap array, the heap's storage and the list of
   touched nodes are sized to the largest graph seen on the thread and never shrink. The heap never reads an
   index-in-heap slot it has not written during the same search, so that array needs no clearing. */

namespace meshgap
{
    namespace
    {
        constexpr std::uint32_t NO_NODE = std::numeric_limits<std::uint32_t>::max();
        constexpr double INF = std::numeric_limits<double>::infinity();

        /** \brief The heap's storage as boost::d_ary_heap_indirect needs it (a std::vector-like container) over the
            caller's array of one slot per node: a node enters the heap at most once per search, so it never fills
            up, and a push never allocates. */
        struct HeapStorage
        {
            using value_type = std::uint32_t;
            using size_type = std::size_t;

            std::uint32_t *slots;
            size_type count{0};

            size_type size() const { return count; }
            bool empty() const { return count == 0; }
            void push_back(std::uint32_t x) { slots[count++] = x; }
            void pop_back() { --count; }
            std::uint32_t &back() { return slots[count - 1]; }
            std::uint32_t &operator[](size_type i) { return slots[i]; }
            const std::uint32_t &operator[](size_type i) const { return slots[i]; }
        };

        /** \brief Boost.Graph's Dijkstra queue: 4-ary, indirect on the distance array. */
        using Heap = boost::d_ary_heap_indirect<std::uint32_t, 4, std::size_t *, double *, std::less<double>,
                                                HeapStorage>;

        /** \brief Buffers of one search; the caller owns them (see DijkstraCore::run()). */
        struct SearchBuffers
        {
            double *dist;
            std::uint32_t *pred;
            std::size_t *heapSlots;
            /** \brief The heap's storage, one slot per node. */
            std::uint32_t *heap;
            /** \brief If not null, every node given a finite distance, except the source, is appended here
                (capacity >= the node count). */
            std::vector<std::uint32_t> *touched;
        };

        /** \brief SurfaceGraph's adjacency, with the Dijkstra loop both strategies share. */
        class DijkstraCore
        {
        public:
            explicit DijkstraCore(const SurfaceGraph &graph)
                : offsets_(graph.offsets()), neighbours_(graph.neighbours()), lengths_(graph.lengths()),
                  n_(graph.numNodes())
            {
                for (double len : lengths_)
                    if (!(len >= 0.0 && len < INF))
                        throw Exception("MeshDistances",
                                        "edge length " + std::to_string(len) + " is not a finite non-negative number");
            }

            std::uint32_t numNodes() const { return n_; }

            /** \brief Dijkstra from \e source, until \e target is settled (NO_NODE: never), the next node to settle
                lies farther than \e radius, or every reachable node is settled. On entry \e b.dist must be +inf
                everywhere; \e b.pred and \e b.heapSlots may hold anything. On return, every settled node has its
                final distance and predecessor (the source is its own predecessor). */
            void run(std::uint32_t source, const SearchBuffers &b, std::uint32_t target = NO_NODE,
                     double radius = INF) const
            {
                double *dist = b.dist;
                std::uint32_t *pred = b.pred;
                const std::uint32_t *offsets = offsets_.data(), *neighbours = neighbours_.data();
                const double *lengths = lengths_.data();
                dist[source] = 0.0;
                pred[source] = source;
                Heap queue(dist, b.heapSlots, std::less<double>(), HeapStorage{b.heap});
                queue.push(source);
                while (!queue.empty())
                {
                    const std::uint32_t u = queue.top();
                    queue.pop();
                    const double du = dist[u];
                    if (u == target || du > radius || !(du < INF))
                        return;  // settled the target, or everything left is beyond the radius or unreachable
                    for (std::uint32_t k = offsets[u], end = offsets[u + 1]; k < end; ++k)
                    {
                        // Boost's relax_target() with closed_plus (du and the length are finite).
                        const std::uint32_t v = neighbours[k];
                        const double dv = dist[v];
                        const double candidate = du + lengths[k];
                        if (!(candidate < dv))
                            continue;
                        dist[v] = candidate;
                        pred[v] = u;
                        if (dv < INF)
                            queue.update(v);
                        else
                        {
                            if (b.touched != nullptr)
                                b.touched->push_back(v);
                            queue.push(v);
                        }
                    }
                }
            }

        private:
            const std::vector<std::uint32_t> &offsets_;
            const std::vector<std::uint32_t> &neighbours_;
            const std::vector<double> &lengths_;
            std::uint32_t n_;
        };

        /** \brief Per-thread scratch for on-demand searches, shared by all MeshDistances objects on that thread:
            dist stays +inf between searches, so a search costs only what it touches. Every array is sized (or
            reserved) to the largest graph seen on the thread, so a warmed-up thread searches without allocating. */
        struct Workspace
        {
            std::vector<double> dist;
            std::vector<std::uint32_t> pred;
            std::vector<std::size_t> heapSlots;
            std::vector<std::uint32_t> heap;     // the heap's storage, one slot per node
            std::vector<std::uint32_t> touched;  // capacity >= dist.size(), so push_back never reallocates
            bool busy{false};

            void ensure(std::uint32_t n)
            {
                if (dist.size() < n)
                {
                    dist.resize(n, INF);
                    pred.resize(n);
                    heapSlots.resize(n);
                    heap.resize(n);
                    touched.reserve(n);
                }
            }
        };

        Workspace &threadWorkspace()
        {
            thread_local Workspace workspace;
            return workspace;
        }

        /** \brief One on-demand search in the thread's workspace; the destructor puts the workspace back to +inf. */
        class Search
        {
        public:
            Search(const DijkstraCore &core, std::uint32_t source)
                : core_(core), ws_(threadWorkspace()), source_(source)
            {
                if (ws_.busy)
                    throw Exception("MeshDistances", "nested on-demand search on one thread");
                ws_.ensure(core.numNodes());
                ws_.busy = true;
                ws_.touched.clear();
            }

            ~Search()
            {
                for (std::uint32_t v : ws_.touched)
                    ws_.dist[v] = INF;
                ws_.dist[source_] = INF;
                ws_.touched.clear();
                ws_.busy = false;
            }

            Search(const Search &) = delete;
            Search &operator=(const Search &) = delete;

            /** \brief Search until \e target is settled, the next node lies beyond \e radius, or all is settled. */
            void run(std::uint32_t target, double radius)
            {
                const SearchBuffers buffers{ws_.dist.data(), ws_.pred.data(), ws_.heapSlots.data(), ws_.heap.data(),
                                            &ws_.touched};
                core_.run(source_, buffers, target, radius);
            }

            double dist(std::uint32_t v) const { return ws_.dist[v]; }
            const std::uint32_t *pred() const { return ws_.pred.data(); }
            /** \brief Nodes reached, source excluded. */
            const std::vector<std::uint32_t> &touched() const { return ws_.touched; }

        private:
            const DijkstraCore &core_;
            Workspace &ws_;
            std::uint32_t source_;
        };

        /** \brief Path [u .. v] from a predecessor row (pred[w]: node before w on the path from u; pred[u] == u). */
        void tracePath(const std::uint32_t *pred, std::uint32_t u, std::uint32_t v, std::uint32_t numNodes,
                       std::vector<std::uint32_t> &out)
        {
            out.clear();
            if (pred[v] == NO_NODE)
                return;
            out.push_back(v);
            for (std::uint32_t w = v; w != u;)
            {
                w = pred[w];
                if (w >= numNodes || out.size() >= numNodes)
                    throw Exception("MeshDistances", "broken predecessor chain from node " + std::to_string(u) +
                                                         " to node " + std::to_string(v));
                out.push_back(w);
            }
            std::reverse(out.begin(), out.end());
        }

        unsigned int threadCount(unsigned int requested, std::uint32_t work)
        {
            unsigned int t = requested != 0 ? requested : std::thread::hardware_concurrency();
            t = std::max(1u, t);
            return std::max(1u, static_cast<unsigned int>(std::min<std::uint64_t>(t, work)));
        }

        /** \brief The all-pairs table: D and P as row-major numNodes x numNodes arrays. */
        class DenseMeshDistances : public MeshDistances
        {
        public:
            DenseMeshDistances(std::shared_ptr<const SurfaceGraph> graph, const MeshDistancesOptions &options)
                : MeshDistances(std::move(graph)), n_(graph_->numNodes())
            {
                const std::size_t entries = std::size_t(n_) * n_;
                // Uninitialised on purpose: every entry is written by the cache reader or by the row owner.
                D_.reset(new double[entries]);
                P_.reset(new std::uint32_t[entries]);

                const auto start = std::chrono::steady_clock::now();
                std::string cachePath;
                std::uint64_t hash = 0;
                if (!options.cacheDir.empty())
                {
                    hash = graphHash(*graph_);
                    cachePath = distanceCachePath(options.cacheDir, hash);
                    fromCache_ = readDistanceCache(cachePath, hash, n_, D_.get(), P_.get());
                }
                if (fromCache_)
                    maxDistance_ = scanMaxDistance();
                else
                    compute(threadCount(options.threads, n_));
                const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                OMPL_INFORM("meshgap: all-pairs mesh distances for %u nodes (%.1f MiB) %s in %.3f s", n_,
                            denseTableBytes(n_) / 1048576.0, fromCache_ ? "read from cache" : "computed", seconds);
                if (!cachePath.empty() && !fromCache_)
                    writeDistanceCache(cachePath, hash, n_, D_.get(), P_.get());
            }

            double distance(std::uint32_t u, std::uint32_t v) const override
            {
                check(u);
                check(v);
                return D_[std::size_t(u) * n_ + v];
            }

            void path(std::uint32_t u, std::uint32_t v, std::vector<std::uint32_t> &out) const override
            {
                check(u);
                check(v);
                tracePath(P_.get() + std::size_t(u) * n_, u, v, n_, out);
            }

            void nodesWithin(std::uint32_t u, double r, std::vector<std::uint32_t> &out) const override
            {
                check(u);
                out.clear();
                const double *row = D_.get() + std::size_t(u) * n_;
                for (std::uint32_t w = 0; w < n_; ++w)
                    if (row[w] <= r && row[w] < INF)  // never across components
                        out.push_back(w);
            }

            double maxDistance() const override { return maxDistance_; }

            bool isDense() const override { return true; }

            bool fromCache() const override { return fromCache_; }

        private:
            void check(std::uint32_t u) const
            {
                if (u >= n_)
                    throw Exception("MeshDistances",
                                    "node " + std::to_string(u) + " out of range (" + std::to_string(n_) + " nodes)");
            }

            /** \brief Dijkstra from every source, rows handed out one at a time to \e threads workers. */
            void compute(unsigned int threads)
            {
                const DijkstraCore core(*graph_);
                std::atomic<std::uint32_t> next{0};
                std::vector<double> threadMax(threads, 0.0);
                std::exception_ptr error;
                std::mutex errorMutex;
                auto worker = [&](unsigned int t)
                {
                    try
                    {
                        std::vector<std::size_t> heapSlots(n_);
                        std::vector<std::uint32_t> heap(n_);
                        double localMax = 0.0;
                        for (std::uint32_t s = next++; s < n_; s = next++)
                        {
                            double *dist = D_.get() + std::size_t(s) * n_;
                            std::uint32_t *pred = P_.get() + std::size_t(s) * n_;
                            std::fill(dist, dist + n_, INF);
                            std::fill(pred, pred + n_, NO_NODE);
                            core.run(s, SearchBuffers{dist, pred, heapSlots.data(), heap.data(), nullptr});
                            for (std::uint32_t v = 0; v < n_; ++v)
                                if (dist[v] < INF)
                                    localMax = std::max(localMax, dist[v]);
                        }
                        threadMax[t] = localMax;
                    }
                    catch (...)
                    {
                        std::lock_guard<std::mutex> lock(errorMutex);
                        if (!error)
                            error = std::current_exception();
                        next = n_;  // the others stop after their current row
                    }
                };
                std::vector<std::thread> pool;
                for (unsigned int t = 1; t < threads; ++t)
                    pool.emplace_back(worker, t);
                worker(0);
                for (std::thread &th : pool)
                    th.join();
                if (error)
                    std::rethrow_exception(error);
                maxDistance_ = n_ == 0 ? 0.0 : *std::max_element(threadMax.begin(), threadMax.end());
            }

            double scanMaxDistance() const
            {
                double m = 0.0;
                const std::size_t entries = std::size_t(n_) * n_;
                for (std::size_t k = 0; k < entries; ++k)
                    if (D_[k] < INF)
                        m = std::max(m, D_[k]);
                return m;
            }

            std::uint32_t n_;
            std::unique_ptr<double[]> D_;
            std::unique_ptr<std::uint32_t[]> P_;
            double maxDistance_{0.0};
            bool fromCache_{false};
        };

        /** \brief Bounded Dijkstra per query, in a per-thread workspace. */
        class OnDemandMeshDistances : public MeshDistances
        {
        public:
            explicit OnDemandMeshDistances(std::shared_ptr<const SurfaceGraph> graph)
                : MeshDistances(std::move(graph)), core_(*graph_), n_(graph_->numNodes())
            {
                OMPL_INFORM(
                    "meshgap: mesh distances for %u nodes computed on demand (a full table would take %.1f MiB)", n_,
                    denseTableBytes(n_) / 1048576.0);
            }

            double distance(std::uint32_t u, std::uint32_t v) const override
            {
                check(u);
                check(v);
                if (u == v)
                    return 0.0;
                if (graph_->component(u) != graph_->component(v))
                    return INF;
                Search search(core_, u);
                search.run(v, INF);
                return search.dist(v);
            }

            void path(std::uint32_t u, std::uint32_t v, std::vector<std::uint32_t> &out) const override
            {
                check(u);
                check(v);
                out.clear();
                if (u == v)
                {
                    out.push_back(u);
                    return;
                }
                if (graph_->component(u) != graph_->component(v))
                    return;
                Search search(core_, u);
                search.run(v, INF);
                if (search.dist(v) < INF)
                    tracePath(search.pred(), u, v, n_, out);
            }

            void nodesWithin(std::uint32_t u, double r, std::vector<std::uint32_t> &out) const override
            {
                check(u);
                out.clear();
                if (!(r >= 0.0))
                    return;
                Search search(core_, u);
                search.run(NO_NODE, r);
                // Every node popped had distance <= r, every node still queued has distance > r.
                out.push_back(u);
                for (std::uint32_t w : search.touched())
                    if (search.dist(w) <= r)
                        out.push_back(w);
            }

            double maxDistance() const override
            {
                std::call_once(maxOnce_, [this] { maxDistance_ = doubleSweep(); });
                return maxDistance_;
            }

            bool isDense() const override { return false; }

        private:
            void check(std::uint32_t u) const
            {
                if (u >= n_)
                    throw Exception("MeshDistances",
                                    "node " + std::to_string(u) + " out of range (" + std::to_string(n_) + " nodes)");
            }

            /** \brief Farthest node from \e u and its distance (first such node in search order on ties). */
            std::pair<std::uint32_t, double> farthest(std::uint32_t u) const
            {
                Search search(core_, u);
                search.run(NO_NODE, INF);
                std::pair<std::uint32_t, double> best{u, 0.0};
                for (std::uint32_t w : search.touched())
                    if (search.dist(w) > best.second)
                        best = {w, search.dist(w)};
                return best;
            }

            /** \brief Per component: farthest node b from its first node, then the eccentricity of b. A lower bound
                on the component's diameter (exact on trees and many meshes), at two searches per component. */
            double doubleSweep() const
            {
                std::vector<bool> seen(graph_->numComponents(), false);
                double best = 0.0;
                for (std::uint32_t u = 0; u < n_; ++u)
                {
                    const std::uint32_t c = graph_->component(u);
                    if (seen[c])
                        continue;
                    seen[c] = true;
                    if (graph_->degree(u) == 0)
                        continue;
                    best = std::max(best, farthest(farthest(u).first).second);
                }
                return best;
            }

            DijkstraCore core_;
            std::uint32_t n_;
            mutable std::once_flag maxOnce_;
            mutable double maxDistance_{0.0};
        };
    }  // namespace

    std::size_t MeshDistances::denseTableBytes(std::size_t numNodes)
    {
        constexpr std::size_t perEntry = sizeof(double) + sizeof(std::uint32_t);
        const std::size_t maxNodes = static_cast<std::size_t>(
            std::sqrt(static_cast<long double>(std::numeric_limits<std::size_t>::max() / perEntry)));
        if (numNodes > maxNodes)
            return std::numeric_limits<std::size_t>::max();
        return perEntry * numNodes * numNodes;
    }

    MeshDistancesPtr MeshDistances::build(const std::shared_ptr<const SurfaceGraph> &graph,
                                          const MeshDistancesOptions &options)
    {
        if (!graph)
            throw Exception("MeshDistances::build", "no surface graph given");
        const std::uint32_t n = graph->numNodes();
        if (denseTableBytes(n) <= options.memoryBudgetBytes)
        {
            try
            {
                return std::make_shared<DenseMeshDistances>(graph, options);
            }
            catch (const std::bad_alloc &)
            {
                OMPL_WARN(
                    "meshgap: no memory for the %.1f MiB all-pairs table of %u nodes; computing mesh distances "
                    "on demand instead",
                    denseTableBytes(n) / 1048576.0, n);
            }
        }
        else if (!options.cacheDir.empty())
            OMPL_INFORM(
                "meshgap: the %.1f MiB all-pairs table for %u nodes exceeds the memory budget; no cache is "
                "used for on-demand distances",
                denseTableBytes(n) / 1048576.0, n);
        return std::make_shared<OnDemandMeshDistances>(graph);
    }
}  // namespace meshgap
