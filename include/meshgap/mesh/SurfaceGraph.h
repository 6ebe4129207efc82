#ifndef MESHGAP_MESH_SURFACE_GRAPH_H
#define MESHGAP_MESH_SURFACE_GRAPH_H

#include <cstdint>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief The paper's connectivity matrix Pi (Section II-A.1), stored as compressed rows: the neighbours of node
        i are neighbours()[offsets()[i] .. offsets()[i+1]), with the Euclidean edge lengths beside them. Each mesh
        edge appears in both rows. Immutable once built. */
    class SurfaceGraph
    {
    public:
        SurfaceGraph() = default;
        /** \brief Build from the unique edges of the mesh's triangles. */
        explicit SurfaceGraph(const Mesh &mesh);

        std::uint32_t numNodes() const { return static_cast<std::uint32_t>(offsets_.empty() ? 0 : offsets_.size() - 1); }
        /** \brief Number of undirected edges. */
        std::size_t numEdges() const { return neighbours_.size() / 2; }

        const std::vector<std::uint32_t> &offsets() const { return offsets_; }
        const std::vector<std::uint32_t> &neighbours() const { return neighbours_; }
        const std::vector<double> &lengths() const { return lengths_; }

        std::uint32_t degree(std::uint32_t node) const { return offsets_[node + 1] - offsets_[node]; }
        const std::uint32_t *beginNeighbours(std::uint32_t node) const { return neighbours_.data() + offsets_[node]; }
        const std::uint32_t *endNeighbours(std::uint32_t node) const { return neighbours_.data() + offsets_[node + 1]; }

        /** \brief Connected component of each node, numbered 0 .. numComponents()-1 in order of first node. */
        const std::vector<std::uint32_t> &components() const { return component_; }
        std::uint32_t numComponents() const { return numComponents_; }
        std::uint32_t component(std::uint32_t node) const { return component_[node]; }

    private:
        std::vector<std::uint32_t> offsets_;
        std::vector<std::uint32_t> neighbours_;
        std::vector<double> lengths_;
        std::vector<std::uint32_t> component_;
        std::uint32_t numComponents_{0};
    };
}  // namespace meshgap

#endif
