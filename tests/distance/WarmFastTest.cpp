#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/distance/WarmFast.h"

using namespace meshgap;

namespace
{
    // The exact surface distance (the repository's certified BVH query), or -1 in collision.
    double exactDistance(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        DistanceResult r;
        refineExact(a, b, X_AB, r);
        return r.inCollision ? -1.0 : r.distance;
    }

    // A run of nearby poses: B (a sphere) passes along a concave U-shaped bracket, turning as it goes.
    std::vector<Eigen::Isometry3d> path(int n)
    {
        std::vector<Eigen::Isometry3d> poses;
        for (int i = 0; i < n; ++i)
        {
            const double s = double(i) / (n - 1);
            Eigen::Isometry3d X = test::translation(-1.2 + 2.4 * s, 0.2 * std::sin(6.0 * s), 1.9);
            X.rotate(Eigen::AngleAxisd(1.5 * s, Eigen::Vector3d(0.3, 0.5, 1.0).normalized()));
            poses.push_back(X);
        }
        return poses;
    }

    Mesh bracket()
    {
        // Base plate and two walls (three boxes in one body): several local minima for a ball above it.
        Mesh m = test::box(3.0, 1.0, 0.2, 6);
        m = test::merged(m, test::transformed(test::box(0.2, 1.0, 1.0, 4), test::translation(-2.0, 0.0, 1.2)));
        return test::merged(m, test::transformed(test::box(0.2, 1.0, 1.0, 4), test::translation(2.0, 0.0, 1.2)));
    }
}  // namespace

TEST(WarmFast, NeverBelowTheExactDistanceAndNeverAboveTheWarmNodePair)
{
    const BodyPtr a = test::unrefinedBody(bracket()), b = test::unrefinedBody(test::icosphere(0.5, 2));
    WarmFast solver;
    WarmFastState state;
    const Enumeration enumeration;
    int compared = 0;
    for (const Eigen::Isometry3d &X : path(60))
    {
        DistanceResult r;
        solver.solveWarm(*a, *b, X, state, 7, r);
        const double exact = exactDistance(*a, *b, X);
        if (exact < 0.0)
            continue;
        ++compared;
        // A real pair of surface points: never below the exact distance; never above its own node pair.
        EXPECT_GE(r.distance, exact - 1e-12 * (1.0 + exact));
        const double nodes = (a->node(r.nodes.a) - X * b->node(r.nodes.b)).norm();
        EXPECT_LE(r.distance, nodes + 1e-12);
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-9);
        // The node pair is at least as good as a hill climb's end: no neighbour improves it (oracle: brute force).
        const double d2 = nodes * nodes;
        for (const std::uint32_t *n = a->graph().beginNeighbours(r.nodes.a); n != a->graph().endNeighbours(r.nodes.a); ++n)
            EXPECT_GE((a->node(*n) - X * b->node(r.nodes.b)).squaredNorm(), d2);
        DistanceResult best;
        enumeration.solve(*a, *b, X, DistanceRequest(), best);
        EXPECT_GE(nodes, best.distance - 1e-12);
    }
    EXPECT_EQ(compared, 60);
    EXPECT_EQ(state.queries, 60u);
    EXPECT_GE(state.globalSearches, 1u);
    EXPECT_LT(state.globalSearches, 60u);  // most queries only climb
}

TEST(WarmFast, GlobalSearchOnColdStartOnlyWhenAskedAndOnAJump)
{
    const BodyPtr a = test::unrefinedBody(bracket()), b = test::unrefinedBody(test::icosphere(0.5, 2));
    WarmFast solver;
    solver.setGlobalEvery(0);
    solver.setGapTolerance(std::numeric_limits<double>::infinity());
    WarmFastState state;
    const auto poses = path(30);
    DistanceResult r;
    solver.solveWarm(*a, *b, poses[0], state, 1, r);
    EXPECT_EQ(state.globalSearches, 1u);  // cold start
    const std::size_t coldEvaluations = r.evaluations;
    for (std::size_t i = 1; i < poses.size(); ++i)
    {
        solver.solveWarm(*a, *b, poses[i], state, 1, r);
        EXPECT_LT(r.evaluations, coldEvaluations / 10) << i;  // a climb, not a search
    }
    EXPECT_EQ(state.globalSearches, 1u);

    // With the gap test on, a jump far away (a drift far beyond the last global distance) triggers a search.
    solver.setGapTolerance(0.5);
    Eigen::Isometry3d far = poses.back();
    far.translation() += Eigen::Vector3d(0.0, 0.0, 30.0);
    solver.solveWarm(*a, *b, far, state, 1, r);
    solver.solveWarm(*a, *b, poses.back(), state, 1, r);
    EXPECT_GE(state.globalSearches, 2u);
    // And at a fixed rate.
    solver.setGapTolerance(std::numeric_limits<double>::infinity());
    solver.setGlobalEvery(5);
    const std::size_t before = state.globalSearches;
    for (int i = 0; i < 10; ++i)
        solver.solveWarm(*a, *b, poses.back(), state, 1, r);
    EXPECT_EQ(state.globalSearches, before + 2);
}

TEST(WarmFast, BeyondTheDenseBudgetTheSearchIsBoundedMultistart)
{
    BodyOptions options;
    options.gridSize = 0.0;
    options.distances.memoryBudgetBytes = 1;  // force on-demand mesh distances
    const BodyPtr a = Body::build(bracket(), options), b = Body::build(test::icosphere(0.5, 2), options);
    ASSERT_FALSE(a->distances().isDense());
    WarmFast solver;
    solver.setGlobalEvaluations(3000);
    WarmFastState state;
    DistanceResult r;
    const Eigen::Isometry3d X = path(10)[3];
    solver.solveWarm(*a, *b, X, state, 3, r);
    // The bound: one climb may run to its end past the budget, so allow one climb's worth beyond it.
    EXPECT_LE(r.evaluations, 3000u + 2u * (a->numNodes() + b->numNodes()));
    EXPECT_GE(r.distance, exactDistance(*a, *b, X) - 1e-12);
}

TEST(WarmFast, StatelessFormAndFactory)
{
    const BodyPtr a = test::unrefinedBody(bracket()), b = test::unrefinedBody(test::icosphere(0.5, 2));
    const DistanceSolverPtr solver = allocSolver("warm-fast");
    EXPECT_TRUE(solver->params().setParam("global_every", "8"));
    EXPECT_FALSE(solver->params().setParam("gap_tolerance", "-1"));
    EXPECT_FALSE(solver->params().setParam("global_evaluations", "0"));
    const Eigen::Isometry3d X = path(10)[5];
    DistanceRequest request;
    request.start = NodePair{0, 0};
    DistanceResult warm, cold;
    solver->solve(*a, *b, X, request, warm);
    EXPECT_EQ(warm.iterations, 1u);  // warm: a climb only
    solver->solve(*a, *b, X, DistanceRequest(), cold);
    EXPECT_GT(cold.iterations, 1u);  // cold: the global search ran
    EXPECT_GE(cold.distance, exactDistance(*a, *b, X) - 1e-12);
}

// comb-GA-wl as the global search, seeded from the nearest node-cluster pairs (global_search=comb-GA-wl,
// global_seeding=clusters): still never below the exact distance along the path, never above its own node pair; the
// defaults are the multistart and the paper's random draw.
TEST(WarmFast, ClusterSeededGlobalSearchNeverBelowExact)
{
    const BodyPtr a = test::unrefinedBody(bracket()), b = test::unrefinedBody(test::icosphere(0.5, 2));
    WarmFast solver;
    std::string value;
    ASSERT_TRUE(solver.params().getParam("global_seeding", value));
    EXPECT_EQ(value, "random");
    EXPECT_FALSE(solver.params().setParam("global_seeding", "mixed"));
    ASSERT_TRUE(solver.params().getParam("global_search", value));
    EXPECT_EQ(value, "multistart");
    EXPECT_FALSE(solver.params().setParam("global_search", "enumeration"));
    ASSERT_TRUE(solver.params().setParam("global_search", "comb-GA-wl"));
    EXPECT_TRUE(solver.getGlobalGa());
    ASSERT_TRUE(solver.params().setParam("global_seeding", "clusters"));
    EXPECT_EQ(solver.getGlobalSeeding(), CombGA::Seeding::CLUSTERS);
    solver.setGlobalEvery(4);  // many global searches
    WarmFastState state;
    int compared = 0;
    for (const Eigen::Isometry3d &X : path(40))
    {
        DistanceResult r;
        solver.solveWarm(*a, *b, X, state, 3, r);
        const double exact = exactDistance(*a, *b, X);
        if (exact < 0.0)
            continue;
        ++compared;
        EXPECT_GE(r.distance, exact - 1e-12 * (1.0 + exact));
        EXPECT_LE(r.distance, (a->node(r.nodes.a) - X * b->node(r.nodes.b)).norm() + 1e-12);
    }
    EXPECT_GT(compared, 20);
    EXPECT_GE(state.globalSearches, 10u);
}
