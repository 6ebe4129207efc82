#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "TestMeshes.h"
#include "meshgap/geometry/TriangleBvh.h"

using namespace meshgap;

namespace
{
    /** \brief Each node's range of order(): a leaf's own, an inner node's its children's together. */
    void nodeRanges(const TriangleBvh &bvh, std::uint32_t i, std::vector<std::pair<std::uint32_t, std::uint32_t>> &range)
    {
        const TriangleBvh::Node &node = bvh.nodes()[i];
        if (node.isLeaf())
        {
            range[i] = {node.first, node.count};
            return;
        }
        nodeRanges(bvh, node.first, range);
        nodeRanges(bvh, node.first + 1, range);
        range[i] = {range[node.first].first, range[node.first].second + range[node.first + 1].second};
    }

    /** \brief Triangle \e t's box along \e axes (columns): each corner's coordinate axes.col(c) . p summed
        ((x + y) + z); an aligned node's is the triangle's own box. */
    Eigen::AlignedBox3d boxAlong(const Mesh &m, std::uint32_t t, const TriangleBvh::Node &node)
    {
        Eigen::AlignedBox3d box;
        for (std::uint32_t v : m.triangles[t])
        {
            const Eigen::Vector3d &p = m.vertices[v];
            if (node.aligned)
                box.extend(p);
            else
            {
                Eigen::Vector3d q;
                for (int c = 0; c < 3; ++c)
                    q[c] = (node.axes(0, c) * p.x() + node.axes(1, c) * p.y()) + node.axes(2, c) * p.z();
                box.extend(q);
            }
        }
        return box;
    }

    double halfArea(const Eigen::AlignedBox3d &box)
    {
        const Eigen::Vector3d d = box.sizes();
        return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
    }

    /** \brief Every inner node's split is the least-cost cut by brute force: along each of the node's axes in turn,
        its triangles sorted by centroid along the axis (ties by triangle index), every cut's cost (each side's box
        area along the node's axes times its count) compared; the first least cost in the order
        axis 0, 1, 2 and, on an axis, most triangles on the left first. The left child must hold exactly the
        triangles before that cut. Returns the size of the largest rotated inner node. */
    std::uint32_t expectEverySplitLeastCost(const Mesh &m, const std::string &what)
    {
        const TriangleBvh bvh(m);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> range(bvh.nodes().size());
        nodeRanges(bvh, 0, range);
        std::size_t inner = 0;
        std::uint32_t largestRotated = 0;
        for (std::uint32_t i = 0; i < bvh.nodes().size(); ++i)
        {
            const TriangleBvh::Node &node = bvh.nodes()[i];
            if (node.isLeaf())
                continue;
            ++inner;
            const auto [first, count] = range[i];
            if (!node.aligned)
                largestRotated = std::max(largestRotated, count);
            const std::vector<std::uint32_t> triangles(bvh.order().begin() + first,
                                                       bvh.order().begin() + first + count);
            double bestCost = std::numeric_limits<double>::infinity();
            std::vector<std::uint32_t> bestLeft;
            for (int axis = 0; axis < 3; ++axis)
            {
                std::vector<std::pair<double, std::uint32_t>> sorted;
                for (std::uint32_t t : triangles)
                {
                    const Triangle &f = m.triangles[t];
                    const Eigen::Vector3d centroid = (m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]) / 3.0;
                    const Eigen::Vector3d along = node.aligned ? centroid : Eigen::Vector3d(node.axes.transpose() * centroid);
                    sorted.emplace_back(along[axis], t);
                }
                std::sort(sorted.begin(), sorted.end());
                // Each side's box, the union of its triangles' boxes (exact: minima and maxima do not round).
                std::vector<Eigen::AlignedBox3d> before(count + 1), after(count + 1);
                for (std::uint32_t j = 0; j < count; ++j)
                    before[j + 1] = Eigen::AlignedBox3d(before[j]).extend(boxAlong(m, sorted[j].second, node));
                for (std::uint32_t j = count; j-- > 0;)
                    after[j] = Eigen::AlignedBox3d(after[j + 1]).extend(boxAlong(m, sorted[j].second, node));
                std::uint32_t bestK = 0;
                for (std::uint32_t k = count - 1; k >= 1; --k)
                {
                    const double cost = halfArea(before[k]) * k + halfArea(after[k]) * (count - k);
                    if (cost < bestCost)
                    {
                        bestCost = cost;
                        bestK = k;
                    }
                }
                if (bestK > 0)
                {
                    bestLeft.clear();
                    for (std::uint32_t j = 0; j < bestK; ++j)
                        bestLeft.push_back(sorted[j].second);
                }
            }
            const auto [leftFirst, leftCount] = range[node.first];
            const std::set<std::uint32_t> built(bvh.order().begin() + leftFirst,
                                                bvh.order().begin() + leftFirst + leftCount);
            EXPECT_EQ(built, std::set<std::uint32_t>(bestLeft.begin(), bestLeft.end()))
                << what << ": node " << i << " of " << count << " triangles, " << (node.aligned ? "aligned" : "rotated");
        }
        EXPECT_GT(inner, 0u) << what;
        return largestRotated;
    }

    /** \brief \e n random triangles in the unit cube, each repeated \e copies times (equal centroids). */
    Mesh randomSoup(unsigned seed, int n, int copies)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> unit(0.0, 1.0), small(-0.05, 0.05);
        Mesh m;
        m.source = "soup";
        for (int i = 0; i < n; ++i)
        {
            const Eigen::Vector3d c(unit(rng), unit(rng), unit(rng));
            const auto base = static_cast<std::uint32_t>(m.vertices.size());
            for (int k = 0; k < 3; ++k)
                m.vertices.push_back(c + Eigen::Vector3d(small(rng), small(rng), small(rng)));
            for (int r = 0; r < copies; ++r)
                m.triangles.push_back({base, base + 1 + (r % 2), base + 2 - (r % 2)});
        }
        return m;
    }
}  // namespace

TEST(TriangleBvhBuild, EverySplitIsTheLeastCostCutOfASortedOrder)
{
    for (unsigned seed = 1; seed <= 6; ++seed)
        expectEverySplitLeastCost(randomSoup(seed, 60 + 40 * static_cast<int>(seed), 1 + seed % 2),
                                  "soup " + std::to_string(seed));
    // Lattice meshes: many centroids equal along an axis (ties broken by triangle index).
    expectEverySplitLeastCost(test::box(1, 2, 3, 4), "box");
    expectEverySplitLeastCost(test::grid(2, 1, 12, 9), "grid");
    // A larger soup: long runs of the presorted lists partitioned down the tree.
    expectEverySplitLeastCost(randomSoup(8, 2500, 2), "large soup");
    // Turned, elongated: rotated nodes, the largest of them (from 1,024 triangles) sorted by radix too.
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    EXPECT_GE(expectEverySplitLeastCost(test::transformed(test::box(0.2, 0.3, 3, 20), X), "turned box"), 1024u);
    expectEverySplitLeastCost(test::transformed(randomSoup(9, 400, 2), X), "turned soup");
    expectEverySplitLeastCost(test::transformed(test::icosphere(1.0, 3), X), "turned icosphere");
}

TEST(TriangleBvhBuild, AFlatSliverInAnAxisPlaneGetsAFittedBox)
{
    // A disc in the plane z = 0 fanned out from one rim vertex (as CAD exports a round face): slivers crossing the
    // disc at every angle. Both of a sliver's boxes have zero volume there, yet its aligned box can be hundreds of
    // times its area: every leaf's box (its two largest extents) must be within a small factor of its triangle's
    // area, in the axis plane as on the same disc turned.
    const int n = 64;
    Mesh disc;
    disc.source = "fanned disc";
    for (int i = 0; i < n; ++i)
    {
        const double angle = 2.0 * M_PI * i / n;
        disc.vertices.emplace_back(std::cos(angle), std::sin(angle), 0.0);
    }
    for (int i = 1; i + 1 < n; ++i)
        disc.triangles.push_back({0u, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1)});
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
    const std::pair<const char *, Mesh> cases[] = {{"in the plane z = 0", disc},
                                                   {"turned", test::transformed(disc, turn)}};
    for (const auto &[what, m] : cases)
    {
        const TriangleBvh bvh(m);
        double worst = 0.0;
        for (const TriangleBvh::Node &node : bvh.nodes())
        {
            if (!node.isLeaf())
                continue;
            const Triangle &f = m.triangles[bvh.order()[node.first]];
            const double area =
                0.5 * (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]).norm();
            Eigen::Vector3d half = node.half;
            std::sort(half.data(), half.data() + 3);
            worst = std::max(worst, 4.0 * half[1] * half[2] / area);
        }
        EXPECT_LT(worst, 4.0) << what;
    }
}
