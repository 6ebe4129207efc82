#include "meshgap/mesh/SurfaceGraph.h"

#include <algorithm>
#include <utility>

namespace meshgap
{
    SurfaceGraph::SurfaceGraph(const Mesh &mesh)
    {
        const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
        // Directed half-edges (both directions of every triangle edge), bucketed by their first vertex (a counting
        // sort), then each vertex's neighbours sorted and made unique.
        offsets_.assign(n + 1, 0);
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t v : t)
                offsets_[v + 1] += 2;
        for (std::uint32_t i = 0; i < n; ++i)
            offsets_[i + 1] += offsets_[i];
        neighbours_.resize(offsets_[n]);
        std::vector<std::uint32_t> fill(offsets_.begin(), offsets_.end() - 1);
        for (const Triangle &t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
            {
                const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                neighbours_[fill[a]++] = b;
                neighbours_[fill[b]++] = a;
            }
        std::uint32_t begin = 0, out = 0;
        for (std::uint32_t i = 0; i < n; ++i)
        {
            const std::uint32_t end = offsets_[i + 1];
            std::sort(neighbours_.begin() + begin, neighbours_.begin() + end);
            const auto last = std::unique(neighbours_.begin() + begin, neighbours_.begin() + end);
            out = static_cast<std::uint32_t>(
                std::move(neighbours_.begin() + begin, last, neighbours_.begin() + out) - neighbours_.begin());
            offsets_[i + 1] = out;
            begin = end;
        }
        neighbours_.resize(out);
        neighbours_.shrink_to_fit();
        lengths_.resize(out);
        for (std::uint32_t i = 0; i < n; ++i)
            for (std::uint32_t k = offsets_[i]; k < offsets_[i + 1]; ++k)
                lengths_[k] = (mesh.vertices[i] - mesh.vertices[neighbours_[k]]).norm();

        component_ = labelComponents(mesh, numComponents_);
    }
}  // namespace meshgap
