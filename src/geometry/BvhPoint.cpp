#include "meshgap/geometry/BvhPoint.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "BvhDetail.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    using bvh::threadStack;

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
            const Eigen::Vector3d d = n.local(p);
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
            // Slab test of the ray against the node's box (in the box's frame), padded against roundoff.
            const Eigen::Vector3d lo = -n.local(p);
            const Eigen::Vector3d dir = n.aligned ? d : Eigen::Vector3d(n.axes.transpose() * d);
            const Eigen::Vector3d half = n.half.array() + 1e-9 * (n.center.norm() + n.half.norm() + p.norm());
            double enter = 0.0, leave = std::numeric_limits<double>::infinity();
            bool hit = true;
            for (int k = 0; k < 3 && hit; ++k)
            {
                if (dir[k] == 0.0)
                {
                    hit = std::abs(lo[k]) <= half[k];
                    continue;
                }
                double t0 = (lo[k] - half[k]) / dir[k], t1 = (lo[k] + half[k]) / dir[k];
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
