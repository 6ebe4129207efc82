// The general mesh operations (meshgap/mesh/MeshOperations.h) and the one component labeller (labelComponents() in
// Mesh.h), against Boost.Graph's connected components and hand counts.

#include <gtest/gtest.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/mesh/SurfaceGraph.h"

using namespace meshgap;

namespace
{
    /** \brief Random triangles over \e n vertices (some vertices in no triangle), fixed seed. */
    Mesh randomIndexedSoup(std::uint32_t seed, std::uint32_t n, std::size_t triangles)
    {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<std::uint32_t> pick(0, n - 1);
        Mesh m;
        m.source = "soup " + std::to_string(seed);
        for (std::uint32_t i = 0; i < n; ++i)
            m.vertices.emplace_back(i, 0.5 * i, 0.25 * i);
        for (std::size_t t = 0; t < triangles; ++t)
            m.triangles.push_back({pick(rng), pick(rng), pick(rng)});
        return m;
    }

    /** \brief The oracle: Boost.Graph's connected components over the triangle edges. */
    std::vector<int> boostComponents(const Mesh &m, int &count)
    {
        boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> g(m.vertices.size());
        for (const Triangle &t : m.triangles)
            for (int k = 0; k < 3; ++k)
                boost::add_edge(t[k], t[(k + 1) % 3], g);
        std::vector<int> label(m.vertices.size());
        count = m.vertices.empty() ? 0 : boost::connected_components(g, label.data());
        return label;
    }
}  // namespace

TEST(MeshOperations, LabelComponentsMatchesBoostGraph)
{
    for (std::uint32_t seed = 1; seed <= 30; ++seed)
    {
        const Mesh m = randomIndexedSoup(seed, 40, seed % 20);
        int expected = 0;
        const std::vector<int> oracle = boostComponents(m, expected);
        std::uint32_t count = 0;
        const std::vector<std::uint32_t> label = labelComponents(m, count);
        ASSERT_EQ(static_cast<int>(count), expected) << "seed " << seed;
        EXPECT_EQ(countComponents(m), count) << "seed " << seed;
        EXPECT_EQ(SurfaceGraph(m).numComponents(), count) << "seed " << seed;
        // The same partition, numbered in order of first vertex.
        std::uint32_t next = 0;
        for (std::size_t u = 0; u < m.vertices.size(); ++u)
        {
            if (label[u] == next)
                ++next;
            EXPECT_LT(label[u], next) << "seed " << seed << " vertex " << u;
            for (std::size_t v = 0; v < u; ++v)
                EXPECT_EQ(label[u] == label[v], oracle[u] == oracle[v]) << "seed " << seed;
        }
    }
}

TEST(MeshOperations, SplitComponentsGivesEachPartWithItsOwnVertices)
{
    const Mesh a = test::box(1, 1, 1), b = test::transformed(test::icosphere(0.5, 1), test::translation(5, 0, 0));
    Mesh both = mergeMeshes({a, b}, "both");
    both.vertices.emplace_back(9, 9, 9);  // in no triangle: dropped
    const std::vector<Mesh> parts = splitComponents(both);
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[0].source, "both#0");
    EXPECT_EQ(parts[1].source, "both#1");
    EXPECT_EQ(parts[0].vertices, a.vertices);
    EXPECT_EQ(parts[0].triangles, a.triangles);
    EXPECT_EQ(parts[1].vertices, b.vertices);
    EXPECT_EQ(parts[1].triangles, b.triangles);
    EXPECT_EQ(splitComponents(a).front().source, a.source);  // one part keeps the name

    Mesh bad = a;
    bad.triangles.push_back({0, 1, 99});
    EXPECT_THROW(splitComponents(bad), Exception);
}

TEST(MeshOperations, VolumeMeanAndTransformOfABox)
{
    Mesh box = test::box(1, 2, 3);  // half-sizes: volume 2 x 4 x 6
    EXPECT_NEAR(signedVolume(box), 48.0, 1e-12);
    EXPECT_LT(vertexMean(box).norm(), 1e-12);
    const Eigen::Isometry3d X = test::randomPose(7, 4.0);
    transformMesh(box, X);
    EXPECT_NEAR(signedVolume(box), 48.0, 1e-9);  // a rigid motion keeps the volume
    EXPECT_LT((vertexMean(box) - X.translation()).norm(), 1e-12);
    EXPECT_EQ(vertexMean(Mesh()), Eigen::Vector3d::Zero());
}

// countEdges() against a count kept in a std::map of undirected edges, on random triangle soups over few vertices
// (so edges are shared by one, two or many triangles, and some vertices are used by none).
TEST(MeshOperations, CountEdgesMatchesAMapOfEdges)
{
    std::mt19937 rng(7);
    for (int round = 0; round < 200; ++round)
    {
        Mesh mesh;
        const std::uint32_t n = 3 + rng() % 12;
        for (std::uint32_t v = 0; v < n + 2; ++v)  // the last two vertices are never used
            mesh.vertices.emplace_back(double(v), double(v * v % 7), double(v % 3));
        const int triangles = 1 + static_cast<int>(rng() % 40);
        for (int t = 0; t < triangles; ++t)
        {
            Triangle f{std::uint32_t(rng() % n), std::uint32_t(rng() % n), std::uint32_t(rng() % n)};
            if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2])
                mesh.triangles.push_back(f);
        }
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const Triangle &f : mesh.triangles)
            for (int k = 0; k < 3; ++k)
                ++uses[std::minmax(f[k], f[(k + 1) % 3])];
        std::size_t boundary = 0, nonManifold = 0;
        for (const auto &edge : uses)
        {
            boundary += edge.second == 1;
            nonManifold += edge.second >= 3;
        }
        const EdgeReport report = countEdges(mesh);
        EXPECT_EQ(report.boundaryEdges, boundary) << "round " << round;
        EXPECT_EQ(report.nonManifoldEdges, nonManifold) << "round " << round;
    }
    EXPECT_TRUE(countEdges(test::box(1.0, 2.0, 3.0, 3)).closed());
}
