#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "FclOracle.h"
#include "FclRobotScene.h"
#include "TestMeshes.h"
#include "TestScale.h"
#include "TestSolids.h"
#include "meshgap/geometry/BvhSolid.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

// FCL's primitives (fcl::Box, Sphere, Cylinder, Capsule, Cone) as the oracle: against a triangle mesh, and against
// each other, at 10,000 random poses each (fixed seeds). FCL answers shapes by GJK to a tolerance: distances must
// agree within FCL_TOLERANCE, and the collision verdicts wherever FCL's distance is clear of that tolerance.
#ifdef MESHGAP_HAVE_FCL
namespace
{
    /** \brief How far FCL's GJK (GST_INDEP, distance tolerance 1e-10) may be off: measured at most about 1e-9 on
        these poses; a margin of a hundred. */
    constexpr double FCL_TOLERANCE = 1e-7;

    std::vector<Primitive> shapes()
    {
        std::vector<Primitive> all = test::oneSolidOfEachKind();
        for (Primitive &p : all)  // a pose of its own in its body's frame
            p.pose = test::randomPose(static_cast<std::uint32_t>(p.kind) + 100, 0.1);
        return all;
    }

    double fclDistance(const fcl::CollisionObjectd &a, const fcl::CollisionObjectd &b, bool &collides)
    {
        fcl::DistanceRequestd request(true);
        request.gjk_solver_type = fcl::GST_INDEP;
        request.distance_tolerance = 1e-10;
        fcl::DistanceResultd result;
        fcl::distance(&a, &b, request, result);
        fcl::CollisionRequestd collision;
        collision.gjk_solver_type = fcl::GST_INDEP;
        fcl::CollisionResultd hit;
        fcl::collide(&a, &b, collision, hit);
        collides = hit.isCollision();
        return result.min_distance;
    }

    /** \brief Whether \e q lies in solid \e p placed by \e X, within \e eps: from the solid's own definition. */
    bool inSolid(const Primitive &p, const Isometry3d &X, const Vector3d &q, double eps = 1e-9)
    {
        const Vector3d l = (X * p.pose).inverse() * q;
        const double rho = std::hypot(l.x(), l.y()), h = 0.5 * p.size.y();
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                return ((l.cwiseAbs() - 0.5 * p.size).array() <= eps).all();
            case Primitive::Kind::SPHERE:
                return l.norm() <= p.size.x() + eps;
            case Primitive::Kind::CYLINDER:
                return rho <= p.size.x() + eps && std::abs(l.z()) <= h + eps;
            case Primitive::Kind::CAPSULE:
                return Vector3d(l.x(), l.y(), std::max(0.0, std::abs(l.z()) - h)).norm() <= p.size.x() + eps;
            case Primitive::Kind::CONE:
                return std::abs(l.z()) <= h + eps && rho <= p.size.x() * (h - l.z()) / (2.0 * h) + eps;
        }
        return false;
    }

    /** \brief Tallies of a comparison with FCL. */
    struct PrimitiveFclTally
    {
        int poses{0}, touching{0}, fclShort{0};
    };

    /** \brief Our answer against FCL's at one pose. FCL's distance is that of a pair of points its GJK found, so
        ours (exact, a lower bound) never exceeds it by more than its tolerance. Where ours is smaller by more than
        that, FCL's GJK stopped short: our witnesses must then be real points (\e witnessesReal: one in each solid)
        that far apart, which proves FCL's answer too large; those poses are counted. The collision verdicts agree
        wherever FCL's distance is clear of its tolerance. */
    void expectAgrees(double ours, bool oursCollides, bool witnessesReal, double witnessGap, double fcl,
                      bool fclCollides, const std::string &what, PrimitiveFclTally &tally)
    {
        const double fclClamped = std::max(fcl, 0.0), tolerance = FCL_TOLERANCE * std::max(1.0, fclClamped);
        ++tally.poses;
        tally.touching += oursCollides;
        EXPECT_LE(ours, fclClamped + tolerance) << what;
        if (ours < fclClamped - tolerance)
        {
            ++tally.fclShort;
            EXPECT_TRUE(witnessesReal) << what;
            EXPECT_NEAR(witnessGap, ours, 1e-9) << what;
        }
        if (fcl > FCL_TOLERANCE)
        {
            EXPECT_FALSE(oursCollides) << what << ": FCL finds them " << fcl << " apart";
        }
        if (fclCollides)
        {
            EXPECT_LE(ours, FCL_TOLERANCE) << what << ": FCL finds them in collision";
        }
    }
}  // namespace

TEST(PrimitiveFclTest, EachSolidAgainstATriangleMeshAgreesWithFcl)
{
    // The twisted-box-like test mesh: 80 triangles of an icosphere stretched into an ellipsoid, so that poses cover
    // faces, edges and corners of both.
    Mesh mesh = test::icosphere(0.6, 1);
    for (Vector3d &v : mesh.vertices)
        v = Vector3d(1.4 * v.x(), v.y(), 0.6 * v.z());
    const TriangleBvh bvh(mesh);
    const auto model = test::fclModel(mesh);
    const fcl::CollisionObjectd meshObject(model, fcl::Transform3d::Identity());
    std::mt19937 rng(2024);
    PrimitiveFclTally tally;
    // 10,000 poses a solid (test::scaled: fewer under the sanitizers, the counts below in proportion).
    const int trials = test::scaled(10000, 1000);
    for (const Primitive &p : shapes())
    {
        const auto shape = fclSolidOf(p);
        for (int trial = 0; trial < trials; ++trial)
        {
            const Isometry3d X = test::randomPose(static_cast<std::uint32_t>(rng()), 1.3);
            fcl::CollisionObjectd object(shape, fcl::Transform3d((X * p.pose).matrix()));
            bool fclCollides = false;
            const double fcl = fclDistance(meshObject, object, fclCollides);
            BvhSolidResult r;
            bvhSolidDistance(bvh, p, X, std::numeric_limits<double>::infinity(), -1.0, r);
            const bool collides = bvhSolidCollide(bvh, p, X);
            ASSERT_TRUE(r.found);
            EXPECT_EQ(collides, r.distance == 0.0);
            const Triangle &f = mesh.triangles[r.triangle];
            Vector3d on;
            const bool real = inSolid(p, X, r.onSolid) &&
                              pointTriangleDistance(r.onMesh, mesh.vertices[f[0]], mesh.vertices[f[1]],
                                                    mesh.vertices[f[2]], on) <= 1e-9;
            expectAgrees(r.distance, collides, real, (r.onSolid - r.onMesh).norm(), fcl, fclCollides,
                         "solid kind " + std::to_string(int(p.kind)) + ", trial " + std::to_string(trial), tally);
        }
    }
    EXPECT_EQ(tally.poses, 5 * trials);
    EXPECT_GT(tally.touching, trials / 5) << "the poses should cover collisions too";
    EXPECT_LT(tally.fclShort, tally.poses / 100) << "FCL's GJK stopped short on more than 1% of the poses";
    std::printf("[ note ] FCL's distance above the true one (by more than %g) on %d of %d poses\n", FCL_TOLERANCE,
                tally.fclShort, tally.poses);
}

TEST(PrimitiveFclTest, SolidPairsAgreeWithFcl)
{
    const std::vector<Primitive> all = shapes();
    std::mt19937 rng(77);
    PrimitiveFclTally tally;
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i; j < all.size(); ++j)
        {
            const auto a = fclSolidOf(all[i]), b = fclSolidOf(all[j]);
            for (int trial = 0; trial < 10000 / 15 + 1; ++trial)
            {
                const Isometry3d Xa = test::randomPose(static_cast<std::uint32_t>(rng()), 0.6);
                const Isometry3d Xb = test::randomPose(static_cast<std::uint32_t>(rng()), 0.6);
                const fcl::CollisionObjectd oa(a, fcl::Transform3d((Xa * all[i].pose).matrix()));
                const fcl::CollisionObjectd ob(b, fcl::Transform3d((Xb * all[j].pose).matrix()));
                bool fclCollides = false;
                const double fcl = fclDistance(oa, ob, fclCollides);
                const SolidGap g = primitiveGap(all[i], Xa, all[j], Xb);
                const bool real = inSolid(all[i], Xa, g.onA) && inSolid(all[j], Xb, g.onB);
                expectAgrees(g.distance, g.distance == 0.0, real, (g.onA - g.onB).norm(), fcl, fclCollides,
                             "kinds " + std::to_string(int(all[i].kind)) + "-" + std::to_string(int(all[j].kind)) +
                                 ", trial " + std::to_string(trial),
                             tally);
            }
        }
    EXPECT_GE(tally.poses, 10000);
    EXPECT_GT(tally.touching, 1000);
    EXPECT_LT(tally.fclShort, tally.poses / 100) << "FCL's GJK stopped short on more than 1% of the poses";
    std::printf("[ note ] FCL's distance above the true one (by more than %g) on %d of %d poses\n", FCL_TOLERANCE,
                tally.fclShort, tally.poses);
}
#else
TEST(PrimitiveFclTest, SkippedWithoutFcl)
{
    GTEST_SKIP() << "FCL not found: the oracle of these tests";
}
#endif
