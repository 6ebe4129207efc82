// The scene layer (a robot among many obstacles, with a broad phase and a warm start) against oracles that have
// neither: the minimum over all obstacles of the pair solver (brute force), and FCL on the whole world mesh.

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <random>
#include <thread>

#include "TestNote.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/TriangleDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    Eigen::Isometry3d pose(double x, double y, double z, double angle = 0.0,
                           const Eigen::Vector3d &axis = Eigen::Vector3d::UnitZ())
    {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
        X.translation() = Eigen::Vector3d(x, y, z);
        return X;
    }

    // A concave robot: a U of three boxes (three closed shells, not welded), about 2.2 x 1.6 x 0.6.
    Mesh uRobot()
    {
        Mesh m = test::merged(test::transformed(test::box(1.1, 0.15, 0.3, 2), pose(0, -0.65, 0)),
                              test::transformed(test::box(0.15, 0.8, 0.3, 2), pose(-0.95, 0, 0)));
        return test::merged(m, test::transformed(test::box(0.15, 0.8, 0.3, 2), pose(0.95, 0, 0)));
    }

    // Eight obstacles scattered in [-6, 6]^3, as one world mesh: boxes (some rotated, one long and thin, one a flat
    // slab) and icospheres.
    Mesh scatteredWorld()
    {
        const Eigen::Vector3d tilt(1.0, 2.0, 0.5);
        Mesh w = test::transformed(test::box(1.0, 1.0, 1.0, 2), pose(-3.5, -3.0, 0.0, 0.4, tilt));
        w = test::merged(w, test::transformed(test::icosphere(1.2, 2), pose(3.0, 3.0, 1.0)));
        w = test::merged(w, test::transformed(test::box(4.0, 0.3, 0.3, 3), pose(0.0, 0.5, -3.5, 0.3)));
        w = test::merged(w, test::transformed(test::icosphere(0.7, 1), pose(-2.0, 3.5, 2.5)));
        w = test::merged(w, test::transformed(test::box(0.5, 2.0, 0.8, 2), pose(4.0, -3.0, -1.0, -0.7, tilt)));
        w = test::merged(w, test::transformed(test::icosphere(0.9, 2), pose(0.5, -1.0, 3.5)));
        w = test::merged(w, test::transformed(test::box(1.5, 1.5, 0.2, 2), pose(-4.0, 1.0, -2.0, 0.9)));
        w = test::merged(w, test::transformed(test::box(0.6, 0.6, 0.6, 1), pose(1.5, 1.0, 0.0, 1.1, tilt)));
        w.source = "scattered";
        return w;
    }

    BodyOptions coarse()
    {
        BodyOptions options;
        options.gridSize = 0.3;  // nodes every 0.3 or less: enough for the fast mode, cheap mesh distances
        return options;
    }

    /** \brief The oracle: ExactSolver on every obstacle (no broad phase, no warm start), the minimum kept. */
    struct BruteForce
    {
        double distance{std::numeric_limits<double>::infinity()};
        bool inCollision{false};
        std::vector<double> perObstacle;
    };

    BruteForce sceneBruteForce(const Scene &scene, const Eigen::Isometry3d &X_WR)
    {
        BruteForce b;
        for (const BodyConstPtr &obstacle : scene.obstacles())
        {
            DistanceResult r;
            ExactSolver().solve(*obstacle, scene.robot(), X_WR, DistanceRequest(), r);
            EXPECT_TRUE(r.certified);
            b.perObstacle.push_back(r.distance);
            b.distance = std::min(b.distance, r.distance);
            b.inCollision = b.inCollision || r.inCollision;
        }
        return b;
    }

    /** \brief Distance from \e p to the nearest triangle of \e m. */
    double distanceToSurface(const Mesh &m, const Eigen::Vector3d &p)
    {
        double best = std::numeric_limits<double>::infinity();
        Eigen::Vector3d on;
        for (const Triangle &t : m.triangles)
            best = std::min(best, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on));
        return best;
    }

    /** \brief Random poses over the scattered world: position uniform in [-6, 6]^3, uniform rotation. */
    std::vector<Eigen::Isometry3d> randomPoses(std::uint32_t first, std::size_t count)
    {
        std::vector<Eigen::Isometry3d> poses;
        for (std::uint32_t seed = first; poses.size() < count; ++seed)
            poses.push_back(test::randomPose(seed, 6.0));
        return poses;
    }

    /** \brief A straight-line motion from \e from to \e to, the rotation interpolated (slerp), \e steps + 1 poses. */
    std::vector<Eigen::Isometry3d> straightLine(const Eigen::Isometry3d &from, const Eigen::Isometry3d &to,
                                                std::size_t steps)
    {
        const Eigen::Quaterniond q0(from.linear()), q1(to.linear());
        std::vector<Eigen::Isometry3d> poses;
        for (std::size_t i = 0; i <= steps; ++i)
        {
            const double s = static_cast<double>(i) / static_cast<double>(steps);
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q0.slerp(s, q1).toRotationMatrix();
            X.translation() = (1.0 - s) * from.translation() + s * to.translation();
            poses.push_back(X);
        }
        return poses;
    }
}  // namespace

TEST(Scene, SplitComponentsOfMergedMeshes)
{
    const Mesh a = test::box(1.0, 1.0, 1.0, 2), b = test::icosphere(0.5, 1), c = test::grid(2.0, 1.0, 3, 2);  // open
    Mesh m = test::merged(test::merged(a, test::transformed(b, pose(3, 0, 0))), test::transformed(c, pose(0, 3, 0)));
    // A vertex no triangle uses is dropped; interleave the triangles of the first two parts to check the order.
    m.vertices.emplace_back(9.0, 9.0, 9.0);
    std::swap(m.triangles[1], m.triangles[a.triangles.size()]);  // triangle 1 now belongs to the icosphere
    const std::vector<Mesh> parts = splitComponents(m);
    ASSERT_EQ(parts.size(), 3u);
    // Order of first triangle: box (triangle 0), icosphere (triangle 1), grid.
    EXPECT_EQ(parts[0].triangles.size(), a.triangles.size());
    EXPECT_EQ(parts[1].triangles.size(), b.triangles.size());
    EXPECT_EQ(parts[2].triangles.size(), c.triangles.size());
    EXPECT_EQ(parts[0].vertices.size(), a.vertices.size());
    EXPECT_EQ(parts[1].vertices.size(), b.vertices.size());
    EXPECT_EQ(parts[2].vertices.size(), c.vertices.size());
    std::size_t vertices = 0, triangles = 0;
    for (const Mesh &p : parts)
    {
        vertices += p.vertices.size();
        triangles += p.triangles.size();
        EXPECT_EQ(countComponents(p), 1u);  // connected, and no unused vertex (it would count as a component)
        EXPECT_NO_THROW(p.validate());
    }
    EXPECT_EQ(vertices, m.vertices.size() - 1);
    EXPECT_EQ(triangles, m.triangles.size());
    // Geometry kept: each part's triangles are the original triangles, corner for corner.
    EXPECT_EQ(parts[1].bounds().min(), test::transformed(b, pose(3, 0, 0)).bounds().min());
    const Triangle &t1 = m.triangles[1], &p1 = parts[1].triangles[0];
    for (int k = 0; k < 3; ++k)
        EXPECT_EQ(parts[1].vertices[p1[k]], m.vertices[t1[k]]);

    // The scattered world: eight parts; one part is the whole mesh.
    EXPECT_EQ(splitComponents(scatteredWorld()).size(), 8u);
    EXPECT_EQ(splitComponents(a).size(), 1u);
    EXPECT_EQ(splitComponents(a)[0].triangles, a.triangles);
    Mesh bad = a;
    bad.triangles.push_back({0, 1, 99999});
    EXPECT_THROW(splitComponents(bad), Exception);
}

TEST(Scene, DistanceIsTheMinimumOverAllObstaclesAtRandomPoses)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    ASSERT_EQ(scene->obstacles().size(), 8u);
    std::size_t collisions = 0, free = 0, pairs = 0;
    for (const Eigen::Isometry3d &X : randomPoses(1, 200))
    {
        const BruteForce oracle = sceneBruteForce(*scene, X);
        SceneWarmStart cold;
        SceneResult r;
        scene->distance(X, SceneRequest(), cold, r);
        pairs += r.pairsChecked;
        ASSERT_EQ(r.inCollision, oracle.inCollision);
        EXPECT_EQ(scene->inCollision(X), oracle.inCollision);
        EXPECT_TRUE(r.certified);
        EXPECT_EQ(cold.cold, 1u);  // a fresh warm start answers cold, and keeps no certificate yet
        EXPECT_FALSE(cold.valid);
        ASSERT_LT(r.obstacle, scene->obstacles().size());
        if (r.inCollision)
        {
            ++collisions;
            // The signed distance: the most negative over all obstacles (each pair's signed distance as the pair
            // solver computes it, the same bits), at the smallest index among ties.
            EXPECT_LT(r.distance, 0.0);
            EXPECT_EQ(r.distance, oracle.distance);
            EXPECT_EQ(oracle.perObstacle[r.obstacle], r.distance);
            for (std::size_t k = 0; k < r.obstacle; ++k)
                EXPECT_GT(oracle.perObstacle[k], r.distance);
            EXPECT_EQ(r.distance, r.penetrationDepth > 0.0 ? -r.penetrationDepth : CONTACT_DISTANCE);
            if (r.penetration == Penetration::DEEPEST_NODE)
            {
                EXPECT_NEAR((r.onA - r.onB).norm(), r.penetrationDepth, 1e-12);
            }
            continue;
        }
        ++free;
        // Same pair computation, no seed: the same bits.
        EXPECT_EQ(r.distance, oracle.distance);
        EXPECT_EQ(oracle.perObstacle[r.obstacle], r.distance);
        // Witness points, world frame: at the distance, on the obstacle's surface and on the placed robot's.
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12 * (1.0 + r.distance));
        EXPECT_LT(distanceToSurface(scene->obstacles()[r.obstacle]->surface(), r.onB), 1e-12);
        EXPECT_LT(distanceToSurface(scene->robot().surface(), X.inverse() * r.onA), 1e-12);
    }
    const double meanPairs = static_cast<double>(pairs) / 200.0;
    test::Note() << "[ scene    ] 200 random poses: " << collisions << " colliding, " << free
              << " free; pairs past the broad phase per query: " << meanPairs << " of 8\n";
    EXPECT_GT(collisions, 20u);
    EXPECT_GT(free, 40u);
    EXPECT_LT(meanPairs, 4.0);  // the broad phase must skip most obstacles
}

TEST(Scene, WarmStartNeverChangesTheAnswerAlongAMotion)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    // Three straight-line motions through the scene, the robot turning as it goes; 0.025 or less per step.
    std::vector<Eigen::Isometry3d> poses;
    for (const auto &[from, to] :
         {std::make_pair(pose(-7, -1, 0.3, 0.2), pose(7, 1.5, -0.2, 1.5, Eigen::Vector3d(1, 1, 0))),
          std::make_pair(pose(-5, 5, 4, -0.5, Eigen::Vector3d::UnitX()), pose(5, -5, -4, 0.6)),
          std::make_pair(pose(2, -6, -3, 0.0), pose(-3, 6, 1, 2.0, Eigen::Vector3d(0, 1, 1)))})
    {
        const auto segment = straightLine(from, to, 600);
        poses.insert(poses.end(), segment.begin(), segment.end());
    }
    SceneWarmStart warm, collisionWarm;
    std::size_t warmQueries = 0, hits = 0, collisions = 0, identical = 0, pairsWarm = 0, pairsCold = 0;
    double worstDifference = 0.0;  // relative
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        const bool hadWarm = warm.valid;
        SceneResult w, c;
        scene->distance(poses[i], SceneRequest(), warm, w);
        SceneWarmStart cold;
        scene->distance(poses[i], SceneRequest(), cold, c);
        ASSERT_EQ(w.inCollision, c.inCollision) << "pose " << i;
        // The collision test alone, carried from pose to pose (its own warm start), and stateless.
        ASSERT_EQ(scene->inCollision(poses[i], collisionWarm), c.inCollision) << "pose " << i;
        ASSERT_EQ(scene->inCollision(poses[i]), c.inCollision) << "pose " << i;
        // The same answer bit for bit: ties between triangle pairs are broken canonically (bvhDistance()), so the
        // seed cannot change which pair is reported. Witness points too, when separated.
        EXPECT_EQ(w.distance, c.distance) << "pose " << i;
        // Witness points too; in collision the whole answer (signed distance, obstacle, depth) is a pure function
        // of the pose.
        EXPECT_EQ(w.onA, c.onA) << "pose " << i;
        EXPECT_EQ(w.onB, c.onB) << "pose " << i;
        if (c.inCollision)
        {
            EXPECT_LT(c.distance, 0.0) << "pose " << i;
            EXPECT_EQ(w.obstacle, c.obstacle) << "pose " << i;
            EXPECT_EQ(w.penetration, c.penetration) << "pose " << i;
            EXPECT_EQ(w.penetrationDepth, c.penetrationDepth) << "pose " << i;
        }
        EXPECT_TRUE(w.certified);
        EXPECT_FALSE(c.warmStartHit);
        identical += w.distance == c.distance;
        if (!c.inCollision)
            worstDifference = std::max(worstDifference, std::abs(w.distance - c.distance) / c.distance);
        collisions += w.inCollision;
        warmQueries += hadWarm;
        hits += w.warmStartHit;
        pairsWarm += w.pairsChecked;
        pairsCold += c.pairsChecked;
    }
    const double hitRate = static_cast<double>(hits) / static_cast<double>(warmQueries);
    test::Note() << "[ scene    ] " << poses.size() << " poses along 3 lines (" << collisions
              << " colliding): warm-start hit rate " << hitRate << ", bit-identical distances " << identical
              << " (worst relative difference " << worstDifference << ")"
              << ", pairs per query warm " << static_cast<double>(pairsWarm) / poses.size() << " / cold "
              << static_cast<double>(pairsCold) / poses.size() << "\n";
    RecordProperty("warm_start_hit_rate", std::to_string(hitRate));
    EXPECT_GT(collisions, 10u);
    EXPECT_LT(collisions, poses.size() / 2);
    EXPECT_GT(hitRate, 0.9);  // small steps: the closest obstacle rarely changes
    std::size_t kept = 0, retested = 0;
    for (const ExactWarmStart &pair : collisionWarm.pairs)
    {
        kept += pair.collision.reused;
        retested += pair.collision.retested;
    }
    EXPECT_GT(kept, retested);  // the collision fronts were used
}

TEST(Scene, InCollisionTheDeepestObstacleWinsWhateverTheWarmStartOrOrder)
{
    // Two boxes 3 apart; a long robot box bridging them, 0.05 into the first and 0.15 into the second (faces
    // parallel): signed distance -0.15 at the second, whether the warm start points at the first, the second or
    // nothing, in both modes. With an early stop (a validity check) no depth: CONTACT_DISTANCE.
    const Mesh world = test::merged(test::transformed(test::box(1.0, 1.0, 1.0, 2), pose(-2.5, 0, 0)),
                                    test::transformed(test::box(1.0, 1.0, 1.0, 2), pose(2.5, 0, 0)));
    BodyOptions options;
    options.gridSize = 0.25;
    const ScenePtr scene = Scene::fromMeshes(test::box(1.6, 0.3, 0.3, 4), world, options);
    ASSERT_EQ(scene->obstacles().size(), 2u);
    // Robot x range [0.05 - 1.6, 0.05 + 1.6] = [-1.55, 1.65]: 0.05 into the first box (x <= -1.5), 0.15 into the
    // second (x >= 1.5); its end faces and the boxes' faces are parallel, so those are the depths.
    const Eigen::Isometry3d Y = pose(0.05, 0.2, -0.1);
    const std::size_t second = scene->obstacles()[0]->surface().bounds().min().x() > 0 ? 0 : 1;
    for (bool exact : {true, false})
    {
        SceneRequest request;
        request.exact = exact;
        std::vector<SceneResult> answers;
        for (int start = -1; start < 2; ++start)
        {
            SceneWarmStart warm;
            warm.valid = start >= 0;
            warm.obstacle = start >= 0 ? static_cast<std::size_t>(start) : 0;
            answers.emplace_back();
            scene->distance(Y, request, warm, answers.back());
        }
        for (const SceneResult &r : answers)
        {
            ASSERT_TRUE(r.inCollision);
            EXPECT_EQ(r.penetration, Penetration::DEEPEST_NODE);
            EXPECT_NEAR(r.distance, -0.15, 1e-12);
            EXPECT_EQ(r.obstacle, second);
            EXPECT_EQ(r.distance, answers[0].distance);
            EXPECT_EQ(r.onA, answers[0].onA);
        }
        SceneRequest validity = request;
        validity.stopBelow = 0.0;
        SceneWarmStart warm;
        SceneResult v;
        scene->distance(Y, validity, warm, v);
        EXPECT_TRUE(v.inCollision);
        EXPECT_EQ(v.distance, CONTACT_DISTANCE);
        EXPECT_EQ(v.penetration, Penetration::NOT_COMPUTED);
    }
}

TEST(Scene, StopBelowGivesAnUpperBoundAtOrBelowTheThresholdAndTheExactAnswerAbove)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    const double threshold = 0.4;
    std::size_t stoppedBelow = 0, above = 0;
    SceneWarmStart warm;  // warm along the sequence: the early stop must not spoil the warm start either
    for (const Eigen::Isometry3d &X : randomPoses(1001, 150))
    {
        SceneWarmStart cold;
        SceneResult exact, early;
        scene->distance(X, SceneRequest(), cold, exact);
        SceneRequest request;
        request.stopBelow = threshold;
        scene->distance(X, request, warm, early);
        if (exact.distance > threshold)
        {
            ++above;
            EXPECT_NEAR(early.distance, exact.distance, 1e-12 * (1.0 + exact.distance));
            EXPECT_TRUE(early.certified);
            EXPECT_FALSE(early.inCollision);
        }
        else
        {
            ++stoppedBelow;
            EXPECT_LE(early.distance, threshold);
            // Never below the minimum; the exact answer may sit up to bvhDistance()'s tie slack (1e-12 of the
            // scene's scale) above it, since near-equal pairs are broken by index, not by the last bits.
            EXPECT_GE(early.distance, exact.distance - 1e-12 * 100.0);
            EXPECT_TRUE(!early.inCollision || exact.inCollision);  // a collision reported is real
            if (early.distance > 0.0)
            {
                EXPECT_FALSE(early.certified);
            }
        }
    }
    EXPECT_GT(stoppedBelow, 20u);
    EXPECT_GT(above, 20u);
}

TEST(Scene, UpperBoundGivesTheExactAnswerBelowItAndAProvenAtLeastAbove)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    std::size_t below = 0, atLeast = 0, colliding = 0;
    SceneWarmStart warm;  // warm along the sequence: a bounded answer must not spoil the warm start
    int i = 0;
    for (const Eigen::Isometry3d &X : randomPoses(1002, 200))
    {
        SceneWarmStart cold;
        SceneResult exact, bounded;
        scene->distance(X, SceneRequest(), cold, exact);
        SceneRequest request;
        request.upperBound = 0.25 + 0.5 * (i++ % 5);  // 0.25 .. 2.25: some poses below, some above
        request.stopBelow = i % 2 == 0 ? 0.0 : -1.0;   // with and without the verdict-only collision
        scene->distance(X, request, warm, bounded);
        ASSERT_EQ(bounded.inCollision, exact.inCollision) << X.matrix();  // the verdict whatever the bound
        if (exact.inCollision)
        {
            ++colliding;
            EXPECT_LT(bounded.distance, 0.0);
            EXPECT_FALSE(bounded.atLeast);
        }
        else if (exact.distance < request.upperBound)
        {
            ++below;
            EXPECT_NEAR(bounded.distance, exact.distance, 1e-12 * (1.0 + exact.distance));
            EXPECT_FALSE(bounded.atLeast);
            EXPECT_TRUE(bounded.certified);
            EXPECT_EQ(bounded.obstacle, exact.obstacle);
        }
        else
        {
            ++atLeast;
            EXPECT_TRUE(bounded.atLeast) << exact.distance << " vs bound " << request.upperBound;
            EXPECT_EQ(bounded.distance, request.upperBound);
            EXPECT_TRUE(bounded.certified);
        }
    }
    EXPECT_GT(below, 20u);
    EXPECT_GT(atLeast, 20u);
    EXPECT_GT(colliding, 5u);
    SceneWarmStart w;
    SceneResult r;
    SceneRequest bad;
    bad.upperBound = 0.0;
    EXPECT_THROW(scene->distance(Eigen::Isometry3d::Identity(), bad, w, r), Exception);
}

TEST(Scene, FastModeNeverCallsACollidingPoseFreeAndIsNeverBelowTheExactDistance)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    std::size_t collisions = 0, free = 0, evaluations = 0;
    double worstRatio = 1.0;
    SceneWarmStart warm;
    SceneRequest fast;
    fast.exact = false;
    fast.fallBack = false;  // the node search itself
    fast.seed = 7;
    for (const Eigen::Isometry3d &X : randomPoses(2001, 60))
    {
        SceneWarmStart cold, cold2;
        SceneResult exact, r, again, warmed;
        scene->distance(X, SceneRequest(), cold, exact);
        scene->distance(X, fast, cold2, r);
        ASSERT_EQ(r.inCollision, exact.inCollision);
        EXPECT_FALSE(r.certified);
        scene->distance(X, fast, warm, warmed);
        EXPECT_EQ(warmed.inCollision, exact.inCollision);
        EXPECT_GE(warmed.distance, exact.distance);
        if (exact.inCollision)
        {
            ++collisions;
            // The exact mode's signed distance, warm or cold.
            EXPECT_EQ(r.distance, exact.distance);
            EXPECT_EQ(warmed.distance, exact.distance);
            EXPECT_EQ(r.obstacle, exact.obstacle);
            EXPECT_EQ(r.penetration, exact.penetration);
            continue;
        }
        ++free;
        evaluations += r.evaluations;
        EXPECT_GE(r.distance, exact.distance);  // nodes lie on the surfaces
        EXPECT_GT(r.evaluations, 0u);
        // Witness points are nodes: at the distance reported, the robot's on the placed robot.
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12 * (1.0 + r.distance));
        EXPECT_LT(distanceToSurface(scene->robot().surface(), X.inverse() * r.onA), 1e-9);
        worstRatio = std::max(worstRatio, r.distance / exact.distance);
        // The same seed gives the same answer.
        SceneWarmStart cold3;
        scene->distance(X, fast, cold3, again);
        EXPECT_EQ(again.distance, r.distance);
    }
    test::Note() << "[ scene    ] fast mode, 60 poses (" << collisions << " colliding): worst node/exact distance "
              << worstRatio << ", mean evaluations "
              << static_cast<double>(evaluations) / std::max<std::size_t>(free, 1) << "\n";
    EXPECT_GT(collisions, 5u);
    EXPECT_GT(free, 10u);
}

TEST(Scene, FastModeFallsBackToTheExactQueryWhereTheNodeSearchWouldStartCold)
{
    // SceneRequest::fallBack (the default): a stateless node search (comb-GA-wl, or warm-fast with no warm start)
    // is never run; the exact query answers, bit for bit exact mode's, with no node evaluation. warm-fast carried
    // along a motion runs no global search: each pair's cold start (and every periodic or gap-triggered search) is
    // the exact pair query, which seeds the pair's state; the other queries climb from there, never below the exact
    // distance.
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    SceneRequest fast;
    fast.exact = false;
    for (const std::string solver : {"comb-GA-wl", "comb-SA-wl", "warm-fast"})
        for (const Eigen::Isometry3d &X : randomPoses(4001, 30))
        {
            fast.solver = solver;
            SceneResult exact, r;
            scene->distance(X, SceneRequest(), exact);
            scene->distance(X, fast, r);  // no warm start: a search from scratch
            EXPECT_TRUE(r.fellBack) << solver;
            EXPECT_EQ(r.evaluations, 0u) << solver;
            EXPECT_EQ(r.distance, exact.distance) << solver;
            EXPECT_EQ(r.obstacle, exact.obstacle) << solver;
            EXPECT_EQ(r.certified, exact.certified) << solver;
        }
    // warm-fast carried between unrelated poses: each is a jump, answered by the exact query.
    fast.solver = "warm-fast";
    SceneWarmStart warm;
    for (const Eigen::Isometry3d &X : randomPoses(4002, 30))
    {
        SceneResult exact, r;
        scene->distance(X, SceneRequest(), exact);
        scene->distance(X, fast, warm, r);
        EXPECT_TRUE(r.fellBack);
        EXPECT_EQ(r.evaluations, 0u);
        EXPECT_EQ(r.distance, exact.distance);
    }
    warm.reset();
    std::size_t queries = 0, climbed = 0, exactPairs = 0, pairs = 0, fellBack = 0;
    for (const Eigen::Isometry3d &X : straightLine(pose(-7, -1, 0.3, 0.2), pose(7, 1.5, -0.2, 1.5), 600))
    {
        SceneResult exact, r;
        scene->distance(X, SceneRequest(), exact);
        scene->distance(X, fast, warm, r);
        ASSERT_EQ(r.inCollision, exact.inCollision);
        fellBack += r.fellBack;
        if (exact.inCollision)
            continue;
        ++queries;
        // A surface triangle pair's distance (warm-fast's patch, another frame): roundoff (1e-11 here) aside, never
        // below the exact one.
        EXPECT_GE(r.distance, exact.distance - 1e-9 * (1.0 + exact.distance)) << r.distance - exact.distance;
        exactPairs += r.exactPairs;
        pairs += r.pairsChecked;
        climbed += r.exactPairs == 0;
        for (const WarmFastState &state : warm.fast)
            EXPECT_EQ(state.globalSearches, 0u);  // no global search, ever
    }
    test::Note() << "[ scene    ] warm-fast with fall-back along a motion: " << queries << " free poses, " << climbed
                 << " only climbed; " << exactPairs << " of " << pairs << " pairs answered exactly\n";
    EXPECT_EQ(fellBack, 1u);  // the first pose alone: the run's start
    EXPECT_GT(queries, 100u);
    EXPECT_GT(exactPairs, 0u);
    EXPECT_GT(climbed, queries / 2);  // along a motion most queries only climb
}

TEST(Scene, FastModeRunsTheNamedSolverAndRefusesAnUnknownName)
{
    // SceneRequest::solver: each node-level solver named gives its own answer (enumeration the node minimum, the
    // others never below it), and an unknown name is one error listing the valid ones.
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    SceneRequest request;
    request.exact = false;
    request.fallBack = false;  // each solver's own answer
    std::size_t compared = 0;
    for (const Eigen::Isometry3d &X : randomPoses(77, 12))
    {
        if (scene->inCollision(X))
            continue;
        SceneResult exact, enumerated, climbed;
        scene->distance(X, SceneRequest(), exact);
        request.solver = "enumeration";
        scene->distance(X, request, enumerated);
        request.solver = "hill-climb";
        scene->distance(X, request, climbed);
        // The minimum over node pairs (brute force per obstacle) is what enumeration must give.
        double minimum = std::numeric_limits<double>::infinity();
        for (const BodyConstPtr &o : scene->obstacles())
            for (std::uint32_t i = 0; i < o->numNodes(); ++i)
                for (std::uint32_t j = 0; j < scene->robot().numNodes(); ++j)
                    minimum = std::min(minimum, (o->node(i) - X * scene->robot().node(j)).norm());
        EXPECT_NEAR(enumerated.distance, minimum, 1e-12 * (1.0 + minimum));
        EXPECT_GE(climbed.distance, enumerated.distance - 1e-12 * (1.0 + minimum));
        EXPECT_GE(enumerated.distance, exact.distance);
        ++compared;
    }
    EXPECT_GT(compared, 4u);
    request.solver = "comb-XX";
    SceneResult r;
    try
    {
        scene->distance(test::translation(0, 0, 0), request, r);
        ADD_FAILURE() << "an unknown solver name was accepted";
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("comb-XX"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("comb-GA-wl"), std::string::npos) << e.what();
    }
}

TEST(Scene, ThreadsSharingASceneGiveTheSingleThreadedAnswers)
{
    // One scene, two threads, each with its own warm start, both modes (the fast mode's mesh distances are built
    // on first use, from whichever thread comes first).
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    const std::vector<Eigen::Isometry3d> poses = randomPoses(3001, 40);
    auto run = [&](std::vector<SceneResult> &out)
    {
        SceneWarmStart warm;
        for (const Eigen::Isometry3d &X : poses)
            for (bool exact : {true, false})
            {
                SceneRequest request;
                request.exact = exact;
                out.emplace_back();
                scene->distance(X, request, warm, out.back());
            }
    };
    std::vector<SceneResult> a, b, single;
    std::thread ta(run, std::ref(a)), tb(run, std::ref(b));
    ta.join();
    tb.join();
    run(single);
    ASSERT_EQ(a.size(), single.size());
    ASSERT_EQ(b.size(), single.size());
    for (std::size_t i = 0; i < single.size(); ++i)
    {
        EXPECT_EQ(a[i].distance, single[i].distance) << i;
        EXPECT_EQ(b[i].distance, single[i].distance) << i;
        EXPECT_EQ(a[i].inCollision, single[i].inCollision) << i;
        EXPECT_EQ(b[i].inCollision, single[i].inCollision) << i;
    }
}

TEST(Scene, ARobotSharingAnotherScenesObstaclesGetsTheBruteForceAnswers)
{
    // A second robot (a long slab, unlike the U) among the first scene's obstacles, its broad phase shared: at
    // random poses, every obstacle's pair answer is the oracle's, through one warm start that alternates between
    // the two scenes (each its own, by id).
    const ScenePtr first = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    const Scene second(Body::build(test::box(2.4, 0.3, 0.2, 2), coarse()), *first);
    ASSERT_EQ(second.obstacles(), first->obstacles());
    EXPECT_NE(second.id(), first->id());
    SceneWarmStart warm;
    std::size_t collisions = 0;
    for (const Eigen::Isometry3d &X : randomPoses(11, 120))
        for (const Scene *scene : std::initializer_list<const Scene *>{first.get(), &second})
        {
            const BruteForce oracle = sceneBruteForce(*scene, X);
            SceneResult r;
            scene->distance(X, SceneRequest(), warm, r);
            ASSERT_EQ(r.inCollision, oracle.inCollision);
            EXPECT_EQ(scene->inCollision(X), oracle.inCollision);
            EXPECT_EQ(r.distance, oracle.distance);
            collisions += r.inCollision;
        }
    EXPECT_GT(collisions, 20u);
    EXPECT_THROW(Scene(nullptr, *first), Exception);
}

TEST(Scene, EmptyWorldAndNullBodies)
{
    const ScenePtr scene = std::make_shared<Scene>(Body::build(uRobot(), coarse()), std::vector<BodyConstPtr>());
    SceneWarmStart warm;
    SceneResult r;
    scene->distance(Eigen::Isometry3d::Identity(), SceneRequest(), warm, r);
    EXPECT_EQ(r.distance, std::numeric_limits<double>::infinity());
    EXPECT_FALSE(r.inCollision);
    EXPECT_FALSE(scene->inCollision(Eigen::Isometry3d::Identity()));
    EXPECT_THROW(Scene(nullptr, {}), Exception);
    EXPECT_THROW(Scene(Body::build(uRobot(), coarse()), {nullptr}), Exception);
}

#ifdef MESHGAP_HAVE_FCL
TEST(Scene, OmplAppProblemsMatchFclAtPathStatesAndRandomPoses)
{
    // Each problem's world split into its parts, one obstacle each: at every solution-path state (warm, along the
    // path) and at 100 random poses (cold), the same collision verdict as FCL on the whole world mesh, and where
    // free the same distance within 1e-6 relative (FCL's own accuracy on these meshes). FCL has one blind spot: a
    // robot wholly inside a closed obstacle (or one inside the robot) is a collision for meshgap and free for FCL;
    // such poses are checked to be exactly that, and counted.
    // Abstract has no path, but its world has 17 parts (the others weld into one or two): random poses only.
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    std::size_t problems = 0;
    for (const char *name : {"Easy", "cubicles", "Twistycool", "Abstract"})
    {
        const bool withPath = std::string(name) != "Abstract";
        const fs::path cfg = dir / (std::string(name) + ".cfg"), path = dir / (std::string(name) + ".path");
        if (!fs::exists(cfg) || (withPath && !fs::exists(path)))
            continue;
        problems += withPath;
        const ProblemConfig p = readProblemConfig(cfg.string());
        const Mesh world = loadMesh(p.world), robot = loadRobotMesh(p.robot);
        const ScenePtr scene = Scene::fromMeshes(robot, world);
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        const std::vector<Eigen::Isometry3d> states =
            withPath ? readPoses(path.string()) : std::vector<Eigen::Isometry3d>();

        std::vector<Eigen::Isometry3d> poses = states;
        const Eigen::AlignedBox3d volume = p.volume.value_or(world.bounds());
        std::mt19937 rng(12345);
        std::normal_distribution<double> gauss;
        for (int i = 0; i < 100; ++i)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
            X.linear() = q.normalized().toRotationMatrix();
            for (int k = 0; k < 3; ++k)
                X.translation()[k] = std::uniform_real_distribution<double>(volume.min()[k], volume.max()[k])(rng);
            poses.push_back(X);
        }

        SceneWarmStart warm;
        std::size_t collisions = 0, contained = 0, pairs = 0, pathHits = 0, freeCount = 0;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const bool onPath = i < states.size();
            const Eigen::Isometry3d &X = poses[i];
            SceneWarmStart cold;
            SceneResult r;
            scene->distance(X, SceneRequest(), onPath ? warm : cold, r);
            pairs += r.pairsChecked;
            pathHits += onPath && r.warmStartHit;
            EXPECT_TRUE(r.certified) << name << " pose " << i;
            EXPECT_EQ(scene->inCollision(X), r.inCollision) << name << " pose " << i;
            const bool fclHit = test::fclCollide(fw, fr, X);
            if (r.inCollision && !fclHit)
            {
                // Only containment may explain it: no surface contact, and one body inside the other.
                bool inside = false;
                const Body &rb = scene->robot();
                for (const BodyConstPtr &o : scene->obstacles())
                    inside = inside || containsPoint(*o, X * rb.surface().vertices[rb.surface().triangles[0][0]]) ||
                             containsPoint(rb, X.inverse() * o->surface().vertices[o->surface().triangles[0][0]]);
                EXPECT_TRUE(inside) << name << " pose " << i << ": collision FCL does not see, and no containment";
                EXPECT_GT(test::fclDistance(fw, fr, X), 0.0) << name << " pose " << i;
                ++contained;
                continue;
            }
            ASSERT_EQ(r.inCollision, fclHit) << name << " pose " << i << (onPath ? " (path state)" : "");
            if (r.inCollision)
            {
                ++collisions;
                continue;
            }
            ++freeCount;
            const double d = test::fclDistance(fw, fr, X);
            EXPECT_NEAR(r.distance, d, 1e-6 * d + 1e-9 * world.size()) << name << " pose " << i;
        }
        test::Note() << "[ scene    ] " << name << ": " << scene->obstacles().size() << " obstacles; " << states.size()
                  << " path states + 100 random poses: " << collisions << " colliding, " << contained
                  << " contained (FCL: free), " << freeCount << " free; pairs past the broad phase "
                  << static_cast<double>(pairs) / poses.size() << " per query; warm-start hits along the path "
                  << pathHits << "/" << (states.empty() ? 0 : states.size() - 1) << "\n";
    }
    if (problems == 0)
        GTEST_SKIP() << "OMPL.app problems with paths (Easy, cubicles, Twistycool) not found under " << dir
                     << "; skipping";
}
#endif

TEST(Scene, DepthSkippedGivesTheVerdictAndTheSameFreeAnswers)
{
    const ScenePtr scene = Scene::fromMeshes(uRobot(), scatteredWorld(), coarse());
    std::vector<Eigen::Isometry3d> poses;
    for (const auto &[from, to] :
         {std::make_pair(pose(-7, -1, 0.3, 0.2), pose(7, 1.5, -0.2, 1.5, Eigen::Vector3d(1, 1, 0))),
          std::make_pair(pose(-5, 5, 4, -0.5, Eigen::Vector3d::UnitX()), pose(5, -5, -4, 0.6))})
    {
        const auto segment = straightLine(from, to, 300);
        poses.insert(poses.end(), segment.begin(), segment.end());
    }
    std::size_t collisions = 0, workFull = 0, workVerdict = 0;
    for (bool exact : {true, false})
    {
        SceneRequest full, verdict;
        full.exact = verdict.exact = exact;
        verdict.computeDepth = false;
        SceneWarmStart warm;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            SceneResult f, v, vw;
            scene->distance(poses[i], full, f);
            scene->distance(poses[i], verdict, v);
            scene->distance(poses[i], verdict, warm, vw);
            for (const SceneResult *r : {&v, &vw})
            {
                ASSERT_EQ(r->inCollision, f.inCollision) << "pose " << i;
                if (!f.inCollision)
                {
                    // Fast mode's warm answer follows its history (an upper bound); the others are the same.
                    if (exact || r == &v)
                    {
                        EXPECT_EQ(r->distance, f.distance) << "pose " << i;
                        EXPECT_EQ(r->onA, f.onA) << "pose " << i;
                    }
                    continue;
                }
                EXPECT_EQ(r->distance, CONTACT_DISTANCE) << "pose " << i;
                EXPECT_EQ(r->penetration, Penetration::NOT_COMPUTED) << "pose " << i;
                EXPECT_EQ(r->penetrationDepth, 0.0) << "pose " << i;
                EXPECT_EQ(r->certified, exact || r->fellBack) << "pose " << i;  // fallen back: exact mode's
            }
            if (f.inCollision && exact)
            {
                EXPECT_NE(f.penetration, Penetration::NOT_COMPUTED) << "pose " << i;
                ++collisions;
                workFull += f.boxTests + f.triangleTests;
                workVerdict += v.boxTests + v.triangleTests;
            }
        }
    }
    test::Note() << "[ scene    ] " << collisions << " colliding poses: work with the depth " << workFull
                 << ", verdict alone " << workVerdict << "\n";
    EXPECT_GT(collisions, 10u);
    EXPECT_LT(workVerdict, workFull);  // the depth is what a colliding query pays for
}
