#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "TestMeshes.h"
#include "TestScale.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/geometry/ConvexHull.h"
#include "meshgap/robot/Primitives.h"

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

// The convex outer bound of a body: its hull's vertices grown by a margin must hold every vertex of the mesh (checked
// along random directions and each dropped vertex's own direction, with no use of qhull), and the GJK lower bound
// between it and a solid or another hull must never exceed the exact distance of the meshes (refineExact, the
// traversal) over thousands of random poses; degenerate point sets have no hull and answer as before.
namespace
{
    /** \brief A sphere of \e r with every vertex pushed in by up to a fifth at random: non-convex, most vertices
        inside the hull. */
    Mesh hullBumpySphere(double r, int level, std::uint32_t seed)
    {
        Mesh m = test::icosphere(r, level);
        std::mt19937 rng(seed);
        std::uniform_real_distribution<double> u(0.8, 1.0);
        for (Vector3d &v : m.vertices)
            v *= u(rng);
        m.source = "bumpy sphere";
        return m;
    }

    /** \brief An L of two boxes (non-convex, coplanar faces of many vertices), off the origin. */
    Mesh lShape()
    {
        return test::transformed(test::merged(test::box(0.5, 0.1, 0.1, 4),
                                              test::transformed(test::box(0.1, 0.4, 0.1, 3),
                                                                test::translation(0.4, 0.5, 0.0))),
                                 test::translation(0.3, -0.2, 0.7));
    }

    std::vector<Vector3d> directions(std::size_t n, std::uint32_t seed)
    {
        std::mt19937 rng(seed);
        std::normal_distribution<double> g;
        std::vector<Vector3d> d(n);
        for (Vector3d &x : d)
            x = Vector3d(g(rng), g(rng), g(rng)).normalized();
        return d;
    }

    /** \brief The largest excess of a point's support over the grown vertex set's, over \e dirs: the points lie in
        conv(vertices) + Ball(margin) only if it is at most 0 (brute force; no use of the hull's triangles). */
    double worstExcess(const std::vector<Vector3d> &vertices, double margin, const std::vector<Vector3d> &points,
                       const std::vector<Vector3d> &dirs)
    {
        double worst = -std::numeric_limits<double>::infinity();
        for (const Vector3d &d : dirs)
        {
            double p = -std::numeric_limits<double>::infinity(), v = p;
            for (const Vector3d &x : points)
                p = std::max(p, d.dot(x));
            for (const Vector3d &x : vertices)
                v = std::max(v, d.dot(x));
            worst = std::max(worst, p - v - margin);
        }
        return worst;
    }

    /** \brief The directions in which hull vertex \e k is extreme: the mean of its triangles' normals (and random
        ones): dropping that vertex must show in them. */
    std::vector<Vector3d> vertexDirections(const ConvexHull &hull, std::uint32_t k)
    {
        Vector3d sum = Vector3d::Zero();
        for (const auto &t : hull.triangles())
            if (t[0] == k || t[1] == k || t[2] == k)
            {
                const std::vector<Vector3d> &v = hull.vertices();
                const Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
                if (n.norm() > 0.0)
                    sum += n.normalized() * (n.dot(v[t[0]] - hull.center()) >= 0.0 ? 1.0 : -1.0);
            }
        std::vector<Vector3d> d = directions(200, 7 + k);
        d.push_back(sum.normalized());
        return d;
    }

    void expectHolds(const Mesh &m, const char *what)
    {
        SCOPED_TRACE(what);
        const std::shared_ptr<const ConvexHull> hull = ConvexHull::build(m.vertices);
        ASSERT_TRUE(hull) << what << ": no hull";
        EXPECT_GE(hull->vertices().size(), 4u);
        EXPECT_LE(hull->vertices().size(), m.vertices.size());
        for (const Vector3d &v : hull->vertices())  // the vertices are points of the mesh
            EXPECT_TRUE(std::find(m.vertices.begin(), m.vertices.end(), v) != m.vertices.end());
        EXPECT_GE(hull->margin(), 0.0);
        EXPECT_LT(hull->margin(), 1e-9) << "a margin far above roundoff";
        EXPECT_LE(worstExcess(hull->vertices(), hull->margin(), m.vertices, directions(2000, 3)), 0.0);
        for (const Vector3d &p : m.vertices)  // and each vertex's own direction
            EXPECT_LE(worstExcess(hull->vertices(), hull->margin(), m.vertices, {(p - hull->center()).normalized()}),
                      0.0);
    }

    Primitive placedSolid(Primitive::Kind kind, double x, double y, double z, const Isometry3d &pose)
    {
        Primitive p;
        p.kind = kind;
        p.size = Vector3d(x, y, z);
        p.pose = pose;
        return p;
    }

    /** \brief A body of the solid \e p (its mesh at its pose, as a MoveIt scene builds one). */
    BodyPtr hullSolidBody(const Primitive &p)
    {
        Mesh m;
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                m = boxMesh(p.size);
                break;
            case Primitive::Kind::SPHERE:
                m = sphereMesh(p.size.x(), 16);
                break;
            case Primitive::Kind::CONE:
                m = coneMesh(p.size.x(), p.size.y(), 16);
                break;
            default:  // a capsule inside its cylinder's mesh grown by the radius
                m = cylinderMesh(p.size.x(), p.size.y() + (p.kind == Primitive::Kind::CAPSULE ? 2 * p.size.x() : 0.0),
                                 16);
        }
        BodyOptions options;
        options.gridSize = 0;
        return Body::build(test::transformed(m, p.pose), {p}, options);
    }

    /** \brief The distance of two bodies as refineExact() finds it, taken as the distance its witness points achieve
        (an upper bound of the true distance: for a curved solid, refineExact()'s distance is GJK's lower bound, which
        may lie below the truth by 1e-10 of the scale); 0 in collision. */
    double hullExactDistance(const Body &a, const Body &b, const Isometry3d &X_AB)
    {
        DistanceResult r;
        refineExact(a, b, X_AB, r);
        return r.inCollision ? 0.0 : std::max(r.distance, (r.onA - r.onB).norm());
    }
}  // namespace

TEST(ConvexHull, HoldsEveryVertex)
{
    expectHolds(test::icosphere(0.3, 2), "icosphere");
    expectHolds(hullBumpySphere(0.4, 3, 1), "bumpy sphere");
    expectHolds(lShape(), "L of boxes");
    expectHolds(test::box(0.2, 0.3, 0.05, 6), "box of 6 x 6 squares a face");
    expectHolds(test::transformed(hullBumpySphere(2e-3, 2, 5), test::translation(40.0, -30.0, 10.0)), "small, far");
    // Coplanar points are not vertices: a box of many squares a face has its 8 corners.
    EXPECT_EQ(ConvexHull::build(test::box(0.2, 0.3, 0.05, 6).vertices)->vertices().size(), 8u);
}

TEST(ConvexHull, AFineRoundPartIsCoarsenedAndStillHeld)
{
    // 10,242 vertices all on the hull: more than build() keeps, so it keeps those extreme along its directions and the
    // margin covers the others (the sagitta between kept vertices: well under a hundredth of the radius).
    const Mesh fine = test::transformed(test::icosphere(0.05, 5), test::translation(0.2, 0.1, -0.3));
    ASSERT_GT(fine.vertices.size(), 10000u);
    const std::shared_ptr<const ConvexHull> hull = ConvexHull::build(fine.vertices);
    ASSERT_TRUE(hull);
    EXPECT_LE(hull->vertices().size(), 4096u);
    EXPECT_LT(hull->vertices().size(), fine.vertices.size());
    EXPECT_GT(hull->margin(), 0.0);
    EXPECT_LT(hull->margin(), 0.01 * 0.05);
    EXPECT_LE(worstExcess(hull->vertices(), hull->margin(), fine.vertices, directions(3000, 11)), 0.0);
    EXPECT_GT(worstExcess(hull->vertices(), 0.0, fine.vertices, directions(3000, 11)), 0.0)
        << "without its margin the coarse hull leaves vertices out";
}

TEST(ConvexHull, TheOracleCatchesAShrunkHull)
{
    // A check that never fails proves nothing: with the margin made negative, or one vertex dropped, the brute-force
    // oracle of HoldsEveryVertex must find a mesh vertex outside.
    const Mesh m = hullBumpySphere(0.4, 3, 1);
    const std::shared_ptr<const ConvexHull> hull = ConvexHull::build(m.vertices);
    ASSERT_TRUE(hull);
    EXPECT_GT(worstExcess(hull->vertices(), -1e-6, m.vertices, directions(2000, 3)), 0.0);
    for (std::uint32_t k : {0u, 5u, 17u})
    {
        std::vector<Vector3d> dropped = hull->vertices();
        dropped.erase(dropped.begin() + k);
        EXPECT_GT(worstExcess(dropped, hull->margin(), m.vertices, vertexDirections(*hull, k)), 0.0) << k;
    }
}

namespace
{
    /** \brief The largest dot product of a vertex with \e d, brute force (Eigen's own dot). */
    double mostAlong(const std::vector<Vector3d> &vertices, const Vector3d &d)
    {
        double most = -std::numeric_limits<double>::infinity();
        for (const Vector3d &x : vertices)
            most = std::max(most, d.dot(x));
        return most;
    }

    /** \brief support() must return the very vertex scan() (every vertex tested) returns, whose dot product is the
        brute-force largest to roundoff, along random directions, the axes (exact ties on flat faces and rings), each
        vertex's own direction, scaled ones and degenerate ones. */
    void expectSupportIsTheScans(const std::vector<Vector3d> &points, const char *what)
    {
        SCOPED_TRACE(what);
        const std::shared_ptr<const ConvexHull> hull = ConvexHull::build(points);
        ASSERT_TRUE(hull) << what << ": no hull";
        std::vector<Vector3d> dirs = directions(3000, 19);
        for (int k = 0; k < 3; ++k)
        {
            dirs.push_back(Vector3d::Unit(k));
            dirs.push_back(-Vector3d::Unit(k));
            dirs.push_back(Vector3d::Unit(k) + Vector3d::Unit((k + 1) % 3));
        }
        for (const Vector3d &v : hull->vertices())
            dirs.push_back(v - hull->center());
        // Directions on the edges of the cube map's cells and faces (u, v at multiples of 1/8 and 1/16, a hair
        // either side, and |d_a| = |d_b| ties between faces), where a lookup could pick a neighbouring cell.
        for (int a = 0; a < 3; ++a)
            for (double sign : {1.0, -1.0})
                for (int i = -16; i <= 16; i += 3)
                    for (int j = -16; j <= 16; j += 5)
                        for (double hair : {0.0, 1e-16, -1e-16, 1e-10})
                        {
                            Vector3d d;
                            d[a] = sign;
                            d[(a + 1) % 3] = i / 16.0 + hair;
                            d[(a + 2) % 3] = j / 16.0 - hair;
                            dirs.push_back(d);
                        }
        const std::size_t unit = dirs.size();
        for (std::size_t i = 0; i < unit; i += 7)
        {
            dirs.push_back(1e-200 * dirs[i]);
            dirs.push_back(1e200 * dirs[i]);
        }
        dirs.push_back(Vector3d::Zero());
        dirs.push_back(Vector3d(std::nan(""), 1.0, 0.0));
        dirs.push_back(Vector3d(std::numeric_limits<double>::infinity(), 1.0, 0.0));
        dirs.push_back(Vector3d(1e308, -1e308, 1e308));
        for (const Vector3d &d : dirs)
        {
            const Vector3d s = hull->support(d), t = hull->scan(d);
            ASSERT_TRUE(s == t || (s.array().isNaN().any() && t.array().isNaN().any()))
                << "d " << d.transpose() << ": " << s.transpose() << " against " << t.transpose();
            if (d.allFinite() && d.norm() < 1e100)
            {
                EXPECT_LE(std::abs(d.dot(s) - mostAlong(hull->vertices(), d)), 1e-14 * d.norm() * hull->reach())
                    << d.transpose();
            }
        }
    }
}  // namespace

TEST(ConvexHull, SupportIsTheScansVertex)
{
    expectSupportIsTheScans(hullBumpySphere(0.4, 3, 1).vertices, "bumpy sphere");
    expectSupportIsTheScans(test::icosphere(0.05, 5).vertices, "coarsened fine sphere");
    expectSupportIsTheScans(test::transformed(test::icosphere(2e-3, 3), test::translation(40.0, -30.0, 10.0)).vertices,
                            "small, far");
    expectSupportIsTheScans(lShape().vertices, "L of boxes (8 vertices: not clustered)");
    expectSupportIsTheScans(cylinderMesh(0.1, 0.4, 64).vertices, "cylinder: rings of 64 tied along its axis");
    expectSupportIsTheScans(cylinderMesh(0.3, 1e-6, 200).vertices, "a thin disc, nearly flat");
    expectSupportIsTheScans(coneMesh(0.2, 0.3, 100).vertices, "cone");
    // Many exact ties: a grid of points on the sphere's octahedral symmetry planes (coordinates a few binary values).
    std::vector<Vector3d> lattice;
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j)
            for (int k = -4; k <= 4; ++k)
                if (i * i + j * j + k * k <= 16 && i * i + j * j + k * k >= 9)
                    lattice.emplace_back(0.25 * i, 0.25 * j, 0.25 * k);
    expectSupportIsTheScans(lattice, "lattice ball");
}

TEST(ConvexHull, DegenerateSetsHaveNoHull)
{
    const Vector3d o = Vector3d::Zero(), x = Vector3d::UnitX(), y = Vector3d::UnitY();
    EXPECT_FALSE(ConvexHull::build({}));
    EXPECT_FALSE(ConvexHull::build({o, x, y}));                                        // a single triangle
    EXPECT_FALSE(ConvexHull::build({o, x, y, x + y}));                                 // a flat quad
    EXPECT_FALSE(ConvexHull::build({o, x, 2 * x, 3 * x, 4 * x}));                      // collinear
    EXPECT_FALSE(ConvexHull::build({x, x, x, x, x}));                                  // one point
    EXPECT_FALSE(ConvexHull::build(test::grid(1.0, 2.0, 5, 7).vertices));             // a flat grid
    EXPECT_FALSE(ConvexHull::build({o, x, y, Vector3d(0, 0, std::nan(""))}));          // not finite
    const BodyPtr flat = test::unrefinedBody(test::grid(1.0, 2.0, 5, 7));
    EXPECT_EQ(flat->convexHull(), nullptr);
    // A flat body answers a bounded question with the outer bound asked as without it.
    const BodyPtr ball = test::unrefinedBody(test::icosphere(0.2, 1));
    for (double z : {0.1, 0.25, 0.5, 1.0})
    {
        DistanceRequest plain, outer;
        plain.upperBound = outer.upperBound = 0.3;
        outer.outerBoundFirst = true;
        DistanceResult r0, r1;
        refineExact(*flat, *ball, test::translation(0.5, 0.5, z), r0, plain);
        refineExact(*flat, *ball, test::translation(0.5, 0.5, z), r1, outer);
        EXPECT_EQ(r0.distance, r1.distance) << z;
        EXPECT_EQ(r1.outerBoundProofs, 0u);
    }
}

TEST(ConvexHull, GapNeverExceedsTheMeshDistanceToASolid)
{
    const Mesh meshes[] = {hullBumpySphere(0.3, 3, 2), lShape(), test::icosphere(0.25, 2)};
    const Primitive::Kind kinds[] = {Primitive::Kind::BOX, Primitive::Kind::SPHERE, Primitive::Kind::CYLINDER,
                                     Primitive::Kind::CONE, Primitive::Kind::CAPSULE};
    std::size_t poses = 0, apart = 0;
    const auto seeds = static_cast<std::uint32_t>(test::scaled(200, 20));  // the counts below in proportion
    for (std::size_t i = 0; i < 3; ++i)
    {
        const BodyPtr body = test::unrefinedBody(meshes[i]);
        ASSERT_NE(body->convexHull(), nullptr);
        for (std::size_t k = 0; k < 5; ++k)
            for (std::uint32_t seed = 0; seed < seeds; ++seed)
            {
                const Primitive p = placedSolid(kinds[k], 0.2, 0.5, 0.3, test::randomPose(1000 * k + seed, 0.1));
                const BodyPtr obstacle = hullSolidBody(p);
                const Isometry3d X = test::randomPose(7 + 31 * seed + 1000 * i, 1.0);
                const double exact = hullExactDistance(*body, *obstacle, X);
                const double gap = hullPrimitiveGap(*body->convexHull(), p, X);
                ++poses;
                apart += gap > 0.0 ? 1 : 0;
                ASSERT_LE(gap, exact * (1.0 + 1e-9) + 1e-12) << "mesh " << i << " solid " << k << " seed " << seed;
                if (i == 2)  // a convex mesh: its hull is itself, so the bound is its distance
                {
                    EXPECT_GE(gap, exact - 1e-9) << "solid " << k << " seed " << seed;
                }
            }
    }
    EXPECT_EQ(poses, 15u * seeds);
    EXPECT_GT(apart, 5u * seeds) << "the poses should be mostly apart";
}

TEST(ConvexHull, GapNeverExceedsTheDistanceBetweenMeshes)
{
    const BodyPtr a = test::unrefinedBody(hullBumpySphere(0.3, 3, 3)), b = test::unrefinedBody(lShape());
    const BodyPtr c = test::unrefinedBody(test::icosphere(0.25, 2));
    std::size_t apart = 0;
    const auto seeds = static_cast<std::uint32_t>(test::scaled(1000, 100));  // the count below in proportion
    for (std::uint32_t seed = 0; seed < seeds; ++seed)
    {
        const Isometry3d X = test::randomPose(seed, 1.2);
        const double exact = hullExactDistance(*a, *b, X);
        const double gap = hullGap(*a->convexHull(), *b->convexHull(), X);
        apart += gap > 0.0 ? 1 : 0;
        ASSERT_LE(gap, exact * (1.0 + 1e-9) + 1e-12) << seed;
        const double convex = hullExactDistance(*c, *c, X);  // two convex meshes: the bound is their distance
        const double both = hullGap(*c->convexHull(), *c->convexHull(), X);
        ASSERT_LE(both, convex * (1.0 + 1e-9) + 1e-12) << seed;
        EXPECT_GE(both, convex - 1e-9) << seed;
    }
    EXPECT_GT(apart, 3u * seeds / 10);
}

TEST(ConvexHull, BoundedQuestionsAnswerAsTheTraversal)
{
    // refineExact with the outer bound asked first: the same verdict ("nothing below the bound", or a pair below it)
    // as without, over random poses and bounds, with some answered by the outer bounds alone.
    const BodyPtr link = test::unrefinedBody(hullBumpySphere(0.3, 3, 4));
    const Primitive table = placedSolid(Primitive::Kind::BOX, 2.0, 2.0, 0.1, test::translation(0.0, 0.0, -0.05));
    const BodyPtr tableBody = hullSolidBody(table), other = test::unrefinedBody(lShape());
    std::size_t proofs = 0;
    for (std::uint32_t seed = 0; seed < 600; ++seed)
    {
        const BodyPtr &obstacle = seed % 2 ? tableBody : other;
        Isometry3d X = test::randomPose(seed, 0.6);
        X.translation().z() += 0.35;
        for (double bound : {0.01, 0.05, 0.2})
        {
            DistanceRequest plain, outer;
            plain.upperBound = outer.upperBound = plain.stopBelow = outer.stopBelow = bound;
            plain.computeDepth = outer.computeDepth = false;
            outer.outerBoundFirst = true;
            DistanceResult r0, r1;
            refineExact(*obstacle, *link, X, r0, plain);
            refineExact(*obstacle, *link, X, r1, outer);
            const bool apart0 = !r0.inCollision && !(r0.distance < bound);
            const bool apart1 = !r1.inCollision && !(r1.distance < bound);
            ASSERT_EQ(apart0, apart1) << seed << " " << bound;
            proofs += r1.outerBoundProofs;
        }
    }
    EXPECT_GT(proofs, 100u);
}

namespace
{
    /** \brief The distance of point \e p from the solid box \e b (0 inside). */
    double pointBoxDistance(const Vector3d &p, const Primitive &b)
    {
        const Vector3d local = b.pose.inverse() * p;
        return (local.cwiseAbs() - 0.5 * b.size).cwiseMax(0.0).norm();
    }

    /** \brief The points of \e m placed by \e X0 and by \e X1 and joined by straight lines, at 11 fractions each. */
    std::vector<Vector3d> chordPoints(const Mesh &m, const Isometry3d &X0, const Isometry3d &X1)
    {
        std::vector<Vector3d> points;
        for (const Vector3d &v : m.vertices)
            for (int s = 0; s <= 10; ++s)
                points.push_back((1.0 - s / 10.0) * (X0 * v) + (s / 10.0) * (X1 * v));
        return points;
    }
}  // namespace

TEST(ConvexHull, SweptGapNeverExceedsTheChordsDistance)
{
    // Every vertex's straight line from its place at X0 to its place at X1 lies in the swept hull: its distance from
    // a box (analytic) bounds the swept gap from above, and a grown sweep's gap drops by the growth.
    const Mesh meshes[] = {hullBumpySphere(0.3, 2, 4), lShape()};
    std::size_t apart = 0, tight = 0;
    for (std::size_t i = 0; i < 2; ++i)
    {
        const BodyPtr body = test::unrefinedBody(meshes[i]);
        ASSERT_NE(body->convexHull(), nullptr);
        for (std::uint32_t seed = 0; seed < 150; ++seed)
        {
            const Primitive box = placedSolid(Primitive::Kind::BOX, 0.4, 0.3, 0.2, test::randomPose(500 + seed, 0.1));
            const Isometry3d X0 = test::randomPose(seed, 1.2);
            const Isometry3d X1 = test::randomPose(seed + 9000, 1.2);
            const double gap = sweptHullPrimitiveGap(*body->convexHull(), X0, X1, 0.0, box);
            double least = std::numeric_limits<double>::infinity();
            for (const Vector3d &p : chordPoints(meshes[i], X0, X1))
                least = std::min(least, pointBoxDistance(p, box));
            ASSERT_LE(gap, least * (1.0 + 1e-9) + 1e-12) << "mesh " << i << " seed " << seed;
            // Each end alone (the box's frame, the world, placed in the body's).
            ASSERT_LE(gap, hullPrimitiveGap(*body->convexHull(), box, X0.inverse()) + 1e-12);
            ASSERT_LE(gap, hullPrimitiveGap(*body->convexHull(), box, X1.inverse()) + 1e-12);
            const double grown = sweptHullPrimitiveGap(*body->convexHull(), X0, X1, 0.05, box);
            ASSERT_LE(grown, std::max(0.0, gap - 0.05) + 1e-9) << "mesh " << i << " seed " << seed;
            apart += gap > 0.0 ? 1 : 0;
            tight += gap > 0.5 * least ? 1 : 0;
        }
    }
    EXPECT_GT(apart, 60u) << "the sweeps should be apart from the box often";
    EXPECT_GT(tight, 30u) << "a bound that is close often";
}

namespace
{
    /** \brief The least exact distance between body \e a placed by A0 moved along \e da and \e a placed by B0
        moved along \e db, over 13 x 13 pairs of places (fractions of both translations): the brute-force truth of
        their sweeps' distance, within what the spacing can miss. */
    double leastOverPlaces(const Body &a, const Isometry3d &A0, const Vector3d &da, const Isometry3d &B0,
                           const Vector3d &db)
    {
        double least = std::numeric_limits<double>::infinity();
        for (int s = 0; s <= 12; ++s)
            for (int r = 0; r <= 12; ++r)
            {
                const Isometry3d As = Eigen::Translation3d(s / 12.0 * da) * A0;
                const Isometry3d Br = Eigen::Translation3d(r / 12.0 * db) * B0;
                least = std::min(least, hullExactDistance(a, a, As.inverse() * Br));
            }
        return least;
    }
}  // namespace

TEST(ConvexHull, SweptHullsGapIsTheConvexSweepsDistance)
{
    // Two convex bodies each moved by a translation alone: the swept hull is the body swept along the segment, so
    // the gap is the least distance over the pairs of places (brute force over 13 x 13 fractions, exact distance
    // of the meshes), within what the fractions' spacing can miss.
    const Mesh ball = test::icosphere(0.25, 2);
    const BodyPtr a = test::unrefinedBody(ball);
    std::size_t apart = 0;
    const auto seeds = static_cast<std::uint32_t>(test::scaled(40, 12));  // 169 exact distances each
    for (std::uint32_t seed = 0; seed < seeds; ++seed)
    {
        const Isometry3d A0 = test::randomPose(seed, 1.0), B0 = test::randomPose(seed + 100, 1.0);
        const Vector3d da = test::randomPose(seed + 200, 0.6).translation();
        const Vector3d db = test::randomPose(seed + 300, 0.6).translation();
        const Isometry3d A1 = Eigen::Translation3d(da) * A0, B1 = Eigen::Translation3d(db) * B0;
        const double gap = sweptHullGap(*a->convexHull(), A0, A1, 0.0, *a->convexHull(), B0, B1, 0.0);
        const double least = leastOverPlaces(*a, A0, da, B0, db);
        ASSERT_LE(gap, std::max(0.0, least) * (1.0 + 1e-9) + 1e-12) << seed;
        EXPECT_GE(gap, least - (da.norm() + db.norm()) / 12.0 - 1e-9) << seed;
        apart += gap > 0.0 ? 1 : 0;
    }
    EXPECT_GT(apart, 8u);
}

TEST(ConvexHull, SweptGapFromAnyFirstAxisIsStillABound)
{
    // GJK may start along any direction (the last piece's, kept per question): the gap must stay a lower bound of
    // the swept bodies' distance whatever the first axis (zero, not finite, tiny, huge, pointing the wrong way),
    // converge to the same gap as from the centres' line, and prove a bounded question as that one does.
    const Mesh ball = test::icosphere(0.25, 2);
    const BodyPtr a = test::unrefinedBody(ball);
    const ConvexHull &hull = *a->convexHull();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::size_t apart = 0, provenFirst = 0;
    const auto seeds = static_cast<std::uint32_t>(test::scaled(30, 12));  // 169 exact distances each
    for (std::uint32_t seed = 0; seed < seeds; ++seed)
    {
        // Two translated balls: the gap's truth by brute force over 13 x 13 pairs of places (as above).
        const Isometry3d A0 = test::randomPose(seed, 1.0), B0 = test::randomPose(seed + 100, 1.0);
        const Vector3d da = test::randomPose(seed + 200, 0.6).translation();
        const Vector3d db = test::randomPose(seed + 300, 0.6).translation();
        const Isometry3d A1 = Eigen::Translation3d(da) * A0, B1 = Eigen::Translation3d(db) * B0;
        const double least = leastOverPlaces(*a, A0, da, B0, db);
        const double cold = sweptHullGap(hull, A0, A1, 0.0, hull, B0, B1, 0.0);
        Vector3d found = Vector3d::Zero();
        ASSERT_EQ(sweptHullGap(hull, A0, A1, 0.0, hull, B0, B1, 0.0, std::numeric_limits<double>::infinity(), &found),
                  cold);
        std::vector<Vector3d> firsts = directions(8, seed + 400);
        const Vector3d between = B0.translation() - A0.translation();
        firsts.insert(firsts.end(), {Vector3d::Zero(), Vector3d(nan, 0.0, 0.0), 1e-200 * between, 1e200 * between,
                                     -between, between, found, -found});
        for (std::size_t i = 0; i < firsts.size(); ++i)
        {
            Vector3d axis = firsts[i];
            const double gap = sweptHullGap(hull, A0, A1, 0.0, hull, B0, B1, 0.0,
                                            std::numeric_limits<double>::infinity(), &axis);
            ASSERT_LE(gap, std::max(0.0, least) * (1.0 + 1e-9) + 1e-12) << "seed " << seed << " axis " << i;
            ASSERT_NEAR(gap, cold, 1e-9) << "seed " << seed << " axis " << i;
            if (cold > 0.0)
            {
                ASSERT_TRUE(axis.allFinite() && axis.squaredNorm() > 0.0) << "seed " << seed << " axis " << i;
                // A bounded question: proven from any first axis when the gap is well above it, never above the
                // truth when it stops early.
                Vector3d again = firsts[i];
                const double bounded = sweptHullGap(hull, A0, A1, 0.0, hull, B0, B1, 0.0, 0.5 * cold, &again);
                ASSERT_GT(bounded, 0.5 * cold) << "seed " << seed << " axis " << i;
                ASSERT_LE(bounded, std::max(0.0, least) * (1.0 + 1e-9) + 1e-12) << "seed " << seed << " axis " << i;
            }
        }
        // The axis the full run ended on proves the half-gap question by its first support pair: the bound it gives
        // is within roundoff of the gap itself.
        if (cold > 0.0)
        {
            Vector3d warm = found;
            provenFirst += sweptHullGap(hull, A0, A1, 0.0, hull, B0, B1, 0.0, 0.5 * cold, &warm) >= cold - 1e-9;
        }
        apart += cold > 0.0 ? 1 : 0;
    }
    EXPECT_GT(apart, 8u);
    EXPECT_EQ(provenFirst, apart);

    // Turning sweeps against a box: every vertex's chord bounds the gap from above (analytic), from any first axis.
    const Mesh meshes[] = {hullBumpySphere(0.3, 2, 4), lShape()};
    for (std::size_t m = 0; m < 2; ++m)
    {
        const BodyPtr body = test::unrefinedBody(meshes[m]);
        ASSERT_NE(body->convexHull(), nullptr);
        for (std::uint32_t seed = 0; seed < 40; ++seed)
        {
            const Primitive box = placedSolid(Primitive::Kind::BOX, 0.4, 0.3, 0.2, test::randomPose(700 + seed, 0.1));
            const Isometry3d X0 = test::randomPose(seed + 50, 1.2), X1 = test::randomPose(seed + 9050, 1.2);
            double least = std::numeric_limits<double>::infinity();
            for (const Vector3d &p : chordPoints(meshes[m], X0, X1))
                least = std::min(least, pointBoxDistance(p, box));
            const double cold = sweptHullPrimitiveGap(*body->convexHull(), X0, X1, 0.0, box);
            for (const Vector3d &first : directions(6, seed + 800))
            {
                Vector3d axis = first;
                const double gap = sweptHullPrimitiveGap(*body->convexHull(), X0, X1, 0.0, box,
                                                         std::numeric_limits<double>::infinity(), &axis);
                ASSERT_LE(gap, least * (1.0 + 1e-9) + 1e-12) << "mesh " << m << " seed " << seed;
                ASSERT_NEAR(gap, cold, 1e-9) << "mesh " << m << " seed " << seed;
            }
        }
    }
}

TEST(ConvexHull, SweptGapOfAHullThatStaysIsItsHullsGap)
{
    // A hull whose two poses are the very same is placed once (one support call, not two): its swept gap must be
    // its static GJK gap (hullGap(), in the first body's frame), the same as a sweep between two poses a hair apart
    // (the two-placement path), and never above the meshes' exact distance.
    const Mesh meshes[] = {hullBumpySphere(0.3, 2, 4), lShape()};
    const BodyPtr a = test::unrefinedBody(meshes[0]), b = test::unrefinedBody(meshes[1]);
    const ConvexHull &ha = *a->convexHull(), &hb = *b->convexHull();
    const Isometry3d hair(Eigen::Translation3d(1e-13, -1e-13, 1e-13));
    std::size_t apart = 0;
    for (std::uint32_t seed = 0; seed < 60; ++seed)
    {
        const Isometry3d X = test::randomPose(seed, 1.0), Y = test::randomPose(seed + 1000, 1.0);
        const Isometry3d X_AB = X.inverse() * Y;
        const double stays = sweptHullGap(ha, X, X, 0.0, hb, Y, Y, 0.0);
        const double still = hullGap(ha, hb, X_AB);
        ASSERT_NEAR(stays, still, 1e-9) << seed;
        ASSERT_NEAR(stays, sweptHullGap(ha, X, hair * X, 0.0, hb, Y, hair * Y, 0.0), 1e-9) << seed;
        ASSERT_LE(stays, std::max(0.0, hullExactDistance(*a, *b, X_AB)) * (1.0 + 1e-9) + 1e-12) << seed;
        // One staying, the other moving: the same as its sweep with the first a hair apart.
        const Isometry3d Y1 = test::randomPose(seed + 2000, 1.0);
        ASSERT_NEAR(sweptHullGap(ha, X, X, 0.0, hb, Y, Y1, 0.0), sweptHullGap(ha, X, hair * X, 0.0, hb, Y, Y1, 0.0),
                    1e-9)
            << seed;
        // Against a solid, with a growth: the static gap less the growth.
        const Primitive box = placedSolid(Primitive::Kind::BOX, 0.4, 0.3, 0.2, test::randomPose(seed + 3000, 0.5));
        ASSERT_NEAR(sweptHullPrimitiveGap(ha, X, X, 0.02, box),
                    std::max(0.0, hullPrimitiveGap(ha, box, X.inverse()) - 0.02), 1e-9)
            << seed;
        apart += stays > 0.0 ? 1 : 0;
    }
    EXPECT_GT(apart, 20u);
}
