// The grid of distance bounds and sides that penetration depth prunes with: every cell's bounds against the brute-force
// distance of random points in it, and every decided side against the winding number over every triangle.

#include <gtest/gtest.h>

#include <random>

#include "TestMeshes.h"
#include "TestNote.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/geometry/SurfaceGrid.h"
#include "meshgap/geometry/TriangleDistance.h"

using namespace meshgap;

namespace
{
    double bruteDistance(const Mesh &m, const Eigen::Vector3d &p)
    {
        double d = std::numeric_limits<double>::infinity();
        Eigen::Vector3d on;
        for (const Triangle &t : m.triangles)
            d = std::min(d, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on));
        return d;
    }

    /** \brief Random points of the grid's box (grown by a cell, and a little beyond it): each inside a cell must lie
        within its bounds and, for a decided cell, on its side. Returns how many points fell in decided cells. */
    std::size_t checkGrid(const Body &body, std::uint32_t seed, int points, const std::string &name)
    {
        const SurfaceGrid &grid = body.surfaceGrid();
        const Mesh &m = body.surface();
        const Eigen::AlignedBox3d box = m.bounds();
        const Eigen::Vector3d lo = box.min().array() - 1.2 * grid.cellSize(),
                              size = box.sizes().array() + 2.4 * grid.cellSize();
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::size_t decided = 0, outsideGrid = 0;
        for (int i = 0; i < points; ++i)
        {
            const Eigen::Vector3d p = lo + Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(size);
            const SurfaceGrid::Cell *cell = grid.cell(p);
            if (!cell)
            {
                ++outsideGrid;
                continue;
            }
            // The same cell through the map to grid coordinates a caller folds into its own.
            EXPECT_EQ(grid.cellAt(grid.toGrid() * p), cell) << name << " point " << i;
            const double d = bruteDistance(m, p);
            EXPECT_LE(cell->lo, d) << name << " point " << i;
            EXPECT_GE(cell->hi, d) << name << " point " << i;
            // The triangle nearest to the cell's centre is within hi of every point of the cell.
            EXPECT_LT(cell->triangle, m.triangles.size()) << name;
            if (cell->triangle >= m.triangles.size())
                continue;
            const Triangle &t = m.triangles[cell->triangle];
            Eigen::Vector3d on;
            EXPECT_LE(pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on), cell->hi)
                << name << " point " << i;
            if (cell->side == SurfaceGrid::Side::INSIDE || cell->side == SurfaceGrid::Side::OUTSIDE)
            {
                ++decided;
                EXPECT_GT(cell->lo, 0.0f) << name << " point " << i;
                EXPECT_EQ(cell->side == SurfaceGrid::Side::INSIDE, containsPoint(body, p)) << name << " point " << i;
            }
            if (!body.isClosed())
            {
                EXPECT_TRUE(cell->side == SurfaceGrid::Side::CROSSING || cell->side == SurfaceGrid::Side::UNKNOWN)
                    << name;
            }
        }
        EXPECT_GT(outsideGrid, 0u) << name;  // the sampled box reaches beyond the grid: null cells are seen
        // outsideReach(): the largest lo of a cell outside, counted over every cell.
        double reach = 0.0;
        for (const SurfaceGrid::Cell &cell : grid.cells())
            if (cell.side == SurfaceGrid::Side::OUTSIDE)
                reach = std::max(reach, double(cell.lo));
        EXPECT_EQ(grid.outsideReach(), reach) << name;
        if (body.isClosed())
        {
            EXPECT_GT(reach, 0.0) << name;
        }
        return decided;
    }
}  // namespace

TEST(SurfaceGrid, BoundsAndSidesAgainstBruteForce)
{
    // A U of three overlapping shells (winding 2 where they overlap), a sphere, a thin plate (cells coarser than its
    // thickness: no inside cell), an open sheet, and a box far from its frame's origin.
    const Mesh u = test::merged(
        test::merged(test::transformed(test::box(1.5, 0.2, 0.5, 3), test::translation(0, -1.0, 0)),
                     test::transformed(test::box(0.2, 1.0, 0.5, 3), test::translation(-1.3, 0, 0))),
        test::transformed(test::box(0.2, 1.0, 0.5, 3), test::translation(1.3, 0, 0)));
    const std::vector<std::pair<std::string, Mesh>> meshes = {
        {"U", u},
        {"sphere", test::icosphere(0.7, 3)},
        {"plate", test::box(1.0, 0.8, 0.01, 2)},
        {"sheet", test::grid(1.0, 0.6, 8, 5)},
        {"far box", test::transformed(test::box(0.3, 0.2, 0.4, 2), test::translation(1e4, -2e4, 5e3))}};
    std::size_t decided = 0;
    for (std::size_t k = 0; k < meshes.size(); ++k)
    {
        const BodyPtr body = Body::build(meshes[k].second);
        const std::size_t limit =
            std::max(SurfaceGrid::MIN_CELLS, SurfaceGrid::CELLS_PER_TRIANGLE * body->surface().triangles.size());
        EXPECT_LE(body->surfaceGrid().numCells(), limit) << meshes[k].first;
        const std::size_t here = checkGrid(*body, 7 + k, 1500, meshes[k].first);
        if (meshes[k].first == "U" || meshes[k].first == "sphere")
        {
            EXPECT_GT(here, 300u) << meshes[k].first;  // the check saw decided cells, inside and outside
        }
        decided += here;
    }
    test::Note() << "[ grid     ] " << decided << " random points in decided cells, on their cell's side\n";
}

TEST(SurfaceGrid, InsideCellsExistInAThickBodyAndBoundTheDepthOfItsCentre)
{
    // A cube of half 1: the cell holding its centre is inside, at a distance between lo and hi that brackets 1.
    const BodyPtr cube = Body::build(test::box(1.0, 1.0, 1.0, 2));
    const SurfaceGrid::Cell *cell = cube->surfaceGrid().cell(Eigen::Vector3d::Zero());
    ASSERT_NE(cell, nullptr);
    EXPECT_EQ(cell->side, SurfaceGrid::Side::INSIDE);
    EXPECT_LE(cell->lo, 1.0f);
    EXPECT_GE(cell->hi, 1.0f);
    // The bounds are a cell's diagonal apart (and the margin).
    EXPECT_LE(cell->hi - cell->lo, std::sqrt(3.0) * cube->surfaceGrid().cellSize() * (1.0 + 1e-6));
    EXPECT_EQ(cube->surfaceGrid().cell(Eigen::Vector3d(5.0, 0.0, 0.0)), nullptr);
}
