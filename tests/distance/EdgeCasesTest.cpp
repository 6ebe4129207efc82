// Geometry edge cases: touching bodies, coplanar faces, one body inside another, identical bodies at the
// identity, very thin and very large meshes, and the odd-but-legal meshes users hand us (a single triangle,
// non-manifold edges, inverted normals). Oracles: the analytic value, and FCL. The verdict is never "free" where
// FCL says collision.

#include <gtest/gtest.h>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshLoader.h"

using namespace meshgap;

namespace
{
    DistanceResult exact(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        DistanceResult r;
        ExactSolver().solve(a, b, X_AB, DistanceRequest(), r);
        return r;
    }

    Eigen::Isometry3d rotated(const Eigen::Isometry3d &X, double angle, const Eigen::Vector3d &axis)
    {
        Eigen::Isometry3d R = X;
        R.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
        return R;
    }

    Mesh inverted(Mesh m)
    {
        for (Triangle &t : m.triangles)
            std::swap(t[1], t[2]);
        return m;
    }

    Mesh scaled(Mesh m, double s)
    {
        for (Eigen::Vector3d &v : m.vertices)
            v *= s;
        return m;
    }
}  // namespace

TEST(EdgeCases, TouchingFacesEdgesAndVerticesCollideWithDistanceZero)
{
    // Unit half-size boxes: A at the origin, B touching it face to face, edge to face and vertex to face.
    const BodyPtr box = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 2));
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), diag = Eigen::Vector3d(1, 1, 1).normalized();
    const double edgeReach = std::sqrt(2.0), vertexReach = std::sqrt(3.0);
    // B rotated so that an edge (about z by 45 degrees) or a vertex (the (1,1,1) diagonal along x) points at A.
    Eigen::Isometry3d vertexFirst = Eigen::Isometry3d::Identity();
    vertexFirst.linear() = Eigen::Quaterniond::FromTwoVectors(-diag, Eigen::Vector3d::UnitX()).toRotationMatrix();
    vertexFirst.translation() = Eigen::Vector3d(1.0 + vertexReach, 0.2, -0.1);
    const std::vector<std::pair<const char *, Eigen::Isometry3d>> touching = {
        {"face", test::translation(2.0, 0.3, -0.4)},
        {"edge", rotated(test::translation(1.0 + edgeReach, 0.1, 0.0), M_PI / 4, z)},
        {"vertex", vertexFirst},
    };
    for (const auto &[what, X] : touching)
    {
        const DistanceResult r = exact(*box, *box, X);
        EXPECT_TRUE(r.inCollision) << what;
        EXPECT_LE(r.distance, 0.0) << what;
        EXPECT_GT(r.distance, -1e-9) << what << ": touching is not penetrating";
        EXPECT_TRUE(inCollision(*box, *box, X)) << what;
        // Pulled apart by 1e-6 along x, they are free at that distance.
        Eigen::Isometry3d apart = X;
        apart.translation().x() += 1e-6;
        const DistanceResult s = exact(*box, *box, apart);
        EXPECT_FALSE(s.inCollision) << what;
        EXPECT_NEAR(s.distance, 1e-6, 1e-12) << what;
    }
}

TEST(EdgeCases, CoplanarFacesSideBySideAndOverlapping)
{
    const BodyPtr box = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 3));
    // Side by side with coplanar top and bottom faces: the gap is the distance.
    for (double gap : {1e-8, 1e-3, 0.5})
    {
        const DistanceResult r = exact(*box, *box, test::translation(2.0 + gap, 0.0, 0.0));
        EXPECT_FALSE(r.inCollision) << gap;
        EXPECT_NEAR(r.distance, gap, 1e-12) << gap;
    }
    // Stacked, offset in x and y: the top face of A and the bottom face of B lie in one plane and overlap.
    const DistanceResult stacked = exact(*box, *box, test::translation(0.7, -0.4, 2.0));
    EXPECT_TRUE(stacked.inCollision);
    EXPECT_LE(stacked.distance, 0.0);
    // Two coplanar, overlapping flat grids (open, zero thickness): touching everywhere they overlap.
    const BodyPtr sheet = test::unrefinedBody(test::grid(2.0, 2.0, 4, 4));
    EXPECT_TRUE(exact(*sheet, *sheet, test::translation(0.5, 0.3, 0.0)).inCollision);
    EXPECT_NEAR(exact(*sheet, *sheet, test::translation(0.5, 0.3, 0.25)).distance, 0.25, 1e-12);
}

TEST(EdgeCases, BodyInsideAnotherCollidesWhateverTheWindingOfItsFaces)
{
    const Mesh big = test::box(2.0, 2.0, 2.0, 2), small = test::icosphere(0.5, 2);
    for (const Mesh &outer : {big, inverted(big)})
    {
        const BodyPtr a = test::unrefinedBody(outer), b = test::unrefinedBody(small);
        for (const Eigen::Vector3d &p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.2, -1.3, 0.9)})
        {
            const Eigen::Isometry3d X = test::translation(p.x(), p.y(), p.z());
            EXPECT_TRUE(exact(*a, *b, X).inCollision) << p.transpose();
            EXPECT_TRUE(inCollision(*a, *b, X)) << p.transpose();
            EXPECT_TRUE(inCollision(*b, *a, X.inverse())) << "the other way round, " << p.transpose();
            EXPECT_LE(exact(*a, *b, X).distance, 0.0);
        }
        // Outside the big box the small body is free, at the analytic distance (a face of the box is nearest).
        EXPECT_NEAR(exact(*a, *b, test::translation(3.5, 0.0, 0.0)).distance, 1.0, 0.02);
        EXPECT_FALSE(exact(*a, *b, test::translation(3.5, 0.0, 0.0)).inCollision);
    }
}

TEST(EdgeCases, IdenticalBodiesAtTheIdentityCollide)
{
    for (const Mesh &m : {test::box(1.0, 0.5, 0.25, 2), test::icosphere(1.0, 2), test::grid(1.0, 1.0, 3, 3)})
    {
        const BodyPtr b = test::unrefinedBody(m);
        const DistanceResult r = exact(*b, *b, Eigen::Isometry3d::Identity());
        EXPECT_TRUE(r.inCollision);
        EXPECT_LE(r.distance, 0.0);
        EXPECT_TRUE(inCollision(*b, *b, Eigen::Isometry3d::Identity()));
    }
}

TEST(EdgeCases, LoaderKeepsOddButLegalMeshes)
{
    const std::string odd = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/odd/";
    // A single triangle, three triangles on one edge (non-manifold), every face twice, an inside-out cube.
    EXPECT_EQ(loadMesh(odd + "single_triangle.obj").triangles.size(), 1u);
    EXPECT_EQ(loadMesh(odd + "nonmanifold.obj").triangles.size(), 3u);
    LoadReport report;
    EXPECT_EQ(loadMesh(odd + "duplicated_faces.obj", &report).triangles.size(), 12u);
    EXPECT_EQ(report.clean.duplicates, 12u);
    const Mesh insideOut = loadMesh(odd + "inverted_normals.obj");
    EXPECT_EQ(insideOut.triangles.size(), 12u);
    EXPECT_TRUE(Body::build(insideOut)->isClosed());
}

#ifdef MESHGAP_HAVE_FCL
namespace
{
    // Exact distance and verdict of meshgap against FCL at random poses: identical verdicts (meshgap may call a
    // pose within 1e-9 of touching a collision, never the other way round), distances within 1e-6 relative.
    void expectAgreementWithFcl(const Mesh &ma, const Mesh &mb, double radius, int poses, const char *what)
    {
        const BodyPtr a = test::unrefinedBody(ma), b = test::unrefinedBody(mb);
        const auto fa = test::fclModel(ma), fb = test::fclModel(mb);
        int collisions = 0;
        for (int i = 0; i < poses; ++i)
        {
            const Eigen::Isometry3d X = test::randomPose(1000u + static_cast<std::uint32_t>(i), radius);
            const DistanceResult r = exact(*a, *b, X);
            const bool fclHit = test::fclCollide(fa, fb, X);
            collisions += fclHit;
            if (fclHit)
            {
                EXPECT_TRUE(r.inCollision) << what << " pose " << i << ": FCL says collision, meshgap free";
                continue;
            }
            const double d = test::fclDistance(fa, fb, X);
            if (r.inCollision)
            {
                // Only a containment FCL cannot see, or a touch within roundoff.
                EXPECT_TRUE(d < 1e-9 * radius || containsPoint(*a, X * mb.vertices[0]) ||
                            containsPoint(*b, X.inverse() * ma.vertices[0]))
                    << what << " pose " << i << ": meshgap says collision, FCL distance " << d;
                continue;
            }
            EXPECT_NEAR(r.distance, d, 1e-6 * d + 1e-9 * radius) << what << " pose " << i;
            EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-9 * (1 + r.distance)) << what << " pose " << i;
        }
        EXPECT_GT(collisions, 0) << what << ": no pose collides; the test would not see a missed collision";
        EXPECT_LT(collisions, poses) << what << ": every pose collides; the distances went unchecked";
    }
}  // namespace

TEST(EdgeCases, VeryThinMeshesMatchFcl)
{
    // A sheet 1e-7 thick (closed) and an open single-layer grid against a box.
    expectAgreementWithFcl(test::box(1.0, 1.0, 5e-8, 2), test::box(0.3, 0.2, 0.4, 1), 1.0, 150, "thin box");
    expectAgreementWithFcl(test::grid(2.0, 2.0, 5, 5), test::icosphere(0.3, 1), 0.8, 150, "open grid");
}

TEST(EdgeCases, VeryLargeMeshesMatchFcl)
{
    expectAgreementWithFcl(scaled(test::box(1.0, 0.6, 0.4, 2), 1e6), scaled(test::icosphere(0.5, 2), 1e6), 1.5e6, 150,
                           "scale 1e6");
}

TEST(EdgeCases, VerySmallMeshesGiveTheUnitAnswerScaled)
{
    // FCL is no oracle at this scale (its absolute tolerances give distance 0 for gaps of 1e-5 here), but geometry
    // is: scaling both bodies and the translation by s scales the distance by s and keeps every verdict. The unit
    // answers are FCL's (the test above, and ExactDistance's).
    const double s = 1e-4;
    const Mesh ma = test::box(1.0, 0.6, 0.4, 2), mb = test::icosphere(0.5, 2);
    const BodyPtr a = test::unrefinedBody(ma), b = test::unrefinedBody(mb);
    const BodyPtr as = test::unrefinedBody(scaled(ma, s)), bs = test::unrefinedBody(scaled(mb, s));
    int collisions = 0;
    for (std::uint32_t i = 0; i < 150; ++i)
    {
        const Eigen::Isometry3d X = test::randomPose(1000u + i, 1.5);
        Eigen::Isometry3d Xs = X;
        Xs.translation() *= s;
        const DistanceResult unit = exact(*a, *b, X), small = exact(*as, *bs, Xs);
        EXPECT_EQ(small.inCollision, unit.inCollision) << "pose " << i;
        collisions += unit.inCollision;
        if (!unit.inCollision)
        {
            EXPECT_NEAR(small.distance, s * unit.distance, 1e-9 * s * (1 + unit.distance)) << "pose " << i;
        }
    }
    EXPECT_GT(collisions, 0);
    EXPECT_LT(collisions, 150);
}

TEST(EdgeCases, OddButLegalMeshesMatchFcl)
{
    const std::string odd = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/odd/";
    const Mesh cube = test::box(0.4, 0.3, 0.2, 1);
    for (const char *name : {"single_triangle.obj", "nonmanifold.obj", "duplicated_faces.obj", "inverted_normals.obj"})
        expectAgreementWithFcl(loadMesh(odd + name), cube, 1.2, 150, name);
}
#endif
