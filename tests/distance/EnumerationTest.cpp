#include <gtest/gtest.h>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/SolverFactory.h"

using namespace meshgap;

namespace
{
    // The oracle: every pair, no pruning.
    double bruteForce(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        double best = std::numeric_limits<double>::infinity();
        for (std::uint32_t i = 0; i < a.numNodes(); ++i)
            for (std::uint32_t j = 0; j < b.numNodes(); ++j)
                best = std::min(best, (a.node(i) - X_AB * b.node(j)).squaredNorm());
        return std::sqrt(best);
    }

}  // namespace

TEST(Enumeration, EqualsBruteForceOverAllPairsAtRandomPoses)
{
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 2.0, 0.5, 6)), b = test::unrefinedBody(test::icosphere(0.8, 3));
    const Enumeration enumeration;
    for (std::uint32_t seed = 1; seed <= 30; ++seed)
    {
        const Eigen::Isometry3d X_AB = test::randomPose(seed, 4.0);
        DistanceResult r;
        enumeration.solve(*a, *b, X_AB, DistanceRequest(), r);
        EXPECT_EQ(r.distance, bruteForce(*a, *b, X_AB)) << "seed " << seed;
        // The reported pair and witness points are consistent with the distance.
        EXPECT_NEAR((a->node(r.nodes.a) - X_AB * b->node(r.nodes.b)).norm(), r.distance, 1e-12);
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12);
        EXPECT_TRUE(r.nodeOptimal);
        EXPECT_LE(r.evaluations, std::size_t(a->numNodes()) * b->numNodes());
    }
}

TEST(Enumeration, PrunesFarAwayClusters)
{
    // Two spheres 0.5 apart: one small closest region, so the exact pruning leaves a small share of the pairs
    // (two facing cluster groups, not all 642 x 642 node pairs).
    const BodyPtr s = test::unrefinedBody(test::icosphere(1.0, 3));
    DistanceResult r;
    Enumeration().solve(*s, *s, test::translation(2.5, 0, 0), DistanceRequest(), r);
    EXPECT_EQ(r.distance, bruteForce(*s, *s, test::translation(2.5, 0, 0)));
    EXPECT_LT(r.evaluations, std::size_t(s->numNodes()) * s->numNodes() / 20);
}

TEST(Enumeration, AnalyticGaps)
{
    // Parallel faces with aligned grids: the node distance is the gap itself.
    const BodyPtr box = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 4));
    for (double gap : {1e-6, 0.3, 7.0})
    {
        DistanceResult r;
        Enumeration().solve(*box, *box, test::translation(2.0 + gap, 0, 0), DistanceRequest(), r);
        EXPECT_NEAR(r.distance, gap, 1e-12);
        EXPECT_NEAR(r.onA.x(), 1.0, 1e-15);
        EXPECT_NEAR(r.onB.x(), 1.0 + gap, 1e-12);
    }
    // Two spheres: node distance is at least the true gap, and within the sagitta of the mesh of it.
    const BodyPtr s = test::unrefinedBody(test::icosphere(1.0, 3));
    for (std::uint32_t seed = 1; seed <= 10; ++seed)
    {
        Eigen::Isometry3d X = test::randomPose(seed, 1.0);
        X.translation() = X.translation().normalized() * 3.0;
        DistanceResult r;
        Enumeration().solve(*s, *s, X, DistanceRequest(), r);
        EXPECT_GE(r.distance, 1.0 - 1e-12);
        EXPECT_LE(r.distance, 1.0 + 0.2);  // level-3 icosphere edge ~0.15: nodes lie within that of the pole
    }
}

TEST(Enumeration, CornerToCornerEqualsExactDistance)
{
    // Rotate a cube so its corner (1,1,1) points along +x; B is the same cube turned to point a corner along -x.
    const Eigen::Quaterniond toX = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d::UnitX());
    Eigen::Isometry3d R = Eigen::Isometry3d::Identity();
    R.linear() = toX.toRotationMatrix();
    const Mesh cube = test::transformed(test::box(1, 1, 1, 3), R);
    const BodyPtr a = test::unrefinedBody(cube);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X.translation().x() = 2 * std::sqrt(3.0) + 0.25;
    DistanceResult r;
    Enumeration().solve(*a, *a, X, DistanceRequest(), r);
    EXPECT_NEAR(r.distance, 0.25, 1e-12);
#ifdef MESHGAP_HAVE_FCL
    const auto model = test::fclModel(cube);
    EXPECT_NEAR(test::fclDistance(model, model, X), r.distance, 1e-9);
#endif
}

#ifdef MESHGAP_HAVE_FCL
TEST(Enumeration, NeverBelowFclExactDistance)
{
    // A node pair is a pair of surface points, so its distance can only be at or above the exact minimum.
    const Mesh ma = test::box(1.0, 0.5, 2.0, 3), mb = test::icosphere(0.7, 2);
    const BodyPtr a = test::unrefinedBody(ma), b = test::unrefinedBody(mb);
    const auto fa = test::fclModel(ma), fb = test::fclModel(mb);
    int compared = 0;
    for (std::uint32_t seed = 1; seed <= 40; ++seed)
    {
        const Eigen::Isometry3d X_AB = test::randomPose(seed, 4.0);
        if (test::fclCollide(fa, fb, X_AB))
            continue;
        DistanceResult r;
        Enumeration().solve(*a, *b, X_AB, DistanceRequest(), r);
        EXPECT_GE(r.distance, test::fclDistance(fa, fb, X_AB) - 1e-9) << "seed " << seed;
        ++compared;
    }
    EXPECT_GE(compared, 20);
}
#endif

TEST(SolverFactory, KnowsItsNamesAndRejectsOthers)
{
    for (const std::string &name : solverNames())
        EXPECT_EQ(allocSolver(name)->getName(), name);
    try
    {
        allocSolver("comb-XX");
        FAIL();
    }
    catch (const std::exception &e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("comb-XX"), std::string::npos);
        EXPECT_NE(what.find("enumeration"), std::string::npos);
        EXPECT_NE(what.find("hill-climb"), std::string::npos);
    }
}
