#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <queue>
#include <thread>
#include <vector>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/geometry/Body.h"

using namespace meshgap;

namespace
{
    /** \brief Three separate boxes with their vertices interleaved (one of each in turn, the third box's first),
        after a vertex no triangle uses: parts whose first vertices are not in the order of their triangles. */
    Mesh interleavedParts()
    {
        const Mesh parts[3] = {test::box(1.0, 0.5, 0.3, 2), test::box(0.4, 0.4, 0.4, 1), test::box(2.0, 0.2, 0.2, 3)};
        Mesh m;
        m.source = "test::interleaved";
        m.vertices.emplace_back(9.0, 9.0, 9.0);  // used by no triangle: a component of its own
        std::vector<std::vector<std::uint32_t>> index(3);
        const Eigen::Vector3d offsets[3] = {{0.0, 0.0, 0.0}, {3.0, 0.0, 0.0}, {0.0, 3.0, 0.0}};
        const std::size_t most = std::max({parts[0].vertices.size(), parts[1].vertices.size(),
                                           parts[2].vertices.size()});
        for (std::size_t v = 0; v < most; ++v)
            for (int k : {2, 0, 1})
                if (v < parts[k].vertices.size())
                {
                    index[k].push_back(static_cast<std::uint32_t>(m.vertices.size()));
                    m.vertices.push_back(parts[k].vertices[v] + offsets[k]);
                }
        for (int k = 0; k < 3; ++k)
            for (const Triangle &f : parts[k].triangles)
                m.triangles.push_back({index[k][f[0]], index[k][f[1]], index[k][f[2]]});
        return m;
    }

    /** \brief Oracle: the smallest node of each connected component of the node mesh, components in order of their
        smallest node, by breadth-first search over the node mesh's triangles. */
    std::vector<std::uint32_t> firstNodePerComponent(const Mesh &nodes)
    {
        const std::size_t n = nodes.vertices.size();
        std::vector<std::vector<std::uint32_t>> neighbours(n);
        for (const Triangle &f : nodes.triangles)
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    if (i != j)
                        neighbours[f[i]].push_back(f[j]);
        std::vector<bool> seen(n, false);
        std::vector<std::uint32_t> first;
        for (std::uint32_t start = 0; start < n; ++start)
        {
            if (seen[start])
                continue;
            first.push_back(start);
            std::queue<std::uint32_t> open;
            open.push(start);
            seen[start] = true;
            while (!open.empty())
            {
                const std::uint32_t v = open.front();
                open.pop();
                for (std::uint32_t w : neighbours[v])
                    if (!seen[w])
                    {
                        seen[w] = true;
                        open.push(w);
                    }
            }
        }
        return first;
    }
}  // namespace

// The point per part that containment reads is found from the surface at build; it must be the node the node layer
// (built later, on first use) would pick: the first node of each component of the refined mesh.
TEST(BodyNodeLayer, ComponentPointsFromTheSurfaceAreTheNodeLayersFirstNodes)
{
    for (double grid : {-1.0, 0.0, 0.15})
    {
        BodyOptions options;
        options.gridSize = grid;
        const BodyPtr body = Body::build(interleavedParts(), options);
        const std::vector<std::uint32_t> eager = body->componentNodes();  // read before the node layer exists
        const std::vector<std::uint32_t> oracle = firstNodePerComponent(body->mesh());
        EXPECT_EQ(eager, oracle) << "grid " << grid;
        EXPECT_EQ(eager.size(), 4u);  // three boxes and the unused vertex
        ASSERT_GE(body->numNodes(), body->surface().vertices.size());
        for (std::uint32_t v = 0; v < body->surface().vertices.size(); ++v)
        {
            ASSERT_EQ(body->node(v), body->surface().vertices[v]) << "node " << v << ", grid " << grid;
        }
        if (grid > 0.0)
        {
            EXPECT_GT(body->numNodes(), body->surface().vertices.size());  // refined: nodes were added
        }
    }
}

// Many threads reaching the node layer of a fresh body at once: one build, and every thread sees the layer a body
// built from the same mesh and read on one thread has.
TEST(BodyNodeLayer, FirstUseFromManyThreadsGivesTheSameLayer)
{
    const Mesh mesh = test::box(1.0, 0.7, 0.4, 6);
    const BodyPtr reference = Body::build(mesh);
    const std::uint32_t n = reference->numNodes();
    const std::vector<NodeCluster> &clusters = reference->clusters();
    for (int round = 0; round < 5; ++round)
    {
        const BodyPtr body = Body::build(mesh);
        std::atomic<int> ready{0}, wrong{0};
        auto read = [&](int which)
        {
            ++ready;
            while (ready.load() < 8)
                std::this_thread::yield();
            const std::uint32_t count = which % 2 ? body->numNodes() : body->graph().numNodes();
            if (count != n || body->clusters().size() != clusters.size() ||
                body->radiusAboutOrigin() != reference->radiusAboutOrigin())
                ++wrong;
            for (std::uint32_t i = 0; i < count && i < n; ++i)
                if (body->node(i) != reference->node(i) || body->clusterOrder()[i] != reference->clusterOrder()[i])
                    ++wrong;
        };
        std::vector<std::thread> threads;
        for (int t = 0; t < 8; ++t)
            threads.emplace_back(read, t);
        for (std::thread &t : threads)
            t.join();
        EXPECT_EQ(wrong.load(), 0) << "round " << round;
        EXPECT_EQ(&body->mesh(), &body->mesh());  // one layer, not one per caller
    }
}

// The node layer is built on first use, but a bad adaptive rule is still refused when the body is built.
TEST(BodyNodeLayer, BadAdaptiveRuleFailsAtBuild)
{
    BodyOptions options;
    options.sizing = GridSizing::ADAPTIVE;
    options.adaptive.minFraction = -1.0;
    EXPECT_THROW(Body::build(test::box(1.0, 1.0, 1.0), options), Exception);
    options.adaptive.minFraction = 0.5;
    options.adaptive.maxFraction = 0.1;
    EXPECT_THROW(Body::build(test::box(1.0, 1.0, 1.0), options), Exception);
}

// The ball tree over the node clusters, checked by brute force: clusters hold every node once, in at most 32 each;
// each entry's ball holds every node of its clusters; the entries are depth first (a subtree's clusters are
// consecutive, its entries end at skip), the leaves are the clusters in their order, and an inner entry's clusters
// are exactly its children's.
TEST(BodyNodeLayer, ClusterTreeBallsHoldTheirNodesAndCoverEveryClusterOnce)
{
    for (const Mesh &mesh : {test::icosphere(1.0, 3), test::box(2.0, 0.1, 0.7, 4), test::box(1.0, 1.0, 1.0, 1)})
    {
        const BodyPtr body = Body::build(mesh);
        const std::vector<NodeCluster> &clusters = body->clusters();
        const std::vector<ClusterBall> &tree = body->clusterTree();
        std::vector<int> seen(body->numNodes(), 0);
        for (const NodeCluster &c : clusters)
        {
            EXPECT_LE(c.end - c.begin, 32u);
            for (std::uint32_t k = c.begin; k < c.end; ++k)
                ++seen[body->clusterOrder()[k]];
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(body->numNodes()));
        ASSERT_FALSE(tree.empty());
        EXPECT_EQ(tree[0].firstCluster, 0u);
        EXPECT_EQ(tree[0].endCluster, clusters.size());
        EXPECT_EQ(tree[0].skip, tree.size());
        std::uint32_t leaves = 0;
        for (std::uint32_t e = 0; e < tree.size(); ++e)
        {
            const ClusterBall &ball = tree[e];
            ASSERT_GT(ball.skip, e);
            ASSERT_LE(ball.skip, tree.size());
            for (std::uint32_t c = ball.firstCluster; c < ball.endCluster; ++c)
                for (std::uint32_t k = clusters[c].begin; k < clusters[c].end; ++k)
                    EXPECT_LE((body->node(body->clusterOrder()[k]) - ball.center).norm(), ball.radius) << e;
            if (ball.skip == e + 1)
            {
                // A leaf: the next cluster, its own ball.
                EXPECT_EQ(ball.firstCluster, leaves);
                EXPECT_EQ(ball.endCluster, leaves + 1);
                EXPECT_EQ(ball.center, clusters[leaves].center);
                EXPECT_EQ(ball.radius, clusters[leaves].radius);
                ++leaves;
                continue;
            }
            // Inner: its children follow it and tile its subtree and its clusters, in order.
            std::uint32_t child = e + 1, cluster = ball.firstCluster;
            int children = 0;
            while (child < ball.skip)
            {
                EXPECT_EQ(tree[child].firstCluster, cluster) << e;
                cluster = tree[child].endCluster;
                child = tree[child].skip;
                ++children;
            }
            EXPECT_EQ(child, ball.skip) << e;
            EXPECT_EQ(cluster, ball.endCluster) << e;
            EXPECT_EQ(children, 2) << e;
        }
        EXPECT_EQ(leaves, clusters.size());
    }
}
