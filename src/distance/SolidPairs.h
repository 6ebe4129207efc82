#ifndef MESHGAP_SRC_DISTANCE_SOLID_PAIRS_H
#define MESHGAP_SRC_DISTANCE_SOLID_PAIRS_H

// Internal to the distance layer: exact distance and collision of two bodies when either is built from primitive
// solids (Body::primitives()), answered as those solids (PrimitiveDistance.h, BvhSolid.h).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "meshgap/geometry/Body.h"

namespace meshgap
{
    namespace solids
    {
        /** \brief True when \e body is answered as its solids: it was built from primitives, not boxes alone (a box's
            mesh, boxMesh(), is the box itself: the triangle traversal, with its fronts, answers it exactly). */
        inline bool asSolids(const Body &body)
        {
            for (const Primitive &p : body.primitives())
                if (p.kind != Primitive::Kind::BOX)
                    return true;
            return false;
        }

        /** \brief True when either body is answered as its solids. */
        inline bool answered(const Body &a, const Body &b)
        {
            return asSolids(a) || asSolids(b);
        }

        /** \brief The closest pair of parts found: a triangle or solid of A (\e partA: its triangle index for a
            mesh, its index in primitives() for a solid), one of B, their distance and witnesses (A's frame). */
        struct Nearest
        {
            double d{std::numeric_limits<double>::infinity()};
            bool found{false};  ///< a pair below the upper bound was found (d is its distance, else the bound)
            std::uint32_t partA{0}, partB{0};
            Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
            std::size_t boxTests{0}, triangleTests{0};
            bool exhausted{false};
        };

        /** \brief The least distance between the parts of \e a and of \e b (at \e X_AB) below \e upperBound (else
            d stays infinite), stopping at a pair at or below \e stopBelow (negative: never) or after \e budget
            tests (0: no budget; exhausted then set). \e seedA / \e seedB name a pair to test first. */
        Nearest nearest(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, double upperBound,
                        double stopBelow, std::size_t budget, std::uint32_t seedA = UINT32_MAX,
                        std::uint32_t seedB = UINT32_MAX);

        /** \brief Whether some part of \e a touches or enters some part of \e b. */
        bool touch(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB);

        /** \brief True when the convex outer bounds of \e a and \e b (at \e X_AB) are proven more than \e bound
            apart: each body's solids (Body::primitives(); a box's mesh is that box), else its hull grown by its
            margin (Body::convexHull()), every pair's GJK lower bound above \e bound. False when a body has neither
            (no claim). */
        bool outerApart(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, double bound);

        /** \brief With no part touching: whether a solid of one body lies inside the other, closed, mesh body (one
            point of the solid decides, insideClosedBody()). */
        bool inside(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB);
    }  // namespace solids
}  // namespace meshgap

#endif
