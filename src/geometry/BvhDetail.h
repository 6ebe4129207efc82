#ifndef MESHGAP_GEOMETRY_BVH_DETAIL_H
#define MESHGAP_GEOMETRY_BVH_DETAIL_H

// What the traversals over triangle BVHs share (src/geometry/Bvh*.cpp): box bounds, the relative pose, triangle
// separation, the traversal stacks and the front bookkeeping. Internal: not installed, not part of the API.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/geometry/TriangleBvh.h"

namespace meshgap
{
    namespace bvh
    {
        /** \brief The pose of B in A with |R| precomputed (padded so parallel axes never make a bound too large). */
        struct RelativePose
        {
            Eigen::Matrix3d R, absR;
            Eigen::Vector3d t;
            explicit RelativePose(const Eigen::Isometry3d &X)
                : R(X.linear()), absR(R.cwiseAbs().array() + 1e-12), t(X.translation())
            {
            }
        };

        /** \brief Box \e b (placed by X) seen from box \e a: the rotation C from b's box axes to a's, |C| padded
            (so parallel axes never make a bound too large), and the centre offset T along a's axes. Two aligned
            boxes use X's own (nothing computed, nothing copied). */
        struct BoxPair
        {
            Eigen::Matrix3d ownC, ownAbsC;
            Eigen::Vector3d ownT;
            const Eigen::Matrix3d *C, *absC;
            const Eigen::Vector3d *T;
            BoxPair(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                    const Eigen::Vector3d &offset)
            {
                if (a.aligned && b.aligned)
                {
                    C = &X.R;
                    absC = &X.absR;
                    T = &offset;
                    return;
                }
                ownC = a.axes.transpose() * (X.R * b.axes);
                ownAbsC = ownC.cwiseAbs().array() + 1e-12;
                ownT = a.aligned ? offset : Eigen::Vector3d(a.axes.transpose() * offset);
                C = &ownC;
                absC = &ownAbsC;
                T = &ownT;
            }
        };

        /** \brief The distance bound given by the gaps \e g of two boxes' projections on three orthonormal axes
            (one box's face axes): a point pair's offset has a component of at least g_i along each axis i where
            g_i > 0, so its length is at least the norm of the positive gaps (for boxes apart diagonally, up to
            sqrt(3) times the largest gap alone). The largest gap, <= 0, when the projections overlap on all three. */
        inline double gapOnAxes(const Eigen::Vector3d &g)
        {
            const double largest = g.maxCoeff();
            return largest > 0.0 ? g.cwiseMax(0.0).norm() : largest;
        }

        /** \brief Lower bound on the distance between anything in box \e a and anything in box \e b (B's frame),
            from the sphere gap (cheapest, and rotation-free), then the face-axis gaps of each box (gapOnAxes());
            <= 0 means the boxes may touch. Once a partial bound exceeds \e enough (the caller prunes above it) that
            one is returned: still a lower bound, just not the best of the three. */
        inline double lowerBound(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                                 double enough = std::numeric_limits<double>::infinity())
        {
            const Eigen::Vector3d offset = X.R * b.center + X.t - a.center;
            double bound = offset.norm() - a.radius - b.radius;
            if (bound > enough)
                return bound;
            const BoxPair P(a, b, X, offset);
            const Eigen::Vector3d rb = *P.absC * b.half;  // B's box projected on A's axes
            bound = std::max(bound, gapOnAxes(P.T->cwiseAbs() - a.half - rb));
            if (bound > enough)
                return bound;
            const Eigen::Vector3d s = P.C->transpose() * *P.T;        // T on B's axes
            const Eigen::Vector3d ra = P.absC->transpose() * a.half;  // A's box projected on B's axes
            bound = std::max(bound, gapOnAxes(s.cwiseAbs() - ra - b.half));
            return bound;
        }

        /** \brief The gap between triangles p and q along unit axis \e n, either way round, and that axis pointing
            from p's side to q's (a lower bound on their distance; 0 and no axis when the projections overlap). */
        struct Separation
        {
            double gap{0.0};
            Eigen::Vector3d axis{Eigen::Vector3d::Zero()};

            /** \brief Along \e n of length \e length (gaps divided by it; the axis normalised only if kept). */
            void consider(const Eigen::Vector3d &n, const Eigen::Vector3d *p, const Eigen::Vector3d *q,
                          double length = 1.0)
            {
                const double p0 = n.dot(p[0]), p1 = n.dot(p[1]), p2 = n.dot(p[2]);
                const double q0 = n.dot(q[0]), q1 = n.dot(q[1]), q2 = n.dot(q[2]);
                const double up = (std::min({q0, q1, q2}) - std::max({p0, p1, p2})) / length;    // q beyond p
                const double down = (std::min({p0, p1, p2}) - std::max({q0, q1, q2})) / length;  // p beyond q
                if (up > gap)
                {
                    gap = up;
                    axis = n / length;
                }
                if (down > gap)
                {
                    gap = down;
                    axis = -n / length;
                }
            }
        };

        /** \brief The separating-axis gap of triangles p and q (unit normals \e np and \e nq): along either normal,
            the unit axis \e extra if given, then the nine edge-cross axes until one proves more than \e enough (a
            lower bound on their distance; 0 when no axis separates them, as when they intersect). */
        inline Separation triangleSeparation(const Eigen::Vector3d &np, const Eigen::Vector3d &nq,
                                             const Eigen::Vector3d *p, const Eigen::Vector3d *q, double enough,
                                             const Eigen::Vector3d *extra = nullptr)
        {
            Separation s;
            s.consider(np, p, q);
            s.consider(nq, p, q);
            if (extra && !(s.gap > enough))
                s.consider(*extra, p, q);
            for (int m = 0; m < 9 && !(s.gap > enough); ++m)
            {
                const Eigen::Vector3d n = (p[(m / 3 + 1) % 3] - p[m / 3]).cross(q[(m % 3 + 1) % 3] - q[m % 3]);
                const double length = n.norm();
                if (length > 0.0)  // else parallel edges: no axis
                    s.consider(n, p, q, length);
            }
            return s;
        }

        struct PairEntry
        {
            std::uint32_t a, b;
        };

        /** \brief A traversal stack of this thread, emptied, its capacity kept from earlier calls: once warm, a query
            allocates nothing for it. Each call site has its own \e Site (unique across the files that use it), so no
            traversal ever shares a stack with another one running at the same time (none of them is re-entered). */
        template <typename T, int Site>
        std::vector<T> &threadStack()
        {
            thread_local std::vector<T> stack;
            stack.clear();
            return stack;
        }

        /** \brief Split the pair on the node with the larger sphere (a leaf cannot be split). */
        inline bool splitA(const TriangleBvh::Node &a, const TriangleBvh::Node &b)
        {
            return !a.isLeaf() && (b.isLeaf() || a.radius >= b.radius);
        }

        /** \brief B's motion from an earlier pose \e P to \e X (both B in A's frame), to bound how far the points of a
            node of B moved: nodeMotionBound() with the rotation's part worked out once. */
        struct StepMotion
        {
            Eigen::Matrix3d dR;
            Eigen::Vector3d dt;
            double turn{0.0}, pad{0.0};
            StepMotion(const Eigen::Isometry3d &P, const Eigen::Isometry3d &X, const TriangleBvh::Node &rootB)
                : dR(X.linear() - P.linear()), dt(X.translation() - P.translation())
            {
                const double t = std::sqrt(std::max(0.0, 3.0 - P.linear().cwiseProduct(X.linear()).sum()));
                turn = t + 1e-7 * (t > 0.0);
                pad = 1e-12 * (rootB.center.norm() + rootB.radius + P.translation().norm() + X.translation().norm());
            }
            double displacement(const TriangleBvh::Node &n) const
            {
                return ((dR * n.center + dt).norm() + n.radius * turn) * (1.0 + 1e-12) + pad;
            }
        };

        /** \brief After \e front answered a query: whether it stays valid (\e lasts); when fronts keep failing
            within two queries (motions as large as the gaps they hold), the next traversals from the roots write
            none for a while (BvhFront::backoff). */
        inline void afterUse(BvhFront &front, bool lasts)
        {
            front.valid = lasts;
            ++front.uses;
            if (!lasts && front.uses <= 2)
                front.wait = front.backoff = std::min(2 * front.backoff + 1, 64u);  // it did not pay: wait
            else if (front.uses > 2)
                front.backoff = 0;
        }
    }  // namespace bvh
}  // namespace meshgap

#endif
