#ifndef MESHGAP_GEOMETRY_SURFACE_GRID_H
#define MESHGAP_GEOMETRY_SURFACE_GRID_H

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <vector>

namespace meshgap
{
    class TriangleBvh;

    /** \brief A coarse axis-aligned grid over a body's bounding box (grown by one cell on every side), in the body's
        frame: for each cell, bounds on the distance from any point of the cell to the surface, and, where the
        surface does not reach the cell, which side of it the cell lies on. What penetrationDepth() reads to skip, at
        the price of a cell look-up, the node clusters that cannot hold the deepest node (wholly outside, or not deep
        enough), and to find a deep node to start its search from.

        Bounds. Each cell's centre c is measured exactly (bvhPointDistance()); a point q of the cell is at most the
        cell's half diagonal hd from c, so its distance to the surface lies in [d(c) - hd, d(c) + hd] (the distance
        to a set is 1-Lipschitz). lo and hi are those bounds widened by a roundoff margin (1e-9 relative plus 1e-12
        of the box's size, more than the roundoff of the measurement and of locating a point in a cell) and rounded
        outward to float. Sides. A cell with d(c) > hd (widened) holds no surface point; neighbouring such cells
        (sharing a face) form regions free of surface, each wholly inside or wholly outside a closed surface: one
        robust ray cast (bvhRayWinding(), the directions insideClosedBody() uses) decides a region, INSIDE when the
        winding number is not 0. A region no ray decides, and every region of a surface that is not closed, is
        UNKNOWN. Immutable; thread-safe to read. */
    class SurfaceGrid
    {
    public:
        enum class Side : std::uint8_t
        {
            CROSSING,  ///< the surface may pass through the cell
            INSIDE,    ///< no surface point in the cell, which lies inside the closed surface
            OUTSIDE,   ///< no surface point in the cell, which lies outside it
            UNKNOWN    ///< no surface point in the cell, side not decided
        };

        struct Cell
        {
            float lo;   ///< every point of the cell is at least lo from the surface
            float hi;   ///< and at most hi
            Side side;
            /** \brief The surface triangle nearest to the cell's centre: its distance from any point of the cell is
                at most hi (the centre's distance plus the half diagonal), a bound at the price of one
                point-triangle distance. */
            std::uint32_t triangle;
        };

        /** \brief The grid of \e tree's surface; \e closed: whether the surface is closed (sides decided). Cells of
            edge the box's diagonal / 40 or more, at most CELLS_PER_TRIANGLE per triangle, and at most MAX_CELLS
            (but at least MIN_CELLS). */
        static SurfaceGrid build(const TriangleBvh &tree, bool closed);

        static constexpr std::size_t MAX_CELLS = 32768, MIN_CELLS = 512, CELLS_PER_TRIANGLE = 16;

        /** \brief The cell holding \e p (body frame), or null when \e p lies outside the grid. */
        const Cell *cell(const Eigen::Vector3d &p) const { return cellAt((p - origin_) * inverseSize_); }

        /** \brief The map from the body frame to grid coordinates, in which cell (i, j, k) is [i, i + 1) x [j, j + 1)
            x [k, k + 1): a caller may fold it into its own transform and look cells up with cellAt(). */
        Eigen::Affine3d toGrid() const
        {
            return Eigen::Scaling(inverseSize_) * Eigen::Translation3d(-origin_);
        }

        /** \brief The cell holding grid coordinates \e f (see toGrid()), or null when \e f lies outside the grid. */
        const Cell *cellAt(const Eigen::Vector3d &f) const
        {
            // Compared as doubles first (false for NaN): a cast of a value beyond the grid could overflow. Within
            // the grid each coordinate is below its count (at most MAX_CELLS), so its truncation is a valid index.
            if (!(f.x() >= 0.0 && f.y() >= 0.0 && f.z() >= 0.0 && f.x() < counts_[0] && f.y() < counts_[1] &&
                  f.z() < counts_[2]))
                return nullptr;
            const auto i = static_cast<std::int32_t>(f.x()), j = static_cast<std::int32_t>(f.y()),
                       k = static_cast<std::int32_t>(f.z());
            return &cells_[(std::size_t(k) * n_[1] + std::size_t(j)) * n_[0] + std::size_t(i)];
        }

        double cellSize() const { return size_; }
        /** \brief The largest lo of an OUTSIDE cell (0 when there is none): a ball of a larger radius is never wholly
            outside by its cell. */
        double outsideReach() const { return outsideReach_; }
        std::size_t numCells() const { return cells_.size(); }
        const std::vector<Cell> &cells() const { return cells_; }
        /** \brief Bytes held beyond the object itself. */
        std::size_t memoryBytes() const { return cells_.capacity() * sizeof(Cell); }

    private:
        /** \brief The centre of cell \e index. */
        Eigen::Vector3d centre(std::size_t index) const;
        /** \brief Sets the side of every clear cell (UNKNOWN on entry), region by region. */
        void decideSides(const TriangleBvh &tree);

        Eigen::Vector3d origin_{Eigen::Vector3d::Zero()};  ///< the grid's lowest corner
        double size_{1.0}, inverseSize_{1.0}, outsideReach_{0.0};
        std::size_t n_[3]{0, 0, 0};
        double counts_[3]{0.0, 0.0, 0.0};  ///< n_ as doubles
        std::vector<Cell> cells_;
    };
}  // namespace meshgap

#endif
