#ifndef MESHGAP_MESH_MESH_H
#define MESHGAP_MESH_MESH_H

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "meshgap/Limits.h"

namespace meshgap
{
    /** \brief Index of a triangle's three vertices. */
    using Triangle = std::array<std::uint32_t, 3>;

    /** \brief A triangle surface mesh in its body frame: the paper's node matrix N (#V rows) and facet matrix F
        (#F rows of three node indices), Section II-A.1. Plain data; Body makes it immutable. */
    struct Mesh
    {
        std::vector<Eigen::Vector3d> vertices;  ///< #V node positions
        std::vector<Triangle> triangles;        ///< #F triangles, indices into vertices
        std::string source;                     ///< file it came from, or a generator's name (for messages)

        /** \brief Axis-aligned bounding box of the vertices (empty box for an empty mesh). */
        Eigen::AlignedBox3d bounds() const;

        /** \brief Length of the bounding box diagonal: the body's size, to which tolerances and the default grid
            size are relative. */
        double size() const;

        /** \brief Throws meshgap::Exception naming \e source if the mesh has no triangles, a NaN/Inf coordinate, a
            coordinate beyond MAX_MAGNITUDE (meshgap/Limits.h) or an index out of range. Degenerate triangles are not
            checked here (see removeDegenerate()). */
        void validate() const;
    };

    namespace detail
    {
        /** \brief checkVertex()'s error: throws meshgap::Exception naming \e where, the vertex \e index and what is
            wrong with \e p. */
        [[noreturn]] void throwBadVertex(const std::string &where, std::size_t index, const Eigen::Vector3d &p);
    }  // namespace detail

    /** \brief Throws meshgap::Exception naming \e where unless every coordinate of \e p is finite and within
        MAX_MAGNITUDE (meshgap/Limits.h); the message names the vertex (\e index) and, for one beyond the limit, its
        value. Mesh::validate() checks each vertex with it, and loadMesh() each vertex as it reads it. */
    inline void checkVertex(const std::string &where, std::size_t index, const Eigen::Vector3d &p)
    {
        // Negated, so that a NaN (every comparison with it false) fails too.
        if (!(std::abs(p.x()) <= MAX_MAGNITUDE && std::abs(p.y()) <= MAX_MAGNITUDE && std::abs(p.z()) <= MAX_MAGNITUDE))
            detail::throwBadVertex(where, index, p);
    }

    /** \brief What cleaning a mesh removed. */
    struct CleanReport
    {
        std::size_t degenerate{0};  ///< zero-area triangles (repeated index, or collinear corners)
        std::size_t duplicates{0};  ///< triangles with the same three vertices as an earlier one (either winding)
        std::size_t unused{0};      ///< vertices no triangle uses
    };

    /** \brief How a surface's edges are shared, counted over undirected edges (pairs of vertex indices, so a mesh
        should be welded first: cleanMesh()). A surface is closed (a solid's boundary: inside and outside are
        defined) when it has triangles and every edge is used by exactly two of them: both counts 0. */
    struct EdgeReport
    {
        std::size_t boundaryEdges{0};     ///< edges used by one triangle only (a hole's rim, a sheet's border)
        std::size_t nonManifoldEdges{0};  ///< edges used by three or more triangles (fins, shells meeting on an edge)
        /** \brief Neither boundary nor non-manifold edges (true for no triangles too: see Body::isClosed()). */
        bool closed() const { return boundaryEdges == 0 && nonManifoldEdges == 0; }
    };

    /** \brief Count the boundary and non-manifold edges of \e mesh (indices must be in range). */
    EdgeReport countEdges(const Mesh &mesh);

    /** \brief Weld vertices at identical positions, drop degenerate and duplicated triangles and unused vertices.
        Welding is by exact position (normals, UVs and colours play no part), so flat-shaded files that repeat a
        vertex per face become one connected surface. Triangle order and winding are kept. */
    CleanReport cleanMesh(Mesh &mesh);

    /** \brief Number of connected components of the mesh's vertex-edge graph (vertices used by no triangle are
        components of their own). */
    std::size_t countComponents(const Mesh &mesh);

    /** \brief The connected component of each vertex in the vertex-edge graph (joined along triangle edges),
        numbered from 0 in order of each component's first vertex; a vertex no triangle uses is a component of its
        own. The triangles' indices must be in range (Mesh::validate()). \e count receives the number of components.
        The one component labeller: SurfaceGraph, countComponents() and splitComponents() use it. */
    std::vector<std::uint32_t> labelComponents(const Mesh &mesh, std::uint32_t &count);

    /** \brief Length of the longest triangle edge. */
    double longestEdge(const Mesh &mesh);
}  // namespace meshgap

#endif
