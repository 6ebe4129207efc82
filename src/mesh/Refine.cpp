#include "meshgap/mesh/Refine.h"

#include <boost/container/small_vector.hpp>
#include <cmath>
#include <queue>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        using EdgeKey = std::uint64_t;
        EdgeKey key(std::uint32_t a, std::uint32_t b)
        {
            if (a > b)
                std::swap(a, b);
            return (EdgeKey(a) << 32) | b;
        }

        /** \brief The triangles on an edge: two on a closed manifold surface, held without an allocation. */
        using Incident = boost::container::small_vector<std::uint32_t, 2>;

        /** \brief Longest-edge bisection of \e mesh while some edge ab is longer than (size[a] + size[b]) / 2;
            \e size grows with the mesh (a midpoint gets its edge's mean). */
        class Bisection
        {
        public:
            Bisection(Mesh &mesh, std::vector<double> &size, std::vector<std::uint32_t> &parent)
                : mesh_(mesh), size_(size), parent_(parent)
            {
                edgeTriangles_.reserve(mesh.triangles.size() * 2);
                for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
                    for (int k = 0; k < 3; ++k)
                        addEdge(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3], t);
            }

            void run()
            {
                while (!longest_.empty())
                {
                    const auto [len, e] = longest_.top();
                    longest_.pop();
                    auto found = edgeTriangles_.find(e);
                    if (found == edgeTriangles_.end() || found->second.empty())
                        continue;  // already split
                    if (deferForLonger(found->second, len))
                    {
                        longest_.emplace(len, e);
                        continue;
                    }
                    forced_.erase(e);
                    const Incident incident = std::move(found->second);
                    edgeTriangles_.erase(found);
                    split(static_cast<std::uint32_t>(e >> 32), static_cast<std::uint32_t>(e & 0xffffffffu), incident);
                }
            }

        private:
            double length(std::uint32_t a, std::uint32_t b) const
            {
                return (mesh_.vertices[a] - mesh_.vertices[b]).norm();
            }

            void addEdge(std::uint32_t a, std::uint32_t b, std::uint32_t t)
            {
                auto &list = edgeTriangles_[key(a, b)];
                if (list.empty() && length(a, b) > 0.5 * (size_[a] + size_[b]))
                    longest_.emplace(length(a, b), key(a, b));
                list.push_back(t);
            }

            void removeFromEdge(std::uint32_t a, std::uint32_t b, std::uint32_t t)
            {
                auto &list = edgeTriangles_[key(a, b)];
                for (std::size_t i = 0; i < list.size(); ++i)
                    if (list[i] == t)
                    {
                        list[i] = list.back();
                        list.pop_back();
                        break;
                    }
            }

            /** \brief Rivara: a longer edge of a triangle sharing the edge (of length \e len) goes first (then the
                edge comes back); true if there is one. */
            bool deferForLonger(const Incident &triangles, double len)
            {
                bool deferred = false;
                for (std::uint32_t t : triangles)
                    for (int k = 0; k < 3; ++k)
                    {
                        const std::uint32_t p = mesh_.triangles[t][k], q = mesh_.triangles[t][(k + 1) % 3];
                        const double l = length(p, q);
                        if (l > len && forced_.insert(key(p, q)).second)
                        {
                            longest_.emplace(l, key(p, q));
                            deferred = true;
                        }
                        else if (l > len)
                            deferred = true;  // already queued, and longer, so it is popped before this edge again
                    }
                return deferred;
            }

            /** \brief Split edge ab at its midpoint m: each incident triangle (p, q, r) becomes (p, m, r) and a new
                (m, q, r). */
            void split(std::uint32_t a, std::uint32_t b, const Incident &incident)
            {
                const auto m = static_cast<std::uint32_t>(mesh_.vertices.size());
                mesh_.vertices.push_back(0.5 * (mesh_.vertices[a] + mesh_.vertices[b]));
                size_.push_back(0.5 * (size_[a] + size_[b]));
                for (std::uint32_t t : incident)
                {
                    // Rotate so that the split edge is (p, q) in the triangle's own winding: (p, q, r).
                    const Triangle tri = mesh_.triangles[t];
                    int k = 0;
                    while (!((tri[k] == a || tri[k] == b) && (tri[(k + 1) % 3] == a || tri[(k + 1) % 3] == b)))
                        ++k;
                    const std::uint32_t p = tri[k], q = tri[(k + 1) % 3], r = tri[(k + 2) % 3];
                    const auto u = static_cast<std::uint32_t>(mesh_.triangles.size());
                    mesh_.triangles[t] = {p, m, r};
                    mesh_.triangles.push_back({m, q, r});
                    parent_.push_back(parent_[t]);
                    removeFromEdge(q, r, t);
                    addEdge(q, r, u);
                    addEdge(p, m, t);
                    addEdge(m, q, u);
                    addEdge(m, r, t);
                    addEdge(m, r, u);
                }
            }

            Mesh &mesh_;
            std::vector<double> &size_;
            std::vector<std::uint32_t> &parent_;
            /** \brief Edge -> triangles that use it; a max-heap of edges to split (entries may be stale). */
            std::unordered_map<EdgeKey, Incident> edgeTriangles_;
            std::priority_queue<std::pair<double, EdgeKey>> longest_;
            std::unordered_set<EdgeKey> forced_;  ///< not over their size, but longest in a triangle of one that is
        };

        /** \brief Whether some edge ab of \e mesh is longer than (size[a] + size[b]) / 2 (else there is nothing to
            split, and the bisection's edge map need not be built). */
        bool anyEdgeOver(const Mesh &mesh, const std::vector<double> &size)
        {
            for (const Triangle &t : mesh.triangles)
                for (int k = 0; k < 3; ++k)
                {
                    const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                    if ((mesh.vertices[a] - mesh.vertices[b]).norm() > 0.5 * (size[a] + size[b]))
                        return true;
                }
            return false;
        }

        Mesh refine(const Mesh &input, std::vector<double> size, RefineReport *report,
                    std::vector<std::uint32_t> *parentOut)
        {
            Mesh mesh = input;
            std::vector<std::uint32_t> parent(mesh.triangles.size());
            for (std::uint32_t t = 0; t < parent.size(); ++t)
                parent[t] = t;
            if (report)
            {
                report->nodesBefore = input.vertices.size();
                report->trianglesBefore = input.triangles.size();
            }
            if (!size.empty() && anyEdgeOver(mesh, size))
                Bisection(mesh, size, parent).run();
            if (parentOut)
                parentOut->swap(parent);
            if (report)
            {
                report->nodesAfter = mesh.vertices.size();
                report->trianglesAfter = mesh.triangles.size();
                report->longestEdge = longestEdge(mesh);
            }
            return mesh;
        }
    }  // namespace

    Mesh refineMesh(const Mesh &input, double h, RefineReport *report, std::vector<std::uint32_t> *parentOut)
    {
        std::vector<double> size;
        if (h > 0.0 && std::isfinite(h))
            size.assign(input.vertices.size(), h);
        return refine(input, std::move(size), report, parentOut);
    }

    Mesh refineMesh(const Mesh &input, const std::vector<double> &vertexSize, RefineReport *report,
                    std::vector<std::uint32_t> *parentOut)
    {
        if (vertexSize.size() != input.vertices.size())
            throw Exception("refineMesh", std::to_string(vertexSize.size()) + " sizes for the " +
                                              std::to_string(input.vertices.size()) + " vertices of " + input.source);
        for (std::size_t v = 0; v < vertexSize.size(); ++v)
            if (!(vertexSize[v] > 0.0) || !std::isfinite(vertexSize[v]))
                throw Exception("refineMesh", "size " + std::to_string(vertexSize[v]) + " at vertex " +
                                                  std::to_string(v) + " of " + input.source +
                                                  " is not positive and finite");
        return refine(input, vertexSize, report, parentOut);
    }
}  // namespace meshgap
