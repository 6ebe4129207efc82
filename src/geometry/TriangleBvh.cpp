#include "meshgap/geometry/TriangleBvh.h"

#include <algorithm>
#include <cmath>

#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    TriangleBvh::TriangleBvh(const Mesh &mesh) : mesh_(&mesh)
    {
        const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
        order_.resize(n);
        std::vector<Eigen::Vector3d> centroid(n);
        for (std::uint32_t t = 0; t < n; ++t)
        {
            order_[t] = t;
            const Triangle &f = mesh.triangles[t];
            centroid[t] = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
        }
        normals_.resize(n);
        for (std::uint32_t t = 0; t < n; ++t)
        {
            const Triangle &f = mesh.triangles[t];
            const Eigen::Vector3d c = (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
            const double length = c.norm();
            normals_[t] = length > 0.0 ? Eigen::Vector3d(c / length) : Eigen::Vector3d::Zero();  // zero: no bound
        }
        if (n == 0)
            return;
        nodes_.reserve(2 * n / LEAF_SIZE + 2);
        // Build top-down; each stack entry is (node index, first, count).
        struct Work
        {
            std::uint32_t node, first, count;
        };
        nodes_.push_back(Node());
        std::vector<Work> stack{{0u, 0u, n}};
        while (!stack.empty())
        {
            const Work w = stack.back();
            stack.pop_back();
            Eigen::AlignedBox3d box, centres;
            for (std::uint32_t k = w.first; k < w.first + w.count; ++k)
            {
                const Triangle &f = mesh.triangles[order_[k]];
                for (std::uint32_t v : f)
                    box.extend(mesh.vertices[v]);
                centres.extend(centroid[order_[k]]);
            }
            Node node;
            node.center = box.center();
            node.half = 0.5 * box.sizes();
            double r2 = 0.0;
            for (std::uint32_t k = w.first; k < w.first + w.count; ++k)
                for (std::uint32_t v : mesh.triangles[order_[k]])
                    r2 = std::max(r2, (mesh.vertices[v] - node.center).squaredNorm());
            // Rounding slack: bounds must never cut into the geometry they bound.
            const double slack = 1e-12 * (node.center.norm() + node.half.norm());
            node.radius = std::sqrt(r2) + slack;
            node.half.array() += slack;
            if (w.count <= LEAF_SIZE)
            {
                node.first = w.first;
                node.count = w.count;
                nodes_[w.node] = node;
                continue;
            }
            int axis;
            centres.sizes().maxCoeff(&axis);
            const std::uint32_t half = w.count / 2;
            std::nth_element(order_.begin() + w.first, order_.begin() + w.first + half,
                             order_.begin() + w.first + w.count,
                             [&](std::uint32_t i, std::uint32_t j) { return centroid[i][axis] < centroid[j][axis]; });
            const auto left = static_cast<std::uint32_t>(nodes_.size());
            nodes_.push_back(Node());
            nodes_.push_back(Node());
            node.first = left;
            node.count = 0;
            nodes_[w.node] = node;
            stack.push_back({left, w.first, half});
            stack.push_back({left + 1, w.first + half, w.count - half});
        }
    }

    namespace
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

        /** \brief Lower bound on the distance between anything in box \e a and anything in box \e b (B's frame),
            from the six face-axis gaps and the sphere gap; <= 0 means the boxes may touch. Once a partial bound
            exceeds \e enough (the caller prunes above it) that one is returned: still a lower bound, just not the
            best of the three. */
        double lowerBound(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                          double enough = std::numeric_limits<double>::infinity())
        {
            const Eigen::Vector3d T = X.R * b.center + X.t - a.center;
            double bound = T.norm() - a.radius - b.radius;
            if (bound > enough)
                return bound;
            const Eigen::Vector3d rb = X.absR * b.half;             // B's box projected on A's axes
            bound = std::max(bound, (T.cwiseAbs() - a.half - rb).maxCoeff());
            if (bound > enough)
                return bound;
            const Eigen::Vector3d s = X.R.transpose() * T;          // T on B's axes
            const Eigen::Vector3d ra = X.absR.transpose() * a.half;  // A's box projected on B's axes
            bound = std::max(bound, (s.cwiseAbs() - ra - b.half).maxCoeff());
            return bound;
        }

        /** \brief Full separating-axis test of the two oriented boxes (15 axes): true if they are disjoint. */
        bool separated(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X)
        {
            if (lowerBound(a, b, X) > 0.0)
                return true;
            const Eigen::Vector3d T = X.R * b.center + X.t - a.center;
            const Eigen::Vector3d &ea = a.half, &eb = b.half;
            for (int i = 0; i < 3; ++i)
            {
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                for (int j = 0; j < 3; ++j)
                {
                    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                    const double ra = ea[i1] * X.absR(i2, j) + ea[i2] * X.absR(i1, j);
                    const double rb = eb[j1] * X.absR(i, j2) + eb[j2] * X.absR(i, j1);
                    if (std::abs(T[i2] * X.R(i1, j) - T[i1] * X.R(i2, j)) > ra + rb)
                        return true;
                }
            }
            return false;
        }

        /** \brief Lower bound on the distance between triangles p and q from their separation along unit axis n:
            the gap between the two intervals the corners project to (0 when they overlap or n is zero). */
        double axisGap(const Eigen::Vector3d &n, const Eigen::Vector3d *p, const Eigen::Vector3d *q)
        {
            const double p0 = n.dot(p[0]), p1 = n.dot(p[1]), p2 = n.dot(p[2]);
            const double q0 = n.dot(q[0]), q1 = n.dot(q[1]), q2 = n.dot(q[2]);
            const double gap1 = std::min({q0, q1, q2}) - std::max({p0, p1, p2});
            const double gap2 = std::min({p0, p1, p2}) - std::max({q0, q1, q2});
            return std::max({gap1, gap2, 0.0});
        }

        /** \brief The largest gap (a lower bound on the distance between triangles p and q) along the nine axes
            normal to one edge of each, stopping at the first above \e enough. Cheaper than an exact triangle
            test by far, and it proves most pairs of nearby but not closest triangles apart. */
        double edgeAxesGap(const Eigen::Vector3d *p, const Eigen::Vector3d *q, double enough)
        {
            double gap = 0.0;
            for (int i = 0; i < 3; ++i)
            {
                const Eigen::Vector3d e = p[(i + 1) % 3] - p[i];
                for (int j = 0; j < 3; ++j)
                {
                    const Eigen::Vector3d n = e.cross(q[(j + 1) % 3] - q[j]);
                    const double length = n.norm();
                    if (!(length > 0.0))
                        continue;  // parallel edges: no axis
                    gap = std::max(gap, axisGap(n, p, q) / length);
                    if (gap > enough)
                        return gap;
                }
            }
            return gap;
        }

        struct PairEntry
        {
            std::uint32_t a, b;
        };

        /** \brief A traversal stack of this thread, emptied, its capacity kept from earlier calls: once warm, a query
            allocates nothing for it. Each call site has its own \e Site, so no traversal ever shares a stack with
            another one running at the same time (none of them is re-entered). */
        template <typename T, int Site>
        std::vector<T> &threadStack()
        {
            thread_local std::vector<T> stack;
            stack.clear();
            return stack;
        }

        /** \brief Split the pair on the node with the larger sphere (a leaf cannot be split). */
        bool splitA(const TriangleBvh::Node &a, const TriangleBvh::Node &b)
        {
            return !a.isLeaf() && (b.isLeaf() || a.radius >= b.radius);
        }
    }  // namespace

    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA, std::uint32_t seedB)
    {
        result = BvhDistanceResult();
        result.distance = upperBound;
        if (a.nodes().empty() || b.nodes().empty())
            return;
        const RelativePose X(X_AB);
        // Distances within this slack of each other are ties, broken by the smaller triangle pair (see the header).
        const TriangleBvh::Node &rootA = a.nodes()[0], &rootB = b.nodes()[0];
        const double slack = 1e-12 * (rootA.center.norm() + rootA.radius + rootB.center.norm() + rootB.radius +
                                      X.t.norm());
        std::uint32_t bestA = seedA, bestB = seedB;  // UINT32_MAX: no pair yet (any real pair ranks before it)
        const Mesh &ma = a.mesh(), &mb = b.mesh();
        std::vector<PairEntry> &stack = threadStack<PairEntry, 1>();
        std::vector<double> &bounds = threadStack<double, 2>();
        stack.push_back({0u, 0u});
        bounds.push_back(lowerBound(a.nodes()[0], b.nodes()[0], X));
        ++result.boxTests;
        Eigen::Vector3d pb[3], onA, onB;
        while (!stack.empty())
        {
            const PairEntry e = stack.back();
            const double bound = bounds.back();
            stack.pop_back();
            bounds.pop_back();
            if (bound > result.distance + slack)
                continue;  // nothing in this pair can beat or tie the best so far
            const TriangleBvh::Node &na = a.nodes()[e.a], &nb = b.nodes()[e.b];
            if (na.isLeaf() && nb.isLeaf())
            {
                for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
                {
                    const std::uint32_t tb = b.order()[j];
                    for (int k = 0; k < 3; ++k)
                        pb[k] = X.R * mb.vertices[mb.triangles[tb][k]] + X.t;
                    const Eigen::Vector3d normalB = X.R * b.normals()[tb];
                    for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
                    {
                        const std::uint32_t ta = a.order()[i];
                        const Triangle &fa = ma.triangles[ta];
                        const Eigen::Vector3d pa[3] = {ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]]};
                        // Cheap exact bound first: separation along either triangle's normal. The slack keeps
                        // rounding from pruning a pair at exactly the best distance's value.
                        const double enough = result.distance + slack;
                        double gap = std::max(axisGap(a.normals()[ta], pa, pb), axisGap(normalB, pa, pb));
                        if (!(gap > enough))
                            gap = edgeAxesGap(pa, pb, enough);
                        if (gap > enough)
                            continue;
                        ++result.triangleTests;
                        const double d = triangleDistance(ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]],
                                                          pb[0], pb[1], pb[2], onA, onB);
                        const bool closer = d < result.distance - slack;
                        const bool tieWins = !closer && d <= result.distance + slack &&
                                             (ta < bestA || (ta == bestA && tb < bestB));
                        if (closer || tieWins)
                        {
                            bestA = ta;
                            bestB = tb;
                            result.distance = d;
                            result.found = true;
                            result.triangleA = ta;
                            result.triangleB = tb;
                            result.onA = onA;
                            result.onB = onB;
                            if (d <= stopBelow)
                                return;
                        }
                    }
                }
                continue;
            }
            // Descend; push the farther child first so the nearer one is explored first.
            PairEntry c1, c2;
            if (splitA(na, nb))
            {
                c1 = {na.first, e.b};
                c2 = {na.first + 1, e.b};
            }
            else
            {
                c1 = {e.a, nb.first};
                c2 = {e.a, nb.first + 1};
            }
            // A child above the best so far is pruned whatever its exact bound: stop computing it there.
            double b1 = lowerBound(a.nodes()[c1.a], b.nodes()[c1.b], X, result.distance + slack);
            double b2 = lowerBound(a.nodes()[c2.a], b.nodes()[c2.b], X, result.distance + slack);
            result.boxTests += 2;
            if (b1 < b2)
            {
                std::swap(c1, c2);
                std::swap(b1, b2);
            }
            if (b1 <= result.distance + slack)
            {
                stack.push_back(c1);
                bounds.push_back(b1);
            }
            if (b2 <= result.distance + slack)
            {
                stack.push_back(c2);
                bounds.push_back(b2);
            }
        }
    }

    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, std::uint32_t *hitA,
                    std::uint32_t *hitB)
    {
        if (a.nodes().empty() || b.nodes().empty())
            return false;
        const RelativePose X(X_AB);
        const Mesh &ma = a.mesh(), &mb = b.mesh();
        std::vector<PairEntry> &stack = threadStack<PairEntry, 3>();
        stack.push_back({0u, 0u});
        Eigen::Vector3d pb[3];
        while (!stack.empty())
        {
            const PairEntry e = stack.back();
            stack.pop_back();
            const TriangleBvh::Node &na = a.nodes()[e.a], &nb = b.nodes()[e.b];
            if (separated(na, nb, X))
                continue;
            if (na.isLeaf() && nb.isLeaf())
            {
                for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
                {
                    const std::uint32_t tb = b.order()[j];
                    for (int k = 0; k < 3; ++k)
                        pb[k] = X.R * mb.vertices[mb.triangles[tb][k]] + X.t;
                    for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
                    {
                        const Triangle &fa = ma.triangles[a.order()[i]];
                        if (trianglesIntersect(ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]], pb[0],
                                               pb[1], pb[2]))
                        {
                            if (hitA)
                                *hitA = a.order()[i];
                            if (hitB)
                                *hitB = tb;
                            return true;
                        }
                    }
                }
                continue;
            }
            if (splitA(na, nb))
            {
                stack.push_back({na.first, e.b});
                stack.push_back({na.first + 1, e.b});
            }
            else
            {
                stack.push_back({e.a, nb.first});
                stack.push_back({e.a, nb.first + 1});
            }
        }
        return false;
    }
    void bvhPointDistance(const TriangleBvh &tree, const Eigen::Vector3d &p, double upperBound, double stopBelow,
                          BvhPointResult &result)
    {
        result = BvhPointResult();
        result.distance = upperBound;
        if (tree.nodes().empty())
            return;
        const Mesh &m = tree.mesh();
        // Lower bound on the distance from p to anything in a node: the box distance, or the sphere's.
        auto bound = [&p](const TriangleBvh::Node &n)
        {
            const Eigen::Vector3d d = p - n.center;
            return std::max((d.cwiseAbs() - n.half).cwiseMax(0.0).norm(), d.norm() - n.radius);
        };
        struct Entry
        {
            std::uint32_t node;
            double bound;
        };
        // Depth first, the nearer child first (measured faster here than a best-first heap).
        std::vector<Entry> &stack = threadStack<Entry, 4>();
        stack.push_back({0u, bound(tree.nodes()[0])});
        Eigen::Vector3d on;
        while (!stack.empty())
        {
            const Entry e = stack.back();
            stack.pop_back();
            if (e.bound >= result.distance)
                continue;
            const TriangleBvh::Node &n = tree.nodes()[e.node];
            if (n.isLeaf())
            {
                for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
                {
                    const std::uint32_t t = tree.order()[k];
                    const Triangle &f = m.triangles[t];
                    ++result.triangleTests;
                    const double d = pointTriangleDistance(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], on);
                    if (d < result.distance)
                    {
                        result.distance = d;
                        result.found = true;
                        result.triangle = t;
                        result.closest = on;
                        if (d <= stopBelow)
                            return;
                    }
                }
                continue;
            }
            Entry near{n.first, bound(tree.nodes()[n.first])}, far{n.first + 1, bound(tree.nodes()[n.first + 1])};
            if (far.bound < near.bound)
                std::swap(near, far);
            if (far.bound < result.distance)
                stack.push_back(far);
            if (near.bound < result.distance)
                stack.push_back(near);
        }
    }

    bool bvhRayWinding(const TriangleBvh &tree, const Eigen::Vector3d &p, const Eigen::Vector3d &direction,
                       int &winding)
    {
        winding = 0;
        if (tree.nodes().empty())
            return true;
        const Eigen::Vector3d d = direction.normalized();
        const Mesh &m = tree.mesh();
        // Signs closer to zero than this (relative to the magnitudes multiplied) are not trusted: roundoff in a
        // triple product is a few 1e-16 of them, so 1e-10 leaves a wide margin.
        constexpr double eps = 1e-10;
        std::vector<std::uint32_t> &stack = threadStack<std::uint32_t, 5>();
        stack.push_back(0u);
        while (!stack.empty())
        {
            const TriangleBvh::Node &n = tree.nodes()[stack.back()];
            stack.pop_back();
            // Slab test of the ray against the node's box, padded against roundoff.
            const Eigen::Vector3d lo = n.center - p;
            const Eigen::Vector3d half = n.half.array() + 1e-9 * (n.center.norm() + n.half.norm() + p.norm());
            double enter = 0.0, leave = std::numeric_limits<double>::infinity();
            bool hit = true;
            for (int k = 0; k < 3 && hit; ++k)
            {
                if (d[k] == 0.0)
                {
                    hit = std::abs(lo[k]) <= half[k];
                    continue;
                }
                double t0 = (lo[k] - half[k]) / d[k], t1 = (lo[k] + half[k]) / d[k];
                if (t0 > t1)
                    std::swap(t0, t1);
                enter = std::max(enter, t0);
                leave = std::min(leave, t1);
                hit = enter <= leave;
            }
            if (!hit)
                continue;
            if (!n.isLeaf())
            {
                stack.push_back(n.first);
                stack.push_back(n.first + 1);
                continue;
            }
            for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
            {
                const Triangle &f = m.triangles[tree.order()[k]];
                const Eigen::Vector3d a = m.vertices[f[0]] - p, b = m.vertices[f[1]] - p, c = m.vertices[f[2]] - p;
                // The line p + s d passes the triangle's inside iff these three signed volumes share a sign.
                const double la = a.norm(), lb = b.norm(), lc = c.norm();
                const double u = d.dot(b.cross(c)), v = d.dot(c.cross(a)), w = d.dot(a.cross(b));
                const double tu = eps * lb * lc, tv = eps * lc * la, tw = eps * la * lb;
                const bool allPositive = u > tu && v > tv && w > tw, allNegative = u < -tu && v < -tv && w < -tw;
                if (!allPositive && !allNegative)
                {
                    const bool missed = (u > tu || v > tv || w > tw) && (u < -tu || v < -tv || w < -tw);
                    const bool behind = a.dot(d) < 0.0 && b.dot(d) < 0.0 && c.dot(d) < 0.0;
                    if (missed || behind)
                        continue;
                    return false;  // the line grazes an edge or a corner in front of p: not robust
                }
                // It crosses the plane at s = det(a, b, c) / (u + v + w): in front of p when s > 0.
                const double det = a.dot(b.cross(c));
                if (std::abs(det) <= eps * la * lb * lc)
                    return false;  // p lies on the triangle (to roundoff)
                if ((det > 0.0) == allPositive)
                    winding += allPositive ? 1 : -1;  // d . normal = u + v + w: leaving through the front is +1
            }
        }
        return true;
    }
}  // namespace meshgap
