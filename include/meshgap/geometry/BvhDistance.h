#ifndef MESHGAP_GEOMETRY_BVH_DISTANCE_H
#define MESHGAP_GEOMETRY_BVH_DISTANCE_H

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "meshgap/geometry/BvhFront.h"

namespace meshgap
{
    class TriangleBvh;

    /** \brief What a distance traversal found and what it cost. */
    struct BvhDistanceResult
    {
        /** \brief The smallest triangle-pair distance below the upper bound given, or the upper bound itself when no
            pair beats it (then found is false and the pair fields are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangleA{0}, triangleB{0};
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};  ///< A's frame
        std::size_t boxTests{0}, triangleTests{0};
        /** \brief The search gave up at its budget of tests (bvhDistance()'s \e budget) with pairs left to open:
            distance is then only what was found, and nothing is proven about the pairs left. */
        bool exhausted{false};
    };

    /** \brief Exact minimum distance between the triangles of \e a (frame A) and of \e b placed by \e X_AB, searching
        only for pairs closer than \e upperBound (pass a distance some real pair achieves to prune with it, or
        infinity; \e seedA / \e seedB name that pair, if any). Completes the whole traversal unless \e stopBelow is
        reached (a pair at or below it ends the search early; pass a negative value to never stop). A completed
        traversal with found == false proves no pair is closer than \e upperBound. Intersecting triangles have
        distance 0.

        Ties are canonical: pairs whose distances agree within a rounding slack (1e-12 of the scene's scale) count
        as equally close, and the one with the smallest (triangle of A, triangle of B) wins. So the answer, pair and
        witness points do not depend on the seed or the visiting order: a warm-started query gives the cold query's
        answer bit for bit.

        With \e front, the traversal starts from that certificate of an earlier query between the same trees (if it
        is valid) instead of the roots, and leaves its own front there (BvhFront); the answer is the same.

        With \e seedAxis, the seed pair's distance is exactly \e upperBound (computed by triangleDistance() with B's
        corners placed as R v + t, as here) and \e seedAxis its witness direction (unit, from A's point towards
        B's): the traversal does not test that pair again. 

        With a \e budget (> 0), the search gives up once it has made that many box and triangle tests, with
        result.exhausted set (a bounded question whose answer is not worth its price: the caller asks a cheaper one).
        A budgeted search neither reads nor writes \e front. */
    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA = UINT32_MAX,
                     std::uint32_t seedB = UINT32_MAX, BvhFront *front = nullptr,
                     const Eigen::Vector3d *seedAxis = nullptr, std::size_t budget = 0);

}  // namespace meshgap

#endif
