#ifndef MESHGAP_GEOMETRY_BVH_POINT_H
#define MESHGAP_GEOMETRY_BVH_POINT_H

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace meshgap
{
    class TriangleBvh;

    /** \brief What a point query (bvhPointDistance()) found and what it cost. */
    struct BvhPointResult
    {
        /** \brief Distance from the point to the nearest triangle below the upper bound given, or the upper bound
            itself when none is closer (then found is false and triangle / closest are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangle{0};                         ///< the nearest triangle (mesh index)
        Eigen::Vector3d closest{Eigen::Vector3d::Zero()};  ///< the nearest point on it, body frame
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
