#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/mesh/Refine.h"

using namespace meshgap;

TEST(Refine, ClosedBoxStaysClosedOrientedAndOnItsSurface)
{
    const Mesh box = test::box(1.0, 2.0, 3.0, 1);
    for (double h : {2.0, 0.7, 0.25})
    {
        RefineReport report;
        std::vector<std::uint32_t> parent;
        const Mesh fine = refineMesh(box, h, &report, &parent);
        // Every fine triangle lies in its parent: its corners are on the parent's plane and inside it.
        ASSERT_EQ(parent.size(), fine.triangles.size());
        for (std::size_t t = 0; t < fine.triangles.size(); ++t)
        {
            const Triangle &P = box.triangles[parent[t]];
            const Eigen::Vector3d &p0 = box.vertices[P[0]], &p1 = box.vertices[P[1]], &p2 = box.vertices[P[2]];
            const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
            for (std::uint32_t v : fine.triangles[t])
            {
                const Eigen::Vector3d x = fine.vertices[v];
                EXPECT_NEAR(n.normalized().dot(x - p0), 0.0, 1e-12);
                // Inside: the three sub-areas add up to the whole.
                const double whole = n.norm(), parts = (p1 - x).cross(p2 - x).norm() + (p2 - x).cross(p0 - x).norm() +
                                                       (p0 - x).cross(p1 - x).norm();
                EXPECT_NEAR(parts, whole, 1e-9 * whole);
            }
        }
        EXPECT_LE(longestEdge(fine), h) << h;
        EXPECT_DOUBLE_EQ(report.longestEdge, longestEdge(fine));
        EXPECT_EQ(report.nodesAfter, fine.vertices.size());
        EXPECT_GT(fine.vertices.size(), box.vertices.size());
        // Conforming: a closed surface stays closed (each edge in exactly two triangles) and connected.
        for (const auto &e : test::edgeUse(fine))
            ASSERT_EQ(e.second, 2) << "edge " << e.first.first << "-" << e.first.second << " at h=" << h;
        EXPECT_EQ(countComponents(fine), 1u);
        // Same surface: the area and the enclosed volume are unchanged, and every node lies on the box.
        EXPECT_NEAR(test::area(fine), test::area(box), 1e-12 * test::area(box));
        EXPECT_NEAR(signedVolume(fine), 48.0, 1e-12 * 48.0);
        for (const Eigen::Vector3d &v : fine.vertices)
            EXPECT_NEAR(std::max({std::abs(v.x()) / 1.0, std::abs(v.y()) / 2.0, std::abs(v.z()) / 3.0}), 1.0, 1e-15);
        // The original nodes are kept, first and unchanged.
        for (std::size_t i = 0; i < box.vertices.size(); ++i)
            EXPECT_EQ(fine.vertices[i], box.vertices[i]);
    }
}

TEST(Refine, NonPositiveOrInfiniteGridKeepsTheMesh)
{
    const Mesh box = test::box(1.0, 1.0, 1.0, 2);
    for (double h : {0.0, -1.0, std::numeric_limits<double>::infinity()})
    {
        const Mesh same = refineMesh(box, h);
        EXPECT_EQ(same.vertices, box.vertices);
        EXPECT_EQ(same.triangles, box.triangles);
    }
}

TEST(Refine, LongSliverBecomesBoundedTriangles)
{
    // One 100 x 1 wall triangle pair (as OMPL.app walls are): after refinement no angle collapses badly.
    Mesh wall = test::grid(100.0, 1.0, 1, 1);
    const Mesh fine = refineMesh(wall, 1.0);
    EXPECT_LE(longestEdge(fine), 1.0);
    const double minAngle = test::minimumAngle(fine);
    // Longest-edge bisection keeps angles above half the smallest input angle (Rivara); input min is atan(1/100).
    EXPECT_GE(minAngle, 0.5 * std::atan(0.01));
    EXPECT_NEAR(test::area(fine), 100.0, 1e-9);
    // Boundary edges (used once) lie on the rectangle's border; interior edges are used twice.
    for (const auto &e : test::edgeUse(fine))
        EXPECT_LE(e.second, 2);
}

TEST(Refine, NonManifoldEdgeIsSplitInAllItsTriangles)
{
    // Three triangles share the edge (0,1): a fin. Splitting must keep all three attached to the midpoint.
    Mesh fin;
    fin.vertices = {{0, 0, 0}, {10, 0, 0}, {5, 1, 0}, {5, -1, 0}, {5, 0, 1}};
    fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const Mesh fine = refineMesh(fin, 6.0);
    EXPECT_LE(longestEdge(fine), 6.0);
    EXPECT_EQ(countComponents(fine), 1u);
    int finEdges = 0;
    for (const auto &e : test::edgeUse(fine))
        finEdges += e.second == 3;
    EXPECT_EQ(finEdges, 2);  // (0,m) and (m,1), each still shared by three triangles
}
