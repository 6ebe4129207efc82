#include "meshgap/mesh/Refine.h"

#include <cmath>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

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
    }  // namespace

    Mesh refineMesh(const Mesh &input, double h, RefineReport *report, std::vector<std::uint32_t> *parentOut)
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
        if (h > 0.0 && std::isfinite(h))
        {
            // Edge -> triangles that use it; a max-heap of edges longer than h (entries may be stale).
            std::unordered_map<EdgeKey, std::vector<std::uint32_t>> edgeTriangles;
            edgeTriangles.reserve(mesh.triangles.size() * 2);
            std::priority_queue<std::pair<double, EdgeKey>> longest;
            auto length = [&mesh](std::uint32_t a, std::uint32_t b) {
                return (mesh.vertices[a] - mesh.vertices[b]).norm();
            };
            auto addEdge = [&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
                auto &list = edgeTriangles[key(a, b)];
                if (list.empty())
                {
                    const double len = length(a, b);
                    if (len > h)
                        longest.emplace(len, key(a, b));
                }
                list.push_back(t);
            };
            auto removeFromEdge = [&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
                auto &list = edgeTriangles[key(a, b)];
                for (std::size_t i = 0; i < list.size(); ++i)
                    if (list[i] == t)
                    {
                        list[i] = list.back();
                        list.pop_back();
                        break;
                    }
            };
            for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
                for (int k = 0; k < 3; ++k)
                    addEdge(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3], t);

            while (!longest.empty())
            {
                const EdgeKey e = longest.top().second;
                longest.pop();
                auto found = edgeTriangles.find(e);
                if (found == edgeTriangles.end() || found->second.empty())
                    continue;  // already split
                const std::vector<std::uint32_t> incident = std::move(found->second);
                edgeTriangles.erase(found);
                const auto a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e & 0xffffffffu);
                const auto m = static_cast<std::uint32_t>(mesh.vertices.size());
                mesh.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
                for (std::uint32_t t : incident)
                {
                    // Rotate so that the split edge is (p, q) in the triangle's own winding: (p, q, r).
                    const Triangle tri = mesh.triangles[t];
                    int k = 0;
                    while (!((tri[k] == a || tri[k] == b) && (tri[(k + 1) % 3] == a || tri[(k + 1) % 3] == b)))
                        ++k;
                    const std::uint32_t p = tri[k], q = tri[(k + 1) % 3], r = tri[(k + 2) % 3];
                    const auto u = static_cast<std::uint32_t>(mesh.triangles.size());
                    mesh.triangles[t] = {p, m, r};
                    mesh.triangles.push_back({m, q, r});
                    parent.push_back(parent[t]);
                    removeFromEdge(q, r, t);
                    addEdge(q, r, u);
                    addEdge(p, m, t);
                    addEdge(m, q, u);
                    addEdge(m, r, t);
                    addEdge(m, r, u);
                }
            }
        }
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
}  // namespace meshgap
