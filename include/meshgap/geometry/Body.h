#ifndef MESHGAP_GEOMETRY_BODY_H
#define MESHGAP_GEOMETRY_BODY_H

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/mesh/Mesh.h"
#include "meshgap/mesh/MeshDistances.h"
#include "meshgap/geometry/NodeSizing.h"
#include "meshgap/mesh/Refine.h"
#include "meshgap/mesh/SurfaceGraph.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(Body);

    /** \brief How the grid size of a body's nodes is chosen. */
    enum class GridSizing
    {
        UNIFORM,  ///< one size h everywhere (BodyOptions::gridSize)
        ADAPTIVE  ///< a size that follows the local feature size (BodyOptions::adaptive, adaptiveNodeSizes())
    };

    /** \brief How to turn a mesh into a body. */
    struct BodyOptions
    {
        /** \brief Default grid size as a fraction of the body's size (bounding-box diagonal). */
        static constexpr double DEFAULT_GRID_FRACTION = 1.0 / 25.0;

        /** \brief Target grid size h: edges longer than h are split (see refineMesh()). A negative value means
            DEFAULT_GRID_FRACTION times the body's size; 0 (or +infinity) keeps the mesh as it is. */
        double gridSize{-1.0};
        /** \brief Uniform (gridSize) or adaptive (finer at thin parts, pegs, holes and creases, coarser on large
            thick parts: refineMesh() with the sizes of adaptiveNodeSizes(adaptive)); gridSize is ignored when
            Adaptive. */
        GridSizing sizing{GridSizing::UNIFORM};
        /** \brief The adaptive rule (used when sizing is Adaptive). */
        AdaptiveSizing adaptive;
        /** \brief Mesh distances (built on first use of distances()). */
        MeshDistancesOptions distances;
    };

    /** \brief A group of nearby nodes with a bounding sphere, for exact pruning in enumeration. */
    struct NodeCluster
    {
        Eigen::Vector3d center;  ///< body frame
        double radius;           ///< every node of the cluster is within radius of center
        std::uint32_t begin, end;  ///< range in Body::clusterOrder()
    };

    /** \brief A rigid body for distance queries: its surface as given (with a triangle BVH, for exact distance and
        collision), the refined mesh whose nodes the combinatorial solvers search, the surface graph Pi, mesh
        distances D/P, and node data laid out for fast enumeration. Immutable once built and safe to share between threads;
        the mesh distances are computed on first request (once, thread-safely), since enumeration and hill climbing
        do not need them. */
    class Body
    {
    public:
        /** \brief Build a body from a mesh in its own frame. The mesh must be valid (see Mesh::validate()). */
        static BodyPtr build(Mesh mesh, const BodyOptions &options = BodyOptions());

        const std::string &name() const { return mesh_.source; }
        /** \brief The refined mesh: its vertices are the nodes the combinatorial solvers search. */
        const Mesh &mesh() const { return mesh_; }
        /** \brief The surface as given (cleaned, not refined): what exact distance and collision use. */
        const Mesh &surface() const { return surface_; }
        /** \brief BVH over surface()'s triangles. */
        const TriangleBvh &bvh() const { return *bvh_; }
        /** \brief Surface triangles that contain node \e i (at a corner, on an edge or inside). */
        const std::uint32_t *beginNodeTriangles(std::uint32_t i) const
        {
            return nodeTriangles_.data() + nodeTriangleOffsets_[i];
        }
        const std::uint32_t *endNodeTriangles(std::uint32_t i) const
        {
            return nodeTriangles_.data() + nodeTriangleOffsets_[i + 1];
        }
        /** \brief Surface triangles sharing a corner with surface triangle \e t (t excluded). */
        const std::uint32_t *beginTriangleNeighbours(std::uint32_t t) const
        {
            return triangleNeighbours_.data() + triangleNeighbourOffsets_[t];
        }
        const std::uint32_t *endTriangleNeighbours(std::uint32_t t) const
        {
            return triangleNeighbours_.data() + triangleNeighbourOffsets_[t + 1];
        }
        /** \brief True when every surface edge is shared by exactly two triangles (a closed surface: edges() counts
            no boundary and no non-manifold edge), so inside and outside are defined. Only a closed body has an
            inside: containment is tested, and penetration depth measured, inside closed bodies only; a body that
            is not closed ("open") still collides by surface contact, and its nodes count when they lie inside a
            closed body (penetrationDepth(), DistanceResult::openBody). */
        bool isClosed() const { return closed_; }
        /** \brief Boundary and non-manifold edges of surface() (both 0 for a closed body). */
        const EdgeReport &edges() const { return edges_; }
        /** \brief +1 when the surface's triangles wind outward (positive signed volume), -1 when inward: which side
            of a triangle is inside, for a closed body. */
        double orientation() const { return orientation_; }
        const SurfaceGraph &graph() const { return *graph_; }
        /** \brief One node of each connected component of the surface, in component order: a part with no surface
            contact with another body lies wholly inside or wholly outside it, so one point per part decides. */
        const std::vector<std::uint32_t> &componentNodes() const { return componentNodes_; }
        const RefineReport &refinement() const { return refinement_; }
        /** \brief The grid size used (0 when not refined); with adaptive sizing, the largest target size (every
            node-mesh edge is at most that long unless the input's was). */
        double gridSize() const { return gridSize_; }
        /** \brief True when the nodes were placed by adaptive sizing. */
        bool adaptiveSizing() const { return adaptive_; }
        std::uint32_t numNodes() const { return static_cast<std::uint32_t>(mesh_.vertices.size()); }
        const Eigen::Vector3d &node(std::uint32_t i) const { return mesh_.vertices[i]; }

        /** \brief Mesh distances D and P, built on the first call. */
        const MeshDistances &distances() const;

        /** \brief Leaf clusters of nodes (at most 32 nodes each), and the node order they index. Node coordinates in
            that order are given as separate x, y, z arrays (structure of arrays). */
        const std::vector<NodeCluster> &clusters() const { return clusters_; }
        const std::vector<std::uint32_t> &clusterOrder() const { return order_; }
        const std::vector<double> &xs() const { return xs_; }
        const std::vector<double> &ys() const { return ys_; }
        const std::vector<double> &zs() const { return zs_; }

        /** \brief Radius of the smallest origin-centred ball holding every node (bounds how far a node moves under a
            rotation about the body origin). */
        double radiusAboutOrigin() const { return originRadius_; }

    private:
        Body() = default;
        void buildClusters();
        void buildSurfaceMaps(const std::vector<std::uint32_t> &parent);

        Mesh surface_;
        std::unique_ptr<TriangleBvh> bvh_;
        Mesh mesh_;
        std::vector<std::uint32_t> nodeTriangleOffsets_, nodeTriangles_;
        std::vector<std::uint32_t> triangleNeighbourOffsets_, triangleNeighbours_;
        bool closed_{false};
        EdgeReport edges_;
        double orientation_{1.0};
        RefineReport refinement_;
        double gridSize_{0.0};
        bool adaptive_{false};
        std::shared_ptr<const SurfaceGraph> graph_;
        std::vector<std::uint32_t> componentNodes_;
        MeshDistancesOptions distanceOptions_;
        mutable std::once_flag distancesOnce_;
        mutable MeshDistancesConstPtr distances_;
        std::vector<NodeCluster> clusters_;
        std::vector<std::uint32_t> order_;
        std::vector<double> xs_, ys_, zs_;
        double originRadius_{0.0};
    };
}  // namespace meshgap

#endif
