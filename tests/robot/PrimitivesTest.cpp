// URDF's and MoveIt's boxes, cylinders, spheres and cones as meshes: closed, wound outward, the volume and extent the
// formulas give; the round ones circumscribe the true shape (every point of it inside the mesh), and the distance from
// the mesh to a point is the analytic distance less at most the documented excess.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "meshgap/Exception.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/TriangleDistance.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/Primitives.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestScale.h"

namespace meshgap
{
    namespace
    {
        /** \brief Every edge used once in each direction: closed and consistently wound. */
        void expectClosedAndConsistent(const Mesh &m)
        {
            for (const auto &[edge, count] : test::edgeUse(m))
                EXPECT_EQ(count, 2) << edge.first << "-" << edge.second;
            std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
            for (const Triangle &t : m.triangles)
                for (int k = 0; k < 3; ++k)
                {
                    const std::pair<std::uint32_t, std::uint32_t> edge(t[k], t[(k + 1) % 3]);
                    EXPECT_EQ(++directed[edge], 1);
                }
            EXPECT_TRUE(Body::build(m)->isClosed());
        }

        /** \brief How far \e p is inside the convex mesh \e m: the least of its distances below the face planes
            (negative outside). Every vertex is checked to be inside every face plane (the mesh convex). */
        double depthInside(const Mesh &m, const Eigen::Vector3d &p)
        {
            double least = std::numeric_limits<double>::infinity();
            for (const Triangle &t : m.triangles)
            {
                const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
                const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
                least = std::min(least, n.dot(a - p));
            }
            return least;
        }

        void expectConvex(const Mesh &m)
        {
            for (const Eigen::Vector3d &v : m.vertices)
                EXPECT_GE(depthInside(m, v), -1e-14 * m.bounds().diagonal().norm());
        }

        /** \brief Distance from \e p to the mesh's surface, brute force over its triangles. */
        double meshDistance(const Mesh &m, const Eigen::Vector3d &p)
        {
            double least = std::numeric_limits<double>::infinity();
            Eigen::Vector3d on;
            for (const Triangle &t : m.triangles)
                least = std::min(least, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]],
                                                              m.vertices[t[2]], on));
            return least;
        }

        /** \brief Distance from \e p (outside) to the solid cylinder about z of \e radius, z in [-h, h]. */
        double cylinderDistance(const Eigen::Vector3d &p, double radius, double h)
        {
            const double radial = std::max(0.0, p.head<2>().norm() - radius);
            const double axial = std::max(0.0, std::abs(p.z()) - h);
            return std::hypot(radial, axial);
        }
    }  // namespace

    TEST(Primitives, BoxHasItsVolumeAndExtent)
    {
        const Mesh m = boxMesh(Eigen::Vector3d(0.2, 0.3, 0.5));
        expectClosedAndConsistent(m);
        EXPECT_NEAR(signedVolume(m), 0.2 * 0.3 * 0.5, 1e-15);
        EXPECT_TRUE(m.bounds().max().isApprox(Eigen::Vector3d(0.1, 0.15, 0.25), 1e-15));
        EXPECT_TRUE(m.bounds().min().isApprox(Eigen::Vector3d(-0.1, -0.15, -0.25), 1e-15));
    }

    TEST(Primitives, CylinderIsTheCircumscribedPrism)
    {
        for (unsigned int n : {3u, 8u, 32u})
        {
            const Mesh m = cylinderMesh(0.1, 0.4, n);
            expectClosedAndConsistent(m);
            expectConvex(m);
            // The regular n-gon circumscribed about the circle (area n r^2 tan(pi / n)), times the length.
            EXPECT_NEAR(signedVolume(m), n * 0.01 * std::tan(M_PI / n) * 0.4, 1e-14) << n;
            EXPECT_NEAR(m.bounds().max().z(), 0.2, 1e-15);
            EXPECT_NEAR(m.bounds().min().z(), -0.2, 1e-15);
            const double excess = 0.1 * (1.0 / std::cos(M_PI / n) - 1.0);
            for (const Eigen::Vector3d &v : m.vertices)
                EXPECT_LE(v.head<2>().norm(), 0.1 + excess + 1e-15);
        }
    }

    TEST(Primitives, EveryPointOfTheTrueCylinderIsInsideItsMeshAndDistancesAreBoundedBelow)
    {
        std::mt19937 random(7);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (unsigned int n : {3u, 7u, 32u})
        {
            const double r = 0.3, h = 0.5, excess = r * (1.0 / std::cos(M_PI / n) - 1.0);
            const Mesh m = cylinderMesh(r, 2 * h, n);
            for (int k = 0; k < 2000; ++k)
            {
                // On the true cylinder's side (the circle the mesh must hold), and a point inside.
                const double a = 2 * M_PI * unit(random), z = h * (2 * unit(random) - 1);
                const Eigen::Vector3d side(r * std::cos(a), r * std::sin(a), z);
                EXPECT_GE(depthInside(m, side), -1e-15) << n << " " << side.transpose();
                EXPECT_GE(depthInside(m, unit(random) * side), -1e-15);
                // Outside: the mesh's distance is at most the cylinder's, and at least it less the excess.
                const Eigen::Vector3d out = side * (1 + 3 * unit(random)) + Eigen::Vector3d(0, 0, 2 * unit(random) - 1);
                const double exact = cylinderDistance(out, r, h);
                if (exact <= 0.0)
                    continue;
                const double mesh = depthInside(m, out) > 0.0 ? -meshDistance(m, out) : meshDistance(m, out);
                EXPECT_LE(mesh, exact + 1e-12) << n;
                EXPECT_GE(mesh, exact - excess - 1e-12) << n;
            }
        }
    }

    TEST(Primitives, SphereCircumscribesTheBallAndDistancesAreBoundedBelow)
    {
        std::mt19937 random(11);
        std::normal_distribution<double> normal;
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (unsigned int n : {4u, 16u, 32u, 64u})
        {
            const double r = 0.3, excess = sphereExcess(r, n);
            const Mesh m = sphereMesh(r, n);
            expectClosedAndConsistent(m);
            expectConvex(m);
            const double ball = 4.0 / 3.0 * M_PI * r * r * r;
            EXPECT_GT(signedVolume(m), ball);  // circumscribed
            EXPECT_LE(excess, r * (1.0 / std::pow(std::cos(M_PI / n), 2) - 1.0) + 1e-15) << n;
            for (const Eigen::Vector3d &v : m.vertices)
            {
                EXPECT_GE(v.norm(), r);
                EXPECT_LE(v.norm(), r + excess + 1e-15);
            }
            for (int k = 0; k < test::scaled(2000); ++k)
            {
                const Eigen::Vector3d u = Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
                EXPECT_GE(depthInside(m, r * u), -1e-15) << n << " " << u.transpose();
                // Signed: a point between the sphere and the mesh is inside the mesh.
                const double exact = r * 3 * unit(random) + 1e-3;
                const Eigen::Vector3d p = (r + exact) * u;
                const double mesh = depthInside(m, p) > 0.0 ? -meshDistance(m, p) : meshDistance(m, p);
                EXPECT_LE(mesh, exact + 1e-12) << n;
                EXPECT_GE(mesh, exact - excess - 1e-12) << n;
            }
            if (n == 64)
            {
                EXPECT_NEAR(signedVolume(m), ball, 0.01 * ball);
            }
        }
    }

    TEST(Primitives, ConeCircumscribesTheTrueCone)
    {
        std::mt19937 random(13);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        for (unsigned int n : {3u, 32u})
        {
            const double r = 0.2, length = 0.6;
            const Mesh m = coneMesh(r, length, n);
            expectClosedAndConsistent(m);
            expectConvex(m);
            EXPECT_NEAR(signedVolume(m), n * r * r * std::tan(M_PI / n) * length / 3.0, 1e-14) << n;
            EXPECT_NEAR(m.bounds().max().z(), 0.3, 1e-15);
            EXPECT_NEAR(m.bounds().min().z(), -0.3, 1e-15);
            for (int k = 0; k < 2000; ++k)
            {
                // A point of the true cone's surface: the circle at height t shrinks linearly to the apex.
                const double a = 2 * M_PI * unit(random), t = unit(random), rho = r * (1 - t);
                const Eigen::Vector3d p(rho * std::cos(a), rho * std::sin(a), -0.3 + t * length);
                EXPECT_GE(depthInside(m, p), -1e-15) << n << " " << p.transpose();
            }
        }
    }

    TEST(Primitives, AgainstFclsTrueCylinderAndSphereTheMeshesAreSafeAndWithinTheirExcess)
    {
#ifndef MESHGAP_HAVE_FCL
        GTEST_SKIP() << "FCL not found: no oracle";
#else
        // A small box at 10,000 random poses about each shape: where FCL's true primitive touches the box, the
        // circumscribed mesh does too (safe); apart, the mesh's exact distance is FCL's less at most the excess.
        std::mt19937 random(17);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        const double r = 0.2, h = 0.6;
        const BodyConstPtr box = Body::build(boxMesh(Eigen::Vector3d(0.1, 0.05, 0.08)));
        const auto boxModel = test::fclModel(box->surface());
        struct Shape
        {
            BodyConstPtr mesh;
            std::shared_ptr<fcl::CollisionGeometryd> exact;
            double excess;
        };
        const std::vector<Shape> shapes = {
            {Body::build(cylinderMesh(r, h, 32)), std::make_shared<fcl::Cylinderd>(r, h),
             r * (1.0 / std::cos(M_PI / 32) - 1.0)},
            {Body::build(sphereMesh(r, 32)), std::make_shared<fcl::Sphered>(r), sphereExcess(r, 32)}};
        const int poses = test::scaled(10000, 1000);  // the counts below in proportion
        for (const Shape &shape : shapes)
        {
            std::size_t touching = 0, apart = 0;
            for (int k = 0; k < poses; ++k)
            {
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                X.translation() = 0.45 * Eigen::Vector3d(unit(random), unit(random), unit(random));
                X.linear() = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random))
                                 .normalized()
                                 .toRotationMatrix();
                fcl::CollisionObjectd a(shape.exact, fcl::Transform3d::Identity()),
                    b(boxModel, fcl::Transform3d(X.matrix()));
                fcl::CollisionRequestd collideRequest;
                fcl::CollisionResultd collideResult;
                fcl::collide(&a, &b, collideRequest, collideResult);
                if (collideResult.isCollision())
                {
                    ++touching;
                    EXPECT_TRUE(inCollision(*shape.mesh, *box, X)) << X.translation().transpose();
                    continue;
                }
                // GJK to a tight tolerance: at its default it stops up to 1e-4 above the true distance.
                fcl::DistanceRequestd request(true);
                request.gjk_solver_type = fcl::GST_INDEP;
                request.distance_tolerance = 1e-12;
                fcl::DistanceResultd fclResult;
                fcl::distance(&a, &b, request, fclResult);
                DistanceResult mine;
                refineExact(*shape.mesh, *box, X, mine);
                if (fclResult.min_distance < 1e-4)
                    continue;  // GJK's tolerance near contact
                ++apart;
                EXPECT_LE(mine.distance, fclResult.min_distance + 1e-6);
                EXPECT_GE(mine.distance, fclResult.min_distance - shape.excess - 1e-6) << (&shape - shapes.data());
            }
            EXPECT_GT(touching, 500u * poses / 10000);
            EXPECT_GT(apart, 500u * poses / 10000);
        }
#endif
    }

    TEST(Primitives, BadSizesGetOneClearErrorEach)
    {
        EXPECT_THROW(boxMesh(Eigen::Vector3d(0.1, 0.0, 0.1)), Exception);
        EXPECT_THROW(boxMesh(Eigen::Vector3d(0.1, std::nan(""), 0.1)), Exception);
        EXPECT_THROW(cylinderMesh(-0.1, 0.1, 8), Exception);
        EXPECT_THROW(cylinderMesh(0.1, 0.1, 2), Exception);
        EXPECT_THROW(sphereMesh(0.1, 3), Exception);
        EXPECT_THROW(coneMesh(0.1, 0.0, 8), Exception);
        EXPECT_THROW(coneMesh(0.1, 0.1, 2), Exception);
        try
        {
            sphereMesh(std::numeric_limits<double>::infinity(), 8);
            FAIL();
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find("sphere: radius"), std::string::npos) << e.what();
        }
    }
}  // namespace meshgap
