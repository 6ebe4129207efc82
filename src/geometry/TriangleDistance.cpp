#include "meshgap/geometry/TriangleDistance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace meshgap
{
    namespace
    {
        using Vec = Eigen::Vector3d;

        /* A triangle whose height over its longest edge is at most this fraction of that edge (about five units of
           roundoff) is treated as the union of its edges: dropping its face moves no distance by more than that
           height, far below TRIANGLE_CONTACT_TOLERANCE, and keeps the plane frame below well defined. */
        constexpr double FLAT_HEIGHT2 = 1e-30;

        /* Slack of the slab certificate that ends the search early, relative to the scale of
           TRIANGLE_CONTACT_TOLERANCE: a few units of roundoff, so an early answer is never more than that above the
           minimum, and exact ties (parallel faces, whose corners lie on the slab's planes) still certify. */
        constexpr double CERTIFICATE_SLACK = 4e-16;

        /** \brief Squared distance from \e p to the segment [a, a + e], ee = e.e; \e t gets the closest point's
            parameter in [0, 1]. A zero-length segment is its start point. */
        inline double pointSegment2(const Vec &p, const Vec &a, const Vec &e, double ee, double &t)
        {
            const Vec d = p - a;
            t = 0.0;
            if (ee > 0.0)
            {
                const double de = d.dot(e);
                if (de >= ee)
                    t = 1.0;
                else if (de > 0.0)
                    t = de / ee;
            }
            return (d - t * e).squaredNorm();
        }

        /** \brief Interior candidate of the segments [p, p + d1] and [q, q + d2] (ee2 = d2.d2): s is the first line's
            parameter of the lines' closest pair, t the projection of p + s d1 onto the second segment. False unless
            both lie strictly inside (0, 1); then the boundary candidates (endpoint to segment) contain the minimum.

            s = ((q - p) x d2).n / n.n with n = d1 x d2 is accurate to about eps / sin(angle), which moves p + s d1
            along a valley whose distance to the second line grows only with sin(angle): the candidate distance is
            accurate to roundoff times the extent even for nearly parallel segments. Any s in (0, 1) gives a valid
            pair of points, so a poor s can only overestimate, and the boundary candidates bound that. */
        inline bool segmentInterior2(const Vec &p, const Vec &d1, const Vec &q, const Vec &d2, double ee2, double &s,
                                     double &t, double &dist2)
        {
            const Vec n = d1.cross(d2);
            const double nn = n.squaredNorm();
            if (!(nn > 0.0))
                return false;
            const Vec r = q - p;
            s = r.cross(d2).dot(n) / nn;
            if (!(s > 0.0 && s < 1.0))
                return false;
            const Vec w = r - s * d1;  // q - (p + s d1)
            t = -w.dot(d2) / ee2;
            if (!(t > 0.0 && t < 1.0))
                return false;
            dist2 = (w + t * d2).squaredNorm();
            return true;
        }

        /** \brief Orthonormal frame of a triangle's plane built on its longest edge ab by Gram-Schmidt (twice, so u
            and v are orthogonal to roundoff even for slivers): the triangle is (0,0), (L,0), (cx,cy) in (u, v),
            counter-clockwise, cy > 0, and n = u x v. \e face is false for a flat triangle (height at most
            sqrt(FLAT_HEIGHT2) L, collinear corners, or a point). */
        struct Frame
        {
            Vec o, u, v, n;
            double L{0.0}, cx{0.0}, cy{0.0};
            int k{0};  ///< the frame's corners (0,0), (L,0), (cx,cy) are the triangle's corners k, k+1, k+2 (mod 3)
            bool face{false};
        };

        inline void makeFrame(const Vec t[3], Frame &f)
        {
            const double l0 = (t[1] - t[0]).squaredNorm(), l1 = (t[2] - t[1]).squaredNorm(),
                         l2 = (t[0] - t[2]).squaredNorm();
            int k = 0;
            double lk = l0;
            if (l1 > lk)
            {
                k = 1;
                lk = l1;
            }
            if (l2 > lk)
            {
                k = 2;
                lk = l2;
            }
            const Vec &a = t[k], &b = t[(k + 1) % 3], &c = t[(k + 2) % 3];
            f.k = k;
            f.o = a;
            f.face = false;
            if (!(lk > 0.0))
                return;
            const Vec e = b - a, g = c - a;
            const double inv = 1.0 / lk;
            const double ge = g.dot(e);
            Vec w = g - (ge * inv) * e;
            w -= (w.dot(e) * inv) * e;
            f.L = std::sqrt(lk);
            f.u = e * (1.0 / f.L);
            const double h2 = w.squaredNorm();
            if (!(h2 > FLAT_HEIGHT2 * lk))
                return;
            f.cy = std::sqrt(h2);
            f.v = w * (1.0 / f.cy);
            f.n = f.u.cross(f.v);
            f.cx = ge / f.L;
            f.face = true;
        }

        /** \brief Whether (x, y) in the frame's plane coordinates is in the closed 2-D triangle. */
        inline bool insideFace(const Frame &f, double x, double y)
        {
            return y >= 0.0 && (f.cx - f.L) * y - f.cy * (x - f.L) >= 0.0 && f.cy * x - f.cx * y >= 0.0;
        }

        inline bool lexLess(const Vec &a, const Vec &b)
        {
            if (a.x() != b.x())
                return a.x() < b.x();
            if (a.y() != b.y())
                return a.y() < b.y();
            return a.z() < b.z();
        }

        /** \brief Copy a triangle's corners into \e out in lexicographic order. */
        inline void sortedCorners(const Vec &c0, const Vec &c1, const Vec &c2, Vec out[3])
        {
            const Vec *p[3] = {&c0, &c1, &c2};
            if (lexLess(*p[1], *p[0]))
                std::swap(p[0], p[1]);
            if (lexLess(*p[2], *p[1]))
                std::swap(p[1], p[2]);
            if (lexLess(*p[1], *p[0]))
                std::swap(p[0], p[1]);
            out[0] = *p[0];
            out[1] = *p[1];
            out[2] = *p[2];
        }

        /** \brief Whether corner-sorted triangle \e b comes before \e a. */
        inline bool triangleLess(const Vec b[3], const Vec a[3])
        {
            for (int i = 0; i < 3; ++i)
            {
                if (lexLess(b[i], a[i]))
                    return true;
                if (lexLess(a[i], b[i]))
                    return false;
            }
            return false;
        }

        /** \brief The pair in canonical order (corners sorted, then the triangles), so every result is a function
            of the two point sets only. \e swapped tells the caller to swap the witnesses back. */
        struct Canonical
        {
            Vec A[3], B[3];
            bool swapped{false};

            Canonical(const Vec &a0, const Vec &a1, const Vec &a2, const Vec &b0, const Vec &b1, const Vec &b2)
            {
                sortedCorners(a0, a1, a2, A);
                sortedCorners(b0, b1, b2, B);
                if (triangleLess(B, A))
                {
                    swapped = true;
                    for (int i = 0; i < 3; ++i)
                        std::swap(A[i], B[i]);
                }
            }
        };

        /** \brief Whether the slab between the planes through \e onA and \e onB normal to v = onB - onA holds A on
            one side and B on the other, each corner allowed \e slack (a length) across: then no pair of points is
            closer than |v| - 2 slack, so the candidate is the minimum. */
        inline bool certified(const Vec A[3], const Vec B[3], const Vec &onA, const Vec &onB, double slack)
        {
            const Vec v = onB - onA;
            const double s = slack * v.norm();
            for (int i = 0; i < 3; ++i)
                if ((A[i] - onA).dot(v) > s || (B[i] - onB).dot(v) < -s)
                    return false;
            return true;
        }

        /** \brief Result of solve(). */
        struct Solution
        {
            double distance2{std::numeric_limits<double>::infinity()};  ///< squared distance, 0 when intersecting
            Vec onA{Vec::Zero()}, onB{Vec::Zero()};
            bool intersect{false};  ///< as documented for trianglesIntersect()
        };

        /** \brief The scale of TRIANGLE_CONTACT_TOLERANCE for the pair. */
        inline double contactScale(const Vec A[3], const Vec B[3])
        {
            Vec lo = A[0], hi = A[0];
            for (int i = 1; i < 3; ++i)
            {
                lo = lo.cwiseMin(A[i]);
                hi = hi.cwiseMax(A[i]);
            }
            for (int i = 0; i < 3; ++i)
            {
                lo = lo.cwiseMin(B[i]);
                hi = hi.cwiseMax(B[i]);
            }
            return std::max((hi - lo).maxCoeff(), std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
        }

        /** \brief Whether the axis \e n separates A from B by more than tol: their projections on it are intervals
            more than tol |n| apart. The six corners' projections are compared on the same vector n, so this is a
            proof of separation whatever the accuracy of n (a sliver's normal is poorly determined); with a
            triangle's (unnormalised) normal it is the plane test. */
        inline bool separatedAlong(const Vec &n, const Vec A[3], const Vec B[3], double tol)
        {
            const double pa1 = (A[1] - A[0]).dot(n), pa2 = (A[2] - A[0]).dot(n);
            const double pb0 = (B[0] - A[0]).dot(n), pb1 = (B[1] - A[0]).dot(n), pb2 = (B[2] - A[0]).dot(n);
            const double aLo = std::min({0.0, pa1, pa2}), aHi = std::max({0.0, pa1, pa2});
            const double bLo = std::min({pb0, pb1, pb2}), bHi = std::max({pb0, pb1, pb2});
            const double gap = std::max(bLo - aHi, aLo - bHi);
            return gap > 0.0 && gap * gap > tol * tol * n.squaredNorm();
        }

        /** \brief The steps of solve() for the canonically ordered triangles A and B, and what they share: each
            triangle's plane frame, the other's corners placed in it, and the best candidate so far (out). */
        class PairSolve
        {
        public:
            PairSolve(const Vec *A, const Vec *B) : A_(A), B_(B)
            {
                const double scale = contactScale(A, B);
                const double tol = TRIANGLE_CONTACT_TOLERANCE * scale;
                tol2_ = tol * tol;
                slack_ = CERTIFICATE_SLACK * scale;
                // Separated by either triangle's plane with more than the contact tolerance: they cannot intersect.
                separated = separatedAlong((A[1] - A[0]).cross(A[2] - A[0]), A, B, tol) ||
                            separatedAlong((B[1] - B[0]).cross(B[2] - B[0]), A, B, tol);
            }

            bool separated;
            Solution out;

            /** \brief Each triangle's corners in the other's plane frame, with the three edge orientations (>= 0:
                inner side) and whether the foot lies inside the other face. */
            void placeCorners()
            {
                makeFrame(A_, fa_);
                makeFrame(B_, fb_);
                auto place = [](const Frame &f, const Vec &p, double &x, double &y, double &z, double o[3])
                {
                    const Vec d = p - f.o;
                    x = d.dot(f.u);
                    y = d.dot(f.v);
                    z = d.dot(f.n);
                    o[0] = y;
                    o[1] = (f.cx - f.L) * y - f.cy * (x - f.L);
                    o[2] = f.cy * x - f.cx * y;
                    return o[0] >= 0.0 && o[1] >= 0.0 && o[2] >= 0.0;
                };
                for (int i = 0; i < 3; ++i)
                {
                    if (fb_.face)
                        inB_[i] = place(fb_, A_[i], xa_[i], ya_[i], za_[i], oa_[i]);
                    if (fa_.face)
                        inA_[i] = place(fa_, B_[i], xb_[i], yb_[i], zb_[i], ob_[i]);
                }
            }

            /** \brief An edge of one triangle crossing the other's face: they intersect, the crossing point is
                common (set in out). */
            bool edgeCrossesFace()
            {
                for (int side = 0; side < 2; ++side)
                {
                    const Frame &f = side ? fa_ : fb_;
                    if (!f.face)
                        continue;
                    const Vec *P = side ? B_ : A_;
                    const double *x = side ? xb_ : xa_, *y = side ? yb_ : ya_, *z = side ? zb_ : za_;
                    for (int i = 0; i < 3; ++i)
                    {
                        const int j = (i + 1) % 3;
                        if (!((z[i] <= 0.0 && z[j] >= 0.0) || (z[i] >= 0.0 && z[j] <= 0.0)) || z[i] == z[j])
                            continue;  // no sign change, or the edge lies in the plane (left to the 2-D features)
                        const double lambda = z[i] / (z[i] - z[j]);
                        if (!insideFace(f, x[i] + lambda * (x[j] - x[i]), y[i] + lambda * (y[j] - y[i])))
                            continue;
                        out.intersect = true;
                        out.distance2 = 0.0;
                        out.onA = out.onB = P[i] + lambda * (P[j] - P[i]);
                        return true;
                    }
                }
                return false;
            }

            /** \brief Finished: a contact within the tolerance, or a candidate the slab certificate proves minimal. */
            bool finished()
            {
                if (!separated && out.distance2 <= tol2_)
                {
                    out.intersect = true;
                    out.distance2 = 0.0;
                    out.onA = out.onB = 0.5 * (out.onA + out.onB);
                    return true;
                }
                return out.distance2 < std::numeric_limits<double>::infinity() &&
                       certified(A_, B_, out.onA, out.onB, slack_);
            }

            /** \brief Corner pairs (a cheap first upper bound for the pruning of the later steps), then vertex-face
                pairs whose foot lies inside the face. */
            void cornersAndFaces()
            {
                double &best2 = out.distance2;
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j)
                    {
                        const double c2 = (B_[j] - A_[i]).squaredNorm();
                        if (c2 < best2)
                        {
                            best2 = c2;
                            out.onA = A_[i];
                            out.onB = B_[j];
                        }
                    }
                for (int side = 0; side < 2; ++side)
                {
                    const Frame &f = side ? fa_ : fb_;
                    const Vec *P = side ? B_ : A_;
                    const double *x = side ? xb_ : xa_, *y = side ? yb_ : ya_, *z = side ? zb_ : za_;
                    const bool *in = side ? inA_ : inB_;
                    for (int i = 0; i < 3; ++i)
                        if (in[i] && z[i] * z[i] < best2)
                        {
                            best2 = z[i] * z[i];
                            const Vec foot = f.o + x[i] * f.u + y[i] * f.v;
                            out.onA = side ? foot : P[i];
                            out.onB = side ? P[i] : foot;
                        }
                }
            }

            /** \brief Vertex-edge pairs (the boundary of every edge-edge pair). A corner whose foot is inside the other
                face has the face closer than its edges; otherwise the closest point is on an edge the foot lies
                beyond (orientation < 0), no closer than z^2 + (distance to the edge's line)^2. Frame edge m of a
                triangle is its edge (k + m) % 3, k the frame's first corner; o[0] is the distance to edge 0's line,
                o[1] and o[2] that distance times the edge's length. */
            void vertexEdge()
            {
                double &best2 = out.distance2;
                for (int side = 0; side < 2; ++side)
                {
                    const Frame &f = side ? fa_ : fb_;
                    const Vec *P = side ? B_ : A_, *T = side ? A_ : B_;
                    const Vec *eT = side ? eA_ : eB_;
                    const double *eeT = side ? eeA_ : eeB_;
                    const bool *in = side ? inA_ : inB_;
                    const double *z = side ? zb_ : za_;
                    const double(*o)[3] = side ? ob_ : oa_;
                    for (int i = 0; i < 3; ++i)
                    {
                        if (in[i] || (f.face && z[i] * z[i] >= best2))
                            continue;
                        for (int m = 0; m < 3; ++m)
                        {
                            const int j = f.face ? (f.k + m) % 3 : m;
                            if (f.face &&
                                (o[i][m] >= 0.0 || z[i] * z[i] + o[i][m] * o[i][m] / (m ? eeT[j] : 1.0) >= best2))
                                continue;
                            double t;
                            const double c2 = pointSegment2(P[i], T[j], eT[j], eeT[j], t);
                            if (c2 < best2)
                            {
                                best2 = c2;
                                const Vec q = T[j] + t * eT[j];
                                out.onA = side ? q : P[i];
                                out.onB = side ? P[i] : q;
                            }
                        }
                    }
                }
            }

            /** \brief Edge-edge pairs with the closest points inside both edges, skipping pairs that one triangle's
                plane keeps at least sqrt(best2) apart (an edge entirely on one side of it, that far away). */
            void edgeEdge()
            {
                double &best2 = out.distance2;
                auto planeBound = [](const Frame &f, const double *z, int i)
                {
                    const double z0 = z[i], z1 = z[(i + 1) % 3];
                    if (!f.face || (z0 < 0.0) != (z1 < 0.0) || z0 == 0.0 || z1 == 0.0)
                        return 0.0;
                    const double m = std::min(std::abs(z0), std::abs(z1));
                    return m * m;
                };
                for (int i = 0; i < 3; ++i)
                {
                    if (planeBound(fb_, za_, i) >= best2)
                        continue;
                    for (int j = 0; j < 3; ++j)
                    {
                        if (planeBound(fa_, zb_, j) >= best2)
                            continue;
                        double s, t, c2;
                        if (segmentInterior2(A_[i], eA_[i], B_[j], eB_[j], eeB_[j], s, t, c2) && c2 < best2)
                        {
                            best2 = c2;
                            out.onA = A_[i] + s * eA_[i];
                            out.onB = B_[j] + t * eB_[j];
                        }
                    }
                }
            }

            /** \brief The edges of both triangles and their squared lengths, for the last two steps. */
            void edges()
            {
                for (int i = 0; i < 3; ++i)
                {
                    eA_[i] = A_[(i + 1) % 3] - A_[i];
                    eB_[i] = B_[(i + 1) % 3] - B_[i];
                    eeA_[i] = eA_[i].squaredNorm();
                    eeB_[i] = eB_[i].squaredNorm();
                }
            }

        private:
            const Vec *A_, *B_;
            double tol2_, slack_;
            Frame fa_, fb_;
            double xa_[3], ya_[3], za_[3], xb_[3], yb_[3], zb_[3];
            double oa_[3][3], ob_[3][3];  // oa_[i]: corner i of A against fb_'s three edges
            bool inB_[3] = {false, false, false}, inA_[3] = {false, false, false};  // foot inside the other face
            Vec eA_[3], eB_[3];
            double eeA_[3], eeB_[3];
        };

        /** \brief Distance, witnesses and intersection of the canonically ordered triangles A and B. Both public
            triangle-pair functions decide with exactly this, so they always agree; with \e intersectOnly it returns
            as soon as a plane separates them (then only \e intersect, false, is meaningful). */
        Solution solve(const Vec A[3], const Vec B[3], bool intersectOnly)
        {
            PairSolve pair(A, B);
            if (pair.separated && intersectOnly)
                return pair.out;
            pair.placeCorners();
            if (!pair.separated && pair.edgeCrossesFace())
                return pair.out;
            pair.cornersAndFaces();
            if (pair.finished())
                return pair.out;
            pair.edges();
            pair.vertexEdge();
            if (pair.finished())
                return pair.out;
            pair.edgeEdge();
            pair.finished();
            return pair.out;
        }
    }  // namespace

    double segmentSegmentDistance(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, const Eigen::Vector3d &q0,
                                  const Eigen::Vector3d &q1, Eigen::Vector3d &onP, Eigen::Vector3d &onQ)
    {
        const Vec e1 = p1 - p0, e2 = q1 - q0;
        const double ee1 = e1.squaredNorm(), ee2 = e2.squaredNorm();
        double t, best2 = pointSegment2(p0, q0, e2, ee2, t);
        onP = p0;
        onQ = q0 + t * e2;
        double c2 = pointSegment2(p1, q0, e2, ee2, t);
        if (c2 < best2)
        {
            best2 = c2;
            onP = p1;
            onQ = q0 + t * e2;
        }
        c2 = pointSegment2(q0, p0, e1, ee1, t);
        if (c2 < best2)
        {
            best2 = c2;
            onP = p0 + t * e1;
            onQ = q0;
        }
        c2 = pointSegment2(q1, p0, e1, ee1, t);
        if (c2 < best2)
        {
            best2 = c2;
            onP = p0 + t * e1;
            onQ = q1;
        }
        double s;
        if (segmentInterior2(p0, e1, q0, e2, ee2, s, t, c2) && c2 < best2)
        {
            best2 = c2;
            onP = p0 + s * e1;
            onQ = q0 + t * e2;
        }
        return std::sqrt(best2);
    }

    double pointTriangleDistance(const Eigen::Vector3d &p, const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                                 const Eigen::Vector3d &c, Eigen::Vector3d &onT)
    {
        const Vec T[3] = {a, b, c};
        Frame f;
        makeFrame(T, f);
        if (f.face)
        {
            const Vec d = p - f.o;
            const double x = d.dot(f.u), y = d.dot(f.v);
            if (insideFace(f, x, y))
            {
                onT = f.o + x * f.u + y * f.v;
                return std::abs(d.dot(f.n));
            }
        }
        // The foot is outside the face (or there is no face): the closest point is on an edge.
        double best2 = std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i)
        {
            const Vec e = T[(i + 1) % 3] - T[i];
            double t;
            const double c2 = pointSegment2(p, T[i], e, e.squaredNorm(), t);
            if (c2 < best2)
            {
                best2 = c2;
                onT = T[i] + t * e;
            }
        }
        return std::sqrt(best2);
    }

    bool trianglesIntersect(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1, const Eigen::Vector3d &a2,
                            const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, const Eigen::Vector3d &b2)
    {
        const Canonical c(a0, a1, a2, b0, b1, b2);
        return solve(c.A, c.B, true).intersect;
    }

    double triangleDistance(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1, const Eigen::Vector3d &a2,
                            const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, const Eigen::Vector3d &b2,
                            Eigen::Vector3d &onA, Eigen::Vector3d &onB)
    {
        const Canonical c(a0, a1, a2, b0, b1, b2);
        const Solution r = solve(c.A, c.B, false);
        onA = c.swapped ? r.onB : r.onA;
        onB = c.swapped ? r.onA : r.onB;
        return std::sqrt(r.distance2);
    }
}  // namespace meshgap
