#include "meshgap/geometry/Body.h"

#include <algorithm>
#include <cmath>
#include <ompl/util/Console.h>

namespace meshgap
{
    BodyPtr Body::build(Mesh mesh, const BodyOptions &options)
    {
        mesh.validate();
        BodyPtr body(new Body());
        std::vector<std::uint32_t> parent;
        if (options.sizing == GridSizing::ADAPTIVE)
        {
            const std::vector<double> sizes = adaptiveNodeSizes(mesh, options.adaptive);
            body->adaptive_ = true;
            body->gridSize_ = sizes.empty() ? 0.0 : *std::max_element(sizes.begin(), sizes.end());
            body->mesh_ = refineMesh(mesh, sizes, &body->refinement_, &parent);
        }
        else
        {
            double h = options.gridSize;
            if (h < 0.0)
                h = BodyOptions::DEFAULT_GRID_FRACTION * mesh.size();
            if (!std::isfinite(h))
                h = 0.0;
            body->gridSize_ = h;
            body->mesh_ = refineMesh(mesh, h, &body->refinement_, &parent);
        }
        body->surface_ = std::move(mesh);
        body->bvh_ = std::make_unique<TriangleBvh>(body->surface_);
        const Mesh &surface = body->surface_;
        double volume = 0.0;  // six times the signed volume
        for (const Triangle &f : surface.triangles)
            volume += surface.vertices[f[0]].dot(surface.vertices[f[1]].cross(surface.vertices[f[2]]));
        body->orientation_ = volume >= 0.0 ? 1.0 : -1.0;
        body->buildSurfaceMaps(parent);
        body->graph_ = std::make_shared<const SurfaceGraph>(body->mesh_);
        body->componentNodes_.assign(body->graph_->numComponents(), UINT32_MAX);
        for (std::uint32_t i = body->graph_->numNodes(); i-- > 0;)
            body->componentNodes_[body->graph_->component(i)] = i;  // ends at each component's first node
        body->distanceOptions_ = options.distances;
        body->buildClusters();
        for (const Eigen::Vector3d &v : body->mesh_.vertices)
            body->originRadius_ = std::max(body->originRadius_, v.norm());
        return body;
    }

    const MeshDistances &Body::distances() const
    {
        std::call_once(distancesOnce_, [this] {
            distances_ = MeshDistances::build(graph_, distanceOptions_);
            OMPL_INFORM("%s: mesh distances for %u nodes %s", mesh_.source.c_str(), numNodes(),
                        distances_->isDense() ? (distances_->fromCache() ? "read from cache" : "computed (all pairs)") :
                                                "answered on demand");
        });
        return *distances_;
    }

    namespace
    {
        /** \brief Compressed rows from (row, value) pairs, values sorted and unique per row: the pairs bucketed by
            row (a counting sort, O(n)), then each short row sorted on its own. */
        void toRows(const std::vector<std::pair<std::uint32_t, std::uint32_t>> &pairs, std::size_t rows,
                    std::vector<std::uint32_t> &offsets, std::vector<std::uint32_t> &values)
        {
            offsets.assign(rows + 1, 0);
            for (const auto &p : pairs)
                ++offsets[p.first + 1];
            for (std::size_t i = 0; i < rows; ++i)
                offsets[i + 1] += offsets[i];
            values.resize(pairs.size());
            std::vector<std::uint32_t> fill(offsets.begin(), offsets.end() - 1);
            for (const auto &p : pairs)
                values[fill[p.first]++] = p.second;
            // Each row sorted, duplicates dropped, and moved down over the gaps the dropped ones leave.
            std::uint32_t begin = 0, out = 0;
            for (std::size_t i = 0; i < rows; ++i)
            {
                const std::uint32_t end = offsets[i + 1];
                std::sort(values.begin() + begin, values.begin() + end);
                const auto last = std::unique(values.begin() + begin, values.begin() + end);
                out = static_cast<std::uint32_t>(std::move(values.begin() + begin, last, values.begin() + out) -
                                                 values.begin());
                offsets[i + 1] = out;
                begin = end;
            }
            values.resize(out);
            values.shrink_to_fit();
        }
    }  // namespace

    void Body::buildSurfaceMaps(const std::vector<std::uint32_t> &parent)
    {
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        pairs.reserve(3 * mesh_.triangles.size());
        for (std::size_t t = 0; t < mesh_.triangles.size(); ++t)
            for (std::uint32_t v : mesh_.triangles[t])
                pairs.emplace_back(v, parent[t]);
        toRows(pairs, mesh_.vertices.size(), nodeTriangleOffsets_, nodeTriangles_);

        // Triangles around each surface vertex, then each triangle's corner-sharing neighbours.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> corner;
        for (std::uint32_t t = 0; t < surface_.triangles.size(); ++t)
            for (std::uint32_t v : surface_.triangles[t])
                corner.emplace_back(v, t);
        std::vector<std::uint32_t> vertexOffsets, vertexTriangles;
        toRows(corner, surface_.vertices.size(), vertexOffsets, vertexTriangles);
        pairs.clear();
        for (std::uint32_t t = 0; t < surface_.triangles.size(); ++t)
            for (std::uint32_t v : surface_.triangles[t])
                for (std::uint32_t k = vertexOffsets[v]; k < vertexOffsets[v + 1]; ++k)
                    if (vertexTriangles[k] != t)
                        pairs.emplace_back(t, vertexTriangles[k]);
        toRows(pairs, surface_.triangles.size(), triangleNeighbourOffsets_, triangleNeighbours_);

        // Closed: every undirected edge in exactly two triangles.
        edges_ = countEdges(surface_);
        closed_ = !surface_.triangles.empty() && edges_.closed();
    }

    void Body::buildClusters()
    {
        constexpr std::uint32_t LEAF = 32;
        const std::uint32_t n = numNodes();
        order_.resize(n);
        for (std::uint32_t i = 0; i < n; ++i)
            order_[i] = i;
        // Recursive median split along the longest axis of each range's box, leaves of at most LEAF nodes.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0u, n}};
        while (!stack.empty())
        {
            const auto [begin, end] = stack.back();
            stack.pop_back();
            Eigen::AlignedBox3d box;
            for (std::uint32_t k = begin; k < end; ++k)
                box.extend(mesh_.vertices[order_[k]]);
            if (end - begin <= LEAF)
            {
                const Eigen::Vector3d center = box.center();
                double r2 = 0.0;
                for (std::uint32_t k = begin; k < end; ++k)
                    r2 = std::max(r2, (mesh_.vertices[order_[k]] - center).squaredNorm());
                // Pad by a relative epsilon so rounding in the bound never prunes a node that is inside it.
                clusters_.push_back({center, std::sqrt(r2) * (1.0 + 1e-12) + 1e-300, begin, end});
                continue;
            }
            int axis;
            box.sizes().maxCoeff(&axis);
            const std::uint32_t mid = begin + (end - begin) / 2;
            std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                             [&](std::uint32_t i, std::uint32_t j) {
                                 return mesh_.vertices[i][axis] < mesh_.vertices[j][axis];
                             });
            stack.emplace_back(begin, mid);
            stack.emplace_back(mid, end);
        }
        xs_.resize(n);
        ys_.resize(n);
        zs_.resize(n);
        for (std::uint32_t k = 0; k < n; ++k)
        {
            xs_[k] = mesh_.vertices[order_[k]].x();
            ys_[k] = mesh_.vertices[order_[k]].y();
            zs_[k] = mesh_.vertices[order_[k]].z();
        }
    }
}  // namespace meshgap
