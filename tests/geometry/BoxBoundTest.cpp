// The box bounds the distance traversals prune with (BoxBound.h): never above the distance of the two
// boxes (checked against near-nearest point pairs found by long alternating projection, which are real points of the
// boxes), exact where it must be (boxes facing each other across a face), and, on the nodes of real trees, never above
// the least distance of the triangles under them (brute force over all triangle pairs); the traversals that prune with
// it give the brute-force minimum on flat, slanted plates.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "TestMeshes.h"
#include "TestScale.h"
#include "meshgap/geometry/BoxBound.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

using namespace meshgap;

namespace
{
    Eigen::Matrix3d randomRotation(std::mt19937 &rng)
    {
        std::normal_distribution<double> g;
        return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
    }

    /** \brief A pair of points, one in each box (A = [-ha, ha], B = T + C [-hb, hb]), near the nearest pair: many
        rounds of alternating projection from B's centre. Their distance is at least the boxes' distance. */
    double nearPairDistance(const Eigen::Vector3d &ha, const Eigen::Vector3d &hb, const Eigen::Matrix3d &C,
                            const Eigen::Vector3d &T)
    {
        Eigen::Vector3d q = T, p = T.cwiseMax(-ha).cwiseMin(ha);
        for (int round = 0; round < 400; ++round)
        {
            q = T + C * (C.transpose() * (p - T)).cwiseMax(-hb).cwiseMin(hb);
            p = q.cwiseMax(-ha).cwiseMin(ha);
        }
        return (q - p).norm();
    }

    /** \brief A thin plate (the flat part of a CAD body) of \e n x \e n squares, tilted and placed by \e X. */
    Mesh plate(double w, double h, int n, const Eigen::Isometry3d &X)
    {
        return test::transformed(test::box(w, h, 0.002, n), X);
    }

    /** \brief The triangles (indices) under node \e n. */
    void trianglesUnder(const TriangleBvh &tree, std::uint32_t n, std::vector<std::uint32_t> &out)
    {
        const TriangleBvh::Node &node = tree.nodes()[n];
        if (node.isLeaf())
        {
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                out.push_back(tree.order()[k]);
            return;
        }
        trianglesUnder(tree, node.first, out);
        trianglesUnder(tree, node.first + 1, out);
    }

    /** \brief Corners of triangle \e t of \e m, placed by \e X. */
    std::array<Eigen::Vector3d, 3> corners(const Mesh &m, std::uint32_t t, const Eigen::Isometry3d &X)
    {
        return {X * m.vertices[m.triangles[t][0]], X * m.vertices[m.triangles[t][1]],
                X * m.vertices[m.triangles[t][2]]};
    }

    /** \brief Two bodies of slanted plates with many parallel and nearly parallel faces. */
    Mesh plates(std::uint32_t seed)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        Mesh out;
        for (int k = 0; k < 3; ++k)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = randomRotation(rng);
            X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
            out = test::merged(out, plate(0.6 + 0.3 * u(rng), 0.3 + 0.2 * u(rng), 3, X));
        }
        return out;
    }
    /** \brief The traversals' bound (boxbound::pairBound()) on B seen from A (C, T): an aligned A, B's axes C and
        its centre's offset T, as the traversals hold an aligned pair. With \e faces false, the nearest direction's
        gap alone; \e enough as the traversals pass it (infinity: both directions). */
    double boundOf(const Eigen::Vector3d &ha, const Eigen::Vector3d &hb, const Eigen::Matrix3d &C,
                   const Eigen::Vector3d &T, bool faces = true)
    {
        const boxbound::NodePairView p{&ha, &hb, nullptr, &C, &T};
        const double enough = std::numeric_limits<double>::infinity();
        return faces ? boxbound::pairBound<true>(p, enough) : boxbound::pairBound<false>(p, enough);
    }
}  // namespace

TEST(BoxBound, NeverAboveTheDistanceOfTwoBoxesFlatOrNot)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int apart = 0, tight = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
        Eigen::Vector3d ha(0.01 + u(rng), 0.01 + u(rng), 0.01 + u(rng)),
            hb(0.01 + u(rng), 0.01 + u(rng), 0.01 + u(rng));
        if (trial % 3 == 0)  // flat boxes, as a CAD part's leaves and sheets
        {
            ha[trial % 2] = 1e-6;
            hb[(trial / 2) % 3] = 0.0;
        }
        const Eigen::Matrix3d C = trial % 5 == 0 ? Eigen::Matrix3d::Identity() : randomRotation(rng);
        const Eigen::Vector3d T = 4.0 * Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        const double bound = boundOf(ha, hb, C, T, false);
        const double distance = nearPairDistance(ha, hb, C, T);
        ASSERT_LE(bound, distance + 1e-12) << "trial " << trial << ": the bound is above a real point pair's distance";
        if (distance > 1e-3)
        {
            ++apart;
            tight += bound > 0.99 * distance;
        }
        // B's faces too: the better of the two, still below.
        const double both = boundOf(ha, hb, C, T);
        ASSERT_LE(both, distance + 1e-12) << "trial " << trial;
        ASSERT_GE(both, bound) << "trial " << trial;
    }
    // The bound is meant to prune: within 1 % of the distance on most separated pairs.
    EXPECT_GT(apart, 10000);
    EXPECT_GT(tight, 0.7 * apart) << tight << " of " << apart;
}

TEST(BoxBound, TwoPairsAtOnceGiveEachPairsOwnBound)
{
    // pairBounds() (both pairs in one vector register where SSE2 is there) against pairBound() on each pair: the same
    // value, bit for bit (with B's faces or without), whether both pairs are pruned at the nearest direction, one, or
    // neither; the nodes as the traversals hold them (A's axes or none, B's placed axes, the centres' offset), with A
    // aligned in both pairs, one or neither; and never above a real point pair's distance. Flat boxes, overlapping
    // and concentric ones.
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double INF = std::numeric_limits<double>::infinity();
    struct Case
    {
        Eigen::Vector3d ha, hb, offset, T;
        Eigen::Matrix3d axesA, axesB, C;
        bool aligned;
    };
    auto draw = [&](int trial)
    {
        Case c;
        c.ha = Eigen::Vector3d(0.01 + u(rng), 0.01 + u(rng), 0.01 + u(rng));
        c.hb = Eigen::Vector3d(0.01 + u(rng), 0.01 + u(rng), 0.01 + u(rng));
        if (trial % 3 == 0)
        {
            c.ha[trial % 2] = 1e-6;
            c.hb[(trial / 2) % 3] = 0.0;
        }
        c.aligned = trial % 5 < 2;
        c.axesA = c.aligned ? Eigen::Matrix3d::Identity() : randomRotation(rng);
        c.axesB = trial % 5 == 0 ? Eigen::Matrix3d::Identity() : randomRotation(rng);
        c.offset = trial % 7 == 0 ? Eigen::Vector3d::Zero()
                                  : Eigen::Vector3d(4.0 * (u(rng) - 0.5), 4.0 * (u(rng) - 0.5), 4.0 * (u(rng) - 0.5));
        c.C = c.axesA.transpose() * c.axesB;
        c.T = c.axesA.transpose() * c.offset;
        return c;
    };
    int both = 0, one = 0, neither = 0, touching = 0;
    for (int trial = 0; trial < 20000; ++trial)
    {
        const Case c[2] = {draw(trial), draw(trial / 2 + 1)};
        const double enough = trial % 4 == 0 ? INF : trial % 4 == 1 ? -INF : 2.0 * u(rng) - 0.5;
        boxbound::NodePairView held[2];
        for (int k = 0; k < 2; ++k)
            held[k] = {&c[k].ha, &c[k].hb, c[k].aligned ? nullptr : &c[k].axesA, &c[k].axesB, &c[k].offset};
        double fromHeld[2], nearest[2];
        boxbound::pairBounds(held[0], held[1], enough, fromHeld);
        boxbound::pairBounds<false>(held[0], held[1], enough, nearest);  // the nearest direction's gap alone
        for (int k = 0; k < 2; ++k)
        {
            ASSERT_EQ(fromHeld[k], boxbound::pairBound(held[k], enough)) << "trial " << trial << ", pair " << k;
            ASSERT_EQ(nearest[k], boxbound::pairBound<false>(held[k], enough)) << "trial " << trial << ", pair " << k;
            ASSERT_LE(nearest[k], fromHeld[k]) << "trial " << trial << ", pair " << k;
            const double distance = nearPairDistance(c[k].ha, c[k].hb, c[k].C, c[k].T) + 1e-12;
            ASSERT_LE(fromHeld[k], distance) << "trial " << trial << ", pair " << k;
            touching += fromHeld[k] <= 0.0;
        }
        const int pruned = (fromHeld[0] > enough) + (fromHeld[1] > enough);
        (pruned == 2 ? both : pruned == 1 ? one : neither) += 1;
    }
    // Every branch taken many times.
    EXPECT_GT(both, 1000);
    EXPECT_GT(one, 1000);
    EXPECT_GT(neither, 1000);
    EXPECT_GT(touching, 1000);
}

TEST(BoxBound, ExactAcrossAFaceAnEdgeOrACorner)
{
    const Eigen::Vector3d h(1.0, 0.5, 0.25);
    // The nearest direction's gap alone (B's faces would not tell these apart), exact to its roundoff pad (1e-12
    // of the boxes' sizes and offset, a few 1e-12 here).
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    // Face to face, shifted sideways.
    EXPECT_NEAR(boundOf(h, h, I, Eigen::Vector3d(3.0, 0.4, -0.1), false), 1.0, 1e-11);
    // Corner to corner along the diagonal: the face axes alone give 0.5 at most.
    EXPECT_NEAR(boundOf(h, h, I, Eigen::Vector3d(2.5, 1.5, 1.0), false), std::sqrt(0.25 + 0.25 + 0.25), 1e-11);
    // B turned 45 degrees about z: its edge faces A's face.
    const Eigen::Matrix3d C = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d hb(0.5, 0.5, 0.25);
    EXPECT_NEAR(boundOf(h, hb, C, Eigen::Vector3d(3.0, 0.0, 0.0), false), 2.0 - 0.5 * std::sqrt(2.0), 1e-11);
    // Overlapping boxes: no bound.
    EXPECT_LE(boundOf(h, hb, C, Eigen::Vector3d(1.2, 0.0, 0.0)), 0.0);
}

TEST(BoxBound, EveryNodePairOfTwoTreesBoundsItsTriangles)
{
    for (std::uint32_t seed = 1; seed <= static_cast<std::uint32_t>(test::scaled(3)); ++seed)
    {
        const Mesh ma = plates(seed), mb = plates(100 + seed);
        const TriangleBvh a(ma), b(mb);
        std::mt19937 rng(seed);
        for (int pose = 0; pose < 4; ++pose)
        {
            const Eigen::Isometry3d X = test::randomPose(1000 * seed + pose, 1.5);
            // Every triangle pair's distance, then each node pair's least.
            std::vector<std::vector<double>> d(ma.triangles.size(), std::vector<double>(mb.triangles.size()));
            for (std::uint32_t i = 0; i < ma.triangles.size(); ++i)
                for (std::uint32_t j = 0; j < mb.triangles.size(); ++j)
                {
                    const auto p = corners(ma, i, Eigen::Isometry3d::Identity()), q = corners(mb, j, X);
                    Eigen::Vector3d onA, onB;
                    d[i][j] = triangleDistance(p[0], p[1], p[2], q[0], q[1], q[2], onA, onB);
                }
            // The whole traversal, pruning with these bounds: the brute-force minimum.
            double brute = std::numeric_limits<double>::infinity();
            for (const auto &row : d)
                brute = std::min(brute, *std::min_element(row.begin(), row.end()));
            BvhDistanceResult result;
            bvhDistance(a, b, X, std::numeric_limits<double>::infinity(), -1.0, result);
            EXPECT_NEAR(result.distance, brute, 1e-12) << "seed " << seed << " pose " << pose;
            int pruning = 0;
            for (std::uint32_t na = 0; na < a.nodes().size(); na += 3)
                for (std::uint32_t nb = 0; nb < b.nodes().size(); nb += 2)
                {
                    const TriangleBvh::Node &A = a.nodes()[na], &B = b.nodes()[nb];
                    // As the traversals hold the pair: A's axes (none when aligned), B's placed, the offset.
                    const Eigen::Matrix3d placedAxes = X.linear() * B.axes;
                    const Eigen::Vector3d offset = X * B.center - A.center;
                    const double bound = boxbound::pairBound<true>(
                        {&A.half, &B.half, A.aligned ? nullptr : &A.axes, &placedAxes, &offset},
                        std::numeric_limits<double>::infinity());
                    std::vector<std::uint32_t> ta, tb;
                    trianglesUnder(a, na, ta);
                    trianglesUnder(b, nb, tb);
                    double least = std::numeric_limits<double>::infinity();
                    for (std::uint32_t i : ta)
                        for (std::uint32_t j : tb)
                            least = std::min(least, d[i][j]);
                    ASSERT_LE(bound, least) << "seed " << seed << " pose " << pose << " nodes " << na << ", " << nb;
                    pruning += bound > 0.0;
                }
            EXPECT_GT(pruning, 0);
        }
    }
}
