#include "meshgap/geometry/NodeSizing.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "meshgap/Exception.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        /** \brief Two unit normals "face opposite ways" when their dot product is below this (120 degrees). */
        constexpr double OPPOSING_COS = -0.5;

        /** \brief Per tree node, the box of its triangles' unit normals: a lower bound of n_T . m over the node is
            sum_k min(lo_k m_k, hi_k m_k), which prunes whole subtrees that cannot face against m. */
        struct NormalBox
        {
            Eigen::Vector3d lo{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())};
            Eigen::Vector3d hi{Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
            double minDot(const Eigen::Vector3d &m) const
            {
                double s = 0.0;
                for (int k = 0; k < 3; ++k)
                    s += std::min(lo[k] * m[k], hi[k] * m[k]);
                return s;
            }
        };

        double pointBoxDistance(const Eigen::Vector3d &p, const TriangleBvh::Node &node)
        {
            const Eigen::Vector3d d = ((p - node.center).cwiseAbs() - node.half).cwiseMax(0.0);
            return d.norm();
        }
    }  // namespace

    std::vector<double> localFeatureSizes(const Mesh &mesh)
    {
        const std::size_t nv = mesh.vertices.size();
        std::vector<double> lfs(nv, std::numeric_limits<double>::infinity());
        if (mesh.triangles.empty())
            return lfs;
        const TriangleBvh bvh(mesh);
        const auto &nodes = bvh.nodes();
        const auto &order = bvh.order();
        // Unit normals, zero for degenerate triangles (those are skipped).
        std::vector<Eigen::Vector3d> normal(mesh.triangles.size());
        std::vector<char> valid(mesh.triangles.size(), 0);
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        {
            const Triangle &f = mesh.triangles[t];
            const Eigen::Vector3d n =
                (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
            const double len = n.norm();
            if (len > 0.0 && std::isfinite(len))
            {
                normal[t] = n / len;
                valid[t] = 1;
            }
            else
                normal[t].setZero();
        }
        // Normal boxes bottom-up (post-order over the tree, children first + 0 and first + 1).
        std::vector<NormalBox> boxes(nodes.size());
        std::function<void(std::uint32_t)> build = [&](std::uint32_t i) {
            const TriangleBvh::Node &node = nodes[i];
            NormalBox &box = boxes[i];
            if (node.isLeaf())
            {
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                    if (valid[order[k]])
                    {
                        box.lo = box.lo.cwiseMin(normal[order[k]]);
                        box.hi = box.hi.cwiseMax(normal[order[k]]);
                    }
                return;
            }
            build(node.first);
            build(node.first + 1);
            box.lo = boxes[node.first].lo.cwiseMin(boxes[node.first + 1].lo);
            box.hi = boxes[node.first].hi.cwiseMax(boxes[node.first + 1].hi);
        };
        build(0);

        // Incident triangle normals per vertex.
        std::vector<std::vector<std::uint32_t>> incident(nv);
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
            if (valid[t])
                for (std::uint32_t v : mesh.triangles[t])
                    incident[v].push_back(t);

        using Entry = std::pair<double, std::uint32_t>;  // (lower bound, tree node), nearest first
        std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
        std::vector<Eigen::Vector3d> own;
        for (std::size_t v = 0; v < nv; ++v)
        {
            if (incident[v].empty())
                continue;
            own.clear();
            for (std::uint32_t t : incident[v])
                own.push_back(normal[t]);
            auto faces = [&](const NormalBox &box) {
                for (const Eigen::Vector3d &m : own)
                    if (box.minDot(m) < OPPOSING_COS)
                        return true;
                return false;
            };
            const Eigen::Vector3d &p = mesh.vertices[v];
            double best = std::numeric_limits<double>::infinity();
            queue = {};
            if (faces(boxes[0]))
                queue.emplace(pointBoxDistance(p, nodes[0]), 0u);
            while (!queue.empty())
            {
                const auto [bound, i] = queue.top();
                queue.pop();
                if (bound >= best)
                    break;
                const TriangleBvh::Node &node = nodes[i];
                if (node.isLeaf())
                {
                    for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                    {
                        const std::uint32_t t = order[k];
                        if (!valid[t])
                            continue;
                        bool opposing = false;
                        for (const Eigen::Vector3d &m : own)
                            opposing = opposing || normal[t].dot(m) < OPPOSING_COS;
                        if (!opposing)
                            continue;
                        const Triangle &f = mesh.triangles[t];
                        Eigen::Vector3d on;
                        best = std::min(best, pointTriangleDistance(p, mesh.vertices[f[0]], mesh.vertices[f[1]],
                                                                    mesh.vertices[f[2]], on));
                    }
                    continue;
                }
                for (std::uint32_t c : {node.first, node.first + 1})
                    if (faces(boxes[c]))
                    {
                        const double d = pointBoxDistance(p, nodes[c]);
                        if (d < best)
                            queue.emplace(d, c);
                    }
            }
            lfs[v] = best;
        }
        return lfs;
    }

    std::vector<double> adaptiveNodeSizes(const Mesh &mesh, const AdaptiveSizing &rule)
    {
        auto positive = [&](double x, const char *name) {
            if (!(x > 0.0) || !std::isfinite(x))
                throw Exception("AdaptiveSizing", std::string(name) + " must be positive and finite, not " +
                                                      std::to_string(x) + " (" + mesh.source + ")");
        };
        positive(rule.featureFraction, "featureFraction");
        positive(rule.minFraction, "minFraction");
        positive(rule.maxFraction, "maxFraction");
        if (!(rule.grading >= 0.0) || !std::isfinite(rule.grading))
            throw Exception("AdaptiveSizing", "grading must be >= 0 and finite, not " + std::to_string(rule.grading) +
                                                  " (" + mesh.source + ")");
        if (rule.minFraction > rule.maxFraction)
            throw Exception("AdaptiveSizing", "minFraction " + std::to_string(rule.minFraction) +
                                                  " is above maxFraction " + std::to_string(rule.maxFraction));
        const double size = mesh.size();
        const double hMin = rule.minFraction * size, hMax = rule.maxFraction * size;
        const std::vector<double> lfs = localFeatureSizes(mesh);
        std::vector<double> h(mesh.vertices.size());
        for (std::size_t v = 0; v < h.size(); ++v)
            h[v] = std::clamp(rule.featureFraction * lfs[v], hMin, hMax);  // clamp(inf) = hMax
        if (rule.grading == 0.0 || h.empty())
            return h;
        // Multi-source Dijkstra: every vertex starts at its own h0; an edge of length l adds grading * l.
        std::vector<std::vector<std::pair<std::uint32_t, double>>> adjacent(h.size());
        for (const Triangle &f : mesh.triangles)
            for (int k = 0; k < 3; ++k)
            {
                const std::uint32_t a = f[k], b = f[(k + 1) % 3];
                const double l = (mesh.vertices[a] - mesh.vertices[b]).norm();
                adjacent[a].emplace_back(b, l);
                adjacent[b].emplace_back(a, l);
            }
        using Entry = std::pair<double, std::uint32_t>;
        std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
        for (std::uint32_t v = 0; v < h.size(); ++v)
            queue.emplace(h[v], v);
        while (!queue.empty())
        {
            const auto [hv, v] = queue.top();
            queue.pop();
            if (hv > h[v])
                continue;
            for (const auto &[u, l] : adjacent[v])
            {
                const double candidate = hv + rule.grading * l;
                if (candidate < h[u])
                {
                    h[u] = candidate;
                    queue.emplace(candidate, u);
                }
            }
        }
        return h;
    }
}  // namespace meshgap
