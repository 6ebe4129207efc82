#ifndef MESHGAP_DISTANCE_PENETRATION_DEPTH_H
#define MESHGAP_DISTANCE_PENETRATION_DEPTH_H

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/geometry/Body.h"

namespace meshgap
{
    /** \brief A penetration-depth estimate for two bodies at a pose, and its evidence. */
    struct PenetrationEstimate
    {
        /** \brief The depth (>= 0): see penetrationDepth(). */
        double depth{0.0};
        /** \brief DEEPEST_NODE when some node lies inside the other body; otherwise NO_NODE_INSIDE, or OPEN_BODIES when
            neither body is closed. */
        Penetration kind{Penetration::NO_NODE_INSIDE};
        /** \brief For DEEPEST_NODE: the deepest node (on one body) and the nearest point to it on the other body's
            surface, as points of A and of B, in A's frame (onA - onB is then the translation of B, of length depth,
            that brings that node to the surface). Otherwise a point common to two touching triangles (onA == onB),
            when bvhCollide() finds one. */
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
        std::uint32_t triangleA{0}, triangleB{0};  ///< surface triangles holding onA and onB
        bool witnessFound{false};                  ///< onA/onB/triangleA/triangleB were set
        std::size_t nodesTested{0};                ///< nodes inside the other body's bounding box (the candidates)
        std::size_t insideTests{0};    ///< point-in-body tests made (ray casts, with the winding number as fallback)
        std::size_t triangleTests{0};  ///< point-triangle distances computed
    };

    /** \brief What penetrationDepth() carries from one pose to the next, nearby one, for one pair of bodies: the
        deepest node it found last (on which body, and where in that body's node clusters). At the next pose that
        node's depth, found exactly as the search would find it, starts the branch and bound just below it, so the
        clusters and nodes that cannot reach it are never visited. It never changes the answer: a node tied with it
        that comes first in the fixed order still wins (see penetrationDepth()). Belongs to one caller (one thread). */
    struct PenetrationWarmStart
    {
        bool valid{false};          ///< the fields below hold the last deepest node
        bool hostIsA{false};        ///< the node is B's, inside A (true), or A's, inside B
        std::uint32_t cluster{0};   ///< its cluster, an index in the mover's Body::clusters()
        std::uint32_t position{0};  ///< its index in the mover's Body::clusterOrder()
        /** \brief Per node (B's, then A's, by position in clusterOrder()) and per node cluster (B's, then A's), the
            triangle of the other body found nearest to it (to the cluster's centre) at an earlier pose, or none
            (UINT32_MAX): its distance bounds the node's depth, or the cluster's, from above, often enough to skip a
            point query. Sized at the first use; reset() need not clear it (any triangle gives a true bound). */
        std::vector<std::uint32_t> nearest;
        /** \brief Bytes held beyond the object itself. */
        std::size_t memoryBytes() const { return nearest.capacity() * sizeof(std::uint32_t); }
    };

    /** \brief Penetration depth of two colliding bodies, B placed in A's frame by \e X_AB: the depth of the deepest
        node of either body that lies inside the other, closed, body.

        Method. For each closed body, the nodes of the other (the refined mesh's vertices: the surface's own
        vertices plus those refinement added, at most the grid size h apart) that lie in its bounding box are the
        candidates. A candidate's distance to that body's surface is computed exactly with its BVH
        (bvhPointDistance(), stopping as soon as a triangle is nearer than the deepest node so far: such a node
        cannot be the deepest); only a candidate that would be the new deepest is tested for being inside (a ray
        cast through the BVH counting signed crossings, bvhRayWinding(), with containsPoint()'s winding number
        when three directions are all ambiguous). Candidates are visited by branch and bound over the node
        clusters (deepest possible by the grid first, each cluster's centre measured when its turn comes; a cluster
        whose ball the surface does not cross takes one inside test),
        and a local side test at the nearest surface point (angle-weighted pseudonormal) filters the inside tests.
        The clusters are placed once per host, by a descent of the other body's cluster tree (Body::clusterTree())
        that drops at once every ball beyond the host's bounding box or wholly outside it by the grid. Each closed
        body's SurfaceGrid (Body::surfaceGrid(), built on first use) bounds, at the price of a cell look-up, how
        deep a cluster's nodes can be (the cell's hi plus the radius) and says when a ball lies wholly outside: the
        search starts from the depth of the node the grid finds deepest (measured exactly, as the search would) and
        skips without a point query every cluster that cannot beat it (a cluster wider than two cells, unless one of
        its nodes' own cells reaches deeper). A point query starts from the least distance
        to a few triangles near the point: the one nearest to its grid cell's centre, those found nearest to the last
        cluster centre and the last node, and with a warm start the one found nearest to the same node or centre at
        the last pose; often one of them settles the node or the cluster without a query. A verdict-only query
        (stopBelow >= 0, or computeDepth false) skips it all (its cost per colliding pair: bench/README.md,
        "Penetration depth").

        What it estimates. If a point p of B lies inside closed A at distance d from A's surface, every translation
        of B shorter than d keeps p inside A, so the bodies still collide: d, and so the returned depth, is a
        \b lower \b bound on the translational penetration depth (the shortest translation that separates them).
        It is exact for a box pushed face-first into another box (a node at the deepest corner), and for two
        spheres it misses the true depth r1 + r2 - c only by the mesh resolution (the deepest point's distance to
        the nearest node, plus the gap between the sphere and its inscribed mesh). It is 0, with kind
        NO_NODE_INSIDE, when the surfaces cross or touch with no node inside the other body (a shallow crossing
        between two node spacings): a finer grid finds such nodes. Nodes of an open body count when they lie inside
        a closed one (an open sheet through a closed body has points inside it, which is a collision too).

        Open bodies. An open surface (Body::isClosed() false: boundary or non-manifold edges) has no inside, so no
        node is ever taken to lie inside it; a node of an open body inside a closed one counts as any node does
        (the closed body's inside is defined, and the bound above holds: a translation shorter than that node's
        depth leaves it inside). With one body open the depth is thus the deepest node of the open body inside the
        closed one, or 0 with kind NO_NODE_INSIDE; with both bodies open the result is depth 0, kind OPEN_BODIES,
        and the witness is a touching triangle pair. The caller sees DistanceResult::openBody.

        Call it for colliding bodies only (it does not decide collision: separated bodies get NO_NODE_INSIDE, depth
        0, or a node "inside" a body it does not touch when one contains the other, which is a collision). A pure
        function of the bodies and the pose, warm start or not (deterministic ties: of the nodes at the largest
        depth, the first in a fixed order wins: the order of the visit, clusters by decreasing bound by the grid then
        index). Thread-safe.

        Warm start. With \e warm (the caller's, from its last query of this pair), the last deepest node's depth at
        this pose is a lower bound found first, raised to the grid's deepest node's where that node's cell says it
        may lie deeper (poses far apart): the search then skips every cluster and node that cannot go deeper.
        The answer is the same, bit for bit, as without it (the bound starts just below that depth, so a node tied
        with it and visited first still wins); only the cost falls along a run of nearby colliding poses. \e warm
        is then set to the node found (or marked invalid when none is inside). */
    PenetrationEstimate penetrationDepth(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB,
                                         PenetrationWarmStart *warm = nullptr);

    /** \brief Fill \e result for a colliding pair from penetrationDepth(): inCollision, distance =
        -depth (CONTACT_DISTANCE when the depth is 0), penetrationDepth, penetration, and the witness points and
        triangles when it found some; adds to triangleTests. \e warm: as penetrationDepth()'s. */
    void setPenetration(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result,
                        PenetrationWarmStart *warm = nullptr);
}  // namespace meshgap

#endif
