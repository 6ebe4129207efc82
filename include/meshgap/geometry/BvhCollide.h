#ifndef MESHGAP_GEOMETRY_BVH_COLLIDE_H
#define MESHGAP_GEOMETRY_BVH_COLLIDE_H

#include <Eigen/Geometry>
#include <cstdint>

#include "meshgap/geometry/BvhFront.h"

namespace meshgap
{
    class TriangleBvh;

    /** \brief True when some triangle of \e a intersects (or touches) some triangle of \e b placed by \e X_AB;
        stops at the first such pair, which is reported through \e hitA / \e hitB when given. A pair of nodes is
        pruned when their boxes are apart, or when one is a leaf whose triangle lies apart from the other's box (by
        the 13 separating axes of a triangle and a box, with a margin far beyond trianglesIntersect()'s tolerance):
        a leaf's box reaches past its triangle's corners, and a node can meet it there without meeting the
        triangle. */
    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                    std::uint32_t *hitA = nullptr, std::uint32_t *hitB = nullptr);

    /** \brief bvhCollide() carried along a run of nearby poses: \e front keeps the node pairs the last test proved
        apart, each with a lower bound on its gap (the sphere and nearest-direction bound of a box pair, the
        separating-axis gap of a triangle pair, for a leaf and a node the gap its triangle is proven apart from the
        node's box by), and the next test re-tests only the entries whose gap B's motion since then could have
        closed, descending below those that no longer separate. The verdict and the reported pair are those of the
        stateless bvhCollide(): a pair is kept only while its gap exceeds ten times the contact tolerance of
        trianglesIntersect(), and every pair that might touch is decided by trianglesIntersect() itself.

        An entry whose gap B's whole motion since then could have closed is kept if its own node's displacement
        could not have (as in bvhDistance()), else re-tested and descended. A front is written (from the roots) only
        after a small step, at most a tenth of B's bounding radius (a run of nearby poses, as along a path or a
        motion, not a planner's unrelated samples), its box pairs kept apart by twice their node's motion in that
        step, so that they outlast the next one; it is rebuilt when it has grown past FRONT_GROWTH times a fresh
        one or a test re-tested more than half of it; when fronts keep failing within two tests (motions as large
        as the gaps), writing backs off (BvhFront::backoff). A collision leaves no front, and none is
        written until a test has found the bodies apart (a colliding run costs the stateless tests).

        Near contact a front is a fine cut (pairs of leaves kept apart by twice their motion), where the stateless
        test prunes whole box pairs at once: a test with the front (re-testing it, or writing it from the roots)
        visits at most BvhFront::BUDGET times the node pairs of the last stateless test (at least
        BvhFront::MIN_BUDGET); past that it drops the front, backs off as above and answers by the stateless test. A
        warm test therefore costs at most about BUDGET + 1 stateless ones. Belongs to one caller. */
    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, BvhFront &front,
                    std::uint32_t *hitA = nullptr, std::uint32_t *hitB = nullptr);

}  // namespace meshgap

#endif
