#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/geometry/NodeSizing.h"
#include "meshgap/mesh/Refine.h"

using namespace meshgap;

namespace
{
    // Oracle for an axis-aligned box [-h, h] (half extents \e half): a vertex lies on the faces whose coordinate
    // is at +-half; the opposite face of each is 2 half_k away along its normal, and every other face is either
    // not opposing (90 degrees) or farther. So the feature size is the smallest full extent among its faces' axes.
    double boxFeatureSize(const Eigen::Vector3d &v, const Eigen::Vector3d &half, const Eigen::Vector3d &center)
    {
        double lfs = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k)
            if (std::abs(std::abs(v[k] - center[k]) - half[k]) < 1e-12)
                lfs = std::min(lfs, 2.0 * half[k]);
        return lfs;
    }

    // The size field at any point of the refined mesh, interpolated independently of the refinement's own
    // bookkeeping: barycentric coordinates of the point in its parent input triangle.
    double fieldAt(const Mesh &input, const std::vector<double> &size, std::uint32_t parent, const Eigen::Vector3d &x)
    {
        const Triangle &f = input.triangles[parent];
        const Eigen::Vector3d &a = input.vertices[f[0]], &b = input.vertices[f[1]], &c = input.vertices[f[2]];
        const double whole = (b - a).cross(c - a).norm();
        const double wa = (b - x).cross(c - x).norm() / whole, wb = (c - x).cross(a - x).norm() / whole,
                     wc = (a - x).cross(b - x).norm() / whole;
        return wa * size[f[0]] + wb * size[f[1]] + wc * size[f[2]];
    }

    // A thick box and a thin plate (two components, 10 apart): feature sizes 4 and 0.25.
    Mesh blockAndPlate()
    {
        const Mesh block = test::box(2.0, 2.0, 2.0, 3);
        const Mesh plate = test::transformed(test::box(2.0, 2.0, 0.125, 3), test::translation(10.0, 0.0, 0.0));
        return test::merged(block, plate);
    }
}  // namespace

TEST(NodeSizing, FeatureSizeOfABoxIsItsThicknessAcrossEachVertex)
{
    const Eigen::Vector3d half(0.5, 2.0, 4.0);
    const Mesh box = test::box(half.x(), half.y(), half.z(), 4);
    const std::vector<double> lfs = localFeatureSizes(box);
    ASSERT_EQ(lfs.size(), box.vertices.size());
    for (std::size_t v = 0; v < lfs.size(); ++v)
        EXPECT_NEAR(lfs[v], boxFeatureSize(box.vertices[v], half, Eigen::Vector3d::Zero()), 1e-12)
            << "vertex " << v << " at " << box.vertices[v].transpose();
}

TEST(NodeSizing, FeatureSizeIgnoresOtherPartsFacingAwayAndSeesThoseFacingBack)
{
    // Two unit cubes 0.3 apart along x: a vertex on A's +x face sees B's -x face (0.3 away, facing back) before
    // A's own -x face (1 away); a vertex on A's -x face only sees what is behind it (A's +x face, 1 away).
    const Mesh a = test::box(0.5, 0.5, 0.5, 2);
    const Mesh b = test::transformed(a, test::translation(1.3, 0.0, 0.0));
    const Mesh both = test::merged(a, b);
    const std::vector<double> lfs = localFeatureSizes(both);
    for (std::size_t v = 0; v < a.vertices.size(); ++v)
    {
        const Eigen::Vector3d &x = both.vertices[v];
        const double own = boxFeatureSize(x, Eigen::Vector3d::Constant(0.5), Eigen::Vector3d::Zero());
        const double expected = std::abs(x.x() - 0.5) < 1e-12 ? std::min(own, 0.3) : own;
        EXPECT_NEAR(lfs[v], expected, 1e-12) << x.transpose();
    }
}

TEST(NodeSizing, OpenSheetHasNoFeatureSizeAndGetsTheLargestSize)
{
    const Mesh sheet = test::grid(10.0, 10.0, 4, 4);
    for (double l : localFeatureSizes(sheet))
        EXPECT_TRUE(std::isinf(l));
    AdaptiveSizing rule;
    for (double h : adaptiveNodeSizes(sheet, rule))
        EXPECT_DOUBLE_EQ(h, rule.maxFraction * sheet.size());
}

TEST(NodeSizing, SizesAreTheClampedFractionGradedAlongTheEdges)
{
    const Mesh mesh = blockAndPlate();
    AdaptiveSizing rule;
    rule.featureFraction = 0.5;
    rule.minFraction = 0.01;
    rule.maxFraction = 0.1;
    const double size = mesh.size(), hMin = rule.minFraction * size, hMax = rule.maxFraction * size;
    const std::vector<double> lfs = localFeatureSizes(mesh);

    // Ungraded: the clamped fraction, from the oracle's feature sizes.
    rule.grading = 0.0;
    std::vector<double> h0 = adaptiveNodeSizes(mesh, rule);
    for (std::size_t v = 0; v < h0.size(); ++v)
    {
        const bool onPlate = mesh.vertices[v].x() > 5.0;
        const double oracle = onPlate ? boxFeatureSize(mesh.vertices[v], Eigen::Vector3d(2.0, 2.0, 0.125),
                                                       Eigen::Vector3d(10.0, 0.0, 0.0)) :
                                        boxFeatureSize(mesh.vertices[v], Eigen::Vector3d(2.0, 2.0, 2.0),
                                                       Eigen::Vector3d::Zero());
        EXPECT_NEAR(h0[v], std::clamp(0.5 * oracle, hMin, hMax), 1e-12) << mesh.vertices[v].transpose();
    }

    // Graded: min over u of h0_u + g * (shortest path along the edges), by Floyd-Warshall on the input edges.
    rule.grading = 0.3;
    const std::vector<double> h = adaptiveNodeSizes(mesh, rule);
    const std::size_t n = mesh.vertices.size();
    std::vector<double> d(n * n, std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < n; ++i)
        d[i * n + i] = 0.0;
    for (const Triangle &f : mesh.triangles)
        for (int k = 0; k < 3; ++k)
        {
            const std::uint32_t p = f[k], q = f[(k + 1) % 3];
            d[p * n + q] = d[q * n + p] = (mesh.vertices[p] - mesh.vertices[q]).norm();
        }
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j)
                d[i * n + j] = std::min(d[i * n + j], d[i * n + k] + d[k * n + j]);
    for (std::size_t v = 0; v < n; ++v)
    {
        double oracle = std::numeric_limits<double>::infinity();
        for (std::size_t u = 0; u < n; ++u)
            oracle = std::min(oracle, h0[u] + 0.3 * d[u * n + v]);
        EXPECT_NEAR(h[v], oracle, 1e-12) << v;
        EXPECT_LE(h[v], h0[v]);
    }
    (void)lfs;
}

TEST(NodeSizing, BadRulesAndSizesAreRefusedWithAClearError)
{
    const Mesh box = test::box(1.0, 1.0, 1.0, 1);
    AdaptiveSizing rule;
    rule.featureFraction = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(adaptiveNodeSizes(box, rule), Exception);
    rule = AdaptiveSizing();
    rule.grading = -1.0;
    EXPECT_THROW(adaptiveNodeSizes(box, rule), Exception);
    rule = AdaptiveSizing();
    rule.minFraction = 0.5;
    rule.maxFraction = 0.1;
    EXPECT_THROW(adaptiveNodeSizes(box, rule), Exception);
    EXPECT_THROW(refineMesh(box, std::vector<double>(3, 1.0)), Exception);  // wrong length
    std::vector<double> sizes(box.vertices.size(), 1.0);
    sizes[2] = 0.0;
    EXPECT_THROW(refineMesh(box, sizes), Exception);
}

TEST(AdaptiveRefine, ConstantFieldIsTheUniformRefinement)
{
    const Mesh box = test::box(1.0, 2.0, 3.0, 1);
    for (double h : {1.3, 0.4})
    {
        const Mesh uniform = refineMesh(box, h);
        const Mesh adaptive = refineMesh(box, std::vector<double>(box.vertices.size(), h));
        EXPECT_EQ(uniform.vertices, adaptive.vertices);
        EXPECT_EQ(uniform.triangles, adaptive.triangles);
    }
}

TEST(AdaptiveRefine, ConformingOnTheSurfaceAndEveryEdgeWithinTheField)
{
    const Mesh mesh = blockAndPlate();
    AdaptiveSizing rule;
    rule.featureFraction = 0.5;
    rule.minFraction = 0.005;
    rule.maxFraction = 0.1;
    rule.grading = 0.4;
    const std::vector<double> size = adaptiveNodeSizes(mesh, rule);
    RefineReport report;
    std::vector<std::uint32_t> parent;
    const Mesh fine = refineMesh(mesh, size, &report, &parent);
    ASSERT_EQ(parent.size(), fine.triangles.size());
    EXPECT_EQ(report.nodesAfter, fine.vertices.size());
    // Closed surfaces stay closed (no hanging node: each edge in exactly two triangles), same two components.
    for (const auto &e : test::edgeUse(fine))
        ASSERT_EQ(e.second, 2) << e.first.first << "-" << e.first.second;
    EXPECT_EQ(countComponents(fine), 2u);
    EXPECT_NEAR(test::area(fine), test::area(mesh), 1e-12 * test::area(mesh));
    // Input nodes kept first; every node on its parent's plane.
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        EXPECT_EQ(fine.vertices[i], mesh.vertices[i]);
    // Every edge is within the field at its midpoint (interpolated from the parent input triangle).
    for (std::size_t t = 0; t < fine.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
        {
            const Eigen::Vector3d &p = fine.vertices[fine.triangles[t][k]], &q = fine.vertices[fine.triangles[t][(k + 1) % 3]];
            const double field = fieldAt(mesh, size, parent[t], 0.5 * (p + q));
            EXPECT_LE((p - q).norm(), field * (1.0 + 1e-12)) << "triangle " << t;
        }
    // The plate (feature 0.25, size 0.125 before grading) is fine; the block, far from it, is coarse.
    double plateLongest = 0.0, blockShortest = std::numeric_limits<double>::infinity();
    for (const Triangle &f : fine.triangles)
        for (int k = 0; k < 3; ++k)
        {
            const Eigen::Vector3d &p = fine.vertices[f[k]], &q = fine.vertices[f[(k + 1) % 3]];
            if (p.x() > 5.0)
                plateLongest = std::max(plateLongest, (p - q).norm());
            else
                blockShortest = std::min(blockShortest, (p - q).norm());
        }
    EXPECT_LE(plateLongest, 0.125 * (1.0 + 1e-12));
    EXPECT_GE(blockShortest, 0.5 * 0.1 * mesh.size() / 2.0);  // never split below half of the block's size
    // Node counts: more than the coarse uniform grid, far fewer than the uniform grid at the plate's size.
    const std::size_t fineUniform = refineMesh(mesh, 0.125).vertices.size();
    const std::size_t coarseUniform = refineMesh(mesh, 0.1 * mesh.size()).vertices.size();
    EXPECT_GT(fine.vertices.size(), coarseUniform);
    EXPECT_LT(fine.vertices.size(), fineUniform / 2);
}

TEST(AdaptiveRefine, BodyUsesTheAdaptiveNodesAndKeepsTheSurface)
{
    const Mesh mesh = blockAndPlate();
    BodyOptions options;
    options.sizing = GridSizing::ADAPTIVE;
    const BodyPtr body = Body::build(mesh, options);
    EXPECT_TRUE(body->adaptiveSizing());
    const Mesh expected = refineMesh(mesh, adaptiveNodeSizes(mesh, options.adaptive));
    EXPECT_EQ(body->mesh().vertices, expected.vertices);
    EXPECT_EQ(body->surface().vertices, mesh.vertices);
    EXPECT_LE(longestEdge(body->mesh()), body->gridSize() * (1.0 + 1e-12));
}

TEST(AdaptiveRefine, AFineRegionBesideACoarseOneKeepsTheInputAnglesBounded)
{
    // Right triangles (45 degrees) of 0.5; a size of 0.1 left of x = 5 and 1 right of it. Rivara's rule (a
    // triangle's longest edge first) keeps every angle at least half the smallest input angle.
    const Mesh square = test::grid(10.0, 10.0, 20, 20);
    std::vector<double> size(square.vertices.size());
    for (std::size_t v = 0; v < size.size(); ++v)
        size[v] = square.vertices[v].x() < 5.0 - 1e-9 ? 0.1 : 1.0;
    const Mesh fine = refineMesh(square, size);
    EXPECT_GE(test::minimumAngle(fine), 0.5 * M_PI / 4.0);
    for (const auto &e : test::edgeUse(fine))
        EXPECT_LE(e.second, 2);
    EXPECT_NEAR(test::area(fine), 100.0, 1e-9);
}

TEST(AdaptiveRefine, SizesVaryingAlongASliverKeepBoundedAngles)
{
    // One 100 x 1 wall (two slivers, as OMPL.app walls are) with a size of 0.05 at one end and 5 at the other:
    // without Rivara's rule (split a triangle's longest edge first) the fine end's short splits cut slivers again.
    const Mesh wall = test::grid(100.0, 1.0, 1, 1);
    std::vector<double> size(wall.vertices.size());
    for (std::size_t v = 0; v < size.size(); ++v)
        size[v] = wall.vertices[v].x() < 50.0 ? 0.05 : 5.0;
    std::vector<std::uint32_t> parent;
    const Mesh fine = refineMesh(wall, size, nullptr, &parent);
    const double minAngle = test::minimumAngle(fine);
    EXPECT_GE(minAngle, 0.5 * std::atan(0.01));
    EXPECT_NEAR(test::area(fine), 100.0, 1e-9);
    for (const auto &e : test::edgeUse(fine))
        EXPECT_LE(e.second, 2);
    for (std::size_t t = 0; t < fine.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
        {
            const Eigen::Vector3d &p = fine.vertices[fine.triangles[t][k]], &q = fine.vertices[fine.triangles[t][(k + 1) % 3]];
            EXPECT_LE((p - q).norm(), fieldAt(wall, size, parent[t], 0.5 * (p + q)) * (1.0 + 1e-12));
        }
}
