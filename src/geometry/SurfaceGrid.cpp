#include "meshgap/geometry/SurfaceGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        float floatBelow(double x)
        {
            const auto f = static_cast<float>(std::max(x, 0.0));
            return static_cast<double>(f) <= x ? f : std::nextafter(f, 0.0f);
        }

        float floatAbove(double x)
        {
            const auto f = static_cast<float>(x);
            return static_cast<double>(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
        }

        /** \brief The side of the surface \e p lies on by a robust ray cast (insideClosedBody()'s directions), or
            UNKNOWN when every ray grazes an edge or a corner. */
        SurfaceGrid::Side sideOf(const TriangleBvh &tree, const Eigen::Vector3d &p)
        {
            static const Eigen::Vector3d directions[] = {Eigen::Vector3d(0.5773, 0.6532, 0.4898),
                                                         Eigen::Vector3d(-0.3217, 0.8469, -0.4234),
                                                         Eigen::Vector3d(0.7071, -0.2764, -0.6508)};
            for (const Eigen::Vector3d &d : directions)
            {
                int winding = 0;
                if (bvhRayWinding(tree, p, d, winding))
                    return winding != 0 ? SurfaceGrid::Side::INSIDE : SurfaceGrid::Side::OUTSIDE;
            }
            return SurfaceGrid::Side::UNKNOWN;
        }
    }  // namespace

    SurfaceGrid SurfaceGrid::build(const TriangleBvh &tree, bool closed)
    {
        SurfaceGrid grid;
        const Mesh &m = tree.mesh();
        if (m.triangles.empty())
            return grid;
        const Eigen::AlignedBox3d box = m.bounds();
        const double diagonal = box.diagonal().norm();
        double s = std::max(diagonal / 40.0, 1e-300);
        auto count = [&](int k) { return static_cast<std::size_t>(std::ceil(box.sizes()[k] / s)) + 2; };
        // A few cells per triangle, at least MIN_CELLS: a small part's grid is as small as the part.
        const std::size_t limit =
            std::clamp<std::size_t>(CELLS_PER_TRIANGLE * m.triangles.size(), MIN_CELLS, MAX_CELLS);
        while (count(0) * count(1) * count(2) > limit)
            s *= 1.1;
        for (int k = 0; k < 3; ++k)
        {
            grid.n_[k] = count(k);
            grid.counts_[k] = double(grid.n_[k]);
        }
        grid.size_ = s;
        grid.inverseSize_ = 1.0 / s;
        grid.origin_ = box.min() - Eigen::Vector3d::Constant(s);
        const double hd = 0.5 * std::sqrt(3.0) * s;
        const double margin = 1e-12 * (grid.origin_.norm() + diagonal + s);
        grid.cells_.resize(grid.n_[0] * grid.n_[1] * grid.n_[2]);
        std::uint32_t hint = UINT32_MAX;   // the triangle nearest to the last centre: near the next one
        for (std::size_t index = 0; index < grid.cells_.size(); ++index)
        {
            const Eigen::Vector3d c = grid.centre(index);
            double upper = std::numeric_limits<double>::infinity();
            if (hint != UINT32_MAX)
            {
                const Triangle &f = m.triangles[hint];
                Eigen::Vector3d on;
                upper = pointTriangleDistance(c, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], on) *
                            (1.0 + 1e-9) + margin;
            }
            BvhPointResult r;
            bvhPointDistance(tree, c, upper, -1.0, r);
            if (!r.found)
                bvhPointDistance(tree, c, std::numeric_limits<double>::infinity(), -1.0, r);
            hint = r.triangle;
            const double d = r.distance, widen = 1e-9 * (d + hd) + margin;
            Cell &cell = grid.cells_[index];
            cell.lo = floatBelow(d - hd - widen);
            cell.hi = floatAbove(d + hd + widen);
            cell.side = d - widen > hd ? Side::UNKNOWN : Side::CROSSING;  // UNKNOWN: clear, side not decided yet
            cell.triangle = r.triangle;
        }
        if (closed)
            grid.decideSides(tree);
        for (const Cell &cell : grid.cells_)
            if (cell.side == Side::OUTSIDE)
                grid.outsideReach_ = std::max(grid.outsideReach_, double(cell.lo));
        return grid;
    }

    Eigen::Vector3d SurfaceGrid::centre(std::size_t index) const
    {
        const std::size_t i = index % n_[0], j = (index / n_[0]) % n_[1], k = index / (n_[0] * n_[1]);
        return origin_ + size_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
    }

    void SurfaceGrid::decideSides(const TriangleBvh &tree)
    {
        // Regions of clear cells sharing faces, one at a time (a flood fill); up to four of a region's cells are
        // tried until a ray decides.
        std::vector<std::uint8_t> seen(cells_.size(), 0);
        std::vector<std::size_t> region;
        const std::size_t stride[3] = {1, n_[0], n_[0] * n_[1]};
        for (std::size_t start = 0; start < cells_.size(); ++start)
        {
            if (seen[start] || cells_[start].side != Side::UNKNOWN)
                continue;
            region.assign(1, start);
            seen[start] = 1;
            for (std::size_t next = 0; next < region.size(); ++next)
            {
                const std::size_t index = region[next];
                const std::size_t at[3] = {index % n_[0], (index / n_[0]) % n_[1], index / stride[2]};
                for (int axis = 0; axis < 3; ++axis)
                    for (const int step : {-1, 1})
                    {
                        if ((step < 0 && at[axis] == 0) || (step > 0 && at[axis] + 1 == n_[axis]))
                            continue;
                        const std::size_t other = step < 0 ? index - stride[axis] : index + stride[axis];
                        if (!seen[other] && cells_[other].side == Side::UNKNOWN)
                        {
                            seen[other] = 1;
                            region.push_back(other);
                        }
                    }
            }
            Side side = Side::UNKNOWN;
            for (std::size_t t = 0; t < 4 && side == Side::UNKNOWN; ++t)
                side = sideOf(tree, centre(region[t * region.size() / 4]));
            for (const std::size_t index : region)
                cells_[index].side = side;
        }
    }
}  // namespace meshgap
