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

        /** \brief Per vertex of a mesh, the distance to the nearest triangle that faces against one of the vertex's
            own triangles: a BVH over the triangles with a box of unit normals per tree node. */
        class OpposingSearch
        {
        public:
            explicit OpposingSearch(const Mesh &mesh)
                : mesh_(mesh), bvh_(mesh), nodes_(bvh_.nodes()), order_(bvh_.order())
            {
                computeNormals();
                boxes_.resize(nodes_.size());
                buildBox(0);
                incident_.resize(mesh.vertices.size());
                for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
                    if (valid_[t])
                        for (std::uint32_t v : mesh.triangles[t])
                            incident_[v].push_back(t);
            }

            /** \brief The distance from vertex \e v to the nearest opposing triangle (infinity if none, or if \e v
                has no valid triangle). */
            double nearest(std::size_t v)
            {
                double best = std::numeric_limits<double>::infinity();
                if (incident_[v].empty())
                    return best;
                own_.clear();
                for (std::uint32_t t : incident_[v])
                    own_.push_back(normal_[t]);
                const Eigen::Vector3d &p = mesh_.vertices[v];
                queue_ = {};
                if (faces(boxes_[0]))
                    queue_.emplace(pointBoxDistance(p, nodes_[0]), 0u);
                while (!queue_.empty())
                {
                    const auto [bound, i] = queue_.top();
                    queue_.pop();
                    if (bound >= best)
                        break;
                    const TriangleBvh::Node &node = nodes_[i];
                    if (node.isLeaf())
                    {
                        best = std::min(best, nearestInLeaf(p, node));
                        continue;
                    }
                    for (std::uint32_t c : {node.first, node.first + 1})
                        if (faces(boxes_[c]))
                        {
                            const double d = pointBoxDistance(p, nodes_[c]);
                            if (d < best)
                                queue_.emplace(d, c);
                        }
                }
                return best;
            }

        private:
            /** \brief Unit normals, zero for degenerate triangles (those are skipped). */
            void computeNormals()
            {
                normal_.resize(mesh_.triangles.size());
                valid_.assign(mesh_.triangles.size(), 0);
                for (std::size_t t = 0; t < mesh_.triangles.size(); ++t)
                {
                    const Triangle &f = mesh_.triangles[t];
                    const Eigen::Vector3d n = (mesh_.vertices[f[1]] - mesh_.vertices[f[0]])
                                                  .cross(mesh_.vertices[f[2]] - mesh_.vertices[f[0]]);
                    const double len = n.norm();
                    if (len > 0.0 && std::isfinite(len))
                    {
                        normal_[t] = n / len;
                        valid_[t] = 1;
                    }
                    else
                        normal_[t].setZero();
                }
            }

            /** \brief Normal boxes bottom-up (post-order over the tree, children first + 0 and first + 1). */
            void buildBox(std::uint32_t i)
            {
                const TriangleBvh::Node &node = nodes_[i];
                NormalBox &box = boxes_[i];
                if (node.isLeaf())
                {
                    for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                        if (valid_[order_[k]])
                        {
                            box.lo = box.lo.cwiseMin(normal_[order_[k]]);
                            box.hi = box.hi.cwiseMax(normal_[order_[k]]);
                        }
                    return;
                }
                buildBox(node.first);
                buildBox(node.first + 1);
                box.lo = boxes_[node.first].lo.cwiseMin(boxes_[node.first + 1].lo);
                box.hi = boxes_[node.first].hi.cwiseMax(boxes_[node.first + 1].hi);
            }

            bool faces(const NormalBox &box) const
            {
                for (const Eigen::Vector3d &m : own_)
                    if (box.minDot(m) < OPPOSING_COS)
                        return true;
                return false;
            }

            double nearestInLeaf(const Eigen::Vector3d &p, const TriangleBvh::Node &node) const
            {
                double best = std::numeric_limits<double>::infinity();
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                {
                    const std::uint32_t t = order_[k];
                    if (!valid_[t])
                        continue;
                    bool opposing = false;
                    for (const Eigen::Vector3d &m : own_)
                        opposing = opposing || normal_[t].dot(m) < OPPOSING_COS;
                    if (!opposing)
                        continue;
                    const Triangle &f = mesh_.triangles[t];
                    Eigen::Vector3d on;
                    best = std::min(best, pointTriangleDistance(p, mesh_.vertices[f[0]], mesh_.vertices[f[1]],
                                                                mesh_.vertices[f[2]], on));
                }
                return best;
            }

            using Entry = std::pair<double, std::uint32_t>;  // (lower bound, tree node), nearest first
            const Mesh &mesh_;
            const TriangleBvh bvh_;
            const std::vector<TriangleBvh::Node> &nodes_;
            const std::vector<std::uint32_t> &order_;
            std::vector<Eigen::Vector3d> normal_;
            std::vector<char> valid_;
            std::vector<NormalBox> boxes_;
            std::vector<std::vector<std::uint32_t>> incident_;  ///< valid triangles per vertex
            std::vector<Eigen::Vector3d> own_;                  ///< the current vertex's triangle normals
            std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue_;
        };
    }  // namespace

    std::vector<double> localFeatureSizes(const Mesh &mesh)
    {
        std::vector<double> lfs(mesh.vertices.size(), std::numeric_limits<double>::infinity());
        if (mesh.triangles.empty())
            return lfs;
        OpposingSearch search(mesh);
        for (std::size_t v = 0; v < lfs.size(); ++v)
            lfs[v] = search.nearest(v);
        return lfs;
    }

    void checkAdaptiveSizing(const AdaptiveSizing &rule, const std::string &source)
    {
        auto positive = [&](double x, const char *name) {
            if (!(x > 0.0) || !std::isfinite(x))
                throw Exception("AdaptiveSizing", std::string(name) + " must be positive and finite, not " +
                                                      std::to_string(x) + " (" + source + ")");
        };
        positive(rule.featureFraction, "featureFraction");
        positive(rule.minFraction, "minFraction");
        positive(rule.maxFraction, "maxFraction");
        if (!(rule.grading >= 0.0) || !std::isfinite(rule.grading))
            throw Exception("AdaptiveSizing", "grading must be >= 0 and finite, not " + std::to_string(rule.grading) +
                                                  " (" + source + ")");
        if (rule.minFraction > rule.maxFraction)
            throw Exception("AdaptiveSizing", "minFraction " + std::to_string(rule.minFraction) +
                                                  " is above maxFraction " + std::to_string(rule.maxFraction));
    }

    std::vector<double> adaptiveNodeSizes(const Mesh &mesh, const AdaptiveSizing &rule)
    {
        checkAdaptiveSizing(rule, mesh.source);
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
