#ifndef MESHGAP_GEOMETRY_BVH_SOLID_H
#define MESHGAP_GEOMETRY_BVH_SOLID_H

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "meshgap/geometry/Primitive.h"

namespace meshgap
{
    class TriangleBvh;

    /** \brief What a traversal of a triangle BVH against a primitive solid found and what it cost. */
    struct BvhSolidResult
    {
        /** \brief The least triangle-solid distance below the upper bound given (primitiveTriangleGap(): a lower
            bound of the true distance, equal to it to 1e-12 relative), or the upper bound itself when no triangle
            is below it (then found is false and the fields below are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangle{0};  ///< the closest triangle
        Eigen::Vector3d onMesh{Eigen::Vector3d::Zero()}, onSolid{Eigen::Vector3d::Zero()};  ///< the mesh's frame
        std::size_t boxTests{0}, triangleTests{0};
        /** \brief The search gave up at its budget of tests with nodes left to open (as bvhDistance()). */
        bool exhausted{false};
    };

    /** \brief Distance between the (filled) triangles of \e mesh (its frame M) and the solid \e s, whose frame (the
        one Primitive::pose is in) is placed in M by \e X_MS, searching only for triangles closer than \e upperBound.
        A node is pruned by the larger of its box's gap to a ball holding the solid and its gap to a box holding it
        (projected onto either box's axes); a triangle by its gap to that box (against a box solid, along every
        separating axis; against a cylinder, capsule or cone, also its distance to the solid's axis less the
        radius) and its distance to the ball's centre, then by primitiveTriangleGap(), which may stop once it proves
        the triangle cannot win. Stops
        at the first triangle at or below \e stopBelow (negative: never). Ties go to the smaller triangle index, so
        the answer does not depend on \e seed (a triangle tested first, whose distance then prunes the search).
        \e budget as in bvhDistance(). Touching (distance 0) includes a triangle inside the solid; a solid inside a
        closed mesh touches no triangle (the caller tests one point of it: insideClosedBody()). */
    void bvhSolidDistance(const TriangleBvh &mesh, const Primitive &s, const Eigen::Isometry3d &X_MS,
                          double upperBound, double stopBelow, BvhSolidResult &result,
                          std::uint32_t seed = UINT32_MAX, std::size_t budget = 0);

    /** \brief True when some triangle of \e mesh touches or enters the solid \e s placed by \e X_MS (distance 0 as
        primitiveTriangleGap() counts it); the first such triangle goes to \e hit. */
    bool bvhSolidCollide(const TriangleBvh &mesh, const Primitive &s, const Eigen::Isometry3d &X_MS,
                         std::uint32_t *hit = nullptr);
}  // namespace meshgap

#endif
