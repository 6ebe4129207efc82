#include "support/Shapes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        constexpr double pi = 3.14159265358979323846;

        double cross2(const Eigen::Vector2d &u, const Eigen::Vector2d &v)
        {
            return u.x() * v.y() - u.y() * v.x();
        }

        /** \brief Twice the signed area of triangle abc (positive when counter-clockwise). */
        double orient(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c)
        {
            return cross2(b - a, c - a);
        }

        /** \brief Positive when d lies inside the circumcircle of the counter-clockwise triangle abc. */
        double inCircle(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c,
                        const Eigen::Vector2d &d)
        {
            const Eigen::Vector2d ad = a - d, bd = b - d, cd = c - d;
            return ad.squaredNorm() * cross2(bd, cd) + bd.squaredNorm() * cross2(cd, ad) +
                   cd.squaredNorm() * cross2(ad, bd);
        }

        /** \brief Newell's vector of a closed 3D loop: twice its vector area. */
        Eigen::Vector3d newell(const std::vector<Eigen::Vector3d> &corners, const Polyhedron::Loop &loop)
        {
            Eigen::Vector3d n = Eigen::Vector3d::Zero();
            for (std::size_t i = 0; i < loop.size(); ++i)
            {
                const Eigen::Vector3d &p = corners[loop[i]], &q = corners[loop[(i + 1) % loop.size()]];
                n += p.cross(q);
            }
            return n;
        }

        double checkedSize(const SizingFunction &sizing, const Eigen::Vector3d &p)
        {
            const double h = sizing(p);
            if (!(h > 0.0) || !std::isfinite(h))
                throw Exception("meshgap::Polyhedron::mesh", "the sizing function returned " + std::to_string(h) +
                                                                 " (it must be positive and finite)");
            return h;
        }

        /** \brief Parameters in (0, 1) that split segment ab into pieces of equal "sizing length" (integral of
            ds / h), as few as keep every piece within its local grid size; equal pieces for a uniform sizing. */
        std::vector<double> subdivisionParameters(const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                                                  const SizingFunction &sizing)
        {
            constexpr int samples = 64;
            const double length = (b - a).norm();
            std::vector<double> integral(samples + 1, 0.0);
            double previous = 1.0 / checkedSize(sizing, a);
            for (int k = 1; k <= samples; ++k)
            {
                const double w = 1.0 / checkedSize(sizing, a + (b - a) * (double(k) / samples));
                integral[k] = integral[k - 1] + 0.5 * (previous + w) * length / samples;
                previous = w;
            }
            const double total = integral[samples];
            const int pieces = std::max(1, static_cast<int>(std::ceil(total - 1e-9)));
            std::vector<double> t;
            int k = 0;
            for (int j = 1; j < pieces; ++j)
            {
                const double target = total * j / pieces;
                while (k < samples - 1 && integral[k + 1] < target)
                    ++k;
                const double span = integral[k + 1] - integral[k];
                t.push_back((k + (span > 0.0 ? (target - integral[k]) / span : 0.0)) / samples);
            }
            return t;
        }

        /** \brief Triangulation of one planar face in its own 2D frame: ear clipping of the corner polygon (holes
            bridged in), boundary nodes inserted on its edges, then Lawson flips to the constrained Delaunay
            triangulation, longest-edge-propagation-path bisection down to the local grid size and Laplacian
            smoothing of the inner nodes. Boundary edges (those with one triangle) are never split or flipped. */
        class PlanarTriangulation
        {
        public:
            PlanarTriangulation(std::function<double(const Eigen::Vector2d &)> sizing, double scale,
                                std::string where)
              : sizing_(std::move(sizing)), eps_(1e-12 * scale * scale), where_(std::move(where))
            {
            }

            int addPoint(const Eigen::Vector2d &p, bool fixed)
            {
                points_.push_back(p);
                fixed_.push_back(fixed ? 1 : 0);
                return static_cast<int>(points_.size()) - 1;
            }

            const std::vector<Eigen::Vector2d> &points() const
            {
                return points_;
            }
            const std::vector<std::array<int, 3>> &triangles() const
            {
                return triangles_;
            }

            /** \brief Ear-clip the polygon loops[0] (counter-clockwise) minus the holes loops[1..] (clockwise). */
            void triangulatePolygon(const std::vector<std::vector<int>> &loops)
            {
                std::vector<int> polygon = loops[0];
                std::vector<std::vector<int>> holes(loops.begin() + 1, loops.end());
                // Bridge the holes in, rightmost first, each from its rightmost corner to the nearest visible
                // corner of the polygon built so far.
                std::vector<std::size_t> order(holes.size());
                for (std::size_t i = 0; i < order.size(); ++i)
                    order[i] = i;
                auto rightmost = [this](const std::vector<int> &loop) {
                    std::size_t best = 0;
                    for (std::size_t i = 1; i < loop.size(); ++i)
                    {
                        const Eigen::Vector2d &p = points_[loop[i]], &q = points_[loop[best]];
                        if (p.x() > q.x() || (p.x() == q.x() && p.y() > q.y()))
                            best = i;
                    }
                    return best;
                };
                std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
                    return points_[holes[a][rightmost(holes[a])]].x() > points_[holes[b][rightmost(holes[b])]].x();
                });
                std::vector<char> merged(holes.size(), 0);
                for (std::size_t h : order)
                {
                    const std::vector<int> &hole = holes[h];
                    const std::size_t mi = rightmost(hole);
                    const int m = hole[mi];
                    std::size_t best = polygon.size();
                    double bestDistance = std::numeric_limits<double>::infinity();
                    for (std::size_t i = 0; i < polygon.size(); ++i)
                    {
                        const int p = polygon[i];
                        const double d = (points_[p] - points_[m]).norm();
                        if (d >= bestDistance || !inWedge(polygon, i, points_[m]))
                            continue;
                        if (blocked(m, p, polygon, holes, merged))
                            continue;
                        best = i;
                        bestDistance = d;
                    }
                    if (best == polygon.size())
                        throw Exception(where_, "cannot connect a hole to the outer boundary (does it cross it?)");
                    std::vector<int> spliced(polygon.begin(), polygon.begin() + static_cast<long>(best) + 1);
                    for (std::size_t k = 0; k <= hole.size(); ++k)
                        spliced.push_back(hole[(mi + k) % hole.size()]);
                    spliced.insert(spliced.end(), polygon.begin() + static_cast<long>(best), polygon.end());
                    polygon.swap(spliced);
                    merged[h] = 1;
                }
                earClip(polygon);
            }

            /** \brief Put the nodes (in order from a to b) on the boundary edge a -> b. */
            void insertOnBoundary(int a, int b, const std::vector<int> &nodes)
            {
                for (int m : nodes)
                {
                    const int t = triangleOf(a, b);
                    if (t < 0)
                        throw Exception(where_, "internal error: boundary edge missing from the triangulation");
                    const int c = apex(t, a, b);
                    setTriangle(t, a, m, c);
                    setTriangle(triangles_.size(), m, b, c);
                    a = m;
                }
            }

            /** \brief Lawson flips over every inner edge. */
            void makeDelaunay()
            {
                std::vector<std::pair<int, int>> stack;
                for (const auto &t : triangles_)
                    for (int k = 0; k < 3; ++k)
                        if (t[k] < t[(k + 1) % 3])
                            stack.emplace_back(t[k], t[(k + 1) % 3]);
                legalize(stack);
            }

            /** \brief Bisect inner edges longer than the local grid size (longest edge propagation path first),
                restoring the Delaunay property after each split when \e flips. */
            void refine(bool flips)
            {
                for (int round = 0; round < 200; ++round)
                {
                    std::vector<std::pair<double, std::pair<int, int>>> candidates;
                    for (const auto &t : triangles_)
                        for (int k = 0; k < 3; ++k)
                        {
                            const int a = t[k], b = t[(k + 1) % 3];
                            if (a < b && triangleOf(b, a) >= 0)
                            {
                                const double r = ratio(a, b);
                                if (r > 1.0 + 1e-9)
                                    candidates.push_back({r, {a, b}});
                            }
                        }
                    if (candidates.empty())
                        return;
                    std::sort(candidates.begin(), candidates.end(),
                              [](const auto &x, const auto &y) { return x.first > y.first; });
                    for (const auto &candidate : candidates)
                    {
                        const int a = candidate.second.first, b = candidate.second.second;
                        if (triangleOf(a, b) >= 0 && triangleOf(b, a) >= 0 && ratio(a, b) > 1.0 + 1e-9)
                            splitLongestPath(a, b, flips);
                    }
                }
                throw Exception(where_, "refinement did not converge (is the sizing function far too small?)");
            }

            /** \brief Move each inner node towards the mean of its neighbours where that keeps every triangle
                around it positively oriented, then flip back to Delaunay; \e passes times. */
            void smooth(int passes)
            {
                for (int pass = 0; pass < passes; ++pass)
                {
                    std::vector<std::vector<int>> around(points_.size());
                    for (std::size_t t = 0; t < triangles_.size(); ++t)
                        for (int v : triangles_[t])
                            around[v].push_back(static_cast<int>(t));
                    for (std::size_t v = 0; v < points_.size(); ++v)
                    {
                        if (fixed_[v] || around[v].empty())
                            continue;
                        Eigen::Vector2d sum = Eigen::Vector2d::Zero();
                        int count = 0;
                        for (int t : around[v])
                            for (int w : triangles_[t])
                                if (w != static_cast<int>(v))
                                {
                                    sum += points_[w];
                                    ++count;
                                }
                        const Eigen::Vector2d old = points_[v];
                        points_[v] = sum / count;
                        bool valid = true;
                        for (int t : around[v])
                        {
                            const auto &tri = triangles_[t];
                            if (orient(points_[tri[0]], points_[tri[1]], points_[tri[2]]) <= 1e3 * eps_)
                                valid = false;
                        }
                        if (!valid)
                            points_[v] = old;
                    }
                    makeDelaunay();
                }
            }

        private:
            static std::uint64_t key(int a, int b)
            {
                return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
            }

            int triangleOf(int a, int b) const
            {
                auto it = edges_.find(key(a, b));
                return it == edges_.end() ? -1 : it->second;
            }

            int apex(int t, int a, int b) const
            {
                for (int v : triangles_[t])
                    if (v != a && v != b)
                        return v;
                return -1;
            }

            /** \brief Set (or append, when t == size) triangle t to the counter-clockwise abc. */
            void setTriangle(std::size_t t, int a, int b, int c)
            {
                if (t < triangles_.size())
                {
                    const auto old = triangles_[t];
                    for (int k = 0; k < 3; ++k)
                    {
                        auto it = edges_.find(key(old[k], old[(k + 1) % 3]));
                        if (it != edges_.end() && it->second == static_cast<int>(t))
                            edges_.erase(it);
                    }
                    triangles_[t] = {a, b, c};
                }
                else
                    triangles_.push_back({a, b, c});
                const int ti = static_cast<int>(t);
                edges_[key(a, b)] = ti;
                edges_[key(b, c)] = ti;
                edges_[key(c, a)] = ti;
            }

            double ratio(int a, int b) const
            {
                const Eigen::Vector2d &p = points_[a], &q = points_[b];
                return (q - p).norm() / sizing_(0.5 * (p + q));
            }

            /** \brief Is p strictly inside the polygon's interior angle at position i? */
            bool inWedge(const std::vector<int> &polygon, std::size_t i, const Eigen::Vector2d &p) const
            {
                const std::size_t n = polygon.size();
                const Eigen::Vector2d &c = points_[polygon[i]];
                const Eigen::Vector2d next = points_[polygon[(i + 1) % n]] - c;
                const Eigen::Vector2d prev = points_[polygon[(i + n - 1) % n]] - c;
                const Eigen::Vector2d d = p - c;
                auto angleFrom = [](const Eigen::Vector2d &u, const Eigen::Vector2d &v) {
                    double a = std::atan2(cross2(u, v), u.dot(v));
                    return a < 0.0 ? a + 2.0 * pi : a;
                };
                const double span = angleFrom(next, prev), at = angleFrom(next, d);
                return at > 1e-9 && at < span - 1e-9;
            }

            /** \brief Does segment mp touch any polygon or hole edge not incident to m or p? */
            bool blocked(int m, int p, const std::vector<int> &polygon, const std::vector<std::vector<int>> &holes,
                         const std::vector<char> &merged) const
            {
                auto hits = [&](const std::vector<int> &loop) {
                    for (std::size_t i = 0; i < loop.size(); ++i)
                    {
                        const int u = loop[i], v = loop[(i + 1) % loop.size()];
                        if (u == m || u == p || v == m || v == p)
                            continue;
                        if (segmentsTouch(points_[m], points_[p], points_[u], points_[v]))
                            return true;
                    }
                    return false;
                };
                if (hits(polygon))
                    return true;
                for (std::size_t h = 0; h < holes.size(); ++h)
                    if (!merged[h] && hits(holes[h]))
                        return true;
                return false;
            }

            bool segmentsTouch(const Eigen::Vector2d &a, const Eigen::Vector2d &b, const Eigen::Vector2d &c,
                               const Eigen::Vector2d &d) const
            {
                const double d1 = orient(a, b, c), d2 = orient(a, b, d), d3 = orient(c, d, a), d4 = orient(c, d, b);
                if (((d1 > eps_ && d2 < -eps_) || (d1 < -eps_ && d2 > eps_)) &&
                    ((d3 > eps_ && d4 < -eps_) || (d3 < -eps_ && d4 > eps_)))
                    return true;
                auto onSegment = [this](const Eigen::Vector2d &s, const Eigen::Vector2d &e, const Eigen::Vector2d &q,
                                        double o) {
                    return std::abs(o) <= eps_ && (q - s).dot(q - e) <= eps_;
                };
                return onSegment(a, b, c, d1) || onSegment(a, b, d, d2) || onSegment(c, d, a, d3) ||
                       onSegment(c, d, b, d4);
            }

            void earClip(const std::vector<int> &polygon)
            {
                const std::size_t n = polygon.size();
                if (n < 3)
                    throw Exception(where_, "a face loop has fewer than three corners");
                std::vector<std::size_t> next(n), prev(n);
                for (std::size_t i = 0; i < n; ++i)
                {
                    next[i] = (i + 1) % n;
                    prev[i] = (i + n - 1) % n;
                }
                std::vector<char> removed(n, 0);
                std::size_t remaining = n, current = 0, misses = 0;
                while (remaining > 3)
                {
                    if (isEar(polygon, prev, next, removed, current))
                    {
                        const std::size_t p = prev[current], q = next[current];
                        setTriangle(triangles_.size(), polygon[p], polygon[current], polygon[q]);
                        removed[current] = 1;
                        next[p] = q;
                        prev[q] = p;
                        --remaining;
                        current = p;
                        misses = 0;
                    }
                    else
                    {
                        current = next[current];
                        if (++misses > remaining)
                            throw Exception(where_, "ear clipping found no ear (self-intersecting face loop?)");
                    }
                }
                const std::size_t p = prev[current], q = next[current];
                if (orient(points_[polygon[p]], points_[polygon[current]], points_[polygon[q]]) <= eps_)
                    throw Exception(where_, "ear clipping left a degenerate triangle (collinear face corners?)");
                setTriangle(triangles_.size(), polygon[p], polygon[current], polygon[q]);
            }

            bool isEar(const std::vector<int> &polygon, const std::vector<std::size_t> &prev,
                       const std::vector<std::size_t> &next, const std::vector<char> &removed, std::size_t i) const
            {
                const int ia = polygon[prev[i]], ib = polygon[i], ic = polygon[next[i]];
                const Eigen::Vector2d &a = points_[ia], &b = points_[ib], &c = points_[ic];
                if (orient(a, b, c) <= eps_)
                    return false;
                for (std::size_t j = 0; j < polygon.size(); ++j)
                {
                    const int id = polygon[j];
                    if (removed[j] || id == ia || id == ib || id == ic)
                        continue;
                    const Eigen::Vector2d &q = points_[id];
                    if (orient(a, b, q) >= -eps_ && orient(b, c, q) >= -eps_ && orient(c, a, q) >= -eps_)
                        return false;
                }
                return true;
            }

            bool shouldFlip(int a, int b, int c, int d) const
            {
                const Eigen::Vector2d &pa = points_[a], &pb = points_[b], &pc = points_[c], &pd = points_[d];
                if (orient(pa, pd, pc) <= eps_ || orient(pd, pb, pc) <= eps_)
                    return false;
                const double scale = std::max({(pa - pb).squaredNorm(), (pc - pd).squaredNorm()});
                return inCircle(pa, pb, pc, pd) > 1e-10 * scale * scale;
            }

            void legalize(std::vector<std::pair<int, int>> &stack)
            {
                std::size_t budget = 100 * triangles_.size() + 1000;
                while (!stack.empty() && budget-- > 0)
                {
                    const auto [a, b] = stack.back();
                    stack.pop_back();
                    const int t1 = triangleOf(a, b), t2 = triangleOf(b, a);
                    if (t1 < 0 || t2 < 0)
                        continue;
                    const int c = apex(t1, a, b), d = apex(t2, b, a);
                    if (!shouldFlip(a, b, c, d))
                        continue;
                    setTriangle(t1, a, d, c);
                    setTriangle(t2, d, b, c);
                    stack.emplace_back(a, d);
                    stack.emplace_back(d, b);
                    stack.emplace_back(b, c);
                    stack.emplace_back(c, a);
                }
            }

            /** \brief Rivara's longest edge propagation path: walk to longer inner edges of the neighbouring
                triangles, then bisect the last one. */
            void splitLongestPath(int a, int b, bool flips)
            {
                for (int step = 0; step < 10000; ++step)
                {
                    const double length = (points_[a] - points_[b]).norm();
                    bool moved = false;
                    for (int t : {triangleOf(a, b), triangleOf(b, a)})
                    {
                        const auto &tri = triangles_[t];
                        for (int k = 0; k < 3 && !moved; ++k)
                        {
                            const int u = tri[k], v = tri[(k + 1) % 3];
                            if ((points_[u] - points_[v]).norm() > length * (1.0 + 1e-9) && triangleOf(v, u) >= 0)
                            {
                                a = u;
                                b = v;
                                moved = true;
                            }
                        }
                        if (moved)
                            break;
                    }
                    if (!moved)
                        break;
                }
                const int t1 = triangleOf(a, b), t2 = triangleOf(b, a);
                const int c = apex(t1, a, b), d = apex(t2, b, a);
                const int m = addPoint(0.5 * (points_[a] + points_[b]), false);
                setTriangle(t1, a, m, c);
                setTriangle(triangles_.size(), m, b, c);
                setTriangle(t2, b, m, d);
                setTriangle(triangles_.size(), m, a, d);
                if (flips)
                {
                    std::vector<std::pair<int, int>> stack{{c, a}, {b, c}, {d, b}, {a, d}};
                    legalize(stack);
                }
            }

            std::function<double(const Eigen::Vector2d &)> sizing_;
            double eps_;
            std::string where_;
            std::vector<Eigen::Vector2d> points_;
            std::vector<char> fixed_;
            std::vector<std::array<int, 3>> triangles_;
            std::unordered_map<std::uint64_t, int> edges_;
        };

        /** \brief Polygon made counter-clockwise (ccw) or clockwise (!ccw). */
        Polygon2d wound(Polygon2d polygon, bool ccw)
        {
            if ((polygonArea(polygon) > 0.0) != ccw)
                std::reverse(polygon.begin(), polygon.end());
            return polygon;
        }

        bool pointInPolygon(const std::vector<Eigen::Vector2d> &polygon, const Eigen::Vector2d &p)
        {
            bool inside = false;
            for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
            {
                const Eigen::Vector2d &a = polygon[i], &b = polygon[j];
                if ((a.y() > p.y()) != (b.y() > p.y()) &&
                    p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
                    inside = !inside;
            }
            return inside;
        }

        /** \brief An orthonormal pair spanning the plane normal to unit n. */
        std::pair<Eigen::Vector3d, Eigen::Vector3d> planeAxes(const Eigen::Vector3d &n)
        {
            Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
            const Eigen::Vector3d u = (helper - helper.dot(n) * n).normalized();
            return {u, n.cross(u)};
        }
    }  // namespace

    SizingFunction uniformSizing(double h)
    {
        if (!(h > 0.0) || !std::isfinite(h))
            throw Exception("meshgap::uniformSizing", "grid size must be positive and finite, got " +
                                                          std::to_string(h));
        return [h](const Eigen::Vector3d &) { return h; };
    }

    std::uint32_t Polyhedron::addCorner(const Eigen::Vector3d &p)
    {
        if (!p.allFinite())
            throw Exception("meshgap::Polyhedron", "corner with a NaN or infinite coordinate");
        corners_.push_back(p);
        return static_cast<std::uint32_t>(corners_.size() - 1);
    }

    std::size_t Polyhedron::addFace(Loop outer)
    {
        faces_.push_back(Face{{std::move(outer)}});
        return faces_.size() - 1;
    }

    void Polyhedron::addHole(std::size_t face, Loop hole)
    {
        if (face >= faces_.size())
            throw Exception("meshgap::Polyhedron::addHole", "no face " + std::to_string(face));
        faces_[face].loops.push_back(std::move(hole));
    }

    Eigen::Vector3d Polyhedron::faceNormal(std::size_t face) const
    {
        const Eigen::Vector3d n = newell(corners_, faces_.at(face).loops.at(0));
        if (n.norm() == 0.0)
            throw Exception("meshgap::Polyhedron", "face " + std::to_string(face) + " has zero area");
        return n.normalized();
    }

    std::size_t Polyhedron::addBoss(std::size_t face, const std::vector<Eigen::Vector3d> &base, double height)
    {
        const std::string where = "meshgap::Polyhedron::addBoss";
        if (face >= faces_.size())
            throw Exception(where, "no face " + std::to_string(face));
        if (base.size() < 3 || !(std::abs(height) > 0.0) || !std::isfinite(height))
            throw Exception(where, "need a base of three or more corners and a nonzero finite height");
        const Eigen::Vector3d n = faceNormal(face);
        Eigen::Vector3d u, v;
        std::tie(u, v) = planeAxes(n);
        const Eigen::Vector3d origin = corners_[faces_[face].loops[0][0]];
        auto project = [&](const Eigen::Vector3d &p) {
            return Eigen::Vector2d((p - origin).dot(u), (p - origin).dot(v));
        };
        double size = 0.0;
        for (std::uint32_t c : faces_[face].loops[0])
            size = std::max(size, (corners_[c] - origin).norm());
        Polygon2d base2;
        for (const Eigen::Vector3d &p : base)
        {
            if (std::abs((p - origin).dot(n)) > 1e-9 * std::max(1.0, size))
                throw Exception(where, "the base polygon is not on the face's plane");
            base2.push_back(project(p));
        }
        // The base must lie inside the outer loop and clear of the existing holes.
        std::vector<std::vector<Eigen::Vector2d>> loops2;
        for (const Loop &loop : faces_[face].loops)
        {
            loops2.emplace_back();
            for (std::uint32_t c : loop)
                loops2.back().push_back(project(corners_[c]));
        }
        for (const Eigen::Vector2d &p : base2)
        {
            if (!pointInPolygon(loops2[0], p))
                throw Exception(where, "the base polygon is not inside the face");
            for (std::size_t h = 1; h < loops2.size(); ++h)
                if (pointInPolygon(loops2[h], p))
                    throw Exception(where, "the base polygon overlaps a hole of the face");
        }
        for (std::size_t h = 1; h < loops2.size(); ++h)
            for (const Eigen::Vector2d &p : loops2[h])
                if (pointInPolygon(base2, p))
                    throw Exception(where, "the base polygon overlaps a hole of the face");
        // Counter-clockwise about the outward normal.
        std::vector<Eigen::Vector3d> ordered = base;
        if (polygonArea(base2) < 0.0)
            std::reverse(ordered.begin(), ordered.end());
        const std::size_t k = ordered.size();
        Loop bottom, top;
        for (const Eigen::Vector3d &p : ordered)
            bottom.push_back(addCorner(p));
        for (const Eigen::Vector3d &p : ordered)
            top.push_back(addCorner(p + height * n));
        addHole(face, Loop(bottom.rbegin(), bottom.rend()));
        for (std::size_t i = 0; i < k; ++i)
        {
            const std::size_t j = (i + 1) % k;
            addFace({bottom[i], bottom[j], top[j], top[i]});
        }
        return addFace(top);
    }

    double Polyhedron::volume() const
    {
        double v = 0.0;
        for (const Face &f : faces_)
            for (const Loop &loop : f.loops)
                for (std::size_t i = 1; i + 1 < loop.size(); ++i)
                    v += corners_[loop[0]].dot(corners_[loop[i]].cross(corners_[loop[i + 1]]));
        return v / 6.0;
    }

    void Polyhedron::reverse()
    {
        for (Face &f : faces_)
            for (Loop &loop : f.loops)
                std::reverse(loop.begin(), loop.end());
    }

    void Polyhedron::transform(const Eigen::Isometry3d &X)
    {
        for (Eigen::Vector3d &p : corners_)
            p = X * p;
    }

    void Polyhedron::check() const
    {
        const std::string where = "meshgap::Polyhedron";
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (std::size_t f = 0; f < faces_.size(); ++f)
        {
            if (faces_[f].loops.empty() || faces_[f].loops[0].size() < 3)
                throw Exception(where, "face " + std::to_string(f) + " has no outer loop of three or more corners");
            for (const Loop &loop : faces_[f].loops)
            {
                if (loop.size() < 3)
                    throw Exception(where, "face " + std::to_string(f) + " has a loop of fewer than three corners");
                for (std::size_t i = 0; i < loop.size(); ++i)
                {
                    const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
                    if (a >= corners_.size() || b >= corners_.size() || a == b)
                        throw Exception(where, "face " + std::to_string(f) + " has a bad corner index");
                    if (++uses[{a, b}] > 1)
                        throw Exception(where, "edge " + std::to_string(a) + "->" + std::to_string(b) +
                                                   " is used twice in the same direction (faces wound "
                                                   "inconsistently)");
                }
            }
        }
        for (const auto &entry : uses)
            if (uses.find({entry.first.second, entry.first.first}) == uses.end())
                throw Exception(where, "edge " + std::to_string(entry.first.first) + "->" +
                                           std::to_string(entry.first.second) +
                                           " has no face on its other side (the polyhedron is not closed)");
    }

    namespace
    {
        /** \brief The nodes subdividing each polyhedron edge, made once (from its lower-numbered corner) and shared
            by both faces of the edge, so the mesh is watertight by construction. */
        class EdgeNodes
        {
        public:
            EdgeNodes(const std::vector<Eigen::Vector3d> &corners, const SizingFunction &sizing)
              : corners_(corners), sizing_(sizing)
            {
            }

            /** \brief The inner nodes of edge a-b in order from a to b (added to \e m the first time). */
            std::vector<std::uint32_t> along(std::uint32_t a, std::uint32_t b, Mesh &m)
            {
                const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
                auto it = nodes_.find({lo, hi});
                if (it == nodes_.end())
                {
                    std::vector<std::uint32_t> ids;
                    const Eigen::Vector3d p = corners_[lo], q = corners_[hi];
                    for (double t : subdivisionParameters(p, q, sizing_))
                    {
                        ids.push_back(static_cast<std::uint32_t>(m.vertices.size()));
                        m.vertices.push_back(p + t * (q - p));
                    }
                    it = nodes_.emplace(std::make_pair(lo, hi), std::move(ids)).first;
                }
                std::vector<std::uint32_t> ids = it->second;
                if (a != lo)
                    std::reverse(ids.begin(), ids.end());
                return ids;
            }

        private:
            const std::vector<Eigen::Vector3d> &corners_;
            const SizingFunction &sizing_;
            std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> nodes_;
        };

        /** \brief Triangulate face \e f of \e p into \e m: its loops and their edge nodes in the face's plane, then
            Delaunay flips, refinement to the sizing and smoothing; new inner nodes are added to \e m. */
        void meshFace(const Polyhedron &p, std::size_t f, const SizingFunction &sizing, const std::string &name,
                      EdgeNodes &edges, Mesh &m)
        {
            const std::vector<Eigen::Vector3d> &corners = p.corners();
            const std::string where = name + " face " + std::to_string(f);
            const Polyhedron::Face &face = p.faces()[f];
            const Eigen::Vector3d n = p.faceNormal(f);
            Eigen::Vector3d uu, vv;
            std::tie(uu, vv) = planeAxes(n);
            const Eigen::Vector3d origin = corners[face.loops[0][0]];
            double size = 0.0;
            for (const Polyhedron::Loop &loop : face.loops)
                for (std::uint32_t c : loop)
                    size = std::max(size, (corners[c] - origin).norm());
            for (const Polyhedron::Loop &loop : face.loops)
                for (std::uint32_t c : loop)
                    if (std::abs((corners[c] - origin).dot(n)) > 1e-9 * size)
                        throw Exception(where, "the face is not planar");
            auto to2d = [&](const Eigen::Vector3d &q) {
                return Eigen::Vector2d((q - origin).dot(uu), (q - origin).dot(vv));
            };
            PlanarTriangulation tri(
                [&](const Eigen::Vector2d &q) { return checkedSize(sizing, origin + q.x() * uu + q.y() * vv); },
                size, where);
            std::unordered_map<std::uint32_t, int> local;
            std::vector<std::uint32_t> global;
            auto localOf = [&](std::uint32_t id) {
                auto it = local.find(id);
                if (it != local.end())
                    return it->second;
                const int l = tri.addPoint(to2d(m.vertices[id]), true);
                local.emplace(id, l);
                global.push_back(id);
                return l;
            };
            std::vector<std::vector<int>> loops;
            for (std::size_t l = 0; l < face.loops.size(); ++l)
            {
                loops.emplace_back();
                Polygon2d polygon;
                for (std::uint32_t c : face.loops[l])
                {
                    loops.back().push_back(localOf(c));
                    polygon.push_back(to2d(corners[c]));
                }
                const double area = polygonArea(polygon);
                if (l == 0 ? area <= 0.0 : area >= 0.0)
                    throw Exception(where, "a hole loop is wound the same way as the outer loop");
            }
            tri.triangulatePolygon(loops);
            for (const Polyhedron::Loop &loop : face.loops)
                for (std::size_t i = 0; i < loop.size(); ++i)
                {
                    const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
                    std::vector<int> nodes;
                    for (std::uint32_t id : edges.along(a, b, m))
                        nodes.push_back(localOf(id));
                    tri.insertOnBoundary(local.at(a), local.at(b), nodes);
                }
            tri.makeDelaunay();
            tri.refine(true);
            tri.smooth(4);
            tri.refine(true);
            tri.refine(false);  // plain bisection: guarantees the bound whatever the last flips did
            for (std::size_t q = global.size(); q < tri.points().size(); ++q)
            {
                global.push_back(static_cast<std::uint32_t>(m.vertices.size()));
                m.vertices.push_back(origin + tri.points()[q].x() * uu + tri.points()[q].y() * vv);
            }
            for (const auto &t : tri.triangles())
                m.triangles.push_back({global[t[0]], global[t[1]], global[t[2]]});
        }
    }  // namespace

    Mesh Polyhedron::mesh(const SizingFunction &sizing, const std::string &name) const
    {
        check();
        Mesh m;
        m.source = name;
        m.vertices = corners_;
        EdgeNodes edges(corners_, sizing);
        for (std::size_t f = 0; f < faces_.size(); ++f)
            meshFace(*this, f, sizing, name, edges, m);
        return m;
    }

    namespace
    {
        /** \brief Side faces between two consecutive rings of \e segments corners (a ring of one corner is a pole:
            triangles instead of quads), wound from \e a to \e b. */
        void stitchRings(Polyhedron &p, const Polyhedron::Loop &a, const Polyhedron::Loop &b, unsigned int segments)
        {
            for (unsigned int k = 0; k < segments; ++k)
            {
                const unsigned int l = (k + 1) % segments;
                if (a.size() == 1)
                    p.addFace({a[0], b[l], b[k]});
                else if (b.size() == 1)
                    p.addFace({a[k], a[l], b[0]});
                else
                    p.addFace({a[k], a[l], b[l], b[k]});
            }
        }
    }  // namespace

    Polyhedron prismPolyhedron(const Polygon2d &outer, const std::vector<Polygon2d> &holes, double height)
    {
        if (outer.size() < 3 || !(height > 0.0) || !std::isfinite(height))
            throw Exception("meshgap::prismPolyhedron", "need a polygon of three or more corners and a positive "
                                                        "height");
        Polyhedron p;
        std::vector<Polygon2d> loops{wound(outer, true)};
        for (const Polygon2d &hole : holes)
            loops.push_back(wound(hole, false));
        std::vector<Polyhedron::Loop> bottom, top;
        for (const Polygon2d &loop : loops)
        {
            bottom.emplace_back();
            top.emplace_back();
            for (const Eigen::Vector2d &q : loop)
                bottom.back().push_back(p.addCorner(Eigen::Vector3d(q.x(), q.y(), 0.0)));
            for (const Eigen::Vector2d &q : loop)
                top.back().push_back(p.addCorner(Eigen::Vector3d(q.x(), q.y(), height)));
        }
        const std::size_t b = p.addFace(Polyhedron::Loop(bottom[0].rbegin(), bottom[0].rend()));
        for (std::size_t l = 1; l < bottom.size(); ++l)
            p.addHole(b, Polyhedron::Loop(bottom[l].rbegin(), bottom[l].rend()));
        const std::size_t t = p.addFace(top[0]);
        for (std::size_t l = 1; l < top.size(); ++l)
            p.addHole(t, top[l]);
        for (std::size_t l = 0; l < bottom.size(); ++l)
            for (std::size_t i = 0; i < bottom[l].size(); ++i)
            {
                const std::size_t j = (i + 1) % bottom[l].size();
                p.addFace({bottom[l][i], bottom[l][j], top[l][j], top[l][i]});
            }
        return p;
    }

    Polyhedron revolutionPolyhedron(const std::vector<Eigen::Vector2d> &profile, unsigned int segments)
    {
        const std::string where = "meshgap::revolutionPolyhedron";
        const std::size_t n = profile.size();
        if (n < 3 || segments < 3)
            throw Exception(where, "need a profile of three or more points and three or more segments");
        if (profile.front().x() != 0.0 || profile.back().x() != 0.0)
            throw Exception(where, "the profile must start and end on the axis (r = 0)");
        for (std::size_t i = 1; i + 1 < n; ++i)
            if (!(profile[i].x() > 0.0))
                throw Exception(where, "inner profile points must have r > 0");
        for (std::size_t i = 0; i + 1 < n; ++i)
            if (profile[i] == profile[i + 1])
                throw Exception(where, "repeated profile point");
        Polyhedron p;
        // ring[i] holds one corner per segment angle, the single corner of an axis point, or nothing (an axis
        // point at a flat end, which is the centre of a disk face and no corner).
        std::vector<Polyhedron::Loop> ring(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            const double r = profile[i].x(), z = profile[i].y();
            if (r == 0.0)
            {
                // An axis point is a corner only where a cone meets it (a flat end is one disk face).
                const Eigen::Vector2d &neighbour = profile[i == 0 ? 1 : n - 2];
                if (neighbour.y() != z)
                    ring[i].push_back(p.addCorner(Eigen::Vector3d(0.0, 0.0, z)));
            }
            else
                for (unsigned int k = 0; k < segments; ++k)
                {
                    const double a = 2.0 * pi * k / segments;
                    ring[i].push_back(p.addCorner(Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z)));
                }
        }
        auto increasing = [](const Polyhedron::Loop &loop) { return loop; };
        auto decreasing = [](const Polyhedron::Loop &loop) { return Polyhedron::Loop(loop.rbegin(), loop.rend()); };
        // The face between rings i and i+1 in sector k is (i,k) (i,k+1) (i+1,k+1) (i+1,k); flat segments merge
        // their sectors into one disk or annulus with the same boundary orientation.
        for (std::size_t i = 0; i + 1 < n; ++i)
        {
            const Polyhedron::Loop &a = ring[i], &b = ring[i + 1];
            const bool flat = profile[i].y() == profile[i + 1].y();
            if (profile[i].x() == 0.0 && profile[i + 1].x() == 0.0)
                throw Exception(where, "a profile segment lies on the axis");
            if (flat && a.empty())
                p.addFace(decreasing(b));
            else if (flat && b.empty())
                p.addFace(increasing(a));
            else if (flat)
            {
                const bool aOuter = profile[i].x() > profile[i + 1].x();
                const std::size_t f = p.addFace(aOuter ? increasing(a) : decreasing(b));
                p.addHole(f, aOuter ? decreasing(b) : increasing(a));
            }
            else
                stitchRings(p, a, b, segments);
        }
        if (p.volume() < 0.0)
            p.reverse();
        return p;
    }

    namespace
    {
        /** \brief The unit tangents of a tube's \e path segments; throws (naming \e where) for a repeated point, a
            bend of 120 degrees or more, or segments too short for the bends' mitres at \e radius. */
        std::vector<Eigen::Vector3d> tubeTangents(const std::vector<Eigen::Vector3d> &path, double radius,
                                                  const std::string &where)
        {
            std::vector<Eigen::Vector3d> tangent;
            for (std::size_t j = 0; j + 1 < path.size(); ++j)
            {
                const Eigen::Vector3d d = path[j + 1] - path[j];
                if (!(d.norm() > 0.0))
                    throw Exception(where, "repeated path point");
                tangent.push_back(d.normalized());
            }
            for (std::size_t j = 1; j < tangent.size(); ++j)
            {
                if (tangent[j - 1].dot(tangent[j]) < -0.5)
                    throw Exception(where, "a bend of 120 degrees or more");
                // The mitre reaches radius * tan(bend / 2) along each segment; keep it inside both neighbours.
                const double half = 0.5 * std::acos(std::clamp(tangent[j - 1].dot(tangent[j]), -1.0, 1.0));
                const double reach = radius * std::tan(half);
                const double before = (path[j] - path[j - 1]).norm() - (j >= 2 ? reach : 0.0);
                const double after = (path[j + 1] - path[j]).norm() - (j + 2 < path.size() ? reach : 0.0);
                if (reach >= before || reach >= after)
                    throw Exception(where, "path segments too short for the bends at this radius");
            }
            return tangent;
        }
    }  // namespace

    Polyhedron tubePolyhedron(const std::vector<Eigen::Vector3d> &path, double radius, unsigned int segments,
                              unsigned int capRings)
    {
        const std::string where = "meshgap::tubePolyhedron";
        if (path.size() < 2 || segments < 3 || capRings < 1 || !(radius > 0.0) || !std::isfinite(radius))
            throw Exception(where, "need two or more path points, three or more segments, one or more cap rings "
                                   "and a positive radius");
        const std::vector<Eigen::Vector3d> tangent = tubeTangents(path, radius, where);
        Polyhedron p;
        Eigen::Vector3d u, v;
        std::tie(u, v) = planeAxes(tangent[0]);
        std::vector<double> cosines(segments), sines(segments);
        for (unsigned int k = 0; k < segments; ++k)
        {
            cosines[k] = std::cos(2.0 * pi * k / segments);
            sines[k] = std::sin(2.0 * pi * k / segments);
        }
        std::vector<Polyhedron::Loop> stations;
        auto ring = [&](const Eigen::Vector3d &centre, double r, const Eigen::Vector3d &shiftAxis,
                        const Eigen::Vector3d &planeNormal) {
            // Points of the circle (centre, r) in the plane normal to the current tangent, slid along shiftAxis
            // onto the plane through centre normal to planeNormal.
            Polyhedron::Loop loop;
            for (unsigned int k = 0; k < segments; ++k)
            {
                const Eigen::Vector3d offset = r * (cosines[k] * u + sines[k] * v);
                const double t = -offset.dot(planeNormal) / shiftAxis.dot(planeNormal);
                loop.push_back(p.addCorner(centre + offset + t * shiftAxis));
            }
            stations.push_back(loop);
        };
        auto cap = [&](const Eigen::Vector3d &end, const Eigen::Vector3d &outward, bool leaving) {
            std::vector<Polyhedron::Loop> rings;
            const std::size_t first = stations.size();
            for (unsigned int l = 1; l < capRings; ++l)
            {
                const double phi = 0.5 * pi * l / capRings;
                ring(end + radius * std::sin(phi) * outward, radius * std::cos(phi), outward, outward);
            }
            stations.push_back({p.addCorner(end + radius * outward)});
            if (!leaving)  // the start cap runs from its pole towards the tube
                std::reverse(stations.begin() + static_cast<long>(first), stations.end());
        };
        cap(path.front(), -tangent.front(), false);
        ring(path.front(), radius, tangent.front(), tangent.front());
        for (std::size_t j = 1; j + 1 < path.size(); ++j)
        {
            const Eigen::Vector3d mitre = (tangent[j - 1] + tangent[j]).normalized();
            ring(path[j], radius, tangent[j - 1], mitre);
            const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(tangent[j - 1], tangent[j]);
            u = (turn * u).normalized();
            v = tangent[j].cross(u).normalized();
        }
        ring(path.back(), radius, tangent.back(), tangent.back());
        cap(path.back(), tangent.back(), true);
        for (std::size_t i = 0; i + 1 < stations.size(); ++i)
            stitchRings(p, stations[i], stations[i + 1], segments);
        if (p.volume() < 0.0)
            p.reverse();
        return p;
    }

    Mesh makeBox(const Eigen::Vector3d &size, double h)
    {
        const double x = 0.5 * size.x(), y = 0.5 * size.y();
        Polyhedron p = prismPolyhedron({{-x, -y}, {x, -y}, {x, y}, {-x, y}}, {}, size.z());
        Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
        shift.translation().z() = -0.5 * size.z();
        p.transform(shift);
        return p.mesh(uniformSizing(h), "meshgap::makeBox");
    }

    Mesh makeExtrusion(const Polygon2d &outer, const std::vector<Polygon2d> &holes, double height, double h)
    {
        return prismPolyhedron(outer, holes, height).mesh(uniformSizing(h), "meshgap::makeExtrusion");
    }

    Mesh makeRevolution(const std::vector<Eigen::Vector2d> &profile, unsigned int segments, double h)
    {
        return revolutionPolyhedron(profile, segments).mesh(uniformSizing(h), "meshgap::makeRevolution");
    }

    Mesh makeCapsule(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double radius, unsigned int segments,
                     unsigned int capRings, double h)
    {
        return tubePolyhedron({a, b}, radius, segments, capRings).mesh(uniformSizing(h), "meshgap::makeCapsule");
    }

    Mesh makeTube(const std::vector<Eigen::Vector3d> &path, double radius, unsigned int segments,
                  unsigned int capRings, const SizingFunction &sizing)
    {
        return tubePolyhedron(path, radius, segments, capRings).mesh(sizing, "meshgap::makeTube");
    }

    Polygon2d regularPolygon(const Eigen::Vector2d &centre, double circumradius, unsigned int sides, double phase)
    {
        Polygon2d polygon;
        for (unsigned int k = 0; k < sides; ++k)
        {
            const double a = phase + 2.0 * pi * k / sides;
            polygon.push_back(centre + circumradius * Eigen::Vector2d(std::cos(a), std::sin(a)));
        }
        return polygon;
    }

    double polygonArea(const Polygon2d &polygon)
    {
        double area = 0.0;
        for (std::size_t i = 0; i < polygon.size(); ++i)
            area += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
        return 0.5 * area;
    }
}  // namespace meshgap
