#include "meshgap/geometry/TriangleBvh.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace meshgap
{
    namespace
    {
        /** \brief The box of the triangles order[first, first + count) of \e mesh: the tighter of the axis-aligned
            box and the box along the principal axes of their corners (kept only if clearly smaller, an aligned box
            making cheaper tests), with the bounding sphere about its centre; padded against roundoff. */
        TriangleBvh::Node fitNode(const Mesh &mesh, const std::vector<std::uint32_t> &order, std::uint32_t first,
                                  std::uint32_t count)
        {
            Eigen::AlignedBox3d box;
            Eigen::Vector3d mean = Eigen::Vector3d::Zero();
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                {
                    box.extend(mesh.vertices[v]);
                    mean += mesh.vertices[v];
                }
            mean /= 3.0 * count;
            TriangleBvh::Node node;
            node.center = box.center();
            node.half = 0.5 * box.sizes();
            // The principal box: along the eigenvectors of the corners' covariance. Kept if clearly smaller (an
            // aligned box makes cheaper tests).
            Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                {
                    const Eigen::Vector3d d = mesh.vertices[v] - mean;
                    covariance += d * d.transpose();
                }
            Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
            if (axes.determinant() < 0.0)
                axes.col(2) = -axes.col(2);
            Eigen::AlignedBox3d principal;
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                    principal.extend(Eigen::Vector3d(axes.transpose() * mesh.vertices[v]));
            const Eigen::Vector3d principalHalf = 0.5 * principal.sizes();
            auto measure = [](const Eigen::Vector3d &h) { return h.prod() + 1e-3 * h.squaredNorm() * h.minCoeff(); };
            if (axes.allFinite() && measure(principalHalf) < 0.8 * measure(node.half))
            {
                node.axes = axes;
                node.aligned = false;
                node.center = axes * principal.center();
                node.half = principalHalf;
            }
            double r2 = 0.0;
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                    r2 = std::max(r2, (mesh.vertices[v] - node.center).squaredNorm());
            // Rounding slack: bounds must never cut into the geometry they bound (a rotated box's corners are
            // projected with roundoff of a few 1e-16 of the coordinates).
            const double slack = 1e-12 * (node.center.norm() + node.half.norm() + mean.norm());
            node.radius = std::sqrt(r2) + slack;
            node.half.array() += slack;
            return node;
        }

        /** \brief Split the triangles order[first, first + count) in two by the surface area heuristic: along each
            of the node's box \e axes, the triangles sorted by centroid, the cut that minimises the sum over both
            sides of (surface area of the side's box along \e axes) x (its triangle count). The triangles are
            reordered, the first side first; returns its size (between 1 and count - 1). Boxes that fit their
            triangles tightly rather than halves of equal counts: on meshes of unequal density (a tube of slivers
            with capped ends, a fine part welded to a coarse one) far fewer box pairs overlap between two trees. */
        std::uint32_t splitBySurfaceArea(const Mesh &mesh, const std::vector<Eigen::Vector3d> &centroid,
                                         const Eigen::Matrix3d &axes, std::uint32_t first, std::uint32_t count,
                                         std::vector<std::uint32_t> &order)
        {
            // Each triangle's box and centroid along the node's axes, once.
            std::vector<Eigen::AlignedBox3d> boxes(count);
            std::vector<Eigen::Vector3d> centre(count);
            for (std::uint32_t k = 0; k < count; ++k)
            {
                for (std::uint32_t v : mesh.triangles[order[first + k]])
                    boxes[k].extend(Eigen::Vector3d(axes.transpose() * mesh.vertices[v]));
                centre[k] = axes.transpose() * centroid[order[first + k]];
            }
            auto area = [](const Eigen::AlignedBox3d &box)
            {
                const Eigen::Vector3d d = box.sizes();
                return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
            };
            // Sorted along an axis: by the centroid's coordinate, ties by triangle index (deterministic).
            std::vector<std::pair<double, std::uint32_t>> sorted(count), bestSorted;
            auto sortAlong = [&](int axis, std::vector<std::pair<double, std::uint32_t>> &keys)
            {
                for (std::uint32_t k = 0; k < count; ++k)
                    keys[k] = {centre[k][axis], k};
                std::sort(keys.begin(), keys.end(),
                          [&](const auto &x, const auto &y)
                          {
                              return x.first < y.first ||
                                     (x.first == y.first && order[first + x.second] < order[first + y.second]);
                          });
            };
            std::vector<double> leftArea(count);
            double bestCost = std::numeric_limits<double>::infinity();
            std::uint32_t bestCut = count / 2;
            for (int axis = 0; axis < 3; ++axis)
            {
                sortAlong(axis, sorted);
                Eigen::AlignedBox3d left, right;
                for (std::uint32_t k = 0; k < count; ++k)
                    leftArea[k] = area(left.extend(boxes[sorted[k].second]));
                bool better = false;
                for (std::uint32_t k = count - 1; k >= 1; --k)
                {
                    // The first k triangles on one side, the rest on the other.
                    const double cost = leftArea[k - 1] * k + area(right.extend(boxes[sorted[k].second])) * (count - k);
                    if (cost < bestCost)
                    {
                        bestCost = cost;
                        bestCut = k;
                        better = true;
                    }
                }
                if (better || bestSorted.empty())
                    bestSorted.swap(sorted);
                if (sorted.size() != count)
                    sorted.resize(count);
            }
            std::vector<std::uint32_t> reordered(count);
            for (std::uint32_t k = 0; k < count; ++k)
                reordered[k] = order[first + bestSorted[k].second];
            std::copy(reordered.begin(), reordered.end(), order.begin() + first);
            return bestCut;
        }
    }  // namespace

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
            const Eigen::Vector3d c =
                (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
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
            Node node = fitNode(mesh, order_, w.first, w.count);
            if (w.count <= LEAF_SIZE)
            {
                node.first = w.first;
                node.count = w.count;
                nodes_[w.node] = node;
                continue;
            }
            const std::uint32_t half = splitBySurfaceArea(mesh, centroid, node.axes, w.first, w.count, order_);
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
}  // namespace meshgap
