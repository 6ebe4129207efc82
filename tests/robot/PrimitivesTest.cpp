// URDF's boxes, cylinders and spheres as meshes: closed, wound outward, the volume and extent the formulas give.
#include <gtest/gtest.h>

#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/Primitives.h"
#include "TestMeshes.h"

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
    }  // namespace

    TEST(Primitives, BoxHasItsVolumeAndExtent)
    {
        const Mesh m = boxMesh(Eigen::Vector3d(0.2, 0.3, 0.5));
        expectClosedAndConsistent(m);
        EXPECT_NEAR(signedVolume(m), 0.2 * 0.3 * 0.5, 1e-15);
        EXPECT_TRUE(m.bounds().max().isApprox(Eigen::Vector3d(0.1, 0.15, 0.25), 1e-15));
        EXPECT_TRUE(m.bounds().min().isApprox(Eigen::Vector3d(-0.1, -0.15, -0.25), 1e-15));
    }

    TEST(Primitives, CylinderIsTheInscribedPrism)
    {
        for (unsigned int n : {3u, 8u, 32u})
        {
            const Mesh m = cylinderMesh(0.1, 0.4, n);
            expectClosedAndConsistent(m);
            // The regular n-gon inscribed in the circle, times the length.
            EXPECT_NEAR(signedVolume(m), 0.5 * n * 0.01 * std::sin(2 * M_PI / n) * 0.4, 1e-14) << n;
            EXPECT_NEAR(m.bounds().max().z(), 0.2, 1e-15);
            EXPECT_NEAR(m.bounds().min().z(), -0.2, 1e-15);
            for (const Eigen::Vector3d &v : m.vertices)
                EXPECT_LE(v.head<2>().norm(), 0.1 + 1e-15);
        }
    }

    TEST(Primitives, SphereHasEveryVertexOnTheSphereAndAlmostItsVolume)
    {
        for (unsigned int n : {4u, 16u, 64u})
        {
            const Mesh m = sphereMesh(0.3, n);
            expectClosedAndConsistent(m);
            for (const Eigen::Vector3d &v : m.vertices)
                EXPECT_NEAR(v.norm(), 0.3, 1e-15);
            const double ball = 4.0 / 3.0 * M_PI * 0.027;
            EXPECT_GT(signedVolume(m), 0.0);
            EXPECT_LT(signedVolume(m), ball);  // inscribed
            if (n == 64)
            {
                EXPECT_NEAR(signedVolume(m), ball, 0.01 * ball);
            }
        }
    }

    TEST(Primitives, BadSizesGetOneClearErrorEach)
    {
        EXPECT_THROW(boxMesh(Eigen::Vector3d(0.1, 0.0, 0.1)), Exception);
        EXPECT_THROW(boxMesh(Eigen::Vector3d(0.1, std::nan(""), 0.1)), Exception);
        EXPECT_THROW(cylinderMesh(-0.1, 0.1, 8), Exception);
        EXPECT_THROW(cylinderMesh(0.1, 0.1, 2), Exception);
        EXPECT_THROW(sphereMesh(0.1, 3), Exception);
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
