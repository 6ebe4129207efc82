#ifndef MESHGAP_SRC_GEOMETRY_SOLID_CORE_H
#define MESHGAP_SRC_GEOMETRY_SOLID_CORE_H

// Internal to the geometry layer: the convex solids of PrimitiveDistance.h as a core swept by a ball, and GJK on
// their support functions.

#include <Eigen/Geometry>

#include "meshgap/geometry/Primitive.h"

namespace meshgap
{
    class ConvexHull;

    namespace solid
    {
        /** \brief A convex solid: a core (a point, segment, triangle, box, cylinder, cone or the hull of a point set)
            swept by a ball of \e radius (a sphere is a point swept, a capsule a segment), placed in the query frame. */
        struct Core
        {
            enum Type
            {
                POINT,
                SEGMENT,
                TRIANGLE,
                BOX,
                CYLINDER,
                CONE,
                HULL,  ///< conv(hull->vertices()) placed by R and c
                SWEPT  ///< the hull of HULL placed by R and c and placed by R1 and c1 (both placements' points)
            };
            Type type{POINT};
            Eigen::Vector3d p[3]{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
            Eigen::Matrix3d R{Eigen::Matrix3d::Identity()};  ///< BOX, CYLINDER, CONE: the solid's axes
            Eigen::Vector3d c{Eigen::Vector3d::Zero()};      ///< BOX, CYLINDER, CONE: its centre
            Eigen::Vector3d half{Eigen::Vector3d::Zero()};   ///< BOX: half edges; CYLINDER, CONE: (r, r, half length)
            double radius{0.0};
            const ConvexHull *hull{nullptr};  ///< HULL, SWEPT: the vertex set, in its own frame
            Eigen::Matrix3d R1{Eigen::Matrix3d::Identity()};  ///< SWEPT: the second placement
            Eigen::Vector3d c1{Eigen::Vector3d::Zero()};

            /** \brief A point of the core farthest along \e d (the support point; for SWEPT, the farther of both
                placements' support points). */
            Eigen::Vector3d support(const Eigen::Vector3d &d) const;
            /** \brief A point inside the core. */
            Eigen::Vector3d center() const;
            /** \brief The largest distance of a point of the solid (core and ball) from the frame's origin. */
            double reach() const;
            /** \brief True for the cores without a closed form here (curved: cylinder, cone). */
            bool curved() const { return type == CYLINDER || type == CONE; }
        };

        /** \brief \e p placed by \e X (the pose of the frame its pose is in). */
        Core coreOf(const Primitive &p, const Eigen::Isometry3d &X);

        /** \brief The distance of two cores (without their balls): a lower bound \e lower, the distance \e upper that
            the points onA (of a) and onB (of b) achieve, and whether they were found to overlap. */
        struct CoreGap
        {
            double lower{0.0}, upper{0.0};
            Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
            bool overlap{false};
            int iterations{0};
            /** \brief Apart: the last direction from a towards b that GJK looked along (-v, v its point of A - B
                nearest the origin), a good first axis for the next query about nearby placements. */
            Eigen::Vector3d axis{Eigen::Vector3d::Zero()};
        };

        /** \brief GJK on the support functions of \e a and \e b: lower is the support-plane gap (less a roundoff pad
            of 4e-15 \e scale), upper the simplex's distance; stops once they agree to 1e-12 relative or 1e-14
            \e scale, the lower bound exceeds \e enough, the simplex makes no progress (roundoff), or after 256
            iterations (the bounds then as they are). Starts from the support pair along \e first (a direction from
            a towards b; zero or not finite: the line between their centres), whose planes' gap is the first lower
            bound: a pair already more than \e enough apart along it is answered by two support calls. Any first
            direction gives a valid bound. */
        CoreGap gjk(const Core &a, const Core &b, double scale, double enough,
                    const Eigen::Vector3d &first = Eigen::Vector3d::Zero());
    }  // namespace solid
}  // namespace meshgap

#endif
