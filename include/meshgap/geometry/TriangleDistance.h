#ifndef MESHGAP_GEOMETRY_TRIANGLE_DISTANCE_H
#define MESHGAP_GEOMETRY_TRIANGLE_DISTANCE_H

#include <Eigen/Core>

namespace meshgap
{
    /** \brief Relative tolerance of trianglesIntersect() and of the zero case of triangleDistance(): two triangles
        whose computed distance is at most TRIANGLE_CONTACT_TOLERANCE * s are reported as intersecting (touching).
        s (in the input's length unit) is the larger of the six vertices' extent (largest side of their common
        axis-aligned bounding box) and their largest absolute coordinate: coordinates of magnitude M are themselves
        only known to about 1e-16 M (a vertex carried into another frame by a pose moves by that much), so a contact
        finer than that is not meaningful.

        The computations below are accurate to a few units of roundoff times s (about 1e-15 s), also for sliver
        triangles and nearly parallel edges, so the tolerance leaves a margin of about three orders of magnitude:
        a pair that really touches or intersects is never reported free, and a pair reported intersecting is at
        most 1e-12 s apart. */
    constexpr double TRIANGLE_CONTACT_TOLERANCE = 1e-12;

    /** \brief Closest points of the segments [p0, p1] and [q0, q1]; returns their distance.

        All points are in one (any) frame, distances in its length unit. Robust for parallel, collinear,
        intersecting and zero-length segments: the result is the minimum over the four endpoint-to-segment distances
        and, when the lines' closest points fall inside both segments, the interior pair, so it is never below the
        true distance by more than roundoff and never above it by more than roundoff times the segments' extent.
        \param onP closest point on [p0, p1] (output)
        \param onQ closest point on [q0, q1] (output); for parallel segments one of the closest pairs */
    double segmentSegmentDistance(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, const Eigen::Vector3d &q0,
                                  const Eigen::Vector3d &q1, Eigen::Vector3d &onP, Eigen::Vector3d &onQ);

    /** \brief Closest point of the (filled) triangle abc to \e p; returns their distance.

        Same frame and unit for all points. The triangle's plane frame is built on its longest edge by
        Gram-Schmidt, so sliver triangles are handled to roundoff; a degenerate triangle (collinear corners, a repeated
        corner, a single point, or a height below 1e-15 of its longest edge) is treated as the union of its edges.
        \param onT closest point of the triangle (output) */
    double pointTriangleDistance(const Eigen::Vector3d &p, const Eigen::Vector3d &a, const Eigen::Vector3d &b,
                                 const Eigen::Vector3d &c, Eigen::Vector3d &onT);

    /** \brief Whether the (filled) triangles a0a1a2 and b0b1b2 share a point; touching (a shared vertex, a vertex on
        an edge or a face, an edge on a face, coplanar overlap) counts as intersecting.

        Decided as: not separated by either triangle's plane with a margin, and either an edge of one crosses the
        other's face or the exact-distance computation of triangleDistance() gives at most
        TRIANGLE_CONTACT_TOLERANCE times the scale s defined there. Conservative: when in doubt (within that
        tolerance) the answer is \c true. Equal to <tt>triangleDistance(...) == 0</tt> for the same arguments,
        symmetric in the two triangles and invariant under the order of each triangle's corners (bit for bit: the
        input is put in a canonical order first). Degenerate triangles are handled as the union of their edges. */
    bool trianglesIntersect(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1, const Eigen::Vector3d &a2,
                            const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, const Eigen::Vector3d &b2);

    /** \brief Minimum distance between the (filled) triangles a0a1a2 and b0b1b2, with witness points.

        All points in one frame, the distance in its length unit. The minimum over the 6 vertex-face pairs and the 9
        edge-edge pairs (each computed as in pointTriangleDistance() and segmentSegmentDistance()), which is exact for
        disjoint triangles; the search stops early once the slab between the planes normal to the current closest
        pair through its points separates the triangles (a proof that nothing is closer). When the triangles intersect
       (trianglesIntersect() is \c true) the result is exactly 0 and \e onA == \e onB is a common point: a point where
       an edge crosses the other face, or, when they only touch within the tolerance, the midpoint of the closest pair
       (at most half the tolerance from each triangle). Otherwise the witnesses are the closest points and the result is
       their distance (up to roundoff). Symmetric and invariant under corner order like trianglesIntersect(). Pure,
       allocation-free and thread-safe. \param onA closest point on triangle a (output) \param onB closest point on
       triangle b (output) */
    double triangleDistance(const Eigen::Vector3d &a0, const Eigen::Vector3d &a1, const Eigen::Vector3d &a2,
                            const Eigen::Vector3d &b0, const Eigen::Vector3d &b1, const Eigen::Vector3d &b2,
                            Eigen::Vector3d &onA, Eigen::Vector3d &onB);
}  // namespace meshgap

#endif
