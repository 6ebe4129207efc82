#include "meshgap/geometry/Body.h"
#include "meshgap/geometry/PrimitiveDistance.h"

#include <algorithm>
#include <cmath>
#include <ompl/util/Console.h>

namespace meshgap
{
    BodyPtr Body::build(Mesh mesh, const BodyOptions &options)
    {
        mesh.validate();
        if (options.sizing == GridSizing::ADAPTIVE)
            checkAdaptiveSizing(options.adaptive, mesh.source);  // a bad rule fails here, not at first use
        BodyPtr body(new Body());
        body->options_ = options;
        body->surface_ = std::move(mesh);
        body->bvh_ = std::make_unique<TriangleBvh>(body->surface_);
        const Mesh &surface = body->surface_;
        double volume = 0.0;  // six times the signed volume
        for (const Triangle &f : surface.triangles)
            volume += surface.vertices[f[0]].dot(surface.vertices[f[1]].cross(surface.vertices[f[2]]));
        body->orientation_ = volume >= 0.0 ? 1.0 : -1.0;
        // Closed: every undirected edge in exactly two triangles.
        body->edges_ = countEdges(surface);
        body->closed_ = !surface.triangles.empty() && body->edges_.closed();
        // Components numbered in order of first vertex, as the node mesh's (which keeps these vertices first and
        // only adds vertices on their edges).
        std::uint32_t components = 0;
        const std::vector<std::uint32_t> label = labelComponents(surface, components);
        body->componentNodes_.assign(components, UINT32_MAX);
        for (auto v = static_cast<std::uint32_t>(label.size()); v-- > 0;)
            body->componentNodes_[label[v]] = v;  // ends at each component's first vertex
        return body;
    }

    BodyPtr Body::build(Mesh mesh, std::vector<Primitive> primitives, const BodyOptions &options)
    {
        for (const Primitive &p : primitives)
            checkPrimitive(p);
        BodyPtr body = build(std::move(mesh), options);
        body->primitives_ = std::move(primitives);
        return body;
    }

    const Body::NodeLayer &Body::buildNodeLayer() const
    {
        std::call_once(layerOnce_, [this] {
            auto layer = std::make_unique<NodeLayer>();
            std::vector<std::uint32_t> parent;
            if (options_.sizing == GridSizing::ADAPTIVE)
            {
                const std::vector<double> sizes = adaptiveNodeSizes(surface_, options_.adaptive);
                layer->gridSize = sizes.empty() ? 0.0 : *std::max_element(sizes.begin(), sizes.end());
                layer->mesh = refineMesh(surface_, sizes, &layer->refinement, &parent);
            }
            else
            {
                double h = options_.gridSize;
                if (h < 0.0)
                    h = BodyOptions::DEFAULT_GRID_FRACTION * surface_.size();
                if (!std::isfinite(h))
                    h = 0.0;
                layer->gridSize = h;
                layer->mesh = refineMesh(surface_, h, &layer->refinement, &parent);
            }
            buildSurfaceMaps(*layer, parent);
            layer->graph = std::make_shared<const SurfaceGraph>(layer->mesh);
            buildClusters(*layer);
            for (const Eigen::Vector3d &v : layer->mesh.vertices)
                layer->originRadius = std::max(layer->originRadius, v.norm());
            layerStore_ = std::move(layer);
            layer_.store(layerStore_.get(), std::memory_order_release);
        });
        return *layer_.load(std::memory_order_acquire);
    }

    const SurfaceGrid &Body::surfaceGrid() const
    {
        std::call_once(gridOnce_,
                       [this] { grid_ = std::make_unique<const SurfaceGrid>(SurfaceGrid::build(*bvh_, closed_)); });
        return *grid_;
    }

    const ConvexHull *Body::convexHull() const
    {
        std::call_once(hullOnce_, [this] { hull_ = ConvexHull::build(surface_.vertices); });
        return hull_.get();
    }

    const ConvexHull *Body::coarseHull() const
    {
        std::call_once(coarseHullOnce_, [this] { coarseHull_ = ConvexHull::build(surface_.vertices, 192, 384); });
        return coarseHull_.get();
    }

    const MeshDistances &Body::distances() const
    {
        std::call_once(distancesOnce_, [this] {
            distances_ = MeshDistances::build(nodeLayer().graph, options_.distances);
            OMPL_INFORM("%s: mesh distances for %u nodes %s", surface_.source.c_str(), numNodes(),
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

    void Body::buildSurfaceMaps(NodeLayer &layer, const std::vector<std::uint32_t> &parent) const
    {
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        pairs.reserve(3 * layer.mesh.triangles.size());
        for (std::size_t t = 0; t < layer.mesh.triangles.size(); ++t)
            for (std::uint32_t v : layer.mesh.triangles[t])
                pairs.emplace_back(v, parent[t]);
        toRows(pairs, layer.mesh.vertices.size(), layer.nodeTriangleOffsets, layer.nodeTriangles);

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
        toRows(pairs, surface_.triangles.size(), layer.triangleNeighbourOffsets, layer.triangleNeighbours);
    }

    void Body::buildClusters(NodeLayer &layer)
    {
        constexpr std::uint32_t LEAF = 32;
        const Mesh &mesh = layer.mesh;
        std::vector<std::uint32_t> &order = layer.order;
        const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
        order.resize(n);
        for (std::uint32_t i = 0; i < n; ++i)
            order[i] = i;
        // Recursive median split along the longest axis of each range's box, leaves of at most LEAF nodes, the
        // upper half first; each range's ball (its box's centre, padded by a relative epsilon so rounding in a bound
        // never prunes a node inside it) is an entry of the tree, in depth-first order.
        auto split = [&](auto &self, std::uint32_t begin, std::uint32_t end) -> void
        {
            Eigen::AlignedBox3d box;
            for (std::uint32_t k = begin; k < end; ++k)
                box.extend(mesh.vertices[order[k]]);
            const Eigen::Vector3d center = box.center();
            double r2 = 0.0;
            for (std::uint32_t k = begin; k < end; ++k)
                r2 = std::max(r2, (mesh.vertices[order[k]] - center).squaredNorm());
            const double radius = std::sqrt(r2) * (1.0 + 1e-12) + 1e-300;
            const auto entry = static_cast<std::uint32_t>(layer.clusterTree.size());
            const auto first = static_cast<std::uint32_t>(layer.clusters.size());
            layer.clusterTree.push_back({center, radius, first, first, 0});
            if (end - begin <= LEAF)
                layer.clusters.push_back({center, radius, begin, end});
            else
            {
                int axis;
                box.sizes().maxCoeff(&axis);
                const std::uint32_t mid = begin + (end - begin) / 2;
                std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                                 [&](std::uint32_t i, std::uint32_t j)
                                 { return mesh.vertices[i][axis] < mesh.vertices[j][axis]; });
                self(self, mid, end);
                self(self, begin, mid);
            }
            layer.clusterTree[entry].endCluster = static_cast<std::uint32_t>(layer.clusters.size());
            layer.clusterTree[entry].skip = static_cast<std::uint32_t>(layer.clusterTree.size());
        };
        split(split, 0, n);
        layer.xs.resize(n);
        layer.ys.resize(n);
        layer.zs.resize(n);
        for (std::uint32_t k = 0; k < n; ++k)
        {
            layer.xs[k] = mesh.vertices[order[k]].x();
            layer.ys[k] = mesh.vertices[order[k]].y();
            layer.zs[k] = mesh.vertices[order[k]].z();
        }
    }
}  // namespace meshgap
