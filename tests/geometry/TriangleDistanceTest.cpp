#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include "meshgap/geometry/TriangleDistance.h"
#include "TestScale.h"

using namespace meshgap;
using Eigen::Vector3d;

namespace
{
    using Tri = std::array<Vector3d, 3>;

    /* Reference distance between the convex hulls of two sets of one to three points, independent of the code under
       test: every pair of faces (non-empty subsets of corners, 7 x 7 for two triangles) is solved as unconstrained
       least squares on the faces' affine hulls with a Jacobi SVD (minimum-norm solution); the solution's barycentric
       weights, clamped to be non-negative and renormalised, give a feasible pair whose distance is measured. Every
       candidate is a real pair of points of the two hulls, and the pair of faces whose relative interiors hold the
       true minimiser yields it (to roundoff), so the minimum over candidates is the distance. */
    struct HullPair
    {
        double distance;
        Vector3d onP, onQ;
    };

    /** Offset from the face's first corner of the point with the given weights (x = weights of corners 1.., from
        position \e offset), the weights clamped to be non-negative and renormalised: computed from corner
        differences, so it is accurate relative to the face's size, not to the coordinates' magnitude. */
    Vector3d clampedOffset(const std::vector<Vector3d> &pts, const std::vector<int> &ids, const Eigen::VectorXd &x,
                           int offset)
    {
        std::vector<double> w(ids.size());
        double rest = 1.0;
        for (std::size_t k = 1; k < ids.size(); ++k)
        {
            w[k] = x(offset + static_cast<int>(k) - 1);
            rest -= w[k];
        }
        w[0] = rest;
        double sum = 0.0;
        for (double &wk : w)
            sum += (wk = std::max(wk, 0.0));
        Vector3d p = Vector3d::Zero();
        for (std::size_t k = 1; k < ids.size(); ++k)
            p += (sum > 0.0 ? w[k] / sum : 1.0 / static_cast<double>(ids.size())) * (pts[ids[k]] - pts[ids[0]]);
        return p;
    }

    HullPair hullDistance(const std::vector<Vector3d> &P, const std::vector<Vector3d> &Q)
    {
        HullPair best{std::numeric_limits<double>::infinity(), P[0], Q[0]};
        for (unsigned ma = 1; ma < (1u << P.size()); ++ma)
            for (unsigned mb = 1; mb < (1u << Q.size()); ++mb)
            {
                std::vector<int> ia, ib;
                for (int k = 0; k < static_cast<int>(P.size()); ++k)
                    if (ma & (1u << k))
                        ia.push_back(k);
                for (int k = 0; k < static_cast<int>(Q.size()); ++k)
                    if (mb & (1u << k))
                        ib.push_back(k);
                const int na = static_cast<int>(ia.size()) - 1, nb = static_cast<int>(ib.size()) - 1;
                const Vector3d r = P[ia[0]] - Q[ib[0]];
                Eigen::VectorXd x = Eigen::VectorXd::Zero(na + nb);
                if (na + nb > 0)
                {
                    Eigen::MatrixXd M(3, na + nb);
                    for (int k = 0; k < na; ++k)
                        M.col(k) = P[ia[k + 1]] - P[ia[0]];
                    for (int k = 0; k < nb; ++k)
                        M.col(na + k) = -(Q[ib[k + 1]] - Q[ib[0]]);
                    x = M.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(-r);
                }
                const Vector3d dp = clampedOffset(P, ia, x, 0), dq = clampedOffset(Q, ib, x, na);
                const double d = (r + dp - dq).norm();
                if (d < best.distance)
                    best = {d, P[ia[0]] + dp, Q[ib[0]] + dq};
            }
        return best;
    }

    HullPair reference(const Tri &a, const Tri &b)
    {
        return hullDistance({a[0], a[1], a[2]}, {b[0], b[1], b[2]});
    }

    double distanceToTriangle(const Vector3d &p, const Tri &t)
    {
        return hullDistance({p}, {t[0], t[1], t[2]}).distance;
    }

    double distanceToSegment(const Vector3d &p, const Vector3d &s0, const Vector3d &s1)
    {
        return hullDistance({p}, {s0, s1}).distance;
    }

    /** Largest absolute coordinate: the magnitude that bounds the roundoff of any computation on the pair. */
    double coordinateScale(const Tri &a, const Tri &b)
    {
        double m = 0.0;
        for (const Tri *t : {&a, &b})
            for (const Vector3d &v : *t)
                m = std::max(m, v.cwiseAbs().maxCoeff());
        return m;
    }

    /** The scale TRIANGLE_CONTACT_TOLERANCE is relative to: the larger of the six corners' extent (the largest side
        of their bounding box) and their largest absolute coordinate. */
    double contactScale(const Tri &a, const Tri &b)
    {
        Eigen::AlignedBox3d box;
        for (const Tri *t : {&a, &b})
            for (const Vector3d &v : *t)
                box.extend(v);
        return std::max(box.sizes().maxCoeff(), coordinateScale(a, b));
    }

    std::string describe(const Tri &a, const Tri &b)
    {
        std::ostringstream out;
        out << std::setprecision(17);
        for (const Tri *t : {&a, &b})
        {
            out << (t == &a ? "A:" : " B:");
            for (const Vector3d &v : *t)
                out << " (" << v.x() << ", " << v.y() << ", " << v.z() << ")";
        }
        return out.str();
    }

    double dist(const Tri &a, const Tri &b, Vector3d &onA, Vector3d &onB)
    {
        return triangleDistance(a[0], a[1], a[2], b[0], b[1], b[2], onA, onB);
    }

    double dist(const Tri &a, const Tri &b)
    {
        Vector3d onA, onB;
        return dist(a, b, onA, onB);
    }

    bool intersect(const Tri &a, const Tri &b)
    {
        return trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2]);
    }

    /* Everything triangleDistance() and trianglesIntersect() promise for one pair, against the reference:
       - the distance is within tol of the reference (tol = 1e-12 x the largest coordinate), in particular never
         below it by more than tol, except that it is 0 when the reference is within the contact tolerance;
       - each witness lies on its own triangle (distance to it <= tol, plus half the contact tolerance for a contact)
         and the witnesses are the reported distance apart, the same point when the distance is 0;
       - trianglesIntersect() is true exactly when the distance is 0, always when the reference is within roundoff
         (1e-14 x contactScale) of contact and never when it is beyond twice the contact tolerance. */
    ::testing::AssertionResult checkPair(const Tri &a, const Tri &b)
    {
        Vector3d onA, onB;
        const double d = dist(a, b, onA, onB);
        const HullPair ref = reference(a, b);
        const double tol = 1e-12 * coordinateScale(a, b);
        const double contact = TRIANGLE_CONTACT_TOLERANCE * contactScale(a, b);
        auto fail = [&](const std::string &what)
        {
            return ::testing::AssertionFailure()
                   << what << std::setprecision(17) << ": distance " << d << ", reference " << ref.distance << ", tol "
                   << tol << "; " << describe(a, b);
        };
        if (!(d >= 0.0) || !std::isfinite(d))
            return fail("not a finite non-negative distance");
        if (d == 0.0 && ref.distance > contact + tol)
            return fail("zero (contact) beyond the contact tolerance");
        if (d > 0.0 && d < ref.distance - tol)
            return fail("below the reference");
        if (d > ref.distance + tol)
            return fail("above the reference");
        // A contact within the tolerance but not exact has the closest pair's midpoint as its common point.
        const double witnessTol = tol + (d == 0.0 ? 0.5 * contact : 0.0);
        if (distanceToTriangle(onA, a) > witnessTol)
            return fail("witness onA off triangle A");
        if (distanceToTriangle(onB, b) > witnessTol)
            return fail("witness onB off triangle B");
        if (d == 0.0 ? onA != onB : std::abs((onA - onB).norm() - d) > tol)
            return fail("witnesses not at the reported distance");
        const bool hit = intersect(a, b);
        if (hit != (d == 0.0))
            return fail("trianglesIntersect disagrees with triangleDistance == 0");
        if (ref.distance <= 1e-14 * contactScale(a, b) && !hit)
            return fail("touching pair reported free");
        if (ref.distance > 2.0 * contact + tol && hit)
            return fail("separated pair reported intersecting");
        return ::testing::AssertionSuccess();
    }

    /** Random triangles and pairs: generic, sliver, needle, (nearly) collinear, repeated-corner and point triangles,
        scales 1e-3 to 1e3, placed independently, nearly touching, nearly parallel, coplanar or on a lattice. */
    class Generator
    {
    public:
        explicit Generator(std::uint32_t seed) : rng_(seed) {}

        double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
        double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
        int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
        Vector3d inCube(double s) { return Vector3d(uniform(-s, s), uniform(-s, s), uniform(-s, s)); }
        Vector3d unit()
        {
            std::normal_distribution<double> g;
            return Vector3d(g(rng_), g(rng_), g(rng_)).normalized();
        }
        double scale() { return logUniform(1e-3, 1e3); }

        /** A random triangle of size about s around \e center, of a random shape. */
        Tri triangle(const Vector3d &center, double s)
        {
            const Vector3d a = center + inCube(s), b = center + inCube(s);
            const int kind = integer(0, 19);
            if (kind < 10)  // generic
                return {a, b, center + inCube(s)};
            if (kind < 13)  // sliver: third corner within 1e-13 .. 1e-2 of the opposite edge
                return {a, b, a + uniform(0.0, 1.0) * (b - a) + s * logUniform(1e-13, 1e-2) * unit()};
            if (kind < 15)  // needle: one edge 1e-13 .. 1e-2 long
                return {a, a + s * logUniform(1e-13, 1e-2) * unit(), b};
            if (kind < 17)  // collinear up to rounding, third corner inside or outside the segment
                return {a, b, a + uniform(-0.5, 1.5) * (b - a)};
            if (kind < 18)  // repeated corner: exactly a segment
                return {a, b, a};
            if (kind < 19)  // a single point
                return {a, a, a};
            return {a, a + 1e-6 * inCube(s), a + 1e-6 * inCube(s)};  // tiny
        }

        /** A random point of triangle t: interior, on an edge (20%) or a corner (10%). */
        Vector3d pointOn(const Tri &t)
        {
            std::exponential_distribution<double> e;
            double w[3] = {e(rng_), e(rng_), e(rng_)};
            const int k = integer(0, 9);
            if (k < 3)
                w[integer(0, 2)] = 0.0;
            else if (k < 4)
                w[integer(0, 2)] = w[integer(0, 2)] = 0.0;
            const double sum = w[0] + w[1] + w[2];
            if (!(sum > 0.0))
                return t[integer(0, 2)];
            return (w[0] * t[0] + w[1] * t[1] + w[2] * t[2]) / sum;
        }

        double gap(double s)
        {
            static const double gaps[] = {0.0, 1e-15, 1e-13, 1e-11, 1e-9, 1e-6, 1e-3, 1e-1};
            return s * gaps[integer(0, 7)] * uniform(0.5, 1.0);
        }

        /** Triangle t rigidly rotated by \e angle about a random axis through \e pivot. */
        Tri rotated(const Tri &t, const Vector3d &pivot, double angle)
        {
            const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, unit()).toRotationMatrix();
            return {pivot + R * (t[0] - pivot), pivot + R * (t[1] - pivot), pivot + R * (t[2] - pivot)};
        }

        /** One random pair; \e config picks the kind of placement (0..5). */
        std::pair<Tri, Tri> pair(int config)
        {
            const double s = scale();
            const Tri a = triangle(inCube(s), s);
            Tri b;
            switch (config)
            {
                case 0:  // independent
                    b = triangle(a[0] + inCube(2.0 * s), s * logUniform(0.1, 10.0));
                    break;
                case 1:  // a corner of B near (or at) a point of A
                {
                    const Tri shape = triangle(Vector3d::Zero(), s * logUniform(0.1, 10.0));
                    const Vector3d b0 = pointOn(a) + gap(s) * unit();
                    b = {b0, b0 + shape[1] - shape[0], b0 + shape[2] - shape[0]};
                    break;
                }
                case 2:  // an edge of B passing near (or through) a point of A
                {
                    const Vector3d x = pointOn(a) + gap(s) * unit(), e = unit();
                    b = {x - s * uniform(0.01, 1.0) * e, x + s * uniform(0.01, 1.0) * e, x + inCube(s)};
                    break;
                }
                case 3:  // nearly parallel: A turned by a tiny angle, shifted a little
                {
                    const Vector3d c = (a[0] + a[1] + a[2]) / 3.0;
                    const double angle = integer(0, 3) == 0 ? 0.0 : logUniform(1e-14, 1e-2);
                    Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]);
                    n = n.norm() > 0.0 ? n.normalized() : unit();
                    const Vector3d shift = gap(s) * n + uniform(-1.0, 1.0) * (a[1] - a[0]);
                    const Tri r = rotated(a, c, angle);
                    b = {r[0] + shift, r[1] + shift, r[2] + shift};
                    break;
                }
                case 4:  // coplanar up to rounding
                    for (Vector3d &v : b)
                        v = a[0] + uniform(-1.5, 2.5) * (a[1] - a[0]) + uniform(-1.5, 2.5) * (a[2] - a[0]);
                    break;
                default:  // lattice: small integers times a power of two, exact coplanarity, parallels and contacts
                {
                    const double h = std::ldexp(1.0, integer(-10, 10));
                    Tri l[2];
                    for (Tri &t : l)
                        for (Vector3d &v : t)
                            v = h * Vector3d(integer(-2, 2), integer(-2, 2), integer(-1, 1));
                    return {l[0], l[1]};
                }
            }
            return {a, b};
        }

    private:
        std::mt19937 rng_;
    };

    const Vector3d origin(0, 0, 0);
    const double pi = std::acos(-1.0);
}  // namespace

// ------------------------------------------------------------------------------------------------------------------
// Segments

TEST(SegmentSegmentDistance, SkewSegmentsByHand)
{
    // P(s) = (2s, 0, 0), Q(t) = (1, -1 + 2t, 1 + t): minimising |Q - P|^2 gives s = 1/2, t = 1/5 and 1.8.
    Vector3d onP, onQ;
    const double d = segmentSegmentDistance({0, 0, 0}, {2, 0, 0}, {1, -1, 1}, {1, 1, 2}, onP, onQ);
    EXPECT_NEAR(d, std::sqrt(1.8), 1e-15);
    EXPECT_TRUE(onP.isApprox(Vector3d(1, 0, 0), 1e-15));
    EXPECT_TRUE(onQ.isApprox(Vector3d(1, -0.6, 1.2), 1e-15));
}

TEST(SegmentSegmentDistance, CrossingSegmentsMeet)
{
    Vector3d onP, onQ;
    EXPECT_NEAR(segmentSegmentDistance({-1, 0, 0}, {3, 0, 0}, {0.5, -2, 0}, {0.5, 6, 0}, onP, onQ), 0.0, 1e-15);
    EXPECT_TRUE(onP.isApprox(Vector3d(0.5, 0, 0)));
    EXPECT_TRUE(onQ.isApprox(Vector3d(0.5, 0, 0)));
}

TEST(SegmentSegmentDistance, ParallelAndCollinearSegments)
{
    Vector3d onP, onQ;
    // Parallel, overlapping over x in [1, 2]: distance 1, and the witnesses face each other inside the overlap.
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {2, 0, 0}, {1, 0, 1}, {3, 0, 1}, onP, onQ), 1.0);
    EXPECT_DOUBLE_EQ(onP.x(), onQ.x());
    EXPECT_GE(onP.x(), 1.0);
    EXPECT_LE(onP.x(), 2.0);
    // Antiparallel, same.
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {2, 0, 0}, {3, 0, 1}, {1, 0, 1}, onP, onQ), 1.0);
    // Parallel, disjoint along the direction: endpoint to endpoint, sqrt(1^2 + 2^2).
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {2, 0, 0}, {4, 1, 0}, {7, 1, 0}, onP, onQ), std::sqrt(5.0));
    EXPECT_EQ(onP, Vector3d(2, 0, 0));
    EXPECT_EQ(onQ, Vector3d(4, 1, 0));
    // Collinear overlapping: 0; collinear disjoint: the gap.
    EXPECT_EQ(segmentSegmentDistance({0, 0, 0}, {2, 2, 2}, {1, 1, 1}, {5, 5, 5}, onP, onQ), 0.0);
    EXPECT_EQ(onP, onQ);
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}, onP, onQ), std::sqrt(3.0));
    EXPECT_EQ(onP, Vector3d(1, 1, 1));
    EXPECT_EQ(onQ, Vector3d(2, 2, 2));
}

TEST(SegmentSegmentDistance, ZeroLengthSegments)
{
    Vector3d onP, onQ;
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({1, 2, 3}, {1, 2, 3}, {1, 2, 7}, {1, 2, 7}, onP, onQ), 4.0);
    EXPECT_EQ(onP, Vector3d(1, 2, 3));
    EXPECT_EQ(onQ, Vector3d(1, 2, 7));
    // A point over the middle of a segment, and the same with the arguments swapped.
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({1, 3, 0}, {1, 3, 0}, {0, 0, 0}, {4, 0, 0}, onP, onQ), 3.0);
    EXPECT_EQ(onQ, Vector3d(1, 0, 0));
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {4, 0, 0}, {1, 3, 0}, {1, 3, 0}, onP, onQ), 3.0);
    EXPECT_EQ(onP, Vector3d(1, 0, 0));
    // A point beyond the segment's end.
    EXPECT_DOUBLE_EQ(segmentSegmentDistance({0, 0, 0}, {4, 0, 0}, {7, 4, 0}, {7, 4, 0}, onP, onQ), 5.0);
}

TEST(SegmentSegmentDistance, MatchesReferenceOnRandomAndNearlyParallelSegments)
{
    Generator gen(11);
    for (int k = 0; k < 20000; ++k)
    {
        const double s = gen.scale();
        const Vector3d p0 = gen.inCube(s);
        Vector3d p1 = p0 + gen.inCube(s), q0, q1;
        switch (k % 4)
        {
            case 0:  // independent
                q0 = gen.inCube(s);
                q1 = gen.inCube(s);
                break;
            case 1:  // nearly parallel, overlapping or not, near or crossing
            {
                const Vector3d e = (p1 - p0) * gen.uniform(0.1, 2.0);
                const Vector3d tilt = s * gen.logUniform(1e-15, 1e-3) * gen.unit();
                q0 = p0 + gen.uniform(-1.5, 1.5) * (p1 - p0) + gen.gap(s) * gen.unit();
                q1 = q0 + e + tilt;
                break;
            }
            case 2:  // crossing or nearly crossing: through a point of P
            {
                const Vector3d x = p0 + gen.uniform(0.0, 1.0) * (p1 - p0) + gen.gap(s) * gen.unit();
                const Vector3d e = gen.unit() * s;
                q0 = x - gen.uniform(0.0, 1.0) * e;
                q1 = x + gen.uniform(0.0, 1.0) * e;
                break;
            }
            default:  // short segments: zero or tiny length
                q0 = gen.inCube(s);
                q1 = gen.integer(0, 1) ? q0 : Vector3d(q0 + 1e-12 * gen.inCube(s));
                if (gen.integer(0, 1))
                    p1 = p0;
                break;
        }
        Vector3d onP, onQ;
        const double d = segmentSegmentDistance(p0, p1, q0, q1, onP, onQ);
        const double ref = hullDistance({p0, p1}, {q0, q1}).distance;
        const double tol = 1e-12 * std::max({p0.cwiseAbs().maxCoeff(), p1.cwiseAbs().maxCoeff(),
                                             q0.cwiseAbs().maxCoeff(), q1.cwiseAbs().maxCoeff()});
        ASSERT_NEAR(d, ref, tol) << "case " << k;
        ASSERT_LE(distanceToSegment(onP, p0, p1), tol) << "case " << k;
        ASSERT_LE(distanceToSegment(onQ, q0, q1), tol) << "case " << k;
        ASSERT_NEAR((onP - onQ).norm(), d, tol) << "case " << k;
    }
}

// ------------------------------------------------------------------------------------------------------------------
// Point and triangle

TEST(PointTriangleDistance, VoronoiRegionsByHand)
{
    const Vector3d a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
    Vector3d on;
    EXPECT_DOUBLE_EQ(pointTriangleDistance({1, 1, 2}, a, b, c, on), 2.0);  // over the face
    EXPECT_TRUE(on.isApprox(Vector3d(1, 1, 0)));
    EXPECT_DOUBLE_EQ(pointTriangleDistance({1, 1, -2}, a, b, c, on), 2.0);  // under it
    EXPECT_DOUBLE_EQ(pointTriangleDistance({2, -3, 4}, a, b, c, on), 5.0);  // beyond edge ab
    EXPECT_TRUE(on.isApprox(Vector3d(2, 0, 0)));
    EXPECT_NEAR(pointTriangleDistance({3, 3, 0}, a, b, c, on), std::sqrt(2.0), 1e-15);  // beyond the hypotenuse
    EXPECT_TRUE(on.isApprox(Vector3d(2, 2, 0)));
    EXPECT_DOUBLE_EQ(pointTriangleDistance({-3, -4, 0}, a, b, c, on), 5.0);  // beyond corner a
    EXPECT_EQ(on, a);
    EXPECT_EQ(pointTriangleDistance({1, 2, 0}, a, b, c, on), 0.0);  // in the face
}

TEST(PointTriangleDistance, DegenerateAndSliverTriangles)
{
    Vector3d on;
    // Collinear corners (the middle one listed last): the segment from (0,0,0) to (4,0,0).
    EXPECT_DOUBLE_EQ(pointTriangleDistance({2, 3, 4}, {0, 0, 0}, {4, 0, 0}, {1, 0, 0}, on), 5.0);
    EXPECT_EQ(on, Vector3d(2, 0, 0));
    EXPECT_DOUBLE_EQ(pointTriangleDistance({7, 4, 0}, {0, 0, 0}, {1, 0, 0}, {4, 0, 0}, on), 5.0);
    // Repeated corner, single point.
    EXPECT_DOUBLE_EQ(pointTriangleDistance({2, 0, 5}, {0, 0, 0}, {4, 0, 0}, {4, 0, 0}, on), 5.0);
    EXPECT_DOUBLE_EQ(pointTriangleDistance({3, 4, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, on), 5.0);
    EXPECT_EQ(on, Vector3d(0, 0, 0));
    // A sliver 1e-9 wide: a point 1 above its middle (foot inside) and 1 to the side of it.
    const Vector3d a(0, 0, 0), b(1, 0, 0), c(0.5, 1e-9, 0);
    EXPECT_NEAR(pointTriangleDistance({0.5, 2e-10, 1}, a, b, c, on), 1.0, 1e-15);
    EXPECT_NEAR(on.y(), 2e-10, 1e-24);
    EXPECT_NEAR(pointTriangleDistance({0.5, 1.000000001, 0}, a, b, c, on), 1.0, 1e-15);
}

TEST(PointTriangleDistance, MatchesReferenceOnRandomTriangles)
{
    Generator gen(12);
    for (int k = 0; k < 20000; ++k)
    {
        const double s = gen.scale();
        const Tri t = gen.triangle(gen.inCube(s), s);
        const Vector3d p = k % 2 ? gen.pointOn(t) + gen.gap(s) * gen.unit() : Vector3d(gen.inCube(2.0 * s));
        Vector3d on;
        const double d = pointTriangleDistance(p, t[0], t[1], t[2], on);
        const double tol = 1e-12 * std::max(coordinateScale(t, t), p.cwiseAbs().maxCoeff());
        ASSERT_NEAR(d, distanceToTriangle(p, t), tol) << "case " << k << " " << describe(t, {p, p, p});
        ASSERT_LE(distanceToTriangle(on, t), tol) << "case " << k;
        ASSERT_NEAR((p - on).norm(), d, tol) << "case " << k;
    }
}

// ------------------------------------------------------------------------------------------------------------------
// Triangle pairs with analytic answers

TEST(TriangleDistance, ParallelTrianglesOneAboveTheOther)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)};
    for (double h : {3.0, 1e-6, -2.5})
    {
        // The same triangle lifted, and one turned half a turn in the plane (overlapping in xy).
        const Tri lifted{Vector3d(0, 0, h), Vector3d(4, 0, h), Vector3d(0, 4, h)};
        const Tri turned{Vector3d(3, 3, h), Vector3d(-1, 3, h), Vector3d(3, -1, h)};
        for (const Tri &b : {lifted, turned})
        {
            Vector3d onA, onB;
            EXPECT_DOUBLE_EQ(dist(a, b, onA, onB), std::abs(h));
            EXPECT_EQ(onA.z(), 0.0);
            EXPECT_DOUBLE_EQ(onB.z(), h);
            EXPECT_NEAR(onA.x(), onB.x(), 1e-15);
            EXPECT_NEAR(onA.y(), onB.y(), 1e-15);
            EXPECT_TRUE(checkPair(a, b));
        }
    }
}

TEST(TriangleDistance, CoplanarSeparated)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
    // Corner (1,1) of B against A's hypotenuse x + y = 1: (1 + 1 - 1) / sqrt(2).
    const Tri b{Vector3d(1, 1, 0), Vector3d(2, 1, 0), Vector3d(1, 2, 0)};
    Vector3d onA, onB;
    EXPECT_NEAR(dist(a, b, onA, onB), std::sqrt(0.5), 1e-15);
    EXPECT_TRUE(onA.isApprox(Vector3d(0.5, 0.5, 0)));
    EXPECT_EQ(onB, Vector3d(1, 1, 0));
    EXPECT_FALSE(intersect(a, b));
    // Corner to corner along the x axis.
    const Tri c{Vector3d(2, 0, 0), Vector3d(3, 0, 0), Vector3d(2, 1, 0)};
    EXPECT_DOUBLE_EQ(dist(a, c, onA, onB), 1.0);
    EXPECT_EQ(onA, Vector3d(1, 0, 0));
    EXPECT_EQ(onB, Vector3d(2, 0, 0));
    EXPECT_TRUE(checkPair(a, b));
    EXPECT_TRUE(checkPair(a, c));
}

TEST(TriangleDistance, CoplanarOverlappingIsZero)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)};
    const Tri corner{Vector3d(1, 1, 0), Vector3d(5, 1, 0), Vector3d(1, 5, 0)};    // a corner inside A
    const Tri inside{Vector3d(1, 1, 0), Vector3d(2, 1, 0), Vector3d(1, 2, 0)};    // all of B inside A
    const Tri star{Vector3d(3, -1, 0), Vector3d(3, 3, 0), Vector3d(-1, 3, 0)};    // edges cross, no corner inside
    const Tri strip{Vector3d(-1, 1, 0), Vector3d(5, 1, 0), Vector3d(5, 1.5, 0)};  // cuts through A
    for (const Tri &b : {corner, inside, star, strip})
    {
        Vector3d onA, onB;
        EXPECT_EQ(dist(a, b, onA, onB), 0.0);
        EXPECT_EQ(onA, onB);
        EXPECT_LE(distanceToTriangle(onA, a), 1e-15);
        EXPECT_LE(distanceToTriangle(onA, b), 1e-15);
        EXPECT_TRUE(intersect(a, b));
        EXPECT_TRUE(checkPair(a, b));
    }
}

TEST(TriangleDistance, TouchingAtAVertexOrAlongAnEdgeIsZero)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 2, 0)};
    const Tri vertex{Vector3d(2, 0, 0), Vector3d(3, 1, 1), Vector3d(3, -1, 1)};               // corner on corner
    const Tri onEdge{Vector3d(1, 0, 0), Vector3d(1, -1, 1), Vector3d(2, -1, 1)};              // corner on an edge
    const Tri onFace{Vector3d(0.5, 0.5, 0), Vector3d(1, 1, 3), Vector3d(0, 1, 3)};            // corner on the face
    const Tri sharedEdge{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 0, 3)};            // folded along ab
    const Tri edgeOnFace{Vector3d(0.5, 0.5, 0), Vector3d(1, 0.5, 0), Vector3d(0.7, 0.6, 2)};  // an edge lies on A
    const Tri crossEdges{Vector3d(1, -1, 0), Vector3d(1, 1, 0), Vector3d(1, 0, 2)};           // edge across A's edge
    for (const Tri &b : {vertex, onEdge, onFace, sharedEdge, edgeOnFace, crossEdges})
    {
        Vector3d onA, onB;
        EXPECT_EQ(dist(a, b, onA, onB), 0.0) << describe(a, b);
        EXPECT_EQ(onA, onB);
        EXPECT_LE(distanceToTriangle(onA, a), 1e-15);
        EXPECT_LE(distanceToTriangle(onA, b), 1e-15);
        EXPECT_TRUE(intersect(a, b));
        EXPECT_TRUE(checkPair(a, b));
    }
    Vector3d onA, onB;
    dist(a, vertex, onA, onB);
    EXPECT_EQ(onA, Vector3d(2, 0, 0));
}

TEST(TriangleDistance, JustApartAndWithinTheContactTolerance)
{
    // Corner on corner, then B moved away along x by 1e-9 (free) and by 1e-14 (within the tolerance: touching).
    const Tri a{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 2, 0)};
    for (double g : {1e-9, 1e-14})
    {
        const Tri b{Vector3d(2 + g, 0, 0), Vector3d(3 + g, 1, 1), Vector3d(3 + g, -1, 1)};
        const double expected = (2 + g) - 2;  // the gap as represented
        const bool free = expected > TRIANGLE_CONTACT_TOLERANCE * contactScale(a, b);
        EXPECT_EQ(free, g > 1e-12);
        EXPECT_EQ(intersect(a, b), !free);
        EXPECT_EQ(dist(a, b), free ? expected : 0.0);
    }
}

TEST(TriangleDistance, VertexToFace)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)};
    const Tri b{Vector3d(1, 1, 2), Vector3d(0, 0, 5), Vector3d(3, 0, 5)};
    Vector3d onA, onB;
    EXPECT_DOUBLE_EQ(dist(a, b, onA, onB), 2.0);
    EXPECT_TRUE(onA.isApprox(Vector3d(1, 1, 0)));
    EXPECT_EQ(onB, Vector3d(1, 1, 2));
    // And with the roles swapped (B's face under A's corner).
    EXPECT_DOUBLE_EQ(dist(b, a, onB, onA), 2.0);
    EXPECT_TRUE(onA.isApprox(Vector3d(1, 1, 0)));
    EXPECT_TRUE(checkPair(a, b));
}

TEST(TriangleDistance, EdgeToEdgeSkewByHand)
{
    // Edges (0,0,0)-(2,0,0) and (1,-1,1)-(1,1,2): closest at (1,0,0) and (1,-0.6,1.2), sqrt(1.8) apart. The vector
    // m = (0,-0.6,1.2) between them is normal to both edges; A lies in m.x <= 0 and B in m.x >= 1.8 = |m|^2, so no
    // other pair of points is closer.
    const Tri a{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 1, 0)};
    const Tri b{Vector3d(1, -1, 1), Vector3d(1, 1, 2), Vector3d(1, -1, 3)};
    Vector3d onA, onB;
    EXPECT_NEAR(dist(a, b, onA, onB), std::sqrt(1.8), 1e-15);
    EXPECT_TRUE(onA.isApprox(Vector3d(1, 0, 0), 1e-15));
    EXPECT_TRUE(onB.isApprox(Vector3d(1, -0.6, 1.2), 1e-15));
    EXPECT_FALSE(intersect(a, b));
    EXPECT_TRUE(checkPair(a, b));
}

TEST(TriangleDistance, ExactlyParallelEdges)
{
    // Edge e of A from P to P + 2e; B's edge parallel at offset m (m perpendicular to e), shifted by sigma e along it.
    // A lies in m.x <= m.P and B in m.x >= m.(P + m), so the distance is |m| while the edges overlap along e
    // (|sigma| <= 2) and sqrt(|m|^2 + ((|sigma| - 2) |e|)^2) beyond. Integer data: every input is exact.
    const Vector3d P(1, -2, 3);
    const Vector3d dirs[] = {Vector3d(1, 0, 0), Vector3d(1, 1, 0), Vector3d(1, 2, 3), Vector3d(-2, 1, 1)};
    const Vector3d ks[] = {Vector3d(0, 0, 1), Vector3d(0, 1, 0), Vector3d(1, -1, 2)};
    int cases = 0;
    for (const Vector3d &e : dirs)
        for (const Vector3d &k : ks)
        {
            const Vector3d m = e.cross(k);
            if (m.squaredNorm() == 0.0)
                continue;
            const Vector3d w = e.cross(m);  // perpendicular to both e and m
            for (double sigma : {-3.0, -2.0, -1.5, -1.0, 0.0, 0.5, 1.0, 2.0, 3.0})
                for (int flip = 0; flip < 2; ++flip)  // B's edge in the same or the opposite direction
                    for (double lean : {0.0, 1.0})    // A and B both in one plane (lean 0) or not
                    {
                        const Tri a{P, P + 2 * e, P + e - m + lean * w};
                        const Vector3d b0 = P + m + sigma * e, b1 = b0 + 2 * e;
                        const Tri b{flip ? b1 : b0, flip ? b0 : b1, b0 + e + m - lean * w};
                        const double along = std::max(std::abs(sigma) - 2.0, 0.0) * e.norm();
                        const double expected = std::sqrt(m.squaredNorm() + along * along);
                        Vector3d onA, onB;
                        EXPECT_NEAR(dist(a, b, onA, onB), expected, 1e-14 * expected) << describe(a, b);
                        EXPECT_TRUE(checkPair(a, b));
                        if (along == 0.0)  // witnesses face each other across the gap
                        {
                            EXPECT_TRUE((onB - onA).isApprox(m, 1e-14)) << describe(a, b);
                        }
                        ++cases;
                    }
        }
    EXPECT_GT(cases, 100);
}

TEST(TriangleDistance, DegenerateTriangles)
{
    const Tri a{Vector3d(0, 0, 0), Vector3d(4, 0, 0), Vector3d(0, 4, 0)};
    Vector3d onA, onB;
    // A segment (collinear corners) standing over A's face, and one lying flat over it: 2.
    EXPECT_DOUBLE_EQ(dist(a, {Vector3d(1, 1, 3), Vector3d(1, 1, 2), Vector3d(1, 1, 5)}, onA, onB), 2.0);
    EXPECT_EQ(onB, Vector3d(1, 1, 2));
    EXPECT_TRUE(onA.isApprox(Vector3d(1, 1, 0)));
    EXPECT_DOUBLE_EQ(dist(a, {Vector3d(1, 1, 2), Vector3d(2, 1, 2), Vector3d(3, 1, 2)}), 2.0);
    // A point over the face, and one beyond the hypotenuse x + y = 4 in the plane: (5 + 5 - 4) / sqrt(2).
    EXPECT_DOUBLE_EQ(dist(a, {Vector3d(1, 1, 2), Vector3d(1, 1, 2), Vector3d(1, 1, 2)}, onA, onB), 2.0);
    EXPECT_NEAR(dist(a, {Vector3d(5, 5, 0), Vector3d(5, 5, 0), Vector3d(5, 5, 0)}), 6.0 / std::sqrt(2.0), 1e-15);
    // A segment piercing the face (the crossing is inside B, not at a corner; B has a repeated corner): 0 at (1,1,0).
    EXPECT_EQ(dist(a, {Vector3d(1, 1, -1), Vector3d(1, 1, 1), Vector3d(1, 1, 1)}, onA, onB), 0.0);
    EXPECT_EQ(onA, onB);
    EXPECT_TRUE(onA.isApprox(Vector3d(1, 1, 0)));
    // Two skew segments (the pair of EdgeToEdgeSkewByHand): sqrt(1.8).
    const Tri s{Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(1, 0, 0)};
    const Tri t{Vector3d(1, -1, 1), Vector3d(1, 0, 1.5), Vector3d(1, 1, 2)};
    EXPECT_NEAR(dist(s, t, onA, onB), std::sqrt(1.8), 1e-15);
    EXPECT_TRUE(onB.isApprox(Vector3d(1, -0.6, 1.2), 1e-15));
    // Two points.
    EXPECT_DOUBLE_EQ(dist({origin, origin, origin}, {Vector3d(0, 3, 4), Vector3d(0, 3, 4), Vector3d(0, 3, 4)}), 5.0);
    for (const Tri &b : {Tri{Vector3d(1, 1, 3), Vector3d(1, 1, 2), Vector3d(1, 1, 5)},
                         Tri{Vector3d(5, 5, 0), Vector3d(5, 5, 0), Vector3d(5, 5, 0)}, t})
    {
        EXPECT_TRUE(checkPair(a, b));
        EXPECT_TRUE(checkPair(s, b));
    }
}

// ------------------------------------------------------------------------------------------------------------------
// Random pairs against the reference

TEST(TriangleDistance, MatchesFacePairReferenceOnRandomPairs)
{
    Generator gen(2024);
    int zero = 0, positive = 0;
    const int pairs = test::scaled(24000);
    for (int k = 0; k < pairs; ++k)
    {
        const auto [a, b] = gen.pair(k % 6);
        ASSERT_TRUE(checkPair(a, b)) << "case " << k << " (placement " << k % 6 << ")";
        (dist(a, b) == 0.0 ? zero : positive)++;
    }
    // The placements must exercise both outcomes substantially.
    EXPECT_GT(zero, pairs / 12);
    EXPECT_GT(positive, pairs * 5 / 12);
}

// ------------------------------------------------------------------------------------------------------------------
// Intersection

TEST(TrianglesIntersect, SharedPointsAreIntersecting)
{
    Generator gen(7);
    for (int k = 0; k < 10000; ++k)
    {
        const double s = gen.scale();
        const Tri a = gen.triangle(gen.inCube(s), s);
        // B has a corner at a point of A: interior, on an edge, at a corner (exact) or a corner of A itself.
        const Vector3d x = k % 4 == 0 ? a[k % 3] : gen.pointOn(a);
        const Tri shape = gen.triangle(Vector3d::Zero(), s * gen.logUniform(0.1, 10.0));
        const Tri b{x + shape[1] - shape[0], x, x + shape[2] - shape[0]};
        ASSERT_TRUE(intersect(a, b)) << "case " << k << " " << describe(a, b);
        Vector3d onA, onB;
        ASSERT_EQ(dist(a, b, onA, onB), 0.0) << "case " << k;
        ASSERT_EQ(onA, onB);
        ASSERT_TRUE(checkPair(a, b)) << "case " << k;
    }
}

TEST(TrianglesIntersect, PiercedThroughTheInteriorIsIntersecting)
{
    Generator gen(8);
    for (int k = 0; k < 10000; ++k)
    {
        const double s = gen.scale();
        const Vector3d c = gen.inCube(s);
        const Tri a{c + gen.inCube(s), c + gen.inCube(s), c + gen.inCube(s)};
        const Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
        // A point well inside A, an edge of B through it at an angle of 1e-4 to 90 degrees with A's plane.
        double w[3] = {gen.uniform(0.1, 1.0), gen.uniform(0.1, 1.0), gen.uniform(0.1, 1.0)};
        const Vector3d x = (w[0] * a[0] + w[1] * a[1] + w[2] * a[2]) / (w[0] + w[1] + w[2]);
        const Vector3d tangent = gen.unit().cross(n).normalized();
        const double angle = gen.logUniform(1e-4, pi / 2);
        const Vector3d d = std::sin(angle) * n + std::cos(angle) * tangent;
        const double reach = 1e-3 * (a[1] - a[0]).norm();  // short enough to stay inside A's plane region
        const Tri b{x - gen.uniform(0.01, 1.0) * reach * d, x + gen.uniform(0.01, 1.0) * reach * d, x + gen.inCube(s)};
        ASSERT_TRUE(intersect(a, b)) << "case " << k << " " << describe(a, b);
        Vector3d onA, onB;
        ASSERT_EQ(dist(a, b, onA, onB), 0.0) << "case " << k;
        ASSERT_EQ(onA, onB);
        const double tol = 1e-12 * coordinateScale(a, b);
        ASSERT_LE(distanceToTriangle(onA, a), tol) << "case " << k;
        ASSERT_LE(distanceToTriangle(onA, b), tol) << "case " << k;
    }
}

TEST(TrianglesIntersect, SeparatedByAPlaneAreFree)
{
    Generator gen(9);
    for (int k = 0; k < 10000; ++k)
    {
        const double s = gen.scale();
        const double gap = s * std::pow(10.0, -gen.integer(0, 9));  // 1e-9 s .. s
        // A below z = 0, B above z = gap (any shapes), then both moved by one random rigid motion.
        Tri a = gen.triangle(Vector3d::Zero(), s), b = gen.triangle(Vector3d::Zero(), s);
        for (Vector3d &v : a)
            v.z() = -std::abs(v.z());
        for (Vector3d &v : b)
            v.z() = gap + std::abs(v.z());
        const Eigen::Matrix3d R = Eigen::AngleAxisd(gen.uniform(0.0, pi), gen.unit()).toRotationMatrix();
        const Vector3d t = gen.inCube(s);
        for (Tri *tri : {&a, &b})
            for (Vector3d &v : *tri)
                v = R * v + t;
        ASSERT_FALSE(intersect(a, b)) << "case " << k << " gap " << gap << " " << describe(a, b);
        const double d = dist(a, b);
        ASSERT_GE(d, gap - 1e-12 * coordinateScale(a, b)) << "case " << k;
        ASSERT_TRUE(checkPair(a, b)) << "case " << k;
    }
}

TEST(TrianglesIntersect, SymmetricAndInvariantUnderCornerOrder)
{
    const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    Generator gen(10);
    for (int k = 0; k < 1500; ++k)
    {
        const auto [a, b] = gen.pair(k % 6);
        Vector3d onA, onB;
        const double d = dist(a, b, onA, onB);
        const bool hit = intersect(a, b);
        for (const auto &pa : perms)
            for (const auto &pb : perms)
            {
                const Tri a2{a[pa[0]], a[pa[1]], a[pa[2]]}, b2{b[pb[0]], b[pb[1]], b[pb[2]]};
                Vector3d onA2, onB2, onA3, onB3;
                ASSERT_EQ(intersect(a2, b2), hit) << "case " << k;
                ASSERT_EQ(intersect(b2, a2), hit) << "case " << k;
                ASSERT_EQ(dist(a2, b2, onA2, onB2), d) << "case " << k;
                ASSERT_EQ(dist(b2, a2, onB3, onA3), d) << "case " << k;
                ASSERT_EQ(onA2, onA);
                ASSERT_EQ(onB2, onB);
                ASSERT_EQ(onA3, onA);
                ASSERT_EQ(onB3, onB);
            }
    }
}
