#ifndef MESHGAP_GEOMETRY_BOX_BOUND_H
#define MESHGAP_GEOMETRY_BOX_BOUND_H

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

// Inlined into the traversals' inner loop even where the compiler would rather call it (measured: fewer instructions).
#if defined(__GNUC__)
#define MESHGAP_BOX_BOUND_INLINE inline __attribute__((always_inline))
#else
#define MESHGAP_BOX_BOUND_INLINE inline
#endif

namespace meshgap
{
    /** \brief Lower bounds on the distance between two oriented boxes, seen from box A: A = {x : |x_i| <= ha_i} in
        its own frame, B = {T + C y : |y_j| <= hb_j} (C the rotation from B's box axes to A's, T B's centre). Every
        bound here is the gap of the two boxes' projections on some unit direction, which no pair of points of the
        boxes can beat: a lower bound whatever the direction, exact when the direction is the one between the boxes' nearest points. The three face axes of either box are such
        directions, and the direction between the nearest points found below prunes where they do not (boxes apart
        across an edge or a corner, or slanted to each other, as the thin boxes of flat CAD parts are). */
    namespace boxbound
    {
        /** \brief The gap of the boxes' projections on the unit direction \e n (from A towards B; any sign): B's
            least projection minus A's greatest, less \e pad (the caller's allowance for roundoff). */
        inline double gapAlong(const Eigen::Vector3d &n, const Eigen::Vector3d &ha, const Eigen::Vector3d &hb,
                               const Eigen::Matrix3d &C, const Eigen::Vector3d &T, double pad)
        {
            return n.dot(T) - (C.transpose() * n).cwiseAbs().dot(hb) - n.cwiseAbs().dot(ha) - pad;
        }

        /** \brief The bound given by the gaps g_j of the boxes' projections on B's three face axes, less \e pad (|C|
            padded so that nearly parallel axes never make a gap too large): a point pair's offset has a component of
            at least g_j along each axis where g_j > 0, so its length is at least the norm of the positive gaps; the
            largest gap (<= 0) when the projections overlap on all three. */
        MESHGAP_BOX_BOUND_INLINE double gapOnFacesOfB(const Eigen::Vector3d &ha, const Eigen::Vector3d &hb,
                                                      const Eigen::Matrix3d &C, const Eigen::Vector3d &T, double pad)
        {
            const Eigen::Matrix3d absC = C.cwiseAbs().array() + 1e-12;
            const Eigen::Vector3d g = (C.transpose() * T).cwiseAbs() - absC.transpose() * ha - hb;
            const double largest = g.maxCoeff() - pad;
            return largest > 0.0 ? g.cwiseMax(0.0).norm() - 2.0 * pad : largest;  // 2 pad > sqrt(3) pad
        }

        /** \brief The gap of the boxes along the direction between two points found by alternating projection
            (B's centre clamped into A, that point clamped into B, that one into A: near the boxes' nearest pair when
            they are apart, and exactly it when a face of one faces the other's): a lower bound on their distance.
            -infinity when the points meet (the boxes may overlap: no bound). \e pad as for gapAlong(). */
        MESHGAP_BOX_BOUND_INLINE double gapAlongNearest(const Eigen::Vector3d &ha, const Eigen::Vector3d &hb,
                                                        const Eigen::Matrix3d &C, const Eigen::Vector3d &T, double pad)
        {
            const Eigen::Vector3d p0 = T.cwiseMax(-ha).cwiseMin(ha);
            const Eigen::Vector3d y = (C.transpose() * (p0 - T)).cwiseMax(-hb).cwiseMin(hb);
            const Eigen::Vector3d q = T + C * y;
            const Eigen::Vector3d d = q - q.cwiseMax(-ha).cwiseMin(ha);
            const double length = d.norm();
            if (!(length > 0.0))
                return -std::numeric_limits<double>::infinity();
            return gapAlong(d / length, ha, hb, C, T, pad);
        }
    }  // namespace boxbound
}  // namespace meshgap

#endif
