#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "meshgap/Exception.h"
#include "meshgap/geometry/PrimitiveDistance.h"

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

// Primitive distances against closed-form answers: configurations whose distance is known by construction (a plane
// at a known offset from a face, a cap, a generator of a cone; two solids along a known direction), each carried by
// a random rigid motion. Every answer must agree to 1e-9 relative, never exceed the true distance by more than
// roundoff, and its witnesses must lie that far apart.
namespace
{
    Primitive centredSolid(Primitive::Kind kind, double x, double y = 0.0, double z = 0.0)
    {
        Primitive p;
        p.kind = kind;
        p.size = Vector3d(x, y, z);
        return p;
    }

    Isometry3d randomMotion(std::mt19937 &rng, double reach = 3.0)
    {
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        Isometry3d X = Isometry3d::Identity();
        X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
        X.translation() = reach * Vector3d(u(rng), u(rng), u(rng));
        return X;
    }

    /** \brief A large triangle in the plane through \e p normal to \e n (the solid's frame), its centroid at \e p. */
    void planeTriangle(const Vector3d &p, const Vector3d &n, double size, Vector3d t[3])
    {
        const Vector3d u = n.unitOrthogonal(), v = n.normalized().cross(u);
        for (int k = 0; k < 3; ++k)
        {
            const double angle = 2.0 * M_PI * k / 3.0;
            t[k] = p + size * (std::cos(angle) * u + std::sin(angle) * v);
        }
    }

    void expectGap(const SolidGap &g, double expected, const char *what)
    {
        SCOPED_TRACE(what);
        EXPECT_NEAR(g.distance, expected, 1e-9 * expected) << what;
        EXPECT_LE(g.distance, expected * (1.0 + 1e-14) + 1e-15) << "above the true distance";
        EXPECT_GE(g.upper, g.distance);
        EXPECT_NEAR((g.onA - g.onB).norm(), expected, 1e-9 * expected + 1e-12) << "witnesses";
    }

    /** \brief The triangle in the plane at distance \e h beyond the solid's supporting plane of normal \e n
        touching it at \e contact (solid frame), moved with the solid by a random motion: its distance is \e h. */
    void expectPlane(const Primitive &s, const Vector3d &contact, const Vector3d &n, double h, std::mt19937 &rng,
                     const char *what)
    {
        const Isometry3d X = randomMotion(rng);
        Vector3d t[3];
        planeTriangle(contact + h * n.normalized(), n, 0.5, t);
        expectGap(primitiveTriangleGap(s, X, X * t[0], X * t[1], X * t[2]), h, what);
    }
}  // namespace

TEST(PrimitiveDistanceTest, TriangleAgainstEachSolidMatchesTheClosedForm)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> gap(0.01, 2.0);
    for (int trial = 0; trial < 200; ++trial)
    {
        const double h = gap(rng);
        expectPlane(centredSolid(Primitive::Kind::SPHERE, 0.4), Vector3d(0.0, 0.0, 0.4), Vector3d::UnitZ(), h, rng,
                    "sphere");
        expectPlane(centredSolid(Primitive::Kind::CAPSULE, 0.3, 1.0), Vector3d(0.0, 0.0, 0.8), Vector3d::UnitZ(), h,
                    rng, "capsule end");
        expectPlane(centredSolid(Primitive::Kind::CAPSULE, 0.3, 1.0), Vector3d(0.3, 0.0, 0.1), Vector3d::UnitX(), h,
                    rng, "capsule side");
        expectPlane(centredSolid(Primitive::Kind::BOX, 0.4, 0.6, 1.0), Vector3d(0.0, 0.3, 0.0), Vector3d::UnitY(), h,
                    rng, "box face");
        expectPlane(centredSolid(Primitive::Kind::BOX, 0.4, 0.6, 1.0), Vector3d(0.2, 0.3, 0.5), Vector3d(1, 1, 1), h,
                    rng, "box corner");
        expectPlane(centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8), Vector3d(0.0, 0.0, 0.4), Vector3d::UnitZ(), h,
                    rng, "cylinder cap");
        expectPlane(centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8), Vector3d(0.3, 0.0, 0.0), Vector3d::UnitX(), h,
                    rng, "cylinder side");
        expectPlane(centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8), Vector3d(0.0, 0.3, 0.4), Vector3d(0, 1, 1), h,
                    rng, "cylinder rim");
        expectPlane(centredSolid(Primitive::Kind::CONE, 0.3, 0.8), Vector3d(0.0, 0.0, 0.4), Vector3d::UnitZ(), h, rng,
                    "cone apex");
        expectPlane(centredSolid(Primitive::Kind::CONE, 0.3, 0.8), Vector3d(0.0, 0.0, -0.4), -Vector3d::UnitZ(), h, rng,
                    "cone base");
        // A generator of the cone: from the rim point (0.3, 0, -0.4) to the apex; normal (0.8, 0, 0.3).
        expectPlane(centredSolid(Primitive::Kind::CONE, 0.3, 0.8), Vector3d(0.15, 0.0, 0.0), Vector3d(0.8, 0.0, 0.3), h,
                    rng, "cone slant");
    }
}

TEST(PrimitiveDistanceTest, SolidPairsMatchTheClosedForm)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> gap(0.01, 2.0), u(-1.0, 1.0);
    auto pose = [](const Vector3d &t) { return Isometry3d(Eigen::Translation3d(t)); };
    for (int trial = 0; trial < 200; ++trial)
    {
        const double h = gap(rng);
        const Isometry3d X = randomMotion(rng);
        const Primitive sphere = centredSolid(Primitive::Kind::SPHERE, 0.25);
        const Primitive capsule = centredSolid(Primitive::Kind::CAPSULE, 0.2, 1.0);
        const Primitive box = centredSolid(Primitive::Kind::BOX, 0.4, 0.6, 1.0);
        const Primitive cylinder = centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8);
        const Primitive cone = centredSolid(Primitive::Kind::CONE, 0.3, 0.8);
        const Vector3d side = Vector3d(u(rng), u(rng), 0.0).normalized();
        expectGap(primitiveGap(sphere, X, sphere, X * pose(Vector3d(0.5 + h, 0, 0))), h, "sphere-sphere");
        expectGap(primitiveGap(capsule, X, capsule, X * pose((0.4 + h) * side)), h, "capsule-capsule parallel");
        expectGap(primitiveGap(box, X, sphere, X * pose(Vector3d(0.1, 0.2, 0.75 + h))), h, "box-sphere");
        expectGap(primitiveGap(box, X, box, X * pose(Vector3d(0.4 + h, 0.1, -0.2))), h, "box-box");
        expectGap(primitiveGap(box, X, capsule, X * pose(Vector3d(0.1, 0.0, 1.2 + h))), h, "box-capsule end");
        expectGap(primitiveGap(cylinder, X, sphere, X * pose((0.55 + h) * side)), h, "cylinder-sphere side");
        expectGap(primitiveGap(cylinder, X, sphere, X * pose(Vector3d(0.1, 0.0, 0.65 + h))), h, "cylinder-sphere cap");
        expectGap(primitiveGap(cylinder, X, cylinder, X * pose((0.6 + h) * side + Vector3d(0, 0, 0.3))), h,
                  "cylinder-cylinder parallel");
        expectGap(primitiveGap(cylinder, X, capsule, X * pose((0.5 + h) * side)), h, "cylinder-capsule parallel");
        expectGap(primitiveGap(cone, X, sphere, X * pose(Vector3d(0.0, 0.0, 0.65 + h))), h, "cone-sphere apex");
        expectGap(primitiveGap(cone, X, box, X * pose(Vector3d(0.0, 0.1, -0.9 - h))), h, "cone-box base");
        expectGap(primitiveGap(cylinder, X, box, X * pose(Vector3d(0.0, 0.0, 0.9 + h))), h, "cylinder-box cap");
    }
}

TEST(PrimitiveDistanceTest, TouchingAndOverlappingSolidsAreAtZero)
{
    std::mt19937 rng(3);
    const Isometry3d X = randomMotion(rng);
    const Primitive box = centredSolid(Primitive::Kind::BOX, 1.0, 1.0, 1.0);
    Vector3d t[3];
    // A triangle wholly inside the box, one crossing its face, one inside a cylinder and a cone.
    planeTriangle(Vector3d(0.1, 0.0, 0.0), Vector3d::UnitZ(), 0.2, t);
    EXPECT_EQ(primitiveTriangleGap(box, X, X * t[0], X * t[1], X * t[2]).distance, 0.0);
    planeTriangle(Vector3d(0.5, 0.0, 0.0), Vector3d(1, 2, 3), 0.3, t);
    EXPECT_EQ(primitiveTriangleGap(box, X, X * t[0], X * t[1], X * t[2]).distance, 0.0);
    planeTriangle(Vector3d(0.0, 0.0, 0.1), Vector3d(1, 2, 3), 0.05, t);
    const Primitive cylinder = centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8);
    EXPECT_EQ(primitiveTriangleGap(cylinder, X, X * t[0], X * t[1], X * t[2]).distance, 0.0);
    EXPECT_EQ(
        primitiveTriangleGap(centredSolid(Primitive::Kind::CONE, 0.3, 0.8), X, X * t[0], X * t[1], X * t[2]).distance,
        0.0);
    // Solids: nested, crossing, touching along a face.
    const Isometry3d inner = X * Isometry3d(Eigen::Translation3d(0.1, 0.0, 0.0));
    EXPECT_EQ(primitiveGap(box, X, centredSolid(Primitive::Kind::SPHERE, 0.1), inner).distance, 0.0);
    EXPECT_EQ(primitiveGap(centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8), X,
                           centredSolid(Primitive::Kind::CONE, 0.2, 0.4), inner)
                  .distance,
              0.0);
    const Isometry3d touching = X * Isometry3d(Eigen::Translation3d(1.0, 0.3, 0.2));
    EXPECT_EQ(primitiveGap(box, X, box, touching).distance, 0.0);
    EXPECT_EQ(primitiveGap(centredSolid(Primitive::Kind::CYLINDER, 0.5, 1.0), X,
                           centredSolid(Primitive::Kind::CYLINDER, 0.5, 1.0),
                           X * Isometry3d(Eigen::Translation3d(1.0, 0.0, 0.2)))
                  .distance,
              0.0);
}

TEST(PrimitiveDistanceTest, GjkBoundsBracketTheDistance)
{
    // The lower bound reported never exceeds the distance that its witnesses achieve, and they agree to 1e-12
    // relative, or, where roundoff in the simplex stops GJK first, to 1e-10 of the scale (the solids' reach from the
    // origin, here at most 5; measured up to 2e-11 of it).
    std::mt19937 rng(5);
    const Primitive cylinder = centredSolid(Primitive::Kind::CYLINDER, 0.3, 0.8);
    const Primitive cone = centredSolid(Primitive::Kind::CONE, 0.4, 0.5);
    int iterations = 0;
    for (int trial = 0; trial < 2000; ++trial)
    {
        const SolidGap g = primitiveGap(cylinder, randomMotion(rng, 2.0), cone, randomMotion(rng, 2.0));
        if (g.distance == 0.0)
            continue;
        EXPECT_LE(g.distance, (g.onA - g.onB).norm());
        EXPECT_LE(g.upper - g.distance, std::max(1e-12 * g.upper, 5e-10));
        iterations = std::max(iterations, g.iterations);
    }
    EXPECT_LT(iterations, 256) << "a query ran out of iterations";
}

TEST(PrimitiveDistanceTest, BadSizesAreRefusedByName)
{
    EXPECT_THROW(checkPrimitive(centredSolid(Primitive::Kind::SPHERE, -1.0)), Exception);
    EXPECT_THROW(checkPrimitive(centredSolid(Primitive::Kind::CYLINDER, 1.0, std::nan(""))), Exception);
    EXPECT_THROW(checkPrimitive(centredSolid(Primitive::Kind::BOX, 1.0, 0.0, 1.0)), Exception);
    EXPECT_NO_THROW(checkPrimitive(centredSolid(Primitive::Kind::CAPSULE, 1.0, 0.0)));
    try
    {
        checkPrimitive(centredSolid(Primitive::Kind::CONE, 0.2, -3.0));
        FAIL();
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("cone's length"), std::string::npos) << e.what();
    }
}
