#ifndef MESHGAP_GEOMETRY_BOX_BOUND_H
#define MESHGAP_GEOMETRY_BOX_BOUND_H

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
        bound here is the gap of the two boxes' projections on some unit direction n, n.T - sum_j |(C^T n)_j| hb_j -
        sum_i |n_i| ha_i, which no pair of points of the boxes can beat: a lower bound whatever the direction, exact
        when it is the direction between the boxes' nearest points. Two directions are used (lanes::bound()):
        - the direction between two points found by alternating projection (B's centre clamped into A, that point
          clamped into B, that one into A: near the boxes' nearest pair when they are apart, and exactly it when a
          face of one faces the other's); no bound (-infinity) when the points meet (the boxes may overlap);
        - B's three face axes: a point pair's offset has a component of at least g_j along each axis where the gap
          g_j > 0, so its length is at least the norm of the positive gaps (the largest gap, <= 0, when the
          projections overlap on all three; |C| padded by 1e-12 so that nearly parallel axes never make a gap too
          large).
        The second prunes where the first does not (boxes apart across an edge or a corner, or slanted to each other,
        as the thin boxes of flat CAD parts are). */
    namespace boxbound
    {
        /** \brief One box pair as the traversals hold it, before B is seen from A: A's half extents and box axes
            (nullptr: aligned with A's body frame), B's half extents and its box axes and centre offset (B's centre
            minus A's) placed in A's body frame. Then C = axesA^T axesB and T = axesA^T offset. */
        struct NodePairView
        {
            const Eigen::Vector3d *ha, *hb;
            const Eigen::Matrix3d *axesA, *axesB;
            const Eigen::Vector3d *offset;
        };

        /** \brief The traversals' bound written once for any lane type \e V: a double (one box pair) or, where SSE2
            is there (baseline on x86-64), a register of two doubles (two pairs side by side). Every lane goes through
            the same operations in the same order, so a pair's bound is the same bit for bit whichever way it is
            worked out (sums of three terms (x0 + x1) + x2; max and min giving the first argument unless the second
            is greater or less, as std::max and std::min). */
        namespace lanes
        {
            inline double all(double x, double) { return x; }
            inline double add(double x, double y) { return x + y; }
            inline double sub(double x, double y) { return x - y; }
            inline double mul(double x, double y) { return x * y; }
            inline double div(double x, double y) { return x / y; }
            inline double abs(double x) { return std::abs(x); }
            inline double neg(double x) { return -x; }
            inline double max(double x, double y) { return std::max(x, y); }
            inline double min(double x, double y) { return std::min(x, y); }
            inline double root(double x) { return std::sqrt(x); }
            inline bool greater(double x, double y) { return x > y; }
            inline double select(bool mask, double x, double y) { return mask ? x : y; }
            inline bool every(bool mask) { return mask; }
#if defined(__SSE2__)
            using V = __m128d;
            MESHGAP_BOX_BOUND_INLINE V all(double x, V) { return _mm_set1_pd(x); }
            MESHGAP_BOX_BOUND_INLINE V add(V x, V y) { return _mm_add_pd(x, y); }
            MESHGAP_BOX_BOUND_INLINE V sub(V x, V y) { return _mm_sub_pd(x, y); }
            MESHGAP_BOX_BOUND_INLINE V mul(V x, V y) { return _mm_mul_pd(x, y); }
            MESHGAP_BOX_BOUND_INLINE V div(V x, V y) { return _mm_div_pd(x, y); }
            MESHGAP_BOX_BOUND_INLINE V abs(V x) { return _mm_andnot_pd(_mm_set1_pd(-0.0), x); }
            MESHGAP_BOX_BOUND_INLINE V neg(V x) { return _mm_xor_pd(_mm_set1_pd(-0.0), x); }
            /** \brief std::max(x, y) in each lane (maxpd gives its second operand unless the first is greater). */
            MESHGAP_BOX_BOUND_INLINE V max(V x, V y) { return _mm_max_pd(y, x); }
            /** \brief std::min(x, y) in each lane. */
            MESHGAP_BOX_BOUND_INLINE V min(V x, V y) { return _mm_min_pd(y, x); }
            MESHGAP_BOX_BOUND_INLINE V root(V x) { return _mm_sqrt_pd(x); }
            MESHGAP_BOX_BOUND_INLINE V greater(V x, V y) { return _mm_cmpgt_pd(x, y); }
            /** \brief Where \e mask is set, \e x; elsewhere \e y. */
            MESHGAP_BOX_BOUND_INLINE V select(V mask, V x, V y)
            {
                return _mm_or_pd(_mm_and_pd(mask, x), _mm_andnot_pd(mask, y));
            }
            MESHGAP_BOX_BOUND_INLINE bool every(V mask) { return _mm_movemask_pd(mask) == 3; }
#endif
            template <typename L>
            MESHGAP_BOX_BOUND_INLINE L sum(L x0, L x1, L x2)
            {
                return add(add(x0, x1), x2);
            }
            template <typename L>
            MESHGAP_BOX_BOUND_INLINE L dot(const L *x, const L *y)
            {
                return sum(mul(x[0], y[0]), mul(x[1], y[1]), mul(x[2], y[2]));
            }

            /** \brief B seen from A (C[i][j] = C(i, j), T) from A's box axes \e A (A[k][i] = axesA(k, i)), B's
                placed axes \e P and the centres' \e offset: C = A^T P, T = A^T offset. With A the identity, C = P
                and T = offset exactly. */
            template <typename L>
            MESHGAP_BOX_BOUND_INLINE void relative(const L (*A)[3], const L (*P)[3], const L *offset, L (*C)[3], L *T)
            {
                for (int i = 0; i < 3; ++i)
                {
                    for (int j = 0; j < 3; ++j)
                        C[i][j] = sum(mul(A[0][i], P[0][j]), mul(A[1][i], P[1][j]), mul(A[2][i], P[2][j]));
                    T[i] = sum(mul(A[0][i], offset[0]), mul(A[1][i], offset[1]), mul(A[2][i], offset[2]));
                }
            }

            /** \brief The bound of the box pair(s) in the lanes (C[i][j] = C(i, j)), padded for roundoff by 1e-12
                of the sum of |T|, ha and hb: the gap along the nearest direction (the first of the namespace's two)
                and, unless that is above \e enough in every lane, the better of it and the gap on B's faces (|C|
                padded), the latter kept only in the lanes where the former is not above \e enough. Without FACES,
                the gap along the nearest direction alone. */
            template <bool FACES, typename L>
            MESHGAP_BOX_BOUND_INLINE L bound(const L *ha, const L *hb, const L (*C)[3], const L *T, double enough)
            {
                const L zero = all(0.0, T[0]);
                const L pad = mul(all(1e-12, zero), add(add(sum(abs(T[0]), abs(T[1]), abs(T[2])),
                                                            sum(ha[0], ha[1], ha[2])),
                                                        sum(hb[0], hb[1], hb[2])));
                // B's centre clamped into A, that point into B, that one into A: the direction between the last two.
                L toB[3], y[3], d[3];
                for (int i = 0; i < 3; ++i)
                    toB[i] = sub(min(max(T[i], neg(ha[i])), ha[i]), T[i]);
                for (int j = 0; j < 3; ++j)
                    y[j] = min(max(sum(mul(C[0][j], toB[0]), mul(C[1][j], toB[1]), mul(C[2][j], toB[2])), neg(hb[j])),
                               hb[j]);
                for (int i = 0; i < 3; ++i)
                {
                    const L q = add(T[i], sum(mul(C[i][0], y[0]), mul(C[i][1], y[1]), mul(C[i][2], y[2])));
                    d[i] = sub(q, min(max(q, neg(ha[i])), ha[i]));
                }
                const L length = root(dot(d, d));
                L n[3], absN[3], alongB[3];
                for (int i = 0; i < 3; ++i)
                {
                    n[i] = div(d[i], length);
                    absN[i] = abs(n[i]);
                }
                for (int j = 0; j < 3; ++j)
                    alongB[j] = abs(sum(mul(C[0][j], n[0]), mul(C[1][j], n[1]), mul(C[2][j], n[2])));
                const L gap = sub(sub(sub(dot(n, T), dot(alongB, hb)), dot(absN, ha)), pad);
                // Where the points meet (the boxes may overlap): no bound.
                const L nearest =
                    select(greater(length, zero), gap, all(-std::numeric_limits<double>::infinity(), zero));
                const auto pruned = greater(nearest, all(enough, zero));
                if (!FACES || every(pruned))
                    return nearest;
                // The gaps g_j on B's face axes: the norm of the positive ones, or the largest when none is.
                L g[3], positive[3];
                for (int j = 0; j < 3; ++j)
                {
                    const L along = abs(sum(mul(C[0][j], T[0]), mul(C[1][j], T[1]), mul(C[2][j], T[2])));
                    const L spread = sum(mul(add(abs(C[0][j]), all(1e-12, zero)), ha[0]),
                                         mul(add(abs(C[1][j]), all(1e-12, zero)), ha[1]),
                                         mul(add(abs(C[2][j]), all(1e-12, zero)), ha[2]));
                    g[j] = sub(sub(along, spread), hb[j]);
                    positive[j] = max(g[j], zero);
                }
                const L largest = sub(max(max(g[0], g[1]), g[2]), pad);
                const L apart = sub(root(dot(positive, positive)), mul(all(2.0, zero), pad));  // 2 pad > sqrt(3) pad
                const L faces = select(greater(largest, zero), apart, largest);
                return select(pruned, nearest, max(nearest, faces));
            }
        }  // namespace lanes

        /** \brief pairBound() of a box pair as the traversals hold it (NodePairView: C and T worked out here, in the
            lanes' order of operations). */
        template <bool FACES = true>
        MESHGAP_BOX_BOUND_INLINE double pairBound(const NodePairView &p, double enough)
        {
            double ha[3], hb[3], T[3], C[3][3];
            for (int i = 0; i < 3; ++i)
            {
                ha[i] = (*p.ha)[i];
                hb[i] = (*p.hb)[i];
            }
            if (!p.axesA)
                for (int i = 0; i < 3; ++i)
                {
                    T[i] = (*p.offset)[i];
                    for (int j = 0; j < 3; ++j)
                        C[i][j] = (*p.axesB)(i, j);
                }
            else
            {
                double A[3][3], P[3][3], offset[3];
                for (int k = 0; k < 3; ++k)
                {
                    offset[k] = (*p.offset)[k];
                    for (int i = 0; i < 3; ++i)
                    {
                        A[k][i] = (*p.axesA)(k, i);
                        P[k][i] = (*p.axesB)(k, i);
                    }
                }
                lanes::relative(A, P, offset, C, T);
            }
            return lanes::bound<FACES>(ha, hb, C, T, enough);
        }

        /** \brief pairBound() of two box pairs as the traversals hold them, at once (both in one SSE2 register where
            there is one): \e out[k] is pair \e k's, the same bit for bit. C and T are worked out in the lanes too,
            with the identity for an aligned A (which gives C and T exactly as they are). */
        template <bool FACES = true>
        MESHGAP_BOX_BOUND_INLINE void pairBounds(const NodePairView &p0, const NodePairView &p1, double enough,
                                                 double out[2])
        {
#if defined(__SSE2__)
            using lanes::V;
            V ha[3], hb[3], T[3], C[3][3];
            for (int i = 0; i < 3; ++i)
            {
                ha[i] = _mm_set_pd((*p1.ha)[i], (*p0.ha)[i]);
                hb[i] = _mm_set_pd((*p1.hb)[i], (*p0.hb)[i]);
            }
            if (!p0.axesA && !p1.axesA)
                for (int i = 0; i < 3; ++i)
                {
                    T[i] = _mm_set_pd((*p1.offset)[i], (*p0.offset)[i]);
                    for (int j = 0; j < 3; ++j)
                        C[i][j] = _mm_set_pd((*p1.axesB)(i, j), (*p0.axesB)(i, j));
                }
            else
            {
                static const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
                const Eigen::Matrix3d &A0 = p0.axesA ? *p0.axesA : identity, &A1 = p1.axesA ? *p1.axesA : identity;
                V A[3][3], P[3][3], offset[3];
                for (int k = 0; k < 3; ++k)
                {
                    offset[k] = _mm_set_pd((*p1.offset)[k], (*p0.offset)[k]);
                    for (int i = 0; i < 3; ++i)
                    {
                        A[k][i] = _mm_set_pd(A1(k, i), A0(k, i));
                        P[k][i] = _mm_set_pd((*p1.axesB)(k, i), (*p0.axesB)(k, i));
                    }
                }
                lanes::relative(A, P, offset, C, T);
            }
            const V bound = lanes::bound<FACES>(ha, hb, C, T, enough);
            _mm_storel_pd(&out[0], bound);
            _mm_storeh_pd(&out[1], bound);
#else
            out[0] = pairBound<FACES>(p0, enough);
            out[1] = pairBound<FACES>(p1, enough);
#endif
        }
    }  // namespace boxbound
}  // namespace meshgap

#endif
