#ifndef MESHGAP_GEOMETRY_BODY_H
#define MESHGAP_GEOMETRY_BODY_H

#include <Eigen/Core>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/geometry/ConvexHull.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/mesh/Mesh.h"
#include "meshgap/mesh/MeshDistances.h"
#include "meshgap/geometry/NodeSizing.h"
#include "meshgap/mesh/Refine.h"
#include "meshgap/mesh/SurfaceGraph.h"
#include "meshgap/geometry/Primitive.h"
#include "meshgap/geometry/SurfaceGrid.h"

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

    /** \brief An entry of the ball tree over the node clusters, the median split that made them
        (Body::clusterTree()): every node of the clusters [firstCluster, endCluster) of Body::clusters() lies within
        radius of center. A leaf is one cluster (endCluster = firstCluster + 1, its own ball). */
    struct ClusterBall
    {
        Eigen::Vector3d center;  ///< body frame
        double radius;
        std::uint32_t firstCluster, endCluster;
        std::uint32_t skip;  ///< the entry after this one's subtree
    };

    /** \brief A rigid body for distance queries: its surface as given (with a triangle BVH, for exact distance and
        collision), the refined mesh whose nodes the combinatorial solvers search, the surface graph Pi, mesh
        distances D/P, and node data laid out for fast enumeration. Immutable once built and safe to share between threads.
        Body::build() makes what every exact query reads: the surface, its triangle BVH, its edges and orientation,
        one vertex per connected component. The node layer (refined mesh, node-to-triangle maps, surface graph,
        clusters) is built on the first call of an accessor that reads it, once and thread-safely: exact distance and
        collision never read it, the node solvers, their seeds and penetration depth do. The mesh distances are
        likewise built on first request, since enumeration and hill climbing do not need them. */
    class Body
    {
    public:
        /** \brief Build a body from a mesh in its own frame. The mesh must be valid (see Mesh::validate()). */
        static BodyPtr build(Mesh mesh, const BodyOptions &options = BodyOptions());
        /** \brief The same, for a mesh built from \e primitives (in the mesh's frame) that it circumscribes, every
            part of it one of them (primitives()). */
        static BodyPtr build(Mesh mesh, std::vector<Primitive> primitives,
                             const BodyOptions &options = BodyOptions());

        const std::string &name() const { return surface_.source; }
        /** \brief The refined mesh: its vertices are the nodes the combinatorial solvers search. */
        const Mesh &mesh() const { return nodeLayer().mesh; }
        /** \brief The surface as given (cleaned, not refined): what exact distance and collision use. */
        const Mesh &surface() const { return surface_; }
        /** \brief The primitive solids the surface was built from, in its frame, when it was built from primitives
            only (a URDF link of boxes, cylinders and spheres, a MoveIt scene's primitive): the surface circumscribes
            them (it contains each, and is what every meshgap query answers). Empty for a body built from a mesh. */
        const std::vector<Primitive> &primitives() const { return primitives_; }
        /** \brief BVH over surface()'s triangles. */
        const TriangleBvh &bvh() const { return *bvh_; }
        /** \brief Surface triangles that contain node \e i (at a corner, on an edge or inside). */
        const std::uint32_t *beginNodeTriangles(std::uint32_t i) const
        {
            const NodeLayer &layer = nodeLayer();
            return layer.nodeTriangles.data() + layer.nodeTriangleOffsets[i];
        }
        const std::uint32_t *endNodeTriangles(std::uint32_t i) const
        {
            const NodeLayer &layer = nodeLayer();
            return layer.nodeTriangles.data() + layer.nodeTriangleOffsets[i + 1];
        }
        /** \brief Surface triangles sharing a corner with surface triangle \e t (t excluded). */
        const std::uint32_t *beginTriangleNeighbours(std::uint32_t t) const
        {
            const NodeLayer &layer = nodeLayer();
            return layer.triangleNeighbours.data() + layer.triangleNeighbourOffsets[t];
        }
        const std::uint32_t *endTriangleNeighbours(std::uint32_t t) const
        {
            const NodeLayer &layer = nodeLayer();
            return layer.triangleNeighbours.data() + layer.triangleNeighbourOffsets[t + 1];
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
        const SurfaceGraph &graph() const { return *nodeLayer().graph; }
        /** \brief One vertex of surface() in each of its connected components (the component's first), in component
            order: a part with no surface contact with another body lies wholly inside or wholly outside it, so one
            point per part decides. The node mesh keeps surface()'s vertices first, so each is also that node. */
        const std::vector<std::uint32_t> &componentNodes() const { return componentNodes_; }
        const RefineReport &refinement() const { return nodeLayer().refinement; }
        /** \brief The grid size used (0 when not refined); with adaptive sizing, the largest target size (every
            node-mesh edge is at most that long unless the input's was). */
        double gridSize() const { return nodeLayer().gridSize; }
        /** \brief True when the nodes were placed by adaptive sizing. */
        bool adaptiveSizing() const { return options_.sizing == GridSizing::ADAPTIVE; }
        std::uint32_t numNodes() const { return static_cast<std::uint32_t>(nodeLayer().mesh.vertices.size()); }
        const Eigen::Vector3d &node(std::uint32_t i) const { return nodeLayer().mesh.vertices[i]; }

        /** \brief The grid of distance bounds and sides around the surface (SurfaceGrid), built on the first call
            (penetration depth reads it for a closed body). */
        const SurfaceGrid &surfaceGrid() const;

        /** \brief A conservative convex outer bound of the surface (ConvexHull: its vertices' hull grown by a margin
            that holds every vertex), built on the first call (once, thread-safely); null when the surface has none
            (flat, fewer than four vertices, a qhull failure): ask the mesh then. */
        const ConvexHull *convexHull() const;
        /** \brief A looser outer bound of fewer vertices (at most 384: those extreme along 384 directions, when the
            hull has more than 192), its margin covering the rest; cheaper to query where a fraction of a millimetre
            does not matter (a link swept along a piece of motion, RobotScene::sweptApart()). Built on the first
            call; null as convexHull(). */
        const ConvexHull *coarseHull() const;

        /** \brief Mesh distances D and P, built on the first call. */
        const MeshDistances &distances() const;

        /** \brief Leaf clusters of nodes (at most 32 nodes each), and the node order they index. Node coordinates in
            that order are given as separate x, y, z arrays (structure of arrays). */
        const std::vector<NodeCluster> &clusters() const { return nodeLayer().clusters; }
        const std::vector<std::uint32_t> &clusterOrder() const { return nodeLayer().order; }
        /** \brief The ball tree over clusters(), in depth-first order (the root first; an entry's subtree is the
            entries up to its skip): a search that rules a ball out skips every cluster in it at once. */
        const std::vector<ClusterBall> &clusterTree() const { return nodeLayer().clusterTree; }
        const std::vector<double> &xs() const { return nodeLayer().xs; }
        const std::vector<double> &ys() const { return nodeLayer().ys; }
        const std::vector<double> &zs() const { return nodeLayer().zs; }

        /** \brief Radius of the smallest origin-centred ball holding every node (bounds how far a node moves under a
            rotation about the body origin). */
        double radiusAboutOrigin() const { return nodeLayer().originRadius; }

    private:
        /** \brief What the node solvers, their seeds and penetration depth read, built on first use. */
        struct NodeLayer
        {
            Mesh mesh;  ///< the refined mesh: its vertices are the nodes
            RefineReport refinement;
            double gridSize{0.0};
            std::vector<std::uint32_t> nodeTriangleOffsets, nodeTriangles;
            std::vector<std::uint32_t> triangleNeighbourOffsets, triangleNeighbours;
            std::shared_ptr<const SurfaceGraph> graph;
            std::vector<NodeCluster> clusters;
            std::vector<ClusterBall> clusterTree;
            std::vector<std::uint32_t> order;
            std::vector<double> xs, ys, zs;
            double originRadius{0.0};
        };

        Body() = default;
        /** \brief The node layer, built by the first caller (others wait for it); afterwards one load. */
        const NodeLayer &nodeLayer() const
        {
            const NodeLayer *layer = layer_.load(std::memory_order_acquire);
            return layer != nullptr ? *layer : buildNodeLayer();
        }
        const NodeLayer &buildNodeLayer() const;
        static void buildClusters(NodeLayer &layer);
        void buildSurfaceMaps(NodeLayer &layer, const std::vector<std::uint32_t> &parent) const;

        Mesh surface_;
        std::vector<Primitive> primitives_;
        std::unique_ptr<TriangleBvh> bvh_;
        bool closed_{false};
        EdgeReport edges_;
        double orientation_{1.0};
        std::vector<std::uint32_t> componentNodes_;
        BodyOptions options_;
        mutable std::once_flag layerOnce_;
        mutable std::unique_ptr<const NodeLayer> layerStore_;
        mutable std::atomic<const NodeLayer *> layer_{nullptr};
        mutable std::once_flag gridOnce_;
        mutable std::unique_ptr<const SurfaceGrid> grid_;
        mutable std::once_flag hullOnce_;
        mutable std::shared_ptr<const ConvexHull> hull_;
        mutable std::once_flag coarseHullOnce_;
        mutable std::shared_ptr<const ConvexHull> coarseHull_;
        mutable std::once_flag distancesOnce_;
        mutable MeshDistancesConstPtr distances_;
    };
}  // namespace meshgap

#endif
