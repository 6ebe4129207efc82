// GJK (Gilbert, Johnson and Keerthi, 1988) on the support functions of convex cores, with the support-plane gap as a
// certified lower bound: the distance of two convex sets is at least v.w / |v| for any v and w the point of A - B
// least along v. Closest points of the simplex by Voronoi regions (Ericson, Real-Time Collision Detection, 5.1).

#include <algorithm>
#include <cmath>
#include <limits>

#include "SolidCore.h"
#include "meshgap/geometry/ConvexHull.h"

namespace meshgap
{
    namespace solid
    {
        Eigen::Vector3d Core::support(const Eigen::Vector3d &d) const
        {
            switch (type)
            {
                case POINT:
                    return p[0];
                case SEGMENT:
                    return d.dot(p[0]) >= d.dot(p[1]) ? p[0] : p[1];
                case TRIANGLE:
                {
                    const double s0 = d.dot(p[0]), s1 = d.dot(p[1]), s2 = d.dot(p[2]);
                    return s0 >= s1 && s0 >= s2 ? p[0] : (s1 >= s2 ? p[1] : p[2]);
                }
                case BOX:
                {
                    const Eigen::Vector3d l = R.transpose() * d;
                    const Eigen::Vector3d q(l.x() >= 0.0 ? half.x() : -half.x(), l.y() >= 0.0 ? half.y() : -half.y(),
                                            l.z() >= 0.0 ? half.z() : -half.z());
                    return c + R * q;
                }
                case HULL:
                    return c + R * hull->support(R.transpose() * d);
                case SWEPT:
                {
                    const Eigen::Vector3d s0 = c + R * hull->support(R.transpose() * d);
                    const Eigen::Vector3d s1 = c1 + R1 * hull->support(R1.transpose() * d);
                    return d.dot(s0) >= d.dot(s1) ? s0 : s1;
                }
                default:
                    break;
            }
            // Cylinder or cone: in the solid's frame, the rim point along d's part across the axis.
            const Eigen::Vector3d l = R.transpose() * d;
            const double rho = std::hypot(l.x(), l.y());
            Eigen::Vector3d across = Eigen::Vector3d::Zero();
            if (rho > 0.0)
                across = Eigen::Vector3d(half.x() * l.x() / rho, half.x() * l.y() / rho, 0.0);
            if (type == CYLINDER)
                return c + R * (across + Eigen::Vector3d(0.0, 0.0, l.z() >= 0.0 ? half.z() : -half.z()));
            const Eigen::Vector3d apex(0.0, 0.0, half.z()), rim = across - apex;
            return c + R * (l.dot(apex) >= l.dot(rim) ? apex : rim);
        }

        Eigen::Vector3d Core::center() const
        {
            switch (type)
            {
                case POINT:
                    return p[0];
                case SEGMENT:
                    return 0.5 * (p[0] + p[1]);
                case TRIANGLE:
                    return (p[0] + p[1] + p[2]) / 3.0;
                case HULL:
                    return c + R * hull->center();
                case SWEPT:
                    return 0.5 * ((c + R * hull->center()) + (c1 + R1 * hull->center()));
                default:
                    return c;
            }
        }

        double Core::reach() const
        {
            switch (type)
            {
                case POINT:
                    return p[0].norm() + radius;
                case SEGMENT:
                    return std::max(p[0].norm(), p[1].norm()) + radius;
                case TRIANGLE:
                    return std::max({p[0].norm(), p[1].norm(), p[2].norm()}) + radius;
                case HULL:
                    return c.norm() + hull->reach() + radius;
                case SWEPT:
                    return std::max(c.norm(), c1.norm()) + hull->reach() + radius;
                default:
                    return c.norm() + half.norm() + radius;
            }
        }

        namespace
        {
            /** \brief A GJK simplex: up to four points w = a - b of A - B, with a and b, and the weights of the
                closest point to the origin. */
            struct Simplex
            {
                Eigen::Vector3d w[4], a[4], b[4];
                double l[4]{0.0, 0.0, 0.0, 0.0};
                int n{0};

                /** \brief Keep only the vertices of positive weight. */
                void reduce()
                {
                    int m = 0;
                    for (int i = 0; i < n; ++i)
                        if (l[i] > 0.0)
                        {
                            w[m] = w[i];
                            a[m] = a[i];
                            b[m] = b[i];
                            l[m] = l[i];
                            ++m;
                        }
                    n = m;
                }
                Eigen::Vector3d point() const
                {
                    Eigen::Vector3d v = Eigen::Vector3d::Zero();
                    for (int i = 0; i < n; ++i)
                        v += l[i] * w[i];
                    return v;
                }
            };

            /** \brief Weights of the point of segment [A, B] closest to the origin. */
            void segmentWeights(const Eigen::Vector3d &A, const Eigen::Vector3d &B, double *l)
            {
                const Eigen::Vector3d e = B - A;
                const double ee = e.squaredNorm();
                const double t = ee > 0.0 ? std::clamp(-A.dot(e) / ee, 0.0, 1.0) : 0.0;
                l[0] = 1.0 - t;
                l[1] = t;
                if (t >= 1.0)
                    l[0] = 0.0;
            }

            /** \brief Squared distance to the origin of the point of weights \e l on the points \e P. */
            double squaredAt(const Eigen::Vector3d *P, const double *l, int n)
            {
                Eigen::Vector3d v = Eigen::Vector3d::Zero();
                for (int i = 0; i < n; ++i)
                    v += l[i] * P[i];
                return v.squaredNorm();
            }

            /** \brief Weights of the point of the degenerate triangle ABC (as the union of its edges) closest to the
                origin. */
            void edgeWeights(const Eigen::Vector3d *P, double *l)
            {
                double best = std::numeric_limits<double>::infinity();
                for (int e = 0; e < 3; ++e)
                {
                    const int i = e, j = (e + 1) % 3;
                    double s[2], t[3] = {0.0, 0.0, 0.0};
                    segmentWeights(P[i], P[j], s);
                    t[i] = s[0];
                    t[j] = s[1];
                    const double d = squaredAt(P, t, 3);
                    if (d < best)
                    {
                        best = d;
                        std::copy(t, t + 3, l);
                    }
                }
            }

            /** \brief Weights of the point of the filled triangle P[0..2] closest to the origin (Voronoi regions). */
            void triangleWeights(const Eigen::Vector3d *P, double *l)
            {
                const Eigen::Vector3d &A = P[0], &B = P[1], &C = P[2];
                const Eigen::Vector3d ab = B - A, ac = C - A;
                std::fill(l, l + 3, 0.0);
                const double d1 = -ab.dot(A), d2 = -ac.dot(A);
                if (d1 <= 0.0 && d2 <= 0.0)
                    return void(l[0] = 1.0);
                const double d3 = -ab.dot(B), d4 = -ac.dot(B);
                if (d3 >= 0.0 && d4 <= d3)
                    return void(l[1] = 1.0);
                const double vc = d1 * d4 - d3 * d2;
                if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
                {
                    const double t = d1 / (d1 - d3);
                    return void((l[0] = 1.0 - t, l[1] = t));
                }
                const double d5 = -ab.dot(C), d6 = -ac.dot(C);
                if (d6 >= 0.0 && d5 <= d6)
                    return void(l[2] = 1.0);
                const double vb = d5 * d2 - d1 * d6;
                if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
                {
                    const double t = d2 / (d2 - d6);
                    return void((l[0] = 1.0 - t, l[2] = t));
                }
                const double va = d3 * d6 - d5 * d4;
                if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
                {
                    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
                    return void((l[1] = 1.0 - t, l[2] = t));
                }
                const double sum = va + vb + vc;
                if (!(sum > 0.0) || !std::isfinite(sum))
                    return edgeWeights(P, l);  // degenerate: its edges
                l[1] = vb / sum;
                l[2] = vc / sum;
                l[0] = 1.0 - l[1] - l[2];
            }

            /** \brief Weights of the point of the tetrahedron closest to the origin; false when the origin is inside
                (the weights then its barycentric coordinates). */
            bool tetrahedronWeights(const Eigen::Vector3d *P, double *l)
            {
                static const int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {0, 2, 3, 1}, {1, 2, 3, 0}};
                // A flat tetrahedron (its volume within roundoff of 0) has no inside: then every face is tried, as
                // a face test's sign would be roundoff.
                const double reach = std::max({(P[1] - P[0]).norm(), (P[2] - P[0]).norm(), (P[3] - P[0]).norm()});
                const double volume = (P[1] - P[0]).dot((P[2] - P[0]).cross(P[3] - P[0]));
                const bool flat = !(std::abs(volume) > 1e-10 * reach * reach * reach);
                double best = std::numeric_limits<double>::infinity();
                bool outside = false;
                for (const auto &f : faces)
                {
                    const Eigen::Vector3d n = (P[f[1]] - P[f[0]]).cross(P[f[2]] - P[f[0]]);
                    const double sOrigin = -n.dot(P[f[0]]), sOpposite = n.dot(P[f[3]] - P[f[0]]);
                    if (!flat && sOrigin * sOpposite > 0.0)
                        continue;  // the origin is on the inner side of this face
                    outside = true;
                    const Eigen::Vector3d T[3] = {P[f[0]], P[f[1]], P[f[2]]};
                    double t[3], all[4] = {0.0, 0.0, 0.0, 0.0};
                    triangleWeights(T, t);
                    for (int k = 0; k < 3; ++k)
                        all[f[k]] = t[k];
                    const double d = squaredAt(P, all, 4);
                    if (d < best)
                    {
                        best = d;
                        std::copy(all, all + 4, l);
                    }
                }
                if (outside)
                    return true;
                Eigen::Matrix3d M;
                M << P[1] - P[0], P[2] - P[0], P[3] - P[0];
                const Eigen::Vector3d x = M.colPivHouseholderQr().solve(-P[0]);
                l[1] = x[0], l[2] = x[1], l[3] = x[2];
                l[0] = 1.0 - x.sum();
                return false;
            }

            /** \brief The simplex's point closest to the origin: weights set, the simplex reduced to the face that
                holds it; false when the origin lies inside (a tetrahedron holding it: the sets overlap). */
            bool closest(Simplex &s)
            {
                bool apart = true;
                if (s.n == 1)
                    s.l[0] = 1.0;
                else if (s.n == 2)
                    segmentWeights(s.w[0], s.w[1], s.l);
                else if (s.n == 3)
                    triangleWeights(s.w, s.l);
                else
                    apart = tetrahedronWeights(s.w, s.l);
                if (apart)
                    s.reduce();
                return apart;
            }

            void witnesses(const Simplex &s, CoreGap &g)
            {
                g.onA.setZero();
                g.onB.setZero();
                for (int i = 0; i < s.n; ++i)
                {
                    g.onA += s.l[i] * s.a[i];
                    g.onB += s.l[i] * s.b[i];
                }
            }
        }  // namespace

        CoreGap gjk(const Core &a, const Core &b, double scale, double enough, const Eigen::Vector3d &first)
        {
            const double pad = 4e-15 * scale, still = 1e-14 * scale;
            Eigen::Vector3d d = first;
            if (!(d.squaredNorm() > 0.0) || !d.allFinite())
                d = b.center() - a.center();
            if (!(d.squaredNorm() > 0.0))
                d = Eigen::Vector3d::UnitX();
            Simplex s;
            s.a[0] = a.support(d);
            s.b[0] = b.support(-d);
            s.w[0] = s.a[0] - s.b[0];
            s.l[0] = 1.0;
            s.n = 1;
            CoreGap g;
            g.axis = d;
            // The first pair is the support pair along -d: a's farthest point towards b and b's nearest to a, so the
            // sets lie apart by at least the gap between those two planes, -d.w / |d| (the bound the loop takes for
            // v = -d). Far apart along a good first axis (the last query's), a pair is proven here.
            double lower = -std::numeric_limits<double>::infinity();
            const double firstGap = -d.dot(s.w[0]) / d.norm();
            if (firstGap > lower)
                lower = firstGap;  // not a number (an overflow) is no bound
            if (lower - pad > enough)
                return (g.lower = lower - pad, g.upper = s.w[0].norm(), g.onA = s.a[0], g.onB = s.b[0], g);
            Eigen::Vector3d v = s.w[0];
            for (g.iterations = 1; g.iterations <= 256; ++g.iterations)
            {
                const double length = v.norm();
                witnesses(s, g);
                g.upper = length;
                if (!(length > still))
                    return (g.overlap = true, g.lower = 0.0, g);
                const Eigen::Vector3d sa = a.support(-v), sb = b.support(v), w = sa - sb;
                lower = std::max(lower, v.dot(w) / length);
                const bool repeated = std::any_of(s.w, s.w + s.n, [&](const Eigen::Vector3d &x) { return x == w; });
                if (lower - pad > enough || length - lower <= std::max(1e-12 * length, still) || repeated)
                    break;
                s.w[s.n] = w;
                s.a[s.n] = sa;
                s.b[s.n] = sb;
                ++s.n;
                if (!closest(s))
                {
                    g.onA = g.onB = Eigen::Vector3d::Zero();
                    for (int i = 0; i < 4; ++i)
                        g.onA += s.l[i] * s.a[i], g.onB += s.l[i] * s.b[i];
                    return (g.overlap = true, g.lower = 0.0, g.upper = 0.0, g);
                }
                const Eigen::Vector3d next = s.point();
                if (!(next.norm() < length))
                    break;  // no progress: roundoff; the bounds stand
                v = next;
            }
            g.axis = -v;
            g.lower = std::max(0.0, lower - pad);
            return g;
        }
    }  // namespace solid
}  // namespace meshgap
