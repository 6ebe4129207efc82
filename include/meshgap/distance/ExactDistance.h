#ifndef MESHGAP_DISTANCE_EXACT_DISTANCE_H
#define MESHGAP_DISTANCE_EXACT_DISTANCE_H

#include <limits>

#include "meshgap/distance/DistanceSolver.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/geometry/TriangleBvh.h"

namespace meshgap
{
    /** \brief What exact queries between one pair of bodies carry from one pose to the next, nearby one (the paper's
        warm start, III-D, carried to the exact layer): the closest triangle pair of the last query, tested first as
        the best first guess, and the certificate of its traversal (BvhFront), re-tested only where the motion since
        may have changed it. Never changes an answer, only its cost. Belongs to one caller (one thread). */
    struct ExactWarmStart
    {
        bool valid{false};  ///< triangleA / triangleB hold the last closest pair
        std::uint32_t triangleA{0}, triangleB{0};
        BvhFront front;                    ///< of the last distance traversal
        BvhFront collision;                ///< of the last collision test (inCollision() with a warm start)
        PenetrationWarmStart penetration;  ///< the last deepest node, in collision (penetrationDepth())
        /** \brief Bytes held, this object included. */
        std::size_t memoryBytes() const
        {
            return sizeof(*this) + front.memoryBytes() + collision.memoryBytes() + penetration.memoryBytes();
        }
    };

    /** \brief The exact stage after a node-level search (the paper's future work, Section V): turn \e result's node
        answer into the exact distance between the two surfaces, with a certificate.

        1. Seed: the surface triangles around the result's two nodes; exact triangle distances over those pairs, then
           a descent over corner-sharing neighbouring triangles while the distance improves. (No seed when
           result.distance is infinite: the traversal starts from infinity, as a cold exact query.)
        2. Certificate: a BVH traversal (bvhDistance()) with the seed's value as upper bound either proves nothing is
           closer or finds the closer pair. certified is set when it completed.
        3. Collision: an intersecting or touching triangle pair, or, if no surface pair touches, one body wholly
           inside the other: for a closed body, one point of the other body is tested with the generalised winding
           number (FCL misses this case). Open bodies have no inside, so only surface contact counts for them.
           In collision inCollision is set, certified too (the verdict is proven), and distance becomes a signed
           distance, always negative: -penetrationDepth for the depth estimate of penetrationDepth()
           (PenetrationDepth.h: the deepest node of either body inside the other, closed, body; a lower bound on
           the translational penetration depth), or CONTACT_DISTANCE (-2.2e-308) when that depth is 0 (surfaces
           crossing with no node inside, or both bodies open: no inside, no depth). penetration says which; the
           witness points are then the deepest node and its nearest point on the other surface (onA - onB moves
           B by the depth to bring that node out), or a touching point. The signed distance does not depend on the
           seed (a pure function of the pose).
        4. Open bodies: openBody is set when either body is not closed (DistanceResult::openBody says what the
           answer then means).
        5. Primitive solids: a body built from primitives (Body::primitives(), a URDF link of boxes, cylinders and
           spheres, a MoveIt primitive) is answered as its solids, not its circumscribed mesh: steps 1 and 2 become
           the other body's triangle BVH traversed against each solid (bvhSolidDistance(), leaves by
           primitiveTriangleGap()), or every solid against every solid (primitiveGap()) when both bodies are solids;
           the distance is then a lower bound of the solids', exact for
           the closed forms, GJK's certified lower bound for cylinders and cones), and a collision is the solids'
           (touching, or a solid inside the other, closed, mesh: one point of it decides). triangleA / triangleB
           name the closest solid on a body of solids. In collision the depth is still that of the meshes
           (penetrationDepth() reads the node layer): the circumscribed mesh's, which may exceed the solid's.

        Overwrites distance, onA/onB, triangleA/B, certified, inCollision, penetrationDepth, penetration, openBody,
        nodeDistance and adds to triangleTests; keeps nodes and the node-level counters.

        \param request Its stopBelow and upperBound (the rest is the node search's):
        - stopBelow: early stop (a validity check against a clearance needs no more): as soon as a surface pair
        at or below \e stopBelow is known (from the seed or in the traversal), stop there. An answer above
        \e stopBelow is exact and certified as usual; one at or below it is an upper bound on the distance, not
        necessarily the minimum, so certified stays false (except for a proven collision), and inCollision is set
        only if that pair touches: the bodies may still intersect elsewhere, and the containment test is not made.
        With stopBelow >= 0 a collision gets no depth (penetration NOT_COMPUTED, distance CONTACT_DISTANCE): the
        caller asked for the verdict only. Negative (the default): never stop early.

        - upperBound: only a surface pair closer than this matters to the caller (a scene passes the best
        distance found on its other obstacles), so the traversal prunes everything at or above it. When nothing is
        closer, distance is +infinity, certified (nothing below the bound exists) and the witnesses unset; the
        collision verdict is still exact (a containment cannot hide behind the bound). Infinity (the default): no
        bound.

        \param warm The caller's warm start for this pair of bodies, if any: its triangle pair seeds the search
        instead of the result's node pair, its front starts the traversal, and both are updated. */
    void refineExact(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result,
                     const DistanceRequest &request = DistanceRequest(), ExactWarmStart *warm = nullptr);

    /** \brief Exact collision test alone: a touching or intersecting surface triangle pair (bvhCollide()), or one
        closed body wholly inside the other; for a body of primitive solids, its solids' contact (as refineExact(),
        5). Cheaper than refineExact(); the same verdict. With \e warm, the
        surface test carries its front from the caller's last test (warm->collision, bvhCollide() with a front):
        the same verdict at a fraction of the cost along a run of nearby poses. */
    bool inCollision(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, ExactWarmStart *warm = nullptr);

    /** \brief True when \e p (in the body's frame) is inside the closed body \e body: its generalised winding
        number, summed over every surface triangle, is above 1/2. O(n): the definition, and the tests' oracle;
        insideClosedBody() gives the same verdict faster. Always false for an open body or a point outside the
        body's bounding box. */
    bool containsPoint(const Body &body, const Eigen::Vector3d &p);

    /** \brief containsPoint()'s verdict in O(log n): the winding number by ray casting through the BVH
        (bvhRayWinding()) along up to three fixed directions, and containsPoint()'s sum when all three are
        ambiguous. Always false for an open body or a point outside the body's bounding box. */
    bool insideClosedBody(const Body &body, const Eigen::Vector3d &p);

    /**
       @anchor mgExact
       @par Short description
       Exact, certified distance and collision between two bodies: a hill climb from DistanceRequest::start (a warm
       start) when given, then refineExact(); without a start, the BVH traversal alone (a cold exact query).
    */
    class ExactSolver : public DistanceSolver
    {
    public:
        ExactSolver() : DistanceSolver("exact") {}
        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;
    };
}  // namespace meshgap

#endif
