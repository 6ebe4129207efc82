#ifndef MESHGAP_GEOMETRY_PRIMITIVE_DISTANCE_H
#define MESHGAP_GEOMETRY_PRIMITIVE_DISTANCE_H

#include <Eigen/Geometry>
#include <limits>

#include "meshgap/geometry/Primitive.h"

namespace meshgap
{
    /** \brief The distance between a primitive solid and a triangle or another solid, as the solids they are (filled:
        a triangle inside a box touches it), with witness points.

        distance is a lower bound of the true distance, and equal to it to 1e-12 relative:
        - closed forms (a sphere or capsule against a sphere, capsule or triangle: point and segment distances, the
          radii subtracted; a box against a sphere, capsule or triangle: the vertex-feature and edge-edge pairs, a
          separating-axis test for overlap) are exact up to roundoff, as triangleDistance();
        - a cylinder or cone against anything, and two boxes: GJK on the support functions (for two boxes,
          polytopes, it ends at the exact distance), whose support-plane gap is a certified lower bound (every point
          of A - B lies beyond the plane through the last support point normal to the current direction) and whose
          current simplex point an upper bound; iterated until the two agree to 1e-12 relative (or 1e-14 of the
          scale below), or until roundoff in the simplex stops its progress (they then agree to about 1e-11 of the
          scale, 1e-10 at most in tests/geometry/PrimitiveDistanceTest.cpp), and the lower bound reported, less a
          pad of 4e-15 times the scale. Never larger than the true distance.

        Touching or overlapping solids have distance exactly 0 (onA == onB, a point in both up to the tolerance):
        so is a pair closer than TRIANGLE_CONTACT_TOLERANCE times the scale (the larger of the two solids' reach
        from the frame's origin), as triangleDistance() counts touching triangles. 0 is therefore never reported for
        solids apart by more than that, and a positive distance never for solids that touch. */
    struct SolidGap
    {
        /** \brief Lower bound of the distance (see above); 0 when they touch or overlap. */
        double distance{std::numeric_limits<double>::infinity()};
        /** \brief A distance that the witnesses achieve (|onA - onB|): distance <= true distance <= upper. */
        double upper{std::numeric_limits<double>::infinity()};
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};  ///< in the query's frame
        /** \brief GJK iterations (0 for a closed form). */
        int iterations{0};
    };

    /** \brief Throws meshgap::Exception (naming the kind and value) unless \e p's sizes are positive and finite where
        its kind reads them (a capsule's length may be 0: a sphere) and its pose is a finite rigid motion. */
    void checkPrimitive(const Primitive &p);

    /** \brief Centre (in the frame Primitive::pose is in) and radius of a ball holding the solid \e p. */
    void primitiveBoundingBall(const Primitive &p, Eigen::Vector3d &center, double &radius);

    /** \brief Half extents of a box holding the solid \e p, centred on the origin of its pose and along its axes
        (a box's own; a cylinder's, cone's or capsule's r, r and half its length along z, the capsule's caps added). */
    Eigen::Vector3d primitiveBoxHalf(const Primitive &p);

    /** \brief Distance between solid \e s, its frame (the one Primitive::pose is in) placed in the query frame by
        \e X, and the filled triangle abc (query frame): onA on the solid, onB on the triangle. With \e enough, the
        computation may stop once its lower bound exceeds it (a caller that prunes above it): distance is then that
        lower bound, above \e enough, and no longer tight. */
    SolidGap primitiveTriangleGap(const Primitive &s, const Eigen::Isometry3d &X, const Eigen::Vector3d &a,
                                  const Eigen::Vector3d &b, const Eigen::Vector3d &c,
                                  double enough = std::numeric_limits<double>::infinity());

    /** \brief Distance between solid \e a placed by \e X_a and solid \e b placed by \e X_b (each the pose of the
        frame its Primitive::pose is in, in the query frame): onA on a, onB on b. \e enough as above. */
    SolidGap primitiveGap(const Primitive &a, const Eigen::Isometry3d &X_a, const Primitive &b,
                          const Eigen::Isometry3d &X_b, double enough = std::numeric_limits<double>::infinity());
}  // namespace meshgap

#endif
