#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <vector>

#include "TestMeshes.h"
#include "TestScale.h"
#include "TestSolids.h"
#include "meshgap/geometry/BvhSolid.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/geometry/TriangleBvh.h"

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

// The traversal of a mesh's tree against a solid (bvhSolidDistance(), bvhSolidCollide()) prunes by bounds of the
// solid (its ball, its box); brute force over every triangle, with the same triangle-solid gap, is the oracle. The
// solids include flat and long ones (a table top, a rod), whose balls hold much that the solids do not.
namespace
{
    std::vector<Primitive> solids()
    {
        std::vector<Primitive> all = test::oneSolidOfEachKind();
        Primitive table;
        table.kind = Primitive::Kind::BOX;
        table.size = Vector3d(2.0, 1.2, 0.03);
        all.push_back(table);
        Primitive rod;
        rod.kind = Primitive::Kind::CYLINDER;
        rod.size = Vector3d(0.01, 3.0, 0.0);
        all.push_back(rod);
        Primitive plate;
        plate.kind = Primitive::Kind::CAPSULE;
        plate.size = Vector3d(0.005, 2.5, 0.0);
        all.push_back(plate);
        for (std::size_t k = 0; k < all.size(); ++k)  // a pose of its own in its body's frame
            all[k].pose = test::randomPose(static_cast<std::uint32_t>(k) + 300, 0.1);
        return all;
    }

    /** \brief Brute force over every triangle: the least triangle-solid gap (a lower bound of the distance, to
        GJK's convergence on curved solids) and the least distance between a gap's two witness points (real points:
        an upper bound). */
    struct BruteBounds
    {
        double lower, upper;
    };

    BruteBounds bruteForceBounds(const Mesh &mesh, const Primitive &p, const Isometry3d &X)
    {
        BruteBounds b{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        for (const Triangle &t : mesh.triangles)
        {
            const SolidGap g =
                primitiveTriangleGap(p, X, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
            b.lower = std::min(b.lower, g.distance);
            b.upper = std::min(b.upper, g.upper);
        }
        return b;
    }
}  // namespace

TEST(BvhSolid, DistanceAndCollisionAreBruteForcesOverEveryTriangle)
{
    Mesh mesh = test::icosphere(0.3, 2);  // 320 triangles
    for (Vector3d &v : mesh.vertices)
        v = Vector3d(1.5 * v.x(), v.y(), 0.4 * v.z());
    const TriangleBvh bvh(mesh);
    std::mt19937 rng(77);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int touching = 0, near = 0;
    const int trials = test::scaled(600, 40);
    for (const Primitive &p : solids())
        for (int trial = 0; trial < trials; ++trial)
        {
            // Poses about the solid's surface: a point of the solid's box within 0.5 of the mesh's centre.
            const Vector3d half = primitiveBoxHalf(p);
            const Vector3d onBox = p.pose * Vector3d(half.x() * unit(rng), half.y() * unit(rng), half.z() * unit(rng));
            Isometry3d X_MS = test::randomPose(static_cast<std::uint32_t>(rng()), 0.0);
            X_MS.translation() = 0.5 * Vector3d(unit(rng), unit(rng), unit(rng)) - X_MS.linear() * onBox;
            const std::string what = "kind " + std::to_string(int(p.kind)) + " size " +
                                     std::to_string(p.size.x()) + ", trial " + std::to_string(trial);
            // The traversal's answer is a triangle's gap (never below the least) and a lower bound of the distance
            // (never above the upper bound): a triangle pruned by a bound above its distance breaks the second.
            const BruteBounds expected = bruteForceBounds(mesh, p, X_MS);
            const double tol = 1e-12 * (1.0 + expected.upper);
            BvhSolidResult r;
            bvhSolidDistance(bvh, p, X_MS, std::numeric_limits<double>::infinity(), -1.0, r);
            ASSERT_TRUE(r.found) << what;
            EXPECT_GE(r.distance, expected.lower - tol) << what;
            EXPECT_LE(r.distance, expected.upper + tol) << what;
            EXPECT_EQ(bvhSolidCollide(bvh, p, X_MS), expected.lower == 0.0) << what;
            // Bounded: a gap below the bound is found when the distance is below it.
            BvhSolidResult bounded;
            bvhSolidDistance(bvh, p, X_MS, 0.05, -1.0, bounded);
            if (expected.upper < 0.05)
            {
                EXPECT_TRUE(bounded.found) << what;
            }
            if (!(expected.lower < 0.05))
            {
                EXPECT_FALSE(bounded.found) << what;
            }
            if (bounded.found)
            {
                EXPECT_GE(bounded.distance, expected.lower - tol) << what;
                EXPECT_LE(bounded.distance, expected.upper + tol) << what;
            }
            const double expectedDistance = expected.lower;
            touching += expectedDistance == 0.0;
            near += expectedDistance > 0.0 && expectedDistance < 0.05;
        }
    EXPECT_GT(touching, trials) << "the poses should cover collisions";
    EXPECT_GT(near, trials / 2) << "the poses should cover near misses";
}
