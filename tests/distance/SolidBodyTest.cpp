#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "TestMeshes.h"
#include "TestScale.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/robot/Primitives.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

// A body built from primitive solids is answered as its solids by the exact queries (refineExact(), inCollision(),
// Scene): its distance is the least triangle-solid (or solid-solid) distance, by brute force over every pair, and its
// collision verdict is the solids', not the circumscribed mesh's.
namespace
{
    Primitive solid(Primitive::Kind kind, double x, double y = 0.0, double z = 0.0,
                    const Isometry3d &pose = Isometry3d::Identity())
    {
        Primitive p;
        p.kind = kind;
        p.size = Vector3d(x, y, z);
        p.pose = pose;
        return p;
    }

    /** \brief The circumscribed mesh of \e p (as URDF and MoveIt bodies are built), in the body frame. */
    Mesh meshOf(const Primitive &p)
    {
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                return test::transformed(boxMesh(p.size), p.pose);
            case Primitive::Kind::SPHERE:
                return test::transformed(sphereMesh(p.size.x(), 16), p.pose);
            case Primitive::Kind::CONE:
                return test::transformed(coneMesh(p.size.x(), p.size.y(), 16), p.pose);
            default:
                return test::transformed(cylinderMesh(p.size.x(), p.size.y(), 16), p.pose);
        }
    }

    BodyPtr solidBody(const std::vector<Primitive> &parts)
    {
        Mesh m = meshOf(parts[0]);
        for (std::size_t k = 1; k < parts.size(); ++k)
            m = test::merged(m, meshOf(parts[k]));
        BodyOptions options;
        options.gridSize = 0;
        return Body::build(m, parts, options);
    }

    /** \brief Brute force: the least primitiveTriangleGap() over every triangle of \e mesh and solid of \e solids
        (placed by X_MS in the mesh's frame). */
    double solidsBruteForce(const Body &mesh, const Body &solids, const Isometry3d &X_MS)
    {
        double best = std::numeric_limits<double>::infinity();
        const Mesh &m = mesh.surface();
        for (const Primitive &p : solids.primitives())
            for (const Triangle &t : m.triangles)
                best = std::min(best, primitiveTriangleGap(p, X_MS, m.vertices[t[0]], m.vertices[t[1]],
                                                           m.vertices[t[2]])
                                          .distance);
        return best;
    }

    DistanceResult exactRefined(const Body &a, const Body &b, const Isometry3d &X_AB,
                                const DistanceRequest &request = DistanceRequest())
    {
        DistanceResult r;
        refineExact(a, b, X_AB, r, request);
        return r;
    }
}  // namespace

TEST(SolidBodyTest, DistanceIsTheLeastTriangleSolidDistance)
{
    const BodyPtr obstacle = test::unrefinedBody(test::icosphere(0.5, 2));
    const BodyPtr link = solidBody({solid(Primitive::Kind::CYLINDER, 0.1, 0.6),
                                    solid(Primitive::Kind::SPHERE, 0.12, 0, 0, test::translation(0, 0, 0.3)),
                                    solid(Primitive::Kind::BOX, 0.1, 0.2, 0.3, test::translation(0.15, 0, 0))});
    int touching = 0;
    const int seeds = test::scaled(300, 60);  // fewer under the sanitizers, the threshold below in proportion
    for (std::uint32_t seed = 0; seed < static_cast<std::uint32_t>(seeds); ++seed)
    {
        const Isometry3d X = test::randomPose(seed, 1.0);
        const double expected = solidsBruteForce(*obstacle, *link, X);
        const DistanceResult ab = exactRefined(*obstacle, *link, X);
        const DistanceResult ba = exactRefined(*link, *obstacle, X.inverse());
        const bool collides = inCollision(*obstacle, *link, X);
        EXPECT_EQ(collides, inCollision(*link, *obstacle, X.inverse()));
        if (expected == 0.0)
        {
            ++touching;
            EXPECT_TRUE(ab.inCollision && ba.inCollision && collides) << seed;
            continue;
        }
        // A pose may also put the link wholly inside the closed sphere.
        EXPECT_EQ(ab.inCollision, collides) << seed;
        if (collides)
            continue;
        EXPECT_TRUE(ab.certified) << seed;
        EXPECT_NEAR(ab.distance, expected, 1e-12) << seed;  // ties among triangles: the least to roundoff
        EXPECT_NEAR(ba.distance, expected, 1e-10) << seed;  // another frame: GJK to about 1e-11
        EXPECT_NEAR((ab.onA - ab.onB).norm(), expected, 1e-9) << seed;
        // The circumscribed mesh is a lower bound.
        EXPECT_LE(exactRefined(*obstacle, *test::unrefinedBody(link->surface()), X).distance, expected + 1e-12) << seed;
    }
    EXPECT_GT(touching, 20 * seeds / 300);
}

TEST(SolidBodyTest, TheSolidIsFreeWhereItsCircumscribedMeshTouches)
{
    // Regression: a sphere whose 16-segment mesh reaches beyond it. A box face normal to the mesh's farthest vertex,
    // between the sphere and that vertex: the mesh collides, the sphere is apart by half the excess.
    const double r = 0.5;
    const BodyPtr ball = solidBody({solid(Primitive::Kind::SPHERE, r)});
    Vector3d far = Vector3d::Zero();
    for (const Vector3d &v : ball->surface().vertices)
        if (v.norm() > far.norm())
            far = v;
    const double excess = far.norm() - r;
    ASSERT_GT(excess, 1e-3);
    const BodyPtr wall = test::unrefinedBody(boxMesh(Vector3d(0.2, 2.0, 2.0)));
    Isometry3d X_WallBall = Isometry3d::Identity();  // the wall's face x = -0.1 normal to the vertex direction
    X_WallBall.linear() = Eigen::Quaterniond::FromTwoVectors(far.normalized(), Vector3d::UnitX()).toRotationMatrix();
    X_WallBall.translation() = Vector3d(-0.1 - r - 0.5 * excess, 0.0, 0.0);
    EXPECT_TRUE(inCollision(*wall, *test::unrefinedBody(ball->surface()), X_WallBall)) << "the mesh collides";
    EXPECT_FALSE(inCollision(*wall, *ball, X_WallBall)) << "the sphere does not";
    const DistanceResult d = exactRefined(*wall, *ball, X_WallBall);
    EXPECT_FALSE(d.inCollision);
    EXPECT_NEAR(d.distance, 0.5 * excess, 1e-12);
}

TEST(SolidBodyTest, ContainmentEitherWayCollides)
{
    const BodyPtr room = test::unrefinedBody(test::box(2.0, 2.0, 2.0));  // closed, half-sizes 2
    const BodyPtr small = solidBody({solid(Primitive::Kind::CYLINDER, 0.2, 0.5)});
    EXPECT_TRUE(inCollision(*room, *small, test::translation(0.3, 0.2, 0.1)));
    EXPECT_TRUE(exactRefined(*room, *small, test::translation(0.3, 0.2, 0.1)).inCollision);
    EXPECT_TRUE(exactRefined(*small, *room, test::translation(0.3, 0.2, 0.1).inverse()).inCollision);
    // A small mesh inside a big box solid: every triangle touches the filled box.
    const BodyPtr block = solidBody({solid(Primitive::Kind::BOX, 4.0, 4.0, 4.0)});
    const BodyPtr pebble = test::unrefinedBody(test::icosphere(0.1, 1));
    EXPECT_TRUE(inCollision(*block, *pebble, test::translation(0.5, 0.0, 0.0)));
    EXPECT_TRUE(exactRefined(*pebble, *block, test::translation(-0.5, 0.0, 0.0)).inCollision);
    EXPECT_FALSE(inCollision(*block, *pebble, test::translation(2.2, 0.0, 0.0)));
    double lowest = 0.0;  // the pebble's least x
    for (const Vector3d &v : pebble->surface().vertices)
        lowest = std::min(lowest, v.x());
    EXPECT_NEAR(exactRefined(*block, *pebble, test::translation(2.2, 0.0, 0.0)).distance, 0.2 + lowest, 1e-12);
}

TEST(SolidBodyTest, TwoSolidBodiesAndTheBoundsOfARequest)
{
    const BodyPtr a =
        solidBody({solid(Primitive::Kind::CAPSULE, 0.1, 0.5), solid(Primitive::Kind::BOX, 0.2, 0.2, 0.2)});
    const BodyPtr b = solidBody({solid(Primitive::Kind::CONE, 0.2, 0.4)});
    const Isometry3d X = test::translation(0.0, 0.0, 0.8);  // the cone's base at 0.6, the capsule's top at 0.35
    EXPECT_NEAR(exactRefined(*a, *b, X).distance, 0.25, 1e-12);
    DistanceRequest below;
    below.upperBound = 0.2;  // nothing below: infinity, certified
    const DistanceResult none = exactRefined(*a, *b, X, below);
    EXPECT_EQ(none.distance, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(none.certified);
    DistanceRequest early;
    early.stopBelow = 0.3;  // an answer at or below it, not certified
    const DistanceResult stop = exactRefined(*a, *b, X, early);
    EXPECT_LE(stop.distance, 0.3);
    EXPECT_FALSE(stop.certified);
    EXPECT_TRUE(inCollision(*a, *b, test::translation(0.0, 0.0, 0.5)));
}

TEST(SolidBodyTest, ABoundedQuestionAtItsOwnStopFindsWhatIsBelowIt)
{
    // Regression: the question a certified motion asks ("anything at or below the bound?": upperBound and stopBelow
    // both the bound) must find a pair below it, a touching one included, for solids against solids and against a
    // mesh alike.
    const BodyPtr a = solidBody({solid(Primitive::Kind::CAPSULE, 0.1, 0.5)});
    const BodyPtr b = solidBody({solid(Primitive::Kind::CYLINDER, 0.2, 0.4)});
    const BodyPtr mesh = test::unrefinedBody(test::icosphere(0.3, 2));
    DistanceRequest bounded;
    bounded.upperBound = bounded.stopBelow = 0.3;
    bounded.computeDepth = false;
    for (const double z : {0.5, 0.6, 0.8})  // touching, 0.05 apart, 0.25 apart
    {
        const DistanceResult ab = exactRefined(*a, *b, test::translation(0.0, 0.0, z), bounded);
        EXPECT_LE(ab.distance, 0.3) << z;
        EXPECT_EQ(ab.inCollision, z == 0.5) << z;
        const DistanceResult am = exactRefined(*mesh, *a, test::translation(0.0, 0.0, z + 0.1), bounded);
        EXPECT_LE(am.distance, 0.3) << z;
        const DistanceResult ma = exactRefined(*a, *mesh, test::translation(0.0, 0.0, -z - 0.1), bounded);
        EXPECT_LE(ma.distance, 0.3) << z;
    }
}

TEST(SolidBodyTest, SceneAnswersARobotOfSolidsAsItsSolids)
{
    const BodyPtr robot = solidBody({solid(Primitive::Kind::CYLINDER, 0.1, 0.8)});
    std::vector<BodyConstPtr> obstacles = {test::unrefinedBody(test::icosphere(0.3, 2)),
                                           test::unrefinedBody(test::transformed(test::box(0.2, 0.2, 0.2),
                                                                                 test::translation(1.5, 0, 0)))};
    const Scene scene(robot, obstacles);
    SceneWarmStart warm;
    for (std::uint32_t seed = 0; seed < 100; ++seed)
    {
        const Isometry3d X = test::randomPose(seed + 1000, 1.2);
        double expected = std::numeric_limits<double>::infinity();
        for (const BodyConstPtr &o : obstacles)
            expected = std::min(expected, solidsBruteForce(*o, *robot, X));
        SceneRequest request;
        SceneResult cold, carried;
        scene.distance(X, request, cold);
        scene.distance(X, request, warm, carried);
        EXPECT_EQ(scene.inCollision(X), cold.inCollision) << seed;
        if (cold.inCollision)
            continue;
        EXPECT_TRUE(cold.certified);
        EXPECT_NEAR(cold.distance, expected, 1e-12) << seed;
        EXPECT_NEAR(carried.distance, expected, 1e-12) << seed;
    }
}
