// The exact stage against FCL (whole meshes) and analytic geometry.

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    /** \brief A request that only a distance below \e upperBound matters. */
    DistanceRequest bounded(double upperBound)
    {
        DistanceRequest r;
        r.upperBound = upperBound;
        return r;
    }

    BodyPtr body(const Mesh &m, double grid = -1.0)
    {
        BodyOptions options;
        options.gridSize = grid;
        return Body::build(m, options);
    }
}  // namespace

TEST(ExactDistance, AnalyticGapBetweenBoxesWhatever)
{
    const BodyPtr box = body(test::box(1.0, 1.0, 1.0, 2));
    const ExactSolver exact;
    for (double gap : {1e-9, 0.25, 3.0})
    {
        // Rotate B about x: its face still faces A's at x = 1, the gap is unchanged.
        Eigen::Isometry3d X = test::translation(2.0 + gap, 0.3, -0.2);
        X.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
        DistanceResult r;
        exact.solve(*box, *box, X, DistanceRequest(), r);
        EXPECT_NEAR(r.distance, gap, 1e-12 * (1 + gap));
        EXPECT_TRUE(r.certified);
        EXPECT_FALSE(r.inCollision);
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12);
    }
}

TEST(ExactDistance, AnUpperBoundPrunesOnlyWhatCannotBeCloserAndNeverAContainment)
{
    // refineExact(..., upperBound): a scene passes the best distance of its other obstacles.
    const BodyPtr box = body(test::box(1.0, 1.0, 1.0, 2)), ball = body(test::icosphere(0.3, 2));
    const Eigen::Isometry3d apart = test::translation(3.0, 0.2, -0.1);  // box face at x = 1, ball: gap 3 - 1 - 0.3
    DistanceResult free;
    refineExact(*box, *ball, apart, free);
    ASSERT_FALSE(free.inCollision);
    // A bound above the distance changes nothing; one below it leaves nothing to report, proven.
    DistanceResult above;
    refineExact(*box, *ball, apart, above, bounded(free.distance + 0.1));
    EXPECT_EQ(above.distance, free.distance);
    EXPECT_TRUE(above.certified);
    DistanceResult below;
    refineExact(*box, *ball, apart, below, bounded(free.distance - 0.1));
    EXPECT_EQ(below.distance, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(below.certified);
    EXPECT_FALSE(below.inCollision);
    // The ball wholly inside the box is far from its surface, beyond any small bound: still a collision, with depth.
    DistanceResult inside;
    refineExact(*box, *ball, test::translation(0.1, 0.0, 0.0), inside, bounded(1e-3));
    EXPECT_TRUE(inside.inCollision);
    EXPECT_LT(inside.distance, 0.0);
}

#ifdef MESHGAP_HAVE_FCL
TEST(ExactDistance, EqualsFclOnRandomPosesAndAgreesOnCollision)
{
    const Mesh ma = test::uShape(), mb = test::icosphere(0.45, 2);
    const BodyPtr a = body(ma), b = body(mb);
    const auto fa = test::fclModel(ma), fb = test::fclModel(mb);
    const ExactSolver exact;
    int collisions = 0, separated = 0;
    for (std::uint32_t seed = 1; seed <= 300; ++seed)
    {
        const Eigen::Isometry3d X_AB = test::randomPose(seed, 2.0);
        DistanceResult cold, seeded;
        exact.solve(*a, *b, X_AB, DistanceRequest(), cold);
        // The same query seeded from the node-level optimum must give the same answer.
        Enumeration().solve(*a, *b, X_AB, DistanceRequest(), seeded);
        refineExact(*a, *b, X_AB, seeded);
        const bool fclHit = test::fclCollide(fa, fb, X_AB);
        ASSERT_EQ(cold.inCollision, fclHit) << "seed " << seed;
        EXPECT_EQ(seeded.inCollision, fclHit) << "seed " << seed;
        EXPECT_TRUE(cold.certified);
        if (fclHit)
        {
            ++collisions;
            // Signed: negative in collision, and a pure function of the pose (the seed cannot change it).
            EXPECT_LT(cold.distance, 0.0) << "seed " << seed;
            EXPECT_EQ(seeded.distance, cold.distance) << "seed " << seed;
            EXPECT_EQ(seeded.onA, cold.onA) << "seed " << seed;
            EXPECT_EQ(seeded.onB, cold.onB) << "seed " << seed;
            continue;
        }
        ++separated;
        const double d = test::fclDistance(fa, fb, X_AB);
        EXPECT_NEAR(cold.distance, d, 1e-9 * (1 + d)) << "seed " << seed;
        EXPECT_NEAR(seeded.distance, cold.distance, 1e-12 * (1 + d)) << "seed " << seed;
        EXPECT_LE(seeded.distance, seeded.nodeDistance + 1e-12);  // exact is never above the node answer
        EXPECT_NEAR((cold.onA - cold.onB).norm(), cold.distance, 1e-9 * (1 + d));
    }
    EXPECT_GT(collisions, 20);
    EXPECT_GT(separated, 20);
}

TEST(ExactDistance, BodyInsideAnotherIsCollisionWhereFclSaysFree)
{
    const Mesh big = test::box(2.0, 2.0, 2.0, 2), small = test::icosphere(0.5, 1);
    const BodyPtr a = body(big), b = body(small);
    const Eigen::Isometry3d inside = test::translation(0.3, -0.2, 0.1);
    DistanceResult r;
    ExactSolver().solve(*a, *b, inside, DistanceRequest(), r);
    EXPECT_TRUE(r.inCollision);
    // Signed: every node of the sphere is at least 2 - 0.3 - 0.5 deep in the box (PenetrationDepthTest has more).
    EXPECT_LE(r.distance, -1.2 + 1e-12);
    EXPECT_FALSE(test::fclCollide(test::fclModel(big), test::fclModel(small), inside));  // FCL's blind spot
    // And the other way round: the big box around the small sphere.
    DistanceResult s;
    ExactSolver().solve(*b, *a, inside.inverse(), DistanceRequest(), s);
    EXPECT_TRUE(s.inCollision);
    EXPECT_NEAR(s.distance, r.distance, 1e-12);  // the same nodes, the same surface distances
    // Just outside: free.
    DistanceResult t;
    ExactSolver().solve(*a, *b, test::translation(3.0, 0, 0), DistanceRequest(), t);
    EXPECT_FALSE(t.inCollision);
    EXPECT_NEAR(t.distance, 0.5, 1e-12);
}

TEST(ExactDistance, OmplAppPathStatesMatchFcl)
{
    // Every state of the problems' solution paths, and midpoints between them: same collision verdict as FCL, and
    // the same distance within 1e-6 relative (FCL's own accuracy on these meshes).
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    if (!fs::exists(dir))
        GTEST_SKIP() << "OMPL.app problems not found at " << dir << "; skipping";
    for (const char *name : {"Easy", "cubicles", "Twistycool"})
    {
        const ProblemConfig p = readProblemConfig((dir / (std::string(name) + ".cfg")).string());
        const Mesh world = loadMesh(p.world), robot = loadRobotMesh(p.robot);
        const BodyPtr a = body(world), b = body(robot);
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        const std::vector<Eigen::Isometry3d> path = readPoses((dir / (std::string(name) + ".path")).string());
        DistanceRequest warm;
        for (std::size_t i = 0; i < path.size(); ++i)
        {
            DistanceResult r;
            ExactSolver().solve(*a, *b, path[i], warm, r);
            warm.start = r.nodes;  // warm start along the path; must not change the answer
            ASSERT_EQ(r.inCollision, test::fclCollide(fw, fr, path[i])) << name << " state " << i;
            if (!r.inCollision)
            {
                const double d = test::fclDistance(fw, fr, path[i]);
                EXPECT_NEAR(r.distance, d, 1e-6 * d + 1e-9 * world.size()) << name << " state " << i;
            }
        }
    }
}
#endif
