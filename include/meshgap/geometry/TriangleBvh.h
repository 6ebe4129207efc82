#ifndef MESHGAP_GEOMETRY_TRIANGLE_BVH_H
#define MESHGAP_GEOMETRY_TRIANGLE_BVH_H

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief A bounding-volume hierarchy over a mesh's triangles: a binary tree of axis-aligned boxes in the body
        frame (each with a bounding sphere about the box centre), built top-down by median split of the triangle
        centroids along the longest axis, leaves of at most LEAF_SIZE triangles. Between two trees at a relative
        pose, a box pair is bounded from below by the largest separating-axis gap (the boxes are oriented boxes in
        each other's frame) and by the gap of the spheres. Immutable; the mesh must outlive the tree. */
    class TriangleBvh
    {
    public:
        static constexpr std::uint32_t LEAF_SIZE = 1;

        struct Node
        {
            Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< box centre, body frame
            Eigen::Vector3d half{Eigen::Vector3d::Zero()};    ///< box half extents
            double radius{0.0};      ///< every triangle corner of the node lies within radius of center
            std::uint32_t first{0};  ///< leaf: first index in order(); inner: index of the left child
            std::uint32_t count{0};  ///< leaf: number of triangles (> 0); inner: 0 (right child is first + 1)
            bool isLeaf() const { return count > 0; }
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

    /** \brief What a distance traversal found and what it cost. */
    struct BvhDistanceResult
    {
        /** \brief The smallest triangle-pair distance below the upper bound given, or the upper bound itself when no
            pair beats it (then found is false and the pair fields are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangleA{0}, triangleB{0};
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};  ///< A's frame
        std::size_t boxTests{0}, triangleTests{0};
    };

    /** \brief Exact minimum distance between the triangles of \e a (frame A) and of \e b placed by \e X_AB, searching
        only for pairs closer than \e upperBound (pass a distance some real pair achieves to prune with it, or
        infinity; \e seedA / \e seedB name that pair, if any). Completes the whole traversal unless \e stopBelow is
        reached (a pair at or below it ends the search early; pass a negative value to never stop). A completed
        traversal with found == false proves no pair is closer than \e upperBound. Intersecting triangles have
        distance 0.

        Ties are canonical: pairs whose distances agree within a rounding slack (1e-12 of the scene's scale) count
        as equally close, and the one with the smallest (triangle of A, triangle of B) wins. So the answer, pair and
        witness points do not depend on the seed or the visiting order: a warm-started query gives the cold query's
        answer bit for bit. */
    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA = UINT32_MAX,
                     std::uint32_t seedB = UINT32_MAX);

    /** \brief True when some triangle of \e a intersects (or touches) some triangle of \e b placed by \e X_AB;
        stops at the first such pair, which is reported through \e hitA / \e hitB when given. */
    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                    std::uint32_t *hitA = nullptr, std::uint32_t *hitB = nullptr);

    /** \brief What a point query (bvhPointDistance()) found and what it cost. */
    struct BvhPointResult
    {
        /** \brief Distance from the point to the nearest triangle below the upper bound given, or the upper bound
            itself when none is closer (then found is false and triangle / closest are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangle{0};                           ///< the nearest triangle (mesh index)
        Eigen::Vector3d closest{Eigen::Vector3d::Zero()};   ///< the nearest point on it, body frame
        std::size_t triangleTests{0};
    };

    /** \brief Exact distance from \e p (in the tree's body frame) to the nearest triangle of \e tree, searching only
        for triangles closer than \e upperBound; nearer boxes first. A triangle at or below \e stopBelow ends the
        search early (the answer is then only an upper bound; negative: never stop). Deterministic: the same point
        gives the same triangle and closest point. */
    void bvhPointDistance(const TriangleBvh &tree, const Eigen::Vector3d &p, double upperBound, double stopBelow,
                          BvhPointResult &result);

    /** \brief Winding number of \e tree's surface about \e p (body frame) by ray casting: the signed number of
        triangles the ray p + s \e direction (s > 0) crosses, +1 where it leaves through a triangle's front
        (counter-clockwise) side and -1 where it enters. For a closed surface that is the generalised winding number
        (an integer: 0 outside, +-1 inside, more inside overlapping shells), found in O(log n) triangle tests
        instead of O(n). Returns false, leaving \e winding undefined, when the answer is not robust: the ray passes
        within roundoff of a triangle's edge or corner (then try another direction), or \e p lies on the surface. */
    bool bvhRayWinding(const TriangleBvh &tree, const Eigen::Vector3d &p, const Eigen::Vector3d &direction,
                       int &winding);
}  // namespace meshgap

#endif
