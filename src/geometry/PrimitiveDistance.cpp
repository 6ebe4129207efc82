#include "meshgap/geometry/PrimitiveDistance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "SolidCore.h"
#include "meshgap/Exception.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    using solid::Core;
    using solid::CoreGap;

    namespace
    {
        const char *kindName(Primitive::Kind kind)
        {
            switch (kind)
            {
                case Primitive::Kind::BOX:
                    return "box";
                case Primitive::Kind::SPHERE:
                    return "sphere";
                case Primitive::Kind::CYLINDER:
                    return "cylinder";
                case Primitive::Kind::CONE:
                    return "cone";
                case Primitive::Kind::CAPSULE:
                    return "capsule";
            }
            return "primitive";
        }
    }  // namespace

    void checkPrimitive(const Primitive &p)
    {
        const std::string what = std::string("a ") + kindName(p.kind);
        auto positive = [&](double x, const char *name)
        {
            if (!(x > 0.0) || !std::isfinite(x))
                throw Exception("primitive", what + "'s " + name + " " + std::to_string(x) +
                                                 " is not positive and finite");
        };
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                positive(p.size.x(), "x size"), positive(p.size.y(), "y size"), positive(p.size.z(), "z size");
                break;
            case Primitive::Kind::SPHERE:
                positive(p.size.x(), "radius");
                break;
            case Primitive::Kind::CAPSULE:
                positive(p.size.x(), "radius");
                if (!(p.size.y() >= 0.0) || !std::isfinite(p.size.y()))
                    throw Exception("primitive", what + "'s length " + std::to_string(p.size.y()) +
                                                     " is not non-negative and finite");
                break;
            default:
                positive(p.size.x(), "radius"), positive(p.size.y(), "length");
        }
        const Eigen::Matrix3d R = p.pose.linear();
        if (!p.pose.matrix().allFinite() || !(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9) ||
            !(R.determinant() > 0.0))
            throw Exception("primitive", what + "'s pose is not a finite rigid motion");
    }

    void primitiveBoundingBall(const Primitive &p, Eigen::Vector3d &center, double &radius)
    {
        center = p.pose.translation();
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                radius = 0.5 * p.size.norm();
                return;
            case Primitive::Kind::SPHERE:
                radius = p.size.x();
                return;
            case Primitive::Kind::CAPSULE:
                radius = p.size.x() + 0.5 * p.size.y();
                return;
            default:
                radius = std::hypot(p.size.x(), 0.5 * p.size.y());
        }
    }

    Eigen::Vector3d primitiveBoxHalf(const Primitive &p)
    {
        const double r = p.size.x(), h = 0.5 * p.size.y();
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                return 0.5 * p.size;
            case Primitive::Kind::SPHERE:
                return Eigen::Vector3d::Constant(r);
            case Primitive::Kind::CAPSULE:
                return Eigen::Vector3d(r, r, h + r);
            default:  // cylinder, cone
                return Eigen::Vector3d(r, r, h);
        }
    }

    namespace solid
    {
        Core coreOf(const Primitive &p, const Eigen::Isometry3d &X)
        {
            const Eigen::Isometry3d placed = X * p.pose;
            Core core;
            core.R = placed.linear();
            core.c = placed.translation();
            switch (p.kind)
            {
                case Primitive::Kind::BOX:
                    core.type = Core::BOX;
                    core.half = 0.5 * p.size;
                    break;
                case Primitive::Kind::SPHERE:
                    core.type = Core::POINT;
                    core.p[0] = core.c;
                    core.radius = p.size.x();
                    break;
                case Primitive::Kind::CAPSULE:
                    core.type = Core::SEGMENT;
                    core.p[0] = core.c - 0.5 * p.size.y() * core.R.col(2);
                    core.p[1] = core.c + 0.5 * p.size.y() * core.R.col(2);
                    core.radius = p.size.x();
                    break;
                default:
                    core.type = p.kind == Primitive::Kind::CYLINDER ? Core::CYLINDER : Core::CONE;
                    core.half = Eigen::Vector3d(p.size.x(), p.size.x(), 0.5 * p.size.y());
            }
            return core;
        }
    }  // namespace solid

    namespace
    {
        /** \brief The closest pair found so far, by squared distance. */
        struct Nearest
        {
            double d2{std::numeric_limits<double>::infinity()};
            Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
            void offer(const Eigen::Vector3d &a, const Eigen::Vector3d &b)
            {
                const double d = (a - b).squaredNorm();
                if (d < d2)
                    d2 = d, onA = a, onB = b;
            }
        };

        /** \brief The point of box \e box nearest to \e q. */
        Eigen::Vector3d boxPoint(const Core &box, const Eigen::Vector3d &q)
        {
            const Eigen::Vector3d l = box.R.transpose() * (q - box.c);
            return box.c + box.R * l.cwiseMax(-box.half).cwiseMin(box.half);
        }

        /** \brief The point of a point, segment, triangle or box core nearest to \e q. */
        Eigen::Vector3d nearestOn(const Core &core, const Eigen::Vector3d &q)
        {
            Eigen::Vector3d on, ignored;
            switch (core.type)
            {
                case Core::POINT:
                    return core.p[0];
                case Core::SEGMENT:
                    segmentSegmentDistance(q, q, core.p[0], core.p[1], ignored, on);
                    return on;
                case Core::TRIANGLE:
                    pointTriangleDistance(q, core.p[0], core.p[1], core.p[2], on);
                    return on;
                default:
                    return boxPoint(core, q);
            }
        }

        /** \brief Vertices and edges of a point, segment, triangle or box core. */
        struct Polytope
        {
            Eigen::Vector3d v[8];
            int nv{0}, ne{0};
            int e[12][2];
            explicit Polytope(const Core &core)
            {
                if (core.type != Core::BOX)
                {
                    nv = core.type == Core::POINT ? 1 : core.type == Core::SEGMENT ? 2 : 3;
                    std::copy(core.p, core.p + nv, v);
                    ne = nv == 1 ? 0 : nv == 2 ? 1 : 3;
                    for (int k = 0; k < ne; ++k)
                        e[k][0] = k, e[k][1] = (k + 1) % nv;
                    return;
                }
                nv = 8;
                for (int k = 0; k < 8; ++k)
                    v[k] = core.c + core.R * Eigen::Vector3d((k & 1) ? core.half.x() : -core.half.x(),
                                                             (k & 2) ? core.half.y() : -core.half.y(),
                                                             (k & 4) ? core.half.z() : -core.half.z());
                for (int k = 0; k < 8; ++k)
                    for (int bit = 1; bit < 8; bit <<= 1)
                        if (!(k & bit))
                            e[ne][0] = k, e[ne][1] = k | bit, ++ne;
            }
        };

        /** \brief The gap of \e box and the polytope \e q along \e n (any length; 0 length: no gap). */
        double gapAlong(const Eigen::Vector3d &n, const Core &box, const Polytope &q)
        {
            const double length = n.norm();
            if (!(length > 1e-12))
                return -std::numeric_limits<double>::infinity();
            const double centre = n.dot(box.c);
            const double extent = (box.R.transpose() * n).cwiseAbs().dot(box.half);
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int k = 0; k < q.nv; ++k)
                lo = std::min(lo, n.dot(q.v[k])), hi = std::max(hi, n.dot(q.v[k]));
            return std::max(lo - (centre + extent), (centre - extent) - hi) / length;
        }

        /** \brief The largest gap between \e box and \e other (a point, segment, triangle or box) along the
            separating axes of the pair: the box's face normals, the other's, and the cross products of their edge
            directions. Positive: they are apart, and it is a lower bound of their distance; else they overlap. */
        double separation(const Core &box, const Core &other, const Polytope &q)
        {
            Eigen::Vector3d axes[8];
            int n = 0;
            for (int i = 0; i < 3; ++i)
                axes[n++] = box.R.col(i);
            if (other.type == Core::BOX)
                for (int i = 0; i < 3; ++i)
                    axes[n++] = other.R.col(i);
            else if (other.type == Core::TRIANGLE)
                axes[n++] = (other.p[1] - other.p[0]).cross(other.p[2] - other.p[0]);
            double gap = -std::numeric_limits<double>::infinity();
            for (int i = 0; i < n; ++i)
                gap = std::max(gap, gapAlong(axes[i], box, q));
            Eigen::Vector3d edges[3];
            int m = 0;
            if (other.type == Core::BOX)
                for (int i = 0; i < 3; ++i)
                    edges[m++] = other.R.col(i);
            else
                for (int k = 0; k < q.ne; ++k)
                    edges[m++] = q.v[q.e[k][1]] - q.v[q.e[k][0]];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < m; ++j)
                    gap = std::max(gap, gapAlong(box.R.col(i).cross(edges[j]), box, q));
            return gap;
        }

        /** \brief Box against a point, segment, triangle or box: 0 when no axis separates them, the separating gap
            when it exceeds \e enough, else the least of the vertex-to-solid and edge-edge distances (exact for
            disjoint polytopes). onA on the box. */
        CoreGap boxGap(const Core &box, const Core &other, double enough)
        {
            CoreGap g;
            const Polytope p(box), q(other);
            const double gap = separation(box, other, q);
            if (gap > enough)  // a lower bound the caller prunes above: nothing more to compute
                return (g.lower = gap, g.upper = std::numeric_limits<double>::infinity(), g);
            Nearest best;
            for (int k = 0; k < q.nv; ++k)
                best.offer(boxPoint(box, q.v[k]), q.v[k]);
            for (int k = 0; k < p.nv; ++k)
                best.offer(p.v[k], nearestOn(other, p.v[k]));
            Eigen::Vector3d onP, onQ;
            for (int i = 0; i < p.ne; ++i)
                for (int j = 0; j < q.ne; ++j)
                {
                    segmentSegmentDistance(p.v[p.e[i][0]], p.v[p.e[i][1]], q.v[q.e[j][0]], q.v[q.e[j][1]], onP, onQ);
                    best.offer(onP, onQ);
                }
            g.onA = best.onA;
            g.onB = best.onB;
            g.overlap = !(gap > 0.0);
            g.lower = g.upper = g.overlap ? 0.0 : std::sqrt(best.d2);
            return g;
        }

        /** \brief Two of a point, a segment and a triangle: their exact distance (triangleDistance() and its
            parts). */
        CoreGap simplexGap(const Core &a, const Core &b)
        {
            CoreGap g;
            auto corners = [](const Core &c, int k) { return c.p[std::min<int>(k, c.type)]; };
            if (a.type == Core::TRIANGLE || b.type == Core::TRIANGLE)
            {
                if (a.type == Core::POINT || b.type == Core::POINT)
                {
                    const bool pointA = a.type == Core::POINT;
                    const Core &t = pointA ? b : a;
                    Eigen::Vector3d on;
                    const Eigen::Vector3d &q = pointA ? a.p[0] : b.p[0];
                    g.lower = pointTriangleDistance(q, t.p[0], t.p[1], t.p[2], on);
                    g.onA = pointA ? q : on;
                    g.onB = pointA ? on : q;
                }
                else
                    g.lower = triangleDistance(corners(a, 0), corners(a, 1), corners(a, 2), corners(b, 0),
                                               corners(b, 1), corners(b, 2), g.onA, g.onB);
            }
            else
                g.lower = segmentSegmentDistance(corners(a, 0), corners(a, 1), corners(b, 0), corners(b, 1), g.onA,
                                                 g.onB);
            g.upper = g.lower;
            return g;
        }

        CoreGap coreGap(const Core &a, const Core &b, double scale, double enough)
        {
            // GJK for the curved solids, and for two boxes (polytopes: it ends exact, cheaper than 144 edge pairs).
            if (a.curved() || b.curved() || (a.type == Core::BOX && b.type == Core::BOX))
                return solid::gjk(a, b, scale, enough);
            if (a.type == Core::BOX)
                return boxGap(a, b, enough);
            if (b.type == Core::BOX)
            {
                CoreGap g = boxGap(b, a, enough);
                std::swap(g.onA, g.onB);
                return g;
            }
            return simplexGap(a, b);
        }

        /** \brief The solids' gap from their cores' gap: the balls' radii subtracted, contact within the tolerance
            counted as touching (distance 0, one common point). */
        SolidGap solidGap(const Core &a, const Core &b, double enough)
        {
            const double scale = std::max(a.reach(), b.reach());
            const double radii = a.radius + b.radius;
            const CoreGap g = coreGap(a, b, scale, enough + radii);
            SolidGap s;
            s.iterations = g.iterations;
            const Eigen::Vector3d between = g.onB - g.onA;
            const double length = between.norm();
            const Eigen::Vector3d unit = length > 0.0 ? Eigen::Vector3d(between / length) : Eigen::Vector3d::Zero();
            s.distance = g.overlap ? 0.0 : std::max(0.0, g.lower - radii);
            if (s.distance <= TRIANGLE_CONTACT_TOLERANCE * scale)
            {
                const double t = radii > 0.0 ? std::min(1.0, a.radius / radii) * std::min(length, radii) : 0.0;
                s.distance = s.upper = 0.0;
                s.onA = s.onB =
                    radii > 0.0 ? Eigen::Vector3d(g.onA + t * unit) : Eigen::Vector3d(0.5 * (g.onA + g.onB));
                return s;
            }
            s.onA = g.onA + a.radius * unit;
            s.onB = g.onB - b.radius * unit;
            s.upper = std::max(s.distance, g.upper - radii);
            return s;
        }
    }  // namespace

    SolidGap primitiveTriangleGap(const Primitive &s, const Eigen::Isometry3d &X, const Eigen::Vector3d &a,
                                  const Eigen::Vector3d &b, const Eigen::Vector3d &c, double enough)
    {
        Core triangle;
        triangle.type = Core::TRIANGLE;
        triangle.p[0] = a;
        triangle.p[1] = b;
        triangle.p[2] = c;
        return solidGap(solid::coreOf(s, X), triangle, enough);
    }

    SolidGap primitiveGap(const Primitive &a, const Eigen::Isometry3d &X_a, const Primitive &b,
                          const Eigen::Isometry3d &X_b, double enough)
    {
        return solidGap(solid::coreOf(a, X_a), solid::coreOf(b, X_b), enough);
    }
}  // namespace meshgap
