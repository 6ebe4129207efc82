// The signed distance in collision: the penetration-depth estimate against analytic geometry (spheres, boxes, a body
// inside another), its lower-bound property, the point queries it is built on against brute force, and its sign
// against FCL's collision verdict.

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <random>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/geometry/TriangleDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    DistanceResult exactResult(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        DistanceResult r;
        ExactSolver().solve(a, b, X_AB, DistanceRequest(), r);
        return r;
    }

    /** \brief Radius of the largest ball about the origin inside a closed convex mesh around it: the nearest face
        plane. */
    double inradius(const Mesh &m)
    {
        double r = std::numeric_limits<double>::infinity();
        for (const Triangle &t : m.triangles)
        {
            const Eigen::Vector3d n =
                (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
            r = std::min(r, std::abs(n.dot(m.vertices[t[0]])));
        }
        return r;
    }

    Eigen::Vector3d randomUnit(std::mt19937 &rng)
    {
        std::normal_distribution<double> gauss;
        return Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    }
}  // namespace

TEST(PenetrationDepth, PointQueriesEqualBruteForce)
{
    // bvhPointDistance() against the minimum over all triangles; insideClosedBody() (ray casting through the BVH)
    // against containsPoint() (the winding number summed over every triangle), on random points in and around a
    // sphere, a box and three overlapping boxes.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uni(-2.0, 2.0);
    std::size_t inside = 0, outside = 0;
    for (const Mesh &m : {test::icosphere(1.0, 2), test::box(1.0, 0.5, 0.8, 3), test::uShape()})
    {
        const BodyPtr body = test::unrefinedBody(m);
        for (int i = 0; i < 1000; ++i)
        {
            const Eigen::Vector3d p(uni(rng), uni(rng), uni(rng));
            double brute = std::numeric_limits<double>::infinity();
            Eigen::Vector3d on;
            for (const Triangle &t : m.triangles)
                brute =
                    std::min(brute, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on));
            BvhPointResult r;
            bvhPointDistance(body->bvh(), p, std::numeric_limits<double>::infinity(), -1.0, r);
            ASSERT_TRUE(r.found);
            EXPECT_EQ(r.distance, brute) << i;
            EXPECT_NEAR((r.closest - p).norm(), r.distance, 1e-12);
            const bool in = insideClosedBody(*body, p);
            EXPECT_EQ(in, containsPoint(*body, p)) << m.source << " point " << i;
            inside += in;
            outside += !in;
        }
    }
    EXPECT_GT(inside, 100u);
    EXPECT_GT(outside, 1000u);
    // Open bodies have no inside.
    EXPECT_FALSE(insideClosedBody(*test::unrefinedBody(test::grid(1, 1, 2, 2)), Eigen::Vector3d(0.5, 0.5, 0.0)));
}

TEST(PenetrationDepth, OverlappingSpheresWithinTheMeshResolutionOfTheTrueDepth)
{
    // Spheres r1, r2 at centre distance c overlap by r1 + r2 - c, their translational penetration depth. Nodes on
    // the spheres (unrefined icospheres: vertices on the sphere, faces inside it): a node v of B inside A has depth
    // at most r1 - |v - cA| <= r1 + r2 - c (A's mesh lies inside its sphere), and the node nearest B's deepest
    // point p* (within e, the longest edge, of it) has depth at least r_in(A) - |v - cA| >= the true depth minus
    // (r1 - r_in(A)) minus e, where r_in(A) is the distance from A's centre to its nearest face plane.
    const double r1 = 1.0, r2 = 0.6;
    const Mesh ma = test::icosphere(r1, 3), mb = test::icosphere(r2, 3);
    const BodyPtr a = test::unrefinedBody(ma), b = test::unrefinedBody(mb);
    const double slack = (r1 - inradius(ma)) + longestEdge(mb);
    std::mt19937 rng(11);
    double worst = 0.0;
    for (double c : {1.55, 1.4, 1.1, 0.7})
        for (int k = 0; k < 10; ++k)
        {
            const Eigen::Vector3d u = randomUnit(rng);
            Eigen::Isometry3d X = test::translation(c * u.x(), c * u.y(), c * u.z());
            X.linear() = Eigen::AngleAxisd(0.3 * k, randomUnit(rng)).toRotationMatrix();
            const double truth = r1 + r2 - c;
            const DistanceResult r = exactResult(*a, *b, X);
            ASSERT_TRUE(r.inCollision);
            EXPECT_EQ(r.penetration, Penetration::DEEPEST_NODE);
            EXPECT_EQ(r.distance, -r.penetrationDepth);
            EXPECT_LE(r.penetrationDepth, truth + 1e-12) << c;
            EXPECT_GE(r.penetrationDepth, truth - slack) << c;
            worst = std::max(worst, truth - r.penetrationDepth);
            // Witnesses: onA - onB is the translation of B, of length depth, that brings the deepest node out.
            EXPECT_NEAR((r.onA - r.onB).norm(), r.penetrationDepth, 1e-12);
            EXPECT_TRUE(r.certified);
        }
    test::Note() << "[ depth    ] spheres: worst shortfall " << worst << " (bound " << slack << ")\n";
}

TEST(PenetrationDepth, BoxPushedIntoABoxByAKnownAmount)
{
    // B (half 0.5) pushed face-first into A (half 1) by delta along x, shifted and turned about x (its face stays
    // parallel to A's): B's face nodes at x = 1 - delta are delta deep, exactly the translational penetration depth.
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 2));
    const BodyPtr b = test::unrefinedBody(test::box(0.5, 0.5, 0.5, 2));
    for (double delta : {1e-3, 0.05, 0.2})
        for (double angle : {0.0, 0.4})
        {
            Eigen::Isometry3d X = test::translation(1.5 - delta, 0.1, -0.05);
            X.linear() = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
            const DistanceResult r = exactResult(*a, *b, X);
            ASSERT_TRUE(r.inCollision);
            EXPECT_EQ(r.penetration, Penetration::DEEPEST_NODE);
            EXPECT_NEAR(r.distance, -delta, 1e-12) << delta << " " << angle;
            EXPECT_NEAR(std::abs((r.onA - r.onB).x()), delta, 1e-12);
            // And the same from B's side.
            const DistanceResult s = exactResult(*b, *a, X.inverse());
            EXPECT_NEAR(s.distance, -delta, 1e-12);
        }
}

TEST(PenetrationDepth, SmallBodyWhollyInsideABigOne)
{
    // A sphere of radius 0.5 at (0.3, -0.2, 0.1) inside the box [-2, 2]^3: no surface contact (FCL calls it free).
    // Every node of the sphere is at least 2 - 0.3 - 0.5 = 1.2 from the box's surface; the translational depth is
    // 2.2 (the nearest face, x = 2, is 1.7 from the centre: the sphere must move 1.7 + 0.5 to clear it).
    const Mesh big = test::box(2.0, 2.0, 2.0, 2), small = test::icosphere(0.5, 2);
    const BodyPtr a = test::unrefinedBody(big), b = test::unrefinedBody(small);
    const Eigen::Isometry3d inside = test::translation(0.3, -0.2, 0.1);
    for (const DistanceResult &r : {exactResult(*a, *b, inside), exactResult(*b, *a, inside.inverse())})
    {
        ASSERT_TRUE(r.inCollision);
        EXPECT_EQ(r.penetration, Penetration::DEEPEST_NODE);
        EXPECT_GE(r.penetrationDepth, 1.2 - 1e-12);
        EXPECT_LE(r.penetrationDepth, 2.2 + 1e-12);
        EXPECT_LT(r.distance, -1.2 + 1e-12);
    }
#ifdef MESHGAP_HAVE_FCL
    EXPECT_FALSE(test::fclCollide(test::fclModel(big), test::fclModel(small), inside));
#endif
}

TEST(PenetrationDepth, ShallowCrossingWithNoNodeInsideIsStillNegative)
{
    // A long box turned 45 degrees about y, its lowest edge (along y) dipping eps below the top face z = 1 of the
    // unit box: the surfaces cross, but every corner of each lies outside the other. Unrefined: no node inside,
    // distance CONTACT_DISTANCE (< 0). Refined: nodes along that edge lie eps deep, the estimate finds them.
    const double eps = 1e-3;
    const Mesh ma = test::box(1.0, 1.0, 1.0, 1), mb = test::box(0.5, 3.0, 0.5, 1);
    Eigen::Isometry3d X = test::translation(0.0, 0.2, 1.0 - eps + 0.5 * std::sqrt(2.0));
    X.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const DistanceResult coarse = exactResult(*test::unrefinedBody(ma), *test::unrefinedBody(mb), X);
    ASSERT_TRUE(coarse.inCollision);
    EXPECT_EQ(coarse.penetration, Penetration::NO_NODE_INSIDE);
    EXPECT_EQ(coarse.penetrationDepth, 0.0);
    EXPECT_EQ(coarse.distance, CONTACT_DISTANCE);
    EXPECT_LT(coarse.distance, 0.0);
    EXPECT_EQ(coarse.onA, coarse.onB);  // a touching point
    BodyOptions fine;
    fine.gridSize = 0.1;
    const DistanceResult refined = exactResult(*Body::build(ma, fine), *Body::build(mb, fine), X);
    ASSERT_TRUE(refined.inCollision);
    EXPECT_EQ(refined.penetration, Penetration::DEEPEST_NODE);
    EXPECT_GT(refined.penetrationDepth, 0.0);
    EXPECT_LE(refined.penetrationDepth, eps + 1e-12);
#ifdef MESHGAP_HAVE_FCL
    EXPECT_TRUE(test::fclCollide(test::fclModel(ma), test::fclModel(mb), X));
#endif
    // Touching faces (boxes side by side, no overlap): in collision, depth 0.
    const BodyPtr cube = test::unrefinedBody(ma);
    const DistanceResult touching = exactResult(*cube, *cube, test::translation(2.0, 0.3, 0));
    EXPECT_TRUE(touching.inCollision);
    EXPECT_LT(touching.distance, 0.0);
    EXPECT_GE(touching.distance, -1e-12);
}

TEST(PenetrationDepth, OPEN_BODIES)
{
    // Two open sheets crossing: no inside, no depth: CONTACT_DISTANCE, OPEN_BODIES.
    const Mesh sheet = test::grid(2.0, 1.0, 4, 2);
    Eigen::Isometry3d X = test::translation(0.5, 0.5, -0.5);
    X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();  // the plane y = 0.5
    const BodyPtr s = test::unrefinedBody(sheet);
    const DistanceResult r = exactResult(*s, *s, X);
    ASSERT_TRUE(r.inCollision);
    EXPECT_EQ(r.penetration, Penetration::OPEN_BODIES);
    EXPECT_EQ(r.distance, CONTACT_DISTANCE);
    // A sheet through a closed box: its nodes inside the box count (an open body inside a closed one collides).
    const BodyPtr box = test::unrefinedBody(test::box(0.5, 0.5, 0.5, 1));
    const DistanceResult through = exactResult(*box, *s, test::translation(-1.0, -0.5, 0.1));  // sheet at z = 0.1
    ASSERT_TRUE(through.inCollision);
    EXPECT_EQ(through.penetration, Penetration::DEEPEST_NODE);
    EXPECT_GT(through.penetrationDepth, 0.0);
    EXPECT_LE(through.penetrationDepth, 0.4 + 1e-12);  // no sheet point is deeper than the nearest face, z = 0.5
}

TEST(PenetrationDepth, IsALowerBoundAndNeverNonNegativeInCollision)
{
    // Random poses of a sphere around the U: whenever FCL (or containment) says collision the distance is < 0; and
    // the depth is a lower bound on the translational penetration depth: B moved by 0.999 depth in any direction
    // still collides.
    const Mesh ma = test::uShape(), mb = test::icosphere(0.45, 2);
    const BodyPtr a = test::unrefinedBody(ma), b = Body::build(mb);
#ifdef MESHGAP_HAVE_FCL
    const auto fa = test::fclModel(ma), fb = test::fclModel(mb);
#endif
    std::mt19937 rng(3);
    std::size_t collisions = 0, deep = 0;
    for (std::uint32_t seed = 1; seed <= 300; ++seed)
    {
        const Eigen::Isometry3d X = test::randomPose(seed, 2.0);
        const DistanceResult r = exactResult(*a, *b, X);
        EXPECT_EQ(r.inCollision, r.distance < 0.0) << seed;
#ifdef MESHGAP_HAVE_FCL
        if (test::fclCollide(fa, fb, X))
        {
            EXPECT_TRUE(r.inCollision) << seed;
            EXPECT_LT(r.distance, 0.0) << seed;
        }
#endif
        if (!r.inCollision)
            continue;
        ++collisions;
        EXPECT_EQ(r.distance, r.penetrationDepth > 0.0 ? -r.penetrationDepth : CONTACT_DISTANCE);
        if (r.penetration != Penetration::DEEPEST_NODE)
            continue;
        ++deep;
        for (int k = 0; k < 5; ++k)
        {
            const Eigen::Vector3d t = 0.999 * r.penetrationDepth * randomUnit(rng);
            Eigen::Isometry3d moved = X;
            moved.translation() += t;
            EXPECT_TRUE(inCollision(*a, *b, moved)) << seed;
        }
    }
    EXPECT_GT(collisions, 20u);
    EXPECT_GT(deep, 20u);
}

#ifdef MESHGAP_HAVE_FCL
TEST(PenetrationDepth, OmplAppRandomCollidingPosesAreNegative)
{
    // Random poses in the volume of two OMPL.app problems, as scenes (world split into parts): wherever FCL says
    // collision, the signed distance is negative; it is negative exactly when meshgap says collision; a deepest
    // node's witness lies inside the obstacle or the robot, at the depth reported from the other's surface.
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    std::size_t problems = 0;
    for (const char *name : {"cubicles", "Twistycool"})
    {
        const fs::path cfg = dir / (std::string(name) + ".cfg");
        if (!fs::exists(cfg))
            continue;
        ++problems;
        const ProblemConfig p = readProblemConfig(cfg.string());
        const Mesh world = loadMesh(p.world), robot = loadRobotMesh(p.robot);
        const ScenePtr scene = Scene::fromMeshes(robot, world);
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        const Eigen::AlignedBox3d volume = p.volume.value_or(world.bounds());
        std::mt19937 rng(99);
        std::normal_distribution<double> gauss;
        std::size_t collisions = 0, deep = 0;
        for (int i = 0; i < 150; ++i)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
            X.linear() = q.normalized().toRotationMatrix();
            for (int k = 0; k < 3; ++k)
                X.translation()[k] = std::uniform_real_distribution<double>(volume.min()[k], volume.max()[k])(rng);
            SceneWarmStart cold;
            SceneResult r;
            scene->distance(X, SceneRequest(), cold, r);
            EXPECT_EQ(r.inCollision, r.distance < 0.0) << name << " pose " << i;
            if (test::fclCollide(fw, fr, X))
            {
                EXPECT_LT(r.distance, 0.0) << name << " pose " << i;
            }
            if (!r.inCollision)
                continue;
            ++collisions;
            EXPECT_TRUE(r.certified);
            if (r.penetration != Penetration::DEEPEST_NODE)
                continue;
            ++deep;
            EXPECT_NEAR((r.onB - r.onA).norm(), r.penetrationDepth, 1e-9 * world.size());
            const Body &o = *scene->obstacles()[r.obstacle];
            EXPECT_TRUE(containsPoint(o, r.onA) || containsPoint(scene->robot(), X.inverse() * r.onB))
                << name << " pose " << i;
        }
        test::Note() << "[ depth    ] " << name << ": 150 random poses, " << collisions << " colliding, " << deep
                     << " with a node inside\n";
        EXPECT_GT(collisions, 10u);
    }
    if (problems == 0)
        GTEST_SKIP() << "OMPL.app problems (cubicles, Twistycool) not found under " << dir << "; skipping";
}
#endif

namespace
{
    /** \brief Every field of two estimates the same, bit for bit (the counters aside: they say what each cost). */
    void expectSameEstimate(const PenetrationEstimate &warm, const PenetrationEstimate &cold, const std::string &where)
    {
        EXPECT_EQ(warm.depth, cold.depth) << where;
        EXPECT_EQ(warm.kind, cold.kind) << where;
        EXPECT_TRUE(warm.onA == cold.onA && warm.onB == cold.onB) << where;
        EXPECT_EQ(warm.triangleA, cold.triangleA) << where;
        EXPECT_EQ(warm.triangleB, cold.triangleB) << where;
        EXPECT_EQ(warm.witnessFound, cold.witnessFound) << where;
    }

    /** \brief Brute force: the largest distance to \e host's surface (minimum over every triangle) of a node of
        \e mover (placed by \e X_HM) inside it (the winding number over every triangle, containsPoint()); 0 if none. */
    double bruteDeepest(const Body &host, const Body &mover, const Eigen::Isometry3d &X_HM)
    {
        const Mesh &m = host.surface();
        double deepest = 0.0;
        Eigen::Vector3d on;
        for (std::uint32_t i = 0; i < mover.numNodes(); ++i)
        {
            const Eigen::Vector3d p = X_HM * mover.node(i);
            if (!containsPoint(host, p))
                continue;
            double d = std::numeric_limits<double>::infinity();
            for (const Triangle &t : m.triangles)
                d = std::min(d, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on));
            deepest = std::max(deepest, d);
        }
        return deepest;
    }

    /** \brief The warm start naming node \e i of \e mover (its place in the mover's clusters). */
    PenetrationWarmStart seedAt(const Body &mover, std::uint32_t i, bool hostIsA)
    {
        PenetrationWarmStart seed;
        seed.valid = true;
        seed.hostIsA = hostIsA;
        const std::vector<std::uint32_t> &order = mover.clusterOrder();
        seed.position = static_cast<std::uint32_t>(std::find(order.begin(), order.end(), i) - order.begin());
        for (std::uint32_t k = 0; k < mover.clusters().size(); ++k)
            if (mover.clusters()[k].begin <= seed.position && seed.position < mover.clusters()[k].end)
                seed.cluster = k;
        return seed;
    }

    /** \brief \e count poses from \e from to \e to (linear translation, slerp rotation). */
    std::vector<Eigen::Isometry3d> segment(const Eigen::Isometry3d &from, const Eigen::Isometry3d &to, int count)
    {
        std::vector<Eigen::Isometry3d> out;
        const Eigen::Quaterniond qa(from.linear()), qb(to.linear());
        for (int k = 0; k < count; ++k)
        {
            const double s = count > 1 ? double(k) / (count - 1) : 0.0;
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = qa.slerp(s, qb).toRotationMatrix();
            X.translation() = (1.0 - s) * from.translation() + s * to.translation();
            out.push_back(X);
        }
        return out;
    }

    /** \brief Runs \e poses cold and with one warm start carried along; every estimate must be the cold one bit for
        bit. Counts, among colliding poses in a row, the deepest node's moves to the other body and to another
        cluster, and the nodes tested cold and warm. */
    struct WarmAlongMotion
    {
        std::size_t colliding{0}, bodyChanges{0}, clusterJumps{0}, coldNodes{0}, warmNodes{0};

        void run(const Body &a, const Body &b, const std::vector<Eigen::Isometry3d> &poses, const std::string &name)
        {
            PenetrationWarmStart warm;
            for (std::size_t i = 0; i < poses.size(); ++i)
            {
                if (!inCollision(a, b, poses[i]))
                    continue;
                ++colliding;
                const PenetrationWarmStart before = warm;
                const PenetrationEstimate cold = penetrationDepth(a, b, poses[i]);
                const PenetrationEstimate hot = penetrationDepth(a, b, poses[i], &warm);
                expectSameEstimate(hot, cold, name + " pose " + std::to_string(i));
                coldNodes += cold.nodesTested;
                warmNodes += hot.nodesTested;
                if (before.valid && warm.valid)
                {
                    bodyChanges += before.hostIsA != warm.hostIsA;
                    clusterJumps += before.hostIsA == warm.hostIsA && before.cluster != warm.cluster;
                }
            }
        }
    };
}  // namespace

TEST(PenetrationDepth, WarmStartGivesTheColdEstimateAlongCollidingMotions)
{
    // Two refined bars crossing, the second one turning as it slides through the first: the deepest node moves from
    // one bar to the other and from cluster to cluster. At every colliding pose the estimate with a warm start
    // carried from pose to pose is the cold one, bit for bit (depth, witness points and triangles); every 8th pose
    // the depth is also checked against brute force over every node and triangle.
    const BodyPtr a = Body::build(test::box(1.2, 0.25, 0.3, 2)), b = Body::build(test::box(0.2, 0.9, 0.35, 2));
    Eigen::Isometry3d from = test::translation(-1.5, 0.1, 0.05), to = test::translation(1.4, -0.1, 0.1);
    from.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    to.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(3, -1, 2).normalized()).toRotationMatrix();
    const std::vector<Eigen::Isometry3d> poses = segment(from, to, 240);
    WarmAlongMotion bars;
    bars.run(*a, *b, poses, "bars");
    for (std::size_t i = 0; i < poses.size(); i += 8)
    {
        if (!inCollision(*a, *b, poses[i]))
            continue;
        const double truth = std::max(bruteDeepest(*a, *b, poses[i]), bruteDeepest(*b, *a, poses[i].inverse()));
        EXPECT_NEAR(penetrationDepth(*a, *b, poses[i]).depth, truth, 1e-12) << "pose " << i;
    }
    EXPECT_GT(bars.colliding, 100u);
    EXPECT_GT(bars.bodyChanges, 0u);
    EXPECT_GT(bars.clusterJumps, 0u);
    EXPECT_LT(bars.warmNodes, bars.coldNodes);  // the seed prunes (a cost, not a timing)

    // A map: slotted_wall's robot through the wall, along its .poses (then the goal), 150 states.
    const fs::path dir = fs::path(MESHGAP_SOURCE_DIR) / "maps" / "slotted_wall";
    const ProblemConfig config = readProblemConfig((dir / "slotted_wall.cfg").string());
    LoadReport report;
    const Mesh robot = loadRobotMesh(config.robot, &report);
    const ScenePtr scene = Scene::fromMeshes(robot, loadMesh(config.world));
    ASSERT_EQ(scene->obstacles().size(), 1u);
    std::vector<Eigen::Isometry3d> path;
    for (Eigen::Isometry3d X : readPoses((dir / "slotted_wall.poses").string()))
        path.push_back(X.translate(report.omplAppCenter.value()));
    ASSERT_TRUE(config.goal);
    path.push_back(*config.goal);
    std::vector<Eigen::Isometry3d> states;
    for (std::size_t k = 0; k + 1 < path.size(); ++k)
    {
        const std::vector<Eigen::Isometry3d> part = segment(path[k], path[k + 1], 150 / int(path.size() - 1) + 1);
        states.insert(states.end(), part.begin(), part.end() - 1);
    }
    WarmAlongMotion wall;
    wall.run(*scene->obstacles()[0], scene->robot(), states, "slotted_wall");
    EXPECT_GT(wall.colliding, 50u);
    // And the scene's answer, warm against cold (the warm start carries each pair's deepest node).
    SceneWarmStart carried;
    for (std::size_t i = 0; i < states.size(); ++i)
    {
        SceneResult cold, hot;
        scene->distance(states[i], SceneRequest(), cold);
        scene->distance(states[i], SceneRequest(), carried, hot);
        EXPECT_EQ(hot.distance, cold.distance) << i;
        EXPECT_TRUE(hot.onB == cold.onB && hot.onA == cold.onA) << i;
        EXPECT_EQ(hot.penetration, cold.penetration) << i;
    }
    test::Note() << "[ warm     ] bars: " << bars.colliding << " colliding poses, deepest node to the other body "
                 << bars.bodyChanges << " times, to another cluster " << bars.clusterJumps << " times; nodes tested "
                 << bars.coldNodes << " cold, " << bars.warmNodes << " warm. slotted_wall: " << wall.colliding
                 << " colliding states of " << states.size() << ", deepest node to the other body " << wall.bodyChanges
                 << " times, to another cluster " << wall.clusterJumps << " times; nodes tested " << wall.coldNodes
                 << " cold, " << wall.warmNodes << " warm\n";
}

TEST(PenetrationDepth, AWarmSeedNeverChangesWhichTiedNodeWins)
{
    // B (half 0.5, a 4x4 grid per face) pushed face-first into A (half 1) by 0.25 along x: B's leading face nodes
    // and A's face nodes inside B all lie exactly 0.25 deep (coordinates in quarters). The cold search's winner
    // is the first of them in its fixed order. Seeded with any other tied node, of either body, the search must
    // still return that winner: a seed only raises the bound the search starts from, never wins a tie itself.
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 4));
    const BodyPtr b = test::unrefinedBody(test::box(0.5, 0.5, 0.5, 4));
    const Eigen::Isometry3d X = test::translation(1.25, 0.25, 0.0);
    const PenetrationEstimate cold = penetrationDepth(*a, *b, X);
    ASSERT_EQ(cold.kind, Penetration::DEEPEST_NODE);
    EXPECT_NEAR(cold.depth, 0.25, 1e-12);
    // The tied nodes, by brute force over each body's nodes (the same point distance the search uses).
    std::vector<PenetrationWarmStart> tied;
    for (const bool hostIsA : {true, false})
    {
        const Body &host = hostIsA ? *a : *b, &mover = hostIsA ? *b : *a;
        const Eigen::Isometry3d X_HM = hostIsA ? X : X.inverse();
        for (std::uint32_t i = 0; i < mover.numNodes(); ++i)
        {
            const Eigen::Vector3d p = X_HM * mover.node(i);
            BvhPointResult r;
            bvhPointDistance(host.bvh(), p, std::numeric_limits<double>::infinity(), -1.0, r);
            if (r.distance == cold.depth && insideClosedBody(host, p))
                tied.push_back(seedAt(mover, i, hostIsA));
        }
    }
    std::size_t others = 0, ofA = 0;
    PenetrationWarmStart winner;
    penetrationDepth(*a, *b, X, &winner);  // names the cold winner
    for (const PenetrationWarmStart &seed : tied)
    {
        PenetrationWarmStart warm = seed;
        const PenetrationEstimate hot = penetrationDepth(*a, *b, X, &warm);
        expectSameEstimate(hot, cold, "seed at position " + std::to_string(seed.position));
        EXPECT_TRUE(warm.hostIsA == winner.hostIsA && warm.position == winner.position);
        others += seed.hostIsA != winner.hostIsA || seed.position != winner.position;
        ofA += !seed.hostIsA;
    }
    test::Note() << "[ ties     ] " << tied.size() << " nodes tied at depth 0.25 (" << ofA << " of A)\n";
    EXPECT_GE(others, 10u);
    EXPECT_GT(ofA, 0u);
    // A seed that names no node (another body's, or nothing) changes nothing either.
    PenetrationWarmStart stale;
    stale.valid = true;
    stale.cluster = 1000000;
    expectSameEstimate(penetrationDepth(*a, *b, X, &stale), cold, "stale seed");
}

TEST(PenetrationDepth, DeepRandomPosesEqualBruteForceAndTheGridPrunes)
{
    // Thick bodies pushed deep into each other at random poses (seeded), where the surface grid seeds the search
    // with a deep node and skips the clusters that cannot beat it: a U of three overlapping shells (winding 2 where
    // they overlap), a refined box, an icosphere, and a small sphere that fits wholly inside the box. Every depth
    // must equal brute force over every node and triangle (the largest over both bodies), the witness points must
    // be that far apart, and a warm start carried along must change nothing.
    const BodyPtr u = Body::build(test::uShape()), box = Body::build(test::box(0.9, 0.7, 0.6, 3)),
                  ball = Body::build(test::icosphere(0.6, 3)), pebble = Body::build(test::icosphere(0.2, 2));
    const std::vector<std::pair<const Body *, const Body *>> pairs = {
        {u.get(), box.get()}, {box.get(), ball.get()}, {ball.get(), u.get()}, {box.get(), pebble.get()}};
    // 40 poses a pair (test::scaled: fewer under the sanitizers, the thresholds below in proportion).
    const auto poses = static_cast<std::uint32_t>(test::scaled(40, 5));
    std::size_t checked = 0, deep = 0, nodes = 0, clusters = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
        const Body &a = *pairs[k].first, &b = *pairs[k].second;
        PenetrationWarmStart warm;
        for (std::uint32_t i = 0; i < poses; ++i)
        {
            const Eigen::Isometry3d X = test::randomPose(1000 * (k + 1) + i, 0.5);
            if (!inCollision(a, b, X))
                continue;
            const PenetrationEstimate e = penetrationDepth(a, b, X);
            const double truth = std::max(bruteDeepest(a, b, X), bruteDeepest(b, a, X.inverse()));
            const std::string where = "pair " + std::to_string(k) + " pose " + std::to_string(i);
            EXPECT_NEAR(e.depth, truth, 1e-12) << where;
            if (e.kind == Penetration::DEEPEST_NODE)
            {
                EXPECT_NEAR((e.onA - e.onB).norm(), e.depth, 1e-12) << where;
            }
            expectSameEstimate(penetrationDepth(a, b, X, &warm), e, where + " warm");
            ++checked;
            deep += truth > 0.25;
            nodes += e.nodesTested;
            clusters += b.clusters().size() + a.clusters().size();
        }
    }
    test::Note() << "[ deep     ] " << checked << " colliding poses (" << deep << " deeper than 0.25) equal brute force; "
                 << nodes << " nodes measured of " << clusters << " clusters\n";
    EXPECT_GT(checked, 60u * poses / 40);
    EXPECT_GT(deep, 20u * poses / 40);
}
