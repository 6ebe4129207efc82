#ifndef MESHGAP_GEOMETRY_TRIANGLE_BVH_H
#define MESHGAP_GEOMETRY_TRIANGLE_BVH_H

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/mesh/Mesh.h"
#include "meshgap/geometry/BvhCollide.h"
#include "meshgap/geometry/BvhDistance.h"
#include "meshgap/geometry/BvhFront.h"
#include "meshgap/geometry/BvhPoint.h"

namespace meshgap
{
    /** \brief A bounding-volume hierarchy over a mesh's triangles: a binary tree of boxes in the body frame, each the
        tighter (smaller volume; flat ones by area) of the axis-aligned box and the box along the principal axes of
        its triangles' corners, with a bounding sphere about the box centre; built top-down, each node's triangles cut
        in two along one of its box axes where the surface area heuristic (the children's box areas times their
        triangle counts) is least, leaves of at most LEAF_SIZE triangles (a leaf's principal box is flat: a
        triangle's own plane).
        Between two trees at a relative pose, a box pair is bounded from below by the gap of the spheres, then by the
        gap of the boxes along the direction between their nearest points (BoxBound.h). Immutable; the mesh must
        outlive the tree. */
    class TriangleBvh
    {
    public:
        static constexpr std::uint32_t LEAF_SIZE = 1;

        struct Node
        {
            Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< box centre, body frame
            Eigen::Vector3d half{Eigen::Vector3d::Zero()};    ///< box half extents along its axes
            /** \brief The box's axes (columns, body frame; a rotation); the identity when aligned. */
            Eigen::Matrix3d axes{Eigen::Matrix3d::Identity()};
            double radius{0.0};      ///< every triangle corner of the node lies within radius of center
            std::uint32_t first{0};  ///< leaf: first index in order(); inner: index of the left child
            std::uint32_t count{0};  ///< leaf: number of triangles (> 0); inner: 0 (right child is first + 1)
            bool aligned{true};      ///< axes is the identity (the cheaper tests apply)
            bool isLeaf() const { return count > 0; }
            /** \brief \e p (body frame) in the box's frame: relative to its centre, along its axes. */
            Eigen::Vector3d local(const Eigen::Vector3d &p) const
            {
                return aligned ? Eigen::Vector3d(p - center) : Eigen::Vector3d(axes.transpose() * (p - center));
            }
            /** \brief Whether \e p (body frame) lies outside the box. */
            bool outside(const Eigen::Vector3d &p) const { return (local(p).cwiseAbs() - half).maxCoeff() > 0.0; }
        };

        explicit TriangleBvh(const Mesh &mesh);

        const Mesh &mesh() const { return *mesh_; }
        const std::vector<Node> &nodes() const { return nodes_; }
        /** \brief Triangle indices in leaf order. */
        const std::vector<std::uint32_t> &order() const { return order_; }
        /** \brief Unit normal of each triangle (body frame), for the plane-separation bound at the leaves. */
        const std::vector<Eigen::Vector3d> &normals() const { return normals_; }

    private:
        const Mesh *mesh_;
        std::vector<Node> nodes_;
        std::vector<std::uint32_t> order_;
        std::vector<Eigen::Vector3d> normals_;
    };
}  // namespace meshgap

#endif
