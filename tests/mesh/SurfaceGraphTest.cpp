#include <gtest/gtest.h>

#include <set>

#include "TestMeshes.h"
#include "meshgap/mesh/SurfaceGraph.h"

using namespace meshgap;

TEST(SurfaceGraph, BoxByHand)
{
    // 8 corners; 12 box edges + 6 face diagonals = 18 undirected edges.
    const Mesh box = test::box(1, 1, 1, 1);
    const SurfaceGraph g(box);
    EXPECT_EQ(g.numNodes(), 8u);
    EXPECT_EQ(g.numEdges(), 18u);
    EXPECT_EQ(g.numComponents(), 1u);
    std::size_t degreeSum = 0;
    for (std::uint32_t i = 0; i < g.numNodes(); ++i)
        degreeSum += g.degree(i);
    EXPECT_EQ(degreeSum, 36u);
    std::multiset<double> lengths(g.lengths().begin(), g.lengths().end());
    EXPECT_EQ(lengths.count(2.0), 24u);  // box edges, both directions
    EXPECT_EQ(std::count_if(g.lengths().begin(), g.lengths().end(),
                            [](double l) { return std::abs(l - std::sqrt(8.0)) < 1e-15; }),
              12);
}

TEST(SurfaceGraph, RowsAreSymmetricSortedAndMatchTheMesh)
{
    const Mesh m = test::icosphere(1.0, 2);
    const SurfaceGraph g(m);
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const Triangle &t : m.triangles)
        for (int k = 0; k < 3; ++k)
            edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    EXPECT_EQ(g.numEdges(), edges.size());
    for (std::uint32_t i = 0; i < g.numNodes(); ++i)
        for (std::uint32_t k = g.offsets()[i]; k < g.offsets()[i + 1]; ++k)
        {
            const std::uint32_t j = g.neighbours()[k];
            EXPECT_TRUE(edges.count(std::minmax(i, j)));
            EXPECT_DOUBLE_EQ(g.lengths()[k], (m.vertices[i] - m.vertices[j]).norm());
            if (k > g.offsets()[i])
            {
                EXPECT_LT(g.neighbours()[k - 1], j);
            }
        }
}

TEST(SurfaceGraph, ComponentsOfSeparateParts)
{
    Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
    far.translation().x() = 10;
    const Mesh m = test::merged(test::merged(test::box(1, 1, 1, 2), test::transformed(test::icosphere(1, 1), far)),
                                test::grid(1, 1, 2, 2));
    const SurfaceGraph g(m);
    EXPECT_EQ(g.numComponents(), 3u);
    EXPECT_EQ(g.component(0), 0u);
    EXPECT_EQ(g.component(static_cast<std::uint32_t>(m.vertices.size() - 1)), 2u);
    EXPECT_EQ(countComponents(m), 3u);
}
