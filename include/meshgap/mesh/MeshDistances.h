#ifndef MESHGAP_MESH_MESH_DISTANCES_H
#define MESHGAP_MESH_MESH_DISTANCES_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/mesh/SurfaceGraph.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(MeshDistances);

    /** \brief How to build mesh distances. */
    struct MeshDistancesOptions
    {
        /** \brief Largest all-pairs table (D and P together) kept in memory; larger meshes answer on demand. */
        std::size_t memoryBudgetBytes{512ull << 20};
        /** \brief Folder for the on-disk cache of all-pairs tables; empty means no cache. */
        std::string cacheDir;
        /** \brief Threads for the all-pairs build; 0 means std::thread::hardware_concurrency(). */
        unsigned int threads{0};
    };

    /** \brief The paper's mesh distance D and predecessor P (Section II-A.2): shortest paths along mesh edges,
        computed with Dijkstra. One interface for two storage strategies: an all-pairs table when it fits the memory
        budget, bounded on-demand searches otherwise. Nodes in different connected components are at infinite mesh
        distance and have an empty path. All const methods are thread-safe. */
    class MeshDistances
    {
    public:
        virtual ~MeshDistances() = default;

        /** \brief Build for \e graph (which must outlive the result), choosing dense or on-demand by the budget. */
        static MeshDistancesPtr build(const std::shared_ptr<const SurfaceGraph> &graph,
                                      const MeshDistancesOptions &options = MeshDistancesOptions());

        /** \brief Bytes an all-pairs table for \e numNodes nodes takes. */
        static std::size_t denseTableBytes(std::size_t numNodes);

        /** \brief Mesh distance delta_{u->v}; +infinity when u and v are in different components. */
        virtual double distance(std::uint32_t u, std::uint32_t v) const = 0;

        /** \brief Shortest path [u, ..., v] along mesh edges, rebuilt from P as the paper describes: P[u][v] is the
            node before v, P[u][that] the one before it, and so on back to u. Empty if v is unreachable from u. */
        virtual void path(std::uint32_t u, std::uint32_t v, std::vector<std::uint32_t> &out) const = 0;

        /** \brief All nodes w with distance(u, w) <= r, u included, in no particular order. */
        virtual void nodesWithin(std::uint32_t u, double r, std::vector<std::uint32_t> &out) const = 0;

        /** \brief The largest finite mesh distance, max(D): exact for the dense table, a lower bound from a double
            sweep per component for on-demand (the paper uses max(D)/2 as the mutation radius). */
        virtual double maxDistance() const = 0;

        /** \brief True for the all-pairs table. */
        virtual bool isDense() const = 0;

        /** \brief True when the table was read from the on-disk cache rather than computed. */
        virtual bool fromCache() const { return false; }

        const SurfaceGraph &graph() const { return *graph_; }

    protected:
        explicit MeshDistances(std::shared_ptr<const SurfaceGraph> graph) : graph_(std::move(graph)) {}
        std::shared_ptr<const SurfaceGraph> graph_;
    };
}  // namespace meshgap

#endif
