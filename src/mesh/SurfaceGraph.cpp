#include "meshgap/mesh/SurfaceGraph.h"

#include <algorithm>
#include <utility>

namespace meshgap
{
    SurfaceGraph::SurfaceGraph(const Mesh &mesh)
    {
        const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
        // Directed half-edges (both directions of every triangle edge), sorted and made unique.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> half;
        half.reserve(mesh.triangles.size() * 6);
        for (const Triangle &t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
            {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                half.emplace_back(a, b);
                half.emplace_back(b, a);
            }
        std::sort(half.begin(), half.end());
        half.erase(std::unique(half.begin(), half.end()), half.end());

        offsets_.assign(n + 1, 0);
        for (const auto &e : half)
            ++offsets_[e.first + 1];
        for (std::uint32_t i = 0; i < n; ++i)
            offsets_[i + 1] += offsets_[i];
        neighbours_.resize(half.size());
        lengths_.resize(half.size());
        for (std::size_t k = 0; k < half.size(); ++k)
        {
            neighbours_[k] = half[k].second;
            lengths_[k] = (mesh.vertices[half[k].first] - mesh.vertices[half[k].second]).norm();
        }

        component_ = labelComponents(mesh, numComponents_);
    }
}  // namespace meshgap
