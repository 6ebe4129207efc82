// The certificate a warm start keeps (BvhFront): after every query its entries must still be a cut through the tree
// of node pairs (every triangle pair under exactly one entry) whose bounds, lowered by the motion since, are real
// lower bounds, checked by brute force over all triangle pairs; and a traversal from it must give the cold answer
// bit for bit. Along scene paths (tests/scene/WarmCertificateTest.cpp) the same is checked through Scene.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

using namespace meshgap;

namespace
{
    /** \brief The first and one-past-last leaf positions (order()) under node \e n. */
    std::pair<std::uint32_t, std::uint32_t> leafRange(const TriangleBvh &tree, std::uint32_t n)
    {
        const TriangleBvh::Node &node = tree.nodes()[n];
        if (node.isLeaf())
            return {node.first, node.first + node.count};
        return {leafRange(tree, node.first).first, leafRange(tree, node.first + 1).second};
    }

    /** \brief A bumpy, concave body: a refined box with a dent pushed into one face, and a sphere stuck to it. */
    Mesh bumpy(double scale, int n)
    {
        Mesh box = test::box(scale, 0.6 * scale, 0.4 * scale, n);
        for (Eigen::Vector3d &v : box.vertices)
            if (v.z() > 0.39 * scale)
                v.z() -= 0.3 * scale * std::exp(-(v.x() * v.x() + v.y() * v.y()) / (0.2 * scale * scale));
        return test::merged(box, test::transformed(test::icosphere(0.3 * scale, 1), test::translation(scale, 0, 0)));
    }

    /** \brief Poses of B winding around and through A: small steps (as a planner's motion checks) with, every 60
        steps, a jump (as a tree's next extension elsewhere). */
    std::vector<Eigen::Isometry3d> winding(std::uint32_t seed, std::size_t count)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        std::vector<Eigen::Isometry3d> out;
        Eigen::Vector3d p(2.5, 0.0, 0.5), v(-0.02, 0.01, 0.0);
        Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
        Eigen::Vector3d w(0.01, 0.02, 0.015);
        for (std::size_t i = 0; i < count; ++i)
        {
            if (i % 60 == 59)
                p = Eigen::Vector3d(2.0 * u(rng), 1.5 * u(rng), 1.2 * u(rng));  // a jump
            p += v;
            if (p.norm() > 3.0)
                v = -0.5 * v;
            v += 0.004 * Eigen::Vector3d(u(rng), u(rng), u(rng));
            q = (q * Eigen::Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized()))).normalized();
            w += 0.003 * Eigen::Vector3d(u(rng), u(rng), u(rng));
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q.toRotationMatrix();
            X.translation() = p;
            out.push_back(X);
        }
        return out;
    }
}  // namespace

TEST(BvhFront, EveryEntryStaysALowerBoundAndTheFrontACutAlongAMotion)
{
    const Mesh ma = bumpy(1.0, 4), mb = bumpy(0.5, 3);
    const TriangleBvh a(ma), b(mb);
    const std::size_t na = ma.triangles.size(), nb = mb.triangles.size();
    BvhFront front;
    std::size_t checked = 0, touching = 0, pose = 0;
    std::vector<std::uint8_t> covered(na * nb);
    // Every pose is queried (the front carried along is the same at any scale); the brute-force oracle looks at
    // every one at full scale, at every stride()-th under MESHGAP_TEST_SCALE.
    const std::size_t stride = static_cast<std::size_t>(test::stride());
    for (const Eigen::Isometry3d &X : winding(7, 360))
    {
        const bool look = pose++ % stride == 0;
        BvhDistanceResult warm, cold;
        bvhDistance(a, b, X, std::numeric_limits<double>::infinity(), 0.0, warm, UINT32_MAX, UINT32_MAX, &front);
        bvhDistance(a, b, X, std::numeric_limits<double>::infinity(), 0.0, cold);
        ASSERT_EQ(warm.distance, cold.distance);
        if (cold.distance > 0.0)
        {
            // The canonical pair (a touching pair ends the search where it is met: any one will do there).
            ASSERT_EQ(warm.triangleA, cold.triangleA);
            ASSERT_EQ(warm.triangleB, cold.triangleB);
            ASSERT_EQ(warm.onA, cold.onA);
        }
        touching += cold.distance == 0.0;
        if (!front.valid || !look)
            continue;  // to be rebuilt: nothing claimed

        // The oracle: every triangle pair, exactly, at this pose.
        std::vector<double> exact(na * nb);
        Eigen::Vector3d onA, onB, pb[3];
        for (std::uint32_t tb = 0; tb < nb; ++tb)
        {
            for (int k = 0; k < 3; ++k)
                pb[k] = X * mb.vertices[mb.triangles[tb][k]];
            for (std::uint32_t ta = 0; ta < na; ++ta)
            {
                const Triangle &f = ma.triangles[ta];
                exact[ta * nb + tb] = triangleDistance(ma.vertices[f[0]], ma.vertices[f[1]], ma.vertices[f[2]], pb[0],
                                                       pb[1], pb[2], onA, onB);
            }
        }
        std::fill(covered.begin(), covered.end(), 0);
        for (const BvhFront::Entry &e : front.entries)
        {
            const double bound = e.key - front.motion;
            const auto [a0, a1] = leafRange(a, e.a);
            const auto [b0, b1] = leafRange(b, e.b);
            for (std::uint32_t i = a0; i < a1; ++i)
                for (std::uint32_t j = b0; j < b1; ++j)
                {
                    const std::uint32_t ta = a.order()[i], tb = b.order()[j];
                    ++covered[ta * nb + tb];
                    // A lower bound at this pose (to roundoff of the scene's scale).
                    ASSERT_LE(bound, exact[ta * nb + tb] + 1e-12) << "entry (" << e.a << ", " << e.b << ")";
                }
        }
        for (std::size_t k = 0; k < covered.size(); ++k)
            ASSERT_EQ(covered[k], 1) << "triangle pair " << k / nb << ", " << k % nb << " covered " << int(covered[k])
                                     << " times";
        ++checked;
    }
    test::Note() << "[ front    ] " << checked << " fronts checked; entries kept " << front.reused << ", re-tested "
                 << front.retested << ", rebuilds " << front.rebuilds << ", " << touching << " touching poses\n";
    EXPECT_GT(checked, 200u / stride);
    EXPECT_GT(touching, 5u);  // the motion passes through A: collisions (early stops) on the way
    // The fronts checked were used: most queries started from one (the jumps and the deep contacts rebuild it), and
    // kept part of it without a test.
    EXPECT_LT(front.rebuilds, 120u);
    EXPECT_GT(front.rebuilds, 2u);
    EXPECT_GT(front.reused, front.retested / 10);
}

TEST(BvhFront, ACollisionFrontGivesTheStatelessVerdictAndEveryEntryStaysApart)
{
    // bvhCollide() with a front along the winding motion (small steps through A, jumps): the stateless verdict at
    // every pose, a reported pair that really intersects, and every entry of a valid front apart by its bound (key -
    // motion, above the margin) at that pose, checked over all of its triangle pairs.
    const Mesh ma = bumpy(1.0, 4), mb = bumpy(0.5, 3);
    const TriangleBvh a(ma), b(mb);
    const std::size_t nb = mb.triangles.size();
    BvhFront front;
    std::size_t checked = 0, hits = 0, entries = 0, pose = 0;
    Eigen::Vector3d onA, onB, pb[3];
    const std::size_t stride = static_cast<std::size_t>(test::stride());  // the oracle's share of the poses
    for (const Eigen::Isometry3d &X : winding(11, 600))
    {
        const bool look = pose++ % stride == 0;
        std::uint32_t ta = 0, tb = 0;
        const bool warm = bvhCollide(a, b, X, front, &ta, &tb);
        ASSERT_EQ(warm, bvhCollide(a, b, X));
        if (warm)
        {
            ++hits;
            const Triangle &f = ma.triangles[ta], &g = mb.triangles[tb];
            ASSERT_TRUE(trianglesIntersect(ma.vertices[f[0]], ma.vertices[f[1]], ma.vertices[f[2]],
                                           X * mb.vertices[g[0]], X * mb.vertices[g[1]], X * mb.vertices[g[2]]));
            ASSERT_FALSE(front.valid);
            continue;
        }
        if (!front.valid || !look)
            continue;
        std::vector<std::uint8_t> covered(ma.triangles.size() * nb, 0);
        for (const BvhFront::Entry &e : front.entries)
        {
            const double bound = e.key - front.motion;
            const auto [a0, a1] = leafRange(a, e.a);
            const auto [b0, b1] = leafRange(b, e.b);
            for (std::uint32_t j = b0; j < b1; ++j)
            {
                const Triangle &g = mb.triangles[b.order()[j]];
                for (int k = 0; k < 3; ++k)
                    pb[k] = X * mb.vertices[g[k]];
                for (std::uint32_t i = a0; i < a1; ++i)
                {
                    const Triangle &f = ma.triangles[a.order()[i]];
                    ++covered[a.order()[i] * nb + b.order()[j]];
                    const double d = triangleDistance(ma.vertices[f[0]], ma.vertices[f[1]], ma.vertices[f[2]], pb[0],
                                                      pb[1], pb[2], onA, onB);
                    ASSERT_GT(d, 0.0);
                    ASSERT_LE(bound, d + 1e-12) << "entry (" << e.a << ", " << e.b << ")";
                }
            }
        }
        for (std::uint8_t c : covered)
            ASSERT_EQ(c, 1);  // a cut: every triangle pair under exactly one entry
        entries += front.entries.size();
        ++checked;
    }
    EXPECT_GT(hits, 20u);     // the motion passes through A
    EXPECT_GT(checked, 50u / stride);  // and fronts were kept and used between the contacts and the jumps
    EXPECT_GT(front.reused, front.retested);
    EXPECT_GT(front.incoherent, 5u);  // the jumps do not write a front
    EXPECT_GT(entries, checked);
}

namespace
{
    /** \brief Whether some triangle of \e ma intersects some triangle of \e mb placed by \e X, over every pair. B's
        corners are placed as bvhCollide() places them (rotation times corner, plus translation), bit for bit: at a
        pose where a pair's verdict changes (found by bisection) another rounding of the placement could change it. */
    bool bruteForceCollide(const Mesh &ma, const Mesh &mb, const Eigen::Isometry3d &X)
    {
        const Eigen::Matrix3d R = X.linear();
        const Eigen::Vector3d t = X.translation();
        Eigen::Vector3d pb[3];
        for (const Triangle &g : mb.triangles)
        {
            for (int k = 0; k < 3; ++k)
                pb[k] = R * mb.vertices[g[k]] + t;
            for (const Triangle &f : ma.triangles)
                if (trianglesIntersect(ma.vertices[f[0]], ma.vertices[f[1]], ma.vertices[f[2]], pb[0], pb[1], pb[2]))
                    return true;
        }
        return false;
    }

    /** \brief A disc of radius \e r in the plane z = 0, fanned out from one rim vertex into slivers (as CAD exports a
        round face). */
    Mesh fannedDisc(double r, int n)
    {
        Mesh m;
        m.source = "fanned disc";
        for (int i = 0; i < n; ++i)
            m.vertices.emplace_back(r * std::cos(2.0 * M_PI * i / n), r * std::sin(2.0 * M_PI * i / n), 0.0);
        for (int i = 1; i + 1 < n; ++i)
            m.triangles.push_back({0u, static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i + 1)});
        return m;
    }
}  // namespace

TEST(BvhCollide, TheStatelessVerdictIsBruteForceOverEveryTrianglePair)
{
    // bvhCollide() at seeded random poses of B about A (half of them colliding, as a planner's samples near
    // obstacles are): the verdict of every triangle pair tested, and a reported pair that intersects. The children
    // are visited in an order that depends on the pose; the verdict must not. On the bumpy bodies and on a bumpy
    // body against a disc fanned into slivers.
    const Mesh bumpyA = test::merged(bumpy(1.0, 3), fannedDisc(1.2, 40)), mb = bumpy(0.5, 2);
    const TriangleBvh a(bumpyA), b(mb);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> g;
    const int poses = 400 / test::stride();
    int hits = 0;
    for (int i = 0; i < poses; ++i)
    {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
        X.translation() = Eigen::Vector3d(1.8 * u(rng), 1.8 * u(rng), 0.9 * u(rng));
        std::uint32_t ta = UINT32_MAX, tb = UINT32_MAX;
        const bool hit = bvhCollide(a, b, X, &ta, &tb);
        ASSERT_EQ(hit, bruteForceCollide(bumpyA, mb, X)) << "pose " << i;
        if (!hit)
            continue;
        ++hits;
        const Triangle &f = bumpyA.triangles[ta], &h = mb.triangles[tb];
        ASSERT_TRUE(trianglesIntersect(bumpyA.vertices[f[0]], bumpyA.vertices[f[1]], bumpyA.vertices[f[2]],
                                       X * mb.vertices[h[0]], X * mb.vertices[h[1]], X * mb.vertices[h[2]]));
    }
    EXPECT_GT(hits, poses / 5);
    EXPECT_LT(hits, poses - poses / 5);
}

namespace
{
    /** \brief A square wall in the plane x = 0 (half side 2) with a square hole (half side 0.5) through it, the
        frame between them in eight large slanted triangles, each split trapezoid's diagonal running from a hole
        corner to an outer one: their boxes reach into the hole past the triangles' corners. */
    Mesh wallWithHole()
    {
        Mesh m;
        m.source = "wall with a hole";
        const double outer = 2.0, hole = 0.5;
        const double corners[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
        for (const auto &c : corners)
            m.vertices.emplace_back(0.0, outer * c[0], outer * c[1]);
        for (const auto &c : corners)
            m.vertices.emplace_back(0.0, hole * c[0], hole * c[1]);
        for (std::uint32_t i = 0; i < 4; ++i)
        {
            const std::uint32_t j = (i + 1) % 4;
            m.triangles.push_back({i, j, 4 + j});
            m.triangles.push_back({i, 4 + j, 4 + i});
        }
        return m;
    }
}  // namespace

TEST(BvhCollide, ABodyGrazingTheEdgesOfAHoleGetsBruteForcesVerdict)
{
    // A box passing through a hole in a wall of large slanted triangles: the triangles' boxes overlap the box's nodes
    // in the hole where the triangles do not, and a leaf's triangle is tested against the other node's box before
    // descending. At seeded random orientations and directions, the pose where brute force's verdict changes is found
    // by bisection (to a few 1e-16 of the offset), so that the poses on either side of it touch within
    // trianglesIntersect()'s tolerance or miss by a little more: the stateless and the warm test (a front carried
    // along the approach) must give brute force's verdict at each.
    const Mesh ma = wallWithHole(), mb = test::box(0.2, 0.3, 0.25, 2);
    const TriangleBvh a(ma), b(mb);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> g;
    const int approaches = 60 / test::stride();
    int hits = 0, misses = 0;
    for (int i = 0; i < approaches; ++i)
    {
        // From the hole's centre (free: the box fits through it) towards its rim, turned a little.
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::AngleAxisd(0.3 * u(rng), Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized())
                         .toRotationMatrix();
        X.translation() = Eigen::Vector3d(0.1 * u(rng), 0.05 * u(rng), 0.05 * u(rng));
        const Eigen::Vector3d direction = Eigen::Vector3d(0.0, u(rng), u(rng)).normalized();
        auto at = [&](double s) {
            Eigen::Isometry3d Y = X;
            Y.translation() += s * direction;
            return Y;
        };
        ASSERT_FALSE(bruteForceCollide(ma, mb, at(0.0))) << "approach " << i;
        double free = 0.0, touching = 1.0;
        ASSERT_TRUE(bruteForceCollide(ma, mb, at(touching))) << "approach " << i;
        for (int k = 0; k < 80; ++k)
        {
            const double mid = 0.5 * (free + touching);
            (bruteForceCollide(ma, mb, at(mid)) ? touching : free) = mid;
        }
        BvhFront front;
        const double offsets[] = {-1e-3, -1e-6, -1e-9, -1e-11, 0.0, 1e-12, 1e-10, 1e-6, 1e-3};
        for (double d : offsets)
            for (double s : {free + d, touching + d})
            {
                const Eigen::Isometry3d Y = at(s);
                const bool truth = bruteForceCollide(ma, mb, Y);
                ASSERT_EQ(bvhCollide(a, b, Y), truth) << "approach " << i << ", offset " << s;
                ASSERT_EQ(bvhCollide(a, b, Y, front), truth) << "approach " << i << ", offset " << s;
                (truth ? hits : misses) += 1;
            }
    }
    EXPECT_GT(hits, approaches * 6);
    EXPECT_GT(misses, approaches * 6);
}

TEST(BvhFront, ACollisionFrontOverItsBudgetGivesTheStatelessVerdict)
{
    // A fine plate lowered onto another, tilted, in runs of 20 small steps (each run a little aside): near contact
    // a front holds pairs of leaves by the hundred, where the stateless test prunes most of them at once (the
    // plates' boxes are apart along their normals), so writing or re-testing the front runs out of its budget, at
    // free poses and at colliding ones. Every verdict must still be the stateless one, and brute force's.
    const Mesh ma = test::grid(1.0, 1.0, 16, 16), mb = test::grid(0.5, 0.5, 10, 10);
    const TriangleBvh a(ma), b(mb);
    BvhFront front;
    const std::size_t stride = static_cast<std::size_t>(test::stride());
    int hits = 0;
    std::size_t overHit = 0, overFree = 0;  // tests over budget, by verdict
    for (int i = 0; i < 600; ++i)
    {
        const int run = i / 20, step = i % 20;
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() =
            Eigen::AngleAxisd(0.1, Eigen::Vector3d(1.0, 1.0 + 0.1 * run, 0.0).normalized()).toRotationMatrix();
        X.translation() = Eigen::Vector3d(0.1 + 0.01 * run, 0.2 + 0.005 * run, 0.1 - 0.01 * step);
        std::uint32_t ta = UINT32_MAX, tb = UINT32_MAX;
        const std::size_t over = front.overBudget;
        const bool warm = bvhCollide(a, b, X, front, &ta, &tb);
        ASSERT_EQ(warm, bvhCollide(a, b, X)) << "pose " << i;
        (warm ? overHit : overFree) += front.overBudget - over;
        if (static_cast<std::size_t>(i) % (2 * stride) == 0)
        {
            ASSERT_EQ(warm, bruteForceCollide(ma, mb, X)) << "pose " << i;
        }
        if (!warm)
            continue;
        ++hits;
        const Triangle &f = ma.triangles[ta], &h = mb.triangles[tb];
        ASSERT_TRUE(trianglesIntersect(ma.vertices[f[0]], ma.vertices[f[1]], ma.vertices[f[2]], X * mb.vertices[h[0]],
                                       X * mb.vertices[h[1]], X * mb.vertices[h[2]]));
    }
    test::Note() << "[ front    ] " << hits << " colliding poses; over budget " << overHit << " colliding, "
                 << overFree << " free; rebuilds " << front.rebuilds << ", kept " << front.reused << ", re-tested "
                 << front.retested << "\n";
    EXPECT_GT(hits, 100);
    EXPECT_LT(hits, 500);
    // The budget ran out on both kinds of pose, and the stateless test answered; fronts were still kept between.
    EXPECT_GT(overHit, 5u);
    EXPECT_GT(overFree, 5u);
    EXPECT_GT(front.reused, 100u);
}

TEST(BvhFront, MotionBoundCoversEveryPointsDisplacement)
{
    // motionBound(): no point of B's root sphere moves further, checked on random poses and points.
    const Mesh mb = bumpy(0.5, 3);
    const TriangleBvh b(mb);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 200; ++k)
    {
        const Eigen::Isometry3d from = test::randomPose(2 * k + 1, 2.0);
        Eigen::Isometry3d to = from;
        to.translation() += 0.1 * Eigen::Vector3d(u(rng), u(rng), u(rng));
        to.linear() =
            to.linear() *
            Eigen::AngleAxisd(0.2 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
        const double bound = motionBound(b, from, to);
        for (const Eigen::Vector3d &v : mb.vertices)
            ASSERT_LE((to * v - from * v).norm(), bound);
    }
}
