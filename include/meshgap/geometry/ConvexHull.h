#ifndef MESHGAP_GEOMETRY_CONVEX_HULL_H
#define MESHGAP_GEOMETRY_CONVEX_HULL_H

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "meshgap/geometry/Primitive.h"

namespace meshgap
{
    /** \brief A conservative convex outer bound of a point set (a body's surface vertices): the convex hull of some
        of the points (qhull's hull vertices, V') grown by a ball of radius margin() (epsilon), so that every input
        point, hence every triangle of a mesh on them, lies in conv(V') + Ball(epsilon).

        Built by qhull (its triangulated hull, "Qt"); a hull of more than maxVertices vertices (1,024: a finely
        tessellated round part) is replaced by the hull of its vertices extreme along \e directions directions
        (4,096) spread over the sphere, whose margin then covers the vertices left out (the UR5's force sensor: 4,094
        vertices, 551 kept, margin 0.07 mm). Fewer (Body::coarseHull()) make a looser bound, cheaper to query.
        Then certified without trusting qhull's arithmetic:
        - the hull's triangles (each spanned by three points of V') form a closed, consistently oriented surface
          (every directed edge once, its reverse once) whose winding number about c, the mean of V', is not 0, and c
          lies strictly below every triangle along that triangle's normal (a floating-point test with a forward
          error bound on the dot products);
        - then a point p strictly below every triangle lies in conv(V') (the ray from c through p leaves the surface
          at a point x of some triangle T, and p lies between c and x, both below T's vertices along T's normal);
        - every other point gets the least distance to a triangle it is not proven below (each triangle is in
          conv(V'): an upper bound of its distance to the hull);
        - epsilon is the largest of those distances, times 1 + 1e-9, plus 1e-12 times the points' reach from the
          origin (roundoff in the distances).
        A point set qhull cannot hull (fewer than four points, flat or tiny, a qhull error) or one whose surface
        fails the checks above has no hull (build() returns null): the caller uses the mesh. */
    class ConvexHull
    {
    public:
        /** \brief The hull of \e points, or null when there is none (see above). Never throws for a degenerate
            input. */
        static std::shared_ptr<const ConvexHull> build(const std::vector<Eigen::Vector3d> &points,
                                                       std::size_t maxVertices = 1024, int directions = 4096);

        /** \brief V': the hull's vertices (a subset of the points given). */
        const std::vector<Eigen::Vector3d> &vertices() const { return vertices_; }
        /** \brief epsilon: every point given lies within this of conv(vertices()). */
        double margin() const { return margin_; }
        /** \brief A point inside conv(vertices()) (their mean). */
        const Eigen::Vector3d &center() const { return center_; }
        /** \brief The largest distance of a vertex from the frame's origin. */
        double reach() const { return reach_; }
        /** \brief Triangles of the hull's surface, as indices into vertices(), oriented alike. */
        const std::vector<std::array<std::uint32_t, 3>> &triangles() const { return triangles_; }

        /** \brief A vertex farthest along \e d: the very one scan() returns. A hull of at most 512 vertices tests
            only the candidates of the direction cell \e d falls in (see directionCells()); a larger one, the
            vertices of the clusters whose bounding sphere reaches the best value found so far. */
        Eigen::Vector3d support(const Eigen::Vector3d &d) const;

        /** \brief A vertex farthest along \e d, every vertex tested: of those whose computed dot product with \e d
            is largest, the first in vertices(). */
        Eigen::Vector3d scan(const Eigen::Vector3d &d) const;

    private:
        ConvexHull() = default;
        /** \brief Split the vertices into clusters of nearby ones (clustered_), with their bounding spheres. */
        void cluster();
        /** \brief Test the vertices of cluster \e k against the best so far (value, then the smaller index). */
        void scanCluster(std::size_t k, const Eigen::Vector3d &d, double &best, std::uint32_t &where) const;
        /** \brief Split the directions into cells and find each cell's candidates (cells_); none for a large hull. */
        void directionCells();

        std::vector<Eigen::Vector3d> vertices_;
        std::vector<double> xs_, ys_, zs_;  ///< vertices_ as separate arrays, for scan()
        /** \brief The vertices again, cluster by cluster (cluster k from first_[k] to first_[k + 1]), with their
            indices in vertices_; each cluster's bounding sphere (centre, radius); none for a small hull. */
        struct Clusters
        {
            std::vector<double> xs, ys, zs;
            std::vector<std::uint32_t> index, first;
            std::vector<double> cx, cy, cz, radius;
        } clustered_;
        /** \brief The directions as a cube map: a direction d is d_a times (+-e_a + u e_b + v e_c) on the face of
            its largest coordinate a (b, c the next two axes, cyclic), with (u, v) in [-1, 1]^2, cut into side x side
            squares. A cell's candidates, ascending, are the vertices not beaten over the whole cell, by more than
            roundoff, by one same vertex (a vertex farthest along one of the cell's corners or its centre): every
            direction of the cell has scan()'s vertex among them. Cell (face, i, j), face = 2 a + (d_a < 0), holds
            index[first[(face side + i) side + j] ...). */
        struct Cells
        {
            int side{0};  ///< 0: no table
            std::vector<std::uint32_t> first;
            std::vector<std::uint16_t> index;
        } cells_;
        std::vector<std::array<std::uint32_t, 3>> triangles_;
        double margin_{0.0};
        Eigen::Vector3d center_{Eigen::Vector3d::Zero()};
        double reach_{0.0};
    };

    /** \brief A lower bound of the distance between hull \e a (grown by its margin, in frame A) and hull \e b (grown
        by its, placed in A by \e X_AB): GJK on the vertex sets (its certified support-plane gap), less both margins;
        0 when they overlap. Computed only until it exceeds \e enough (then a lower bound above it). */
    double hullGap(const ConvexHull &a, const ConvexHull &b, const Eigen::Isometry3d &X_AB,
                   double enough = std::numeric_limits<double>::infinity());

    /** \brief The same between hull \e a (frame A) and the solid \e p, whose frame (the one Primitive::pose is in)
        \e X_AP places in A. */
    double hullPrimitiveGap(const ConvexHull &a, const Primitive &p, const Eigen::Isometry3d &X_AP,
                            double enough = std::numeric_limits<double>::infinity());

    /** \brief A lower bound of the distance between two swept hulls: \e a placed in one frame by \e A0 and by \e A1
        (the convex hull of both placements), grown by its margin and \e growA, and \e b the same by \e B0, \e B1 and
        \e growB; 0 when they overlap. A body moving from A0 to A1 along a path that strays at most g from the
        straight line between each point's two places stays inside a's set grown by g (every point of the mesh lies
        within the margin of a point of the hull, whose two places span a segment of that set). Computed only
        until it exceeds \e enough. A hull that stays (its second pose the very first, bit for bit) is placed once:
        the same gap as its sweep's, for half the support calls.

        \e axis (optional): GJK's first direction, from a towards b in the placements' frame (zero: the line between
        their centres), and on return, when apart, the last one it looked along: kept per question and passed to the
        next one about nearby placements (the next piece of a motion), a bound that is often proven by the first
        support pair (two support calls). Any first direction gives a valid bound; only its cost changes. */
    double sweptHullGap(const ConvexHull &a, const Eigen::Isometry3d &A0, const Eigen::Isometry3d &A1, double growA,
                        const ConvexHull &b, const Eigen::Isometry3d &B0, const Eigen::Isometry3d &B1, double growB,
                        double enough = std::numeric_limits<double>::infinity(), Eigen::Vector3d *axis = nullptr);

    /** \brief The same between \e a swept from \e A0 to \e A1 (grown by its margin and \e grow) and the solid \e p,
        whose pose is in the frame A0 and A1 place \e a in. */
    double sweptHullPrimitiveGap(const ConvexHull &a, const Eigen::Isometry3d &A0, const Eigen::Isometry3d &A1,
                                 double grow, const Primitive &p,
                                 double enough = std::numeric_limits<double>::infinity(),
                                 Eigen::Vector3d *axis = nullptr);
}  // namespace meshgap

#endif
