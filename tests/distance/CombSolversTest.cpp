#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cstdio>
#include <future>
#include <map>
#include <set>
#include <tuple>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/CombGA.h"
#include "meshgap/distance/CombSA.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/HillClimb.h"
#include "meshgap/distance/MeshMoves.h"
#include "meshgap/distance/SolverFactory.h"

using namespace meshgap;

namespace
{
    const char *const COMB_SOLVERS[] = {"comb-GA-wl", "comb-GA-nl", "comb-SA-wl", "comb-SA-nl"};

    DistanceResult solve(const DistanceSolver &solver, const Body &a, const Body &b, const Eigen::Isometry3d &X_AB,
                         std::uint64_t seed)
    {
        DistanceRequest request;
        request.seed = seed;
        DistanceResult r;
        solver.solve(a, b, X_AB, request, r);
        return r;
    }

    DistanceResult enumerate(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        DistanceResult r;
        Enumeration().solve(a, b, X_AB, DistanceRequest(), r);
        return r;
    }

    /** \brief A concave body with many local minima: an icosphere of radius \e r whose nodes are pushed out or in
        by r * amp * sin(k x + p) sin(k y + 2p) sin(k z + 3p) along their direction (x, y, z). */
    Mesh bumpySphere(double r, int level, double amp, double k, double phase)
    {
        Mesh m = test::icosphere(r, level);
        for (Eigen::Vector3d &v : m.vertices)
        {
            const Eigen::Vector3d d = v.normalized();
            v = d * r *
                (1.0 +
                 amp * std::sin(k * d.x() + phase) * std::sin(k * d.y() + 2 * phase) * std::sin(k * d.z() + 3 * phase));
        }
        return m;
    }

    /** \brief The two bumpy spheres of the concave tests (642 nodes each) and a pose of B at centre distance 2.1. */
    struct BumpyScene
    {
        BodyPtr a = test::unrefinedBody(bumpySphere(1.0, 3, 0.3, 16.0, 0.3));
        BodyPtr b = test::unrefinedBody(bumpySphere(0.8, 3, 0.3, 16.0, 1.1));
        static Eigen::Isometry3d pose(std::uint32_t k)
        {
            Eigen::Isometry3d X = test::randomPose(k, 1.0);
            X.translation() = X.translation().normalized() * 2.1;
            return X;
        }
    };
}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// The mesh operators

TEST(MeshMoves, MatingOffspringLiesOnThePathWithinTheRadiusOfTheFitterParent)
{
    const BodyPtr box = test::unrefinedBody(test::box(1.0, 0.7, 0.4, 5));
    const MeshDistances &D = box->distances();
    QueryRng rng(7);
    MoveScratch scratch;
    std::vector<std::uint32_t> path;
    std::uniform_int_distribution<std::uint32_t> node(0, box->numNodes() - 1);
    for (int trial = 0; trial < 60; ++trial)
    {
        const std::uint32_t fitter = node(rng), other = node(rng);
        const double d2Fitter = 0.1 + trial % 5, d2Other = d2Fitter * (1.0 + trial % 7);
        // The eligible nodes, from D and P directly: on the path, at most r (eq. 5) from the fitter parent.
        D.path(fitter, other, path);
        ASSERT_FALSE(path.empty());
        const double r = D.distance(fitter, other) * d2Fitter / (d2Fitter + d2Other);
        EXPECT_LE(r, 0.5 * D.distance(fitter, other));
        std::set<std::uint32_t> eligible;
        for (std::uint32_t w : path)
            if (D.distance(fitter, w) <= r)
                eligible.insert(w);
        ASSERT_TRUE(eligible.count(fitter));
        std::set<std::uint32_t> drawn;
        for (int k = 0; k < 200; ++k)
        {
            const std::uint32_t child = meshMate(D, fitter, other, d2Fitter, d2Other, rng, scratch);
            drawn.insert(child);
            // On a shortest path between the parents, and within r of the fitter one.
            EXPECT_NEAR(D.distance(fitter, child) + D.distance(child, other), D.distance(fitter, other), 1e-12);
            EXPECT_LE(D.distance(fitter, child), r);
        }
        // Uniform over the eligible nodes: 200 draws reach every one of them (at most a handful).
        EXPECT_EQ(drawn, eligible) << "parents " << fitter << ", " << other;
    }
    // Equal parents give that node; touching parents (both d^2 = 0) give the fitter one.
    EXPECT_EQ(meshMate(D, 5, 5, 1.0, 2.0, rng, scratch), 5u);
    EXPECT_EQ(meshMate(D, 5, 40, 0.0, 0.0, rng, scratch), 5u);
    EXPECT_EQ(matingRadius(2.0, 1.0, 3.0), 0.5);
}

TEST(MeshMoves, RandomMoveWalksThePathWithinTheRadius)
{
    const BodyPtr sphere = test::unrefinedBody(test::icosphere(1.0, 3));
    const MeshDistances &D = sphere->distances();
    const SurfaceGraph &graph = sphere->graph();
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (double l : graph.lengths())
    {
        shortest = std::min(shortest, l);
        longest = std::max(longest, l);
    }
    const double rMax = 0.5 * D.maxDistance();  // the paper's fixed mutation radius
    QueryRng rng(11);
    MoveScratch scratch;
    for (double radius : {rMax, 4 * longest, longest})
    {
        double farthest = 0.0;
        std::set<std::uint32_t> reached;
        for (int k = 0; k < 2000; ++k)
        {
            const std::uint32_t start = static_cast<std::uint32_t>(k * 37 % sphere->numNodes());
            const std::uint32_t moved = randomMove(D, start, radius, rng, scratch);
            EXPECT_NE(moved, start);
            EXPECT_LE(D.distance(start, moved), radius) << "radius " << radius;
            farthest = std::max(farthest, D.distance(start, moved));
            if (start == 0)
                reached.insert(moved);
        }
        // The moves use the radius, not just the first step.
        EXPECT_GT(farthest, 0.75 * radius) << "radius " << radius;
    }
    // Below one edge the move takes one edge: the smallest step the mesh allows (so comb-SA never freezes).
    for (std::uint32_t start = 0; start < 50; ++start)
    {
        const std::uint32_t moved = randomMove(D, start, 0.5 * shortest, rng, scratch);
        EXPECT_TRUE(std::find(graph.beginNeighbours(start), graph.endNeighbours(start), moved) !=
                    graph.endNeighbours(start));
    }
    // The accumulated path lengths are the mesh distances.
    std::vector<std::uint32_t> path;
    std::vector<double> along;
    D.path(3, 600, path);
    pathDistances(graph, path, along);
    for (std::size_t k = 0; k < path.size(); ++k)
        EXPECT_NEAR(along[k], D.distance(3, path[k]), 1e-12);
}

TEST(MeshMoves, TwoComponentBodyJumpsBetweenComponentsAtRandom)
{
    // Two boxes far apart as one body: no path between them, D infinite.
    Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
    far.translation() = Eigen::Vector3d(10, 0, 0);
    const BodyPtr two = test::unrefinedBody(test::merged(test::box(1, 1, 1, 3), test::transformed(test::box(0.5, 0.5, 0.5, 2), far)));
    ASSERT_EQ(two->graph().numComponents(), 2u);
    const MeshDistances &D = two->distances();
    const std::uint32_t n = two->numNodes(), n0 = 6 * 9 + 2, n1 = n - n0;  // box() has 6n^2 + 2 nodes
    ASSERT_EQ(two->graph().component(0), 0u);
    ASSERT_EQ(two->graph().component(n0), 1u);
    QueryRng rng(3);
    MoveScratch scratch;

    // Mating across components: the other parent's node with probability d2Fitter / (d2Fitter + d2Other) = 1/4,
    // the fitter parent's otherwise.
    int jumps = 0;
    const int draws = 4000;
    for (int k = 0; k < draws; ++k)
    {
        const std::uint32_t child = meshMate(D, 2, n0 + 5, 1.0, 3.0, rng, scratch);
        ASSERT_TRUE(child == 2 || child == n0 + 5);
        jumps += child == n0 + 5;
    }
    EXPECT_NEAR(double(jumps) / draws, 0.25, 0.03);

    // Random move: the drawn node is uniform over the other n - 1 nodes; one in the other component is jumped to.
    jumps = 0;
    std::set<std::uint32_t> landed;
    const double radius = 0.5 * D.maxDistance();
    for (int k = 0; k < draws; ++k)
    {
        const std::uint32_t moved = randomMove(D, 7, radius, rng, scratch);
        if (two->graph().component(moved) == 1)
        {
            ++jumps;
            landed.insert(moved);
        }
        else
            EXPECT_LE(D.distance(7, moved), radius);
    }
    EXPECT_NEAR(double(jumps) / draws, double(n1) / (n - 1), 0.03);
    EXPECT_EQ(landed.size(), n1);  // anywhere in the other component

    // At a tenth of that radius the jumps fade by the same factor (2 radius / max(D) = 0.1): a cooling comb-SA
    // stays in its component, and the moves that stay are still within the radius.
    jumps = 0;
    const double small = 0.05 * D.maxDistance();
    const SurfaceGraph &g = two->graph();
    // A move takes at least one edge (the documented rule), so it stays within max(radius, longest edge at 7).
    const double reach = std::max(small, *std::max_element(g.lengths().begin() + g.offsets()[7],
                                                           g.lengths().begin() + g.offsets()[8]));
    for (int k = 0; k < draws; ++k)
    {
        const std::uint32_t moved = randomMove(D, 7, small, rng, scratch);
        if (g.component(moved) == 1)
            ++jumps;
        else
        {
            EXPECT_LE(D.distance(7, moved), reach);
        }
    }
    EXPECT_NEAR(double(jumps) / draws, 0.1 * double(n1) / (n - 1), 0.015);

    // Every solver copes with a body of two components, and finds the closer one's minimum.
    const BodyPtr sphere = test::unrefinedBody(test::icosphere(0.5, 2));
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(10, 1.6, 0.2);  // next to the small box
    const DistanceResult truth = enumerate(*two, *sphere, X);
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        for (std::uint64_t seed = 1; seed <= 3; ++seed)
        {
            const DistanceResult r = solve(*solver, *two, *sphere, X, seed);
            EXPECT_GE(r.distance, truth.distance) << name;
            if (std::string(name).find("-wl") != std::string::npos)
            {
                EXPECT_EQ(r.distance, truth.distance) << name << " seed " << seed;
            }
        }
    }
}

TEST(HillClimb, EvaluationCapStopsExactlyAndChangesNothingBelowIt)
{
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 2.0, 0.5, 5)), b = test::unrefinedBody(test::icosphere(0.8, 2));
    for (std::uint32_t seed = 1; seed <= 20; ++seed)
    {
        const Eigen::Isometry3d X_AB = test::randomPose(seed, 4.0);
        const NodePair start{seed * 13 % a->numNodes(), seed * 29 % b->numNodes()};
        PairEvaluator e1(*a, *b, X_AB), e2(*a, *b, X_AB);
        NodePair p1 = start, p2 = start;
        double d1 = e1.d2(p1), d2 = e2.d2(p2);
        const std::size_t m1 = hillClimb(e1, p1, d1);
        const std::size_t m2 = hillClimb(e2, p2, d2, 1000000);  // a cap never reached: the same climb
        EXPECT_EQ(p1, p2);
        EXPECT_EQ(d1, d2);
        EXPECT_EQ(m1, m2);
        EXPECT_EQ(e1.evaluations(), e2.evaluations());
        // A cap half way: stops there, with the pair it reached and its true d^2.
        const std::size_t cap = 1 + e1.evaluations() / 2;
        PairEvaluator e3(*a, *b, X_AB);
        NodePair p3 = start;
        double d3 = e3.d2(p3);
        hillClimb(e3, p3, d3, cap);
        EXPECT_EQ(e3.evaluations(), cap);
        PairEvaluator check(*a, *b, X_AB);
        EXPECT_EQ(d3, check.d2(p3));
        EXPECT_GE(d3, d1);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The solvers

TEST(CombSolvers, NeverBelowEnumerationAndReportConsistentPairs)
{
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 2.0, 0.5, 4)), b = test::unrefinedBody(test::icosphere(0.8, 2));
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        EXPECT_EQ(solver->getName(), name);
        for (std::uint32_t seed = 1; seed <= 6; ++seed)
        {
            const Eigen::Isometry3d X_AB = test::randomPose(seed, 4.0);
            const DistanceResult truth = enumerate(*a, *b, X_AB);
            const DistanceResult r = solve(*solver, *a, *b, X_AB, seed);
            EXPECT_GE(r.distance, truth.distance) << name << " seed " << seed;
            EXPECT_NEAR(r.distance, (a->node(r.nodes.a) - X_AB * b->node(r.nodes.b)).norm(), 1e-12) << name;
            EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12);
            EXPECT_EQ(r.onA, a->node(r.nodes.a));
            EXPECT_GT(r.evaluations, 0u);
            EXPECT_FALSE(r.nodeOptimal);
            EXPECT_LE(r.convergedAt, r.iterations);
            EXPECT_EQ(r.localSteps == 0, std::string(name).find("-nl") != std::string::npos) << name;
        }
    }
}

TEST(CombSolvers, SameSeedSameResultDifferentSeedsDiffer)
{
    const BumpyScene scene;
    const Eigen::Isometry3d X = BumpyScene::pose(1);
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        std::set<std::tuple<std::size_t, std::uint32_t, std::uint32_t, std::size_t>> outcomes;
        for (std::uint64_t seed = 1; seed <= 8; ++seed)
        {
            DistanceRequest request;
            request.seed = seed;
            request.recordHistory = true;
            DistanceResult r1, r2;
            solver->solve(*scene.a, *scene.b, X, request, r1);
            solver->solve(*scene.a, *scene.b, X, request, r2);
            EXPECT_EQ(r1.distance, r2.distance) << name;
            EXPECT_EQ(r1.nodes, r2.nodes) << name;
            EXPECT_EQ(r1.evaluations, r2.evaluations) << name;
            EXPECT_EQ(r1.localSteps, r2.localSteps) << name;
            EXPECT_EQ(r1.iterations, r2.iterations) << name;
            EXPECT_EQ(r1.convergedAt, r2.convergedAt) << name;
            EXPECT_EQ(r1.history, r2.history) << name;
            outcomes.insert({r1.evaluations, r1.nodes.a, r1.nodes.b, r1.convergedAt});
        }
        EXPECT_GE(outcomes.size(), 5u) << name;  // the seed drives the search
    }
    // The evaluation count itself differs between seeds whenever it is not fixed by the schedule (comb-SA-nl makes
    // exactly one evaluation per iteration).
    for (const char *name : {"comb-GA-wl", "comb-GA-nl", "comb-SA-wl"})
    {
        std::set<std::size_t> counts;
        for (std::uint64_t seed = 1; seed <= 8; ++seed)
            counts.insert(solve(*allocSolver(name), *scene.a, *scene.b, X, seed).evaluations);
        EXPECT_GE(counts.size(), 5u) << name;
    }
}

TEST(CombSolvers, ConcurrentQueriesOnOneSolverMatchSequentialOnes)
{
    const BumpyScene scene;
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        std::vector<std::future<DistanceResult>> runs;
        for (std::uint64_t seed = 1; seed <= 4; ++seed)
            runs.push_back(std::async(std::launch::async, [&, seed]
                                      { return solve(*solver, *scene.a, *scene.b, BumpyScene::pose(2), seed); }));
        for (std::uint64_t seed = 1; seed <= 4; ++seed)
        {
            const DistanceResult parallel = runs[seed - 1].get();
            const DistanceResult sequential = solve(*solver, *scene.a, *scene.b, BumpyScene::pose(2), seed);
            EXPECT_EQ(parallel.nodes, sequential.nodes) << name;
            EXPECT_EQ(parallel.evaluations, sequential.evaluations) << name;
        }
    }
}

TEST(CombSolvers, ConcaveBodiesGlobalMinimumRates)
{
    // Bumpy spheres: hill climbing alone from a random pair ends in one of many local minima.
    const BumpyScene scene;
    const int seeds = 20;
    for (std::uint32_t p = 1; p <= 4; ++p)
    {
        const Eigen::Isometry3d X = BumpyScene::pose(p);
        const DistanceResult truth = enumerate(*scene.a, *scene.b, X);
        int climbs = 0;
        for (std::uint64_t seed = 1; seed <= 100; ++seed)
            climbs += solve(HillClimb(), *scene.a, *scene.b, X, seed).distance == truth.distance;
        EXPECT_LT(climbs, 20) << "pose " << p << ": the scene should be hard for hill climbing alone";

        std::map<std::string, int> hits;
        std::map<std::string, double> mean;
        for (const char *name : COMB_SOLVERS)
        {
            const DistanceSolverPtr solver = allocSolver(name);
            for (std::uint64_t seed = 1; seed <= seeds; ++seed)
            {
                const DistanceResult r = solve(*solver, *scene.a, *scene.b, X, seed);
                EXPECT_GE(r.distance, truth.distance) << name;
                hits[name] += r.distance == truth.distance;
                mean[name] += r.distance / seeds;
            }
        }
        std::printf("bumpy spheres, pose %u (node minimum %.4f): hill climb %d/100", p, truth.distance, climbs);
        for (const char *name : COMB_SOLVERS)
            std::printf(", %s %d/%d (mean %.4f)", name, hits[name], seeds, mean[name]);
        std::printf("\n");
        // The paper: comb-GA-wl found the global minimum in 100 of 100 runs, comb-SA-wl in most (88 of 100 on the
        // handshake), and the local search is what makes both work (Tables III, V, VI).
        EXPECT_GE(hits["comb-GA-wl"], 18) << "pose " << p;
        EXPECT_GT(2 * hits["comb-SA-wl"], seeds) << "pose " << p;
        EXPECT_LT(mean["comb-GA-wl"], mean["comb-GA-nl"]) << "pose " << p;
        EXPECT_LT(mean["comb-SA-wl"], mean["comb-SA-nl"]) << "pose " << p;
    }
}

TEST(CombSolvers, WarmStartAtTheOptimumIsKept)
{
    // Paper III-D: the previous answer as the initial guess. Elitism (GA) and the best-ever record (SA) keep it.
    const BumpyScene scene;
    const Eigen::Isometry3d X = BumpyScene::pose(3);
    const DistanceResult truth = enumerate(*scene.a, *scene.b, X);
    for (const char *name : COMB_SOLVERS)
    {
        DistanceRequest request;
        request.seed = 5;
        request.start = truth.nodes;
        DistanceResult r;
        allocSolver(name)->solve(*scene.a, *scene.b, X, request, r);
        EXPECT_EQ(r.distance, truth.distance) << name;
        EXPECT_EQ(r.convergedAt, 0u) << name;
    }
    DistanceRequest bad;
    bad.start = NodePair{scene.a->numNodes(), 0};
    DistanceResult r;
    EXPECT_THROW(CombGA(true).solve(*scene.a, *scene.b, X, bad, r), Exception);
    EXPECT_THROW(CombSA(true).solve(*scene.a, *scene.b, X, bad, r), Exception);
}

TEST(CombSolvers, ParametersByName)
{
    const BumpyScene scene;
    const Eigen::Isometry3d X = BumpyScene::pose(1);

    CombGA ga(false);
    std::string value;
    ASSERT_TRUE(ga.params().getParam("population", value));
    EXPECT_EQ(value, "50");  // Table I
    EXPECT_TRUE(ga.params().getParam("generations", value));
    EXPECT_EQ(value, "50");
    EXPECT_EQ(ga.getMutationRate(), 0.02);
    EXPECT_EQ(ga.getCrossoverRate(), 0.6);
    const std::size_t before = solve(ga, *scene.a, *scene.b, X, 1).evaluations;
    EXPECT_TRUE(ga.params().setParam("population", "10"));
    EXPECT_EQ(ga.getPopulationSize(), 10u);
    const DistanceResult small = solve(ga, *scene.a, *scene.b, X, 1);
    EXPECT_NE(small.evaluations, before);
    EXPECT_LT(small.evaluations, before);
    EXPECT_TRUE(ga.params().setParam("generations", "3"));
    EXPECT_EQ(solve(ga, *scene.a, *scene.b, X, 1).iterations, 3u);
    EXPECT_TRUE(ga.params().setParam("generations", "50"));
    // The optional convergence test: stop after 2 generations without a better pair.
    EXPECT_TRUE(ga.params().getParam("stall_generations", value));
    EXPECT_EQ(value, "0");  // off by default: G_max only
    EXPECT_TRUE(ga.params().setParam("stall_generations", "2"));
    for (std::uint64_t seed = 1; seed <= 5; ++seed)
    {
        const DistanceResult r = solve(ga, *scene.a, *scene.b, X, seed);
        EXPECT_EQ(r.iterations, std::min<std::size_t>(50, r.convergedAt + 2));
    }
    EXPECT_TRUE(ga.params().setParam("stall_generations", "0"));
    // An odd population: the odd parent passes on unmated.
    EXPECT_TRUE(ga.params().setParam("population", "7"));
    EXPECT_EQ(solve(ga, *scene.a, *scene.b, X, 1).iterations, 50u);
    EXPECT_TRUE(ga.params().setParam("population", "10"));
    EXPECT_TRUE(ga.params().setParam("mutation_rate", "0.5"));
    EXPECT_EQ(ga.getMutationRate(), 0.5);
    EXPECT_TRUE(ga.params().setParam("crossover_rate", "0"));
    EXPECT_EQ(ga.getCrossoverRate(), 0.0);
    // Unknown names and values out of range are refused (OMPL logs each; quiet here) and change nothing.
    const ompl::msg::LogLevel logLevel = ompl::msg::getLogLevel();
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    EXPECT_FALSE(ga.params().setParam("local_search", "1"));  // fixed by the variant's name
    EXPECT_FALSE(ga.params().setParam("no_such_parameter", "1"));
    EXPECT_FALSE(ga.params().setParam("population", "1"));
    EXPECT_FALSE(ga.params().setParam("population", "many"));
    EXPECT_FALSE(ga.params().setParam("mutation_rate", "1.5"));
    ompl::msg::setLogLevel(logLevel);
    EXPECT_EQ(ga.getPopulationSize(), 10u);
    EXPECT_EQ(ga.getMutationRate(), 0.5);
    EXPECT_THROW(ga.setPopulationSize(1), Exception);

    CombSA sa(true);
    EXPECT_EQ(sa.getBoltzmannConstant(), 0.0001);  // Table I
    EXPECT_EQ(sa.getInitialTemperature(), 2500.0);
    EXPECT_EQ(solve(sa, *scene.a, *scene.b, X, 1).iterations, 2500u);  // one iteration per unit of temperature
    EXPECT_TRUE(sa.params().setParam("initial_temperature", "100"));
    EXPECT_EQ(solve(sa, *scene.a, *scene.b, X, 1).iterations, 100u);
    EXPECT_TRUE(sa.params().setParam("boltzmann", "2e-3"));
    EXPECT_EQ(sa.getBoltzmannConstant(), 2e-3);
    ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
    EXPECT_FALSE(sa.params().setParam("boltzmann", "0"));
    EXPECT_FALSE(sa.params().setParam("population", "10"));
    ompl::msg::setLogLevel(logLevel);
    EXPECT_EQ(sa.getBoltzmannConstant(), 2e-3);

    // The schedules: t falls by one per iteration from t_ini; the radius falls from r_max, to r_max/e at half way.
    EXPECT_EQ(CombSA::temperature(2500, 1), 2500.0);
    EXPECT_EQ(CombSA::temperature(2500, 2500), 1.0);
    EXPECT_EQ(CombSA::moveRadius(3.0, 2500, 2500), 3.0);
    EXPECT_NEAR(CombSA::moveRadius(3.0, 2500, 1250), 3.0 / M_E, 1e-12);
    for (double t = 2500; t > 1; t -= 10)
        EXPECT_LT(CombSA::moveRadius(3.0, 2500, t - 10), CombSA::moveRadius(3.0, 2500, t));
}

TEST(CombSolvers, MaxEvaluationsIsAHardCap)
{
    const BumpyScene scene;
    const Eigen::Isometry3d X = BumpyScene::pose(1);
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        const std::size_t uncapped = solve(*solver, *scene.a, *scene.b, X, 4).evaluations;
        for (std::size_t cap : {std::size_t(1), std::size_t(7), std::size_t(60), std::size_t(1000), uncapped / 2,
                                uncapped, 10 * uncapped})
        {
            DistanceRequest request;
            request.seed = 4;
            request.maxEvaluations = cap;
            request.recordHistory = true;
            DistanceResult r;
            solver->solve(*scene.a, *scene.b, X, request, r);
            // Stops as soon as the cap is reached, with a consistent answer.
            EXPECT_EQ(r.evaluations, std::min(cap, uncapped)) << name << " cap " << cap;
            EXPECT_NEAR(r.distance, (scene.a->node(r.nodes.a) - X * scene.b->node(r.nodes.b)).norm(), 1e-12) << name;
            ASSERT_FALSE(r.history.empty());
            EXPECT_EQ(r.history.back(), r.distance);
        }
    }
}

TEST(CombSolvers, HistoryIsNonIncreasingAndEndsAtTheResult)
{
    const BumpyScene scene;
    const Eigen::Isometry3d X = BumpyScene::pose(2);
    for (const char *name : COMB_SOLVERS)
    {
        const DistanceSolverPtr solver = allocSolver(name);
        for (std::uint64_t seed = 1; seed <= 3; ++seed)
        {
            DistanceRequest request;
            request.seed = seed;
            request.recordHistory = true;
            DistanceResult r;
            solver->solve(*scene.a, *scene.b, X, request, r);
            // history[0]: the initial population (start point); then one value per generation (iteration).
            ASSERT_EQ(r.history.size(), r.iterations + 1) << name;
            for (std::size_t k = 1; k < r.history.size(); ++k)
                EXPECT_LE(r.history[k], r.history[k - 1]) << name;
            EXPECT_EQ(r.history.back(), r.distance) << name;
            // convergedAt: where the final value first appears.
            EXPECT_EQ(r.history[r.convergedAt], r.distance) << name;
            if (r.convergedAt > 0)
            {
                EXPECT_GT(r.history[r.convergedAt - 1], r.distance) << name;
            }
            // Without the request, no history.
            request.recordHistory = false;
            DistanceResult quiet;
            solver->solve(*scene.a, *scene.b, X, request, quiet);
            EXPECT_TRUE(quiet.history.empty());
            EXPECT_EQ(quiet.nodes, r.nodes);
        }
    }
}

TEST(CombSolvers, EvolutionBeatsItsInitialPopulationAndMultistartHillClimbing)
{
    // With a population of 10 the initial hill climbs rarely hold the global minimum; selection, mesh mating and
    // mutation must find it. The reference: independent hill climbs from random pairs for the same evaluations.
    const BumpyScene scene;
    CombGA ga(true);
    ga.setPopulationSize(10);
    int hits = 0, initialHits = 0, multistartHits = 0;
    for (std::uint32_t p = 1; p <= 4; ++p)
    {
        const Eigen::Isometry3d X = BumpyScene::pose(p);
        const DistanceResult truth = enumerate(*scene.a, *scene.b, X);
        QueryRng rng(p);
        for (std::uint64_t seed = 1; seed <= 20; ++seed)
        {
            DistanceRequest request;
            request.seed = seed;
            request.recordHistory = true;
            DistanceResult r;
            ga.solve(*scene.a, *scene.b, X, request, r);
            hits += r.distance == truth.distance;
            initialHits += r.history[0] == truth.distance;
            // Multistart with the GA's budget.
            PairEvaluator evaluator(*scene.a, *scene.b, X);
            double best = std::numeric_limits<double>::infinity();
            while (evaluator.evaluations() < r.evaluations)
            {
                NodePair pair{std::uniform_int_distribution<std::uint32_t>(0, scene.a->numNodes() - 1)(rng),
                              std::uniform_int_distribution<std::uint32_t>(0, scene.b->numNodes() - 1)(rng)};
                double d2 = evaluator.d2(pair);
                hillClimb(evaluator, pair, d2, r.evaluations);
                best = std::min(best, d2);
            }
            multistartHits += std::sqrt(best) == truth.distance;
        }
    }
    std::printf(
        "comb-GA-wl, population 10, 4 poses x 20 seeds: %d global minima (%d already in the initial "
        "population); multistart hill climbing with the same evaluations: %d\n",
        hits, initialHits, multistartHits);
    EXPECT_GE(hits, initialHits + 25);
    EXPECT_GE(hits, multistartHits + 10);
}

// ---------------------------------------------------------------------------------------------------------------
// Our variants of comb-GA, off by default: cluster seeding and restarts of a stalled population.

// Seeding::CLUSTERS with two members and no generations (-nl: no climb) answers a node pair of one of the two
// cluster pairs of least signed sphere gap, found here by brute force over Body::clusters(); every variant is never
// below enumeration, consistent with its own pair, repeatable with a seed; the defaults are the paper's.
TEST(CombSolvers, VariantsSeedFromTheNearestClustersAndRestart)
{
    const BumpyScene scene;
    const Body &a = *scene.a, &b = *scene.b;
    for (std::uint32_t k = 1; k <= 4; ++k)
    {
        const Eigen::Isometry3d X = BumpyScene::pose(k);
        std::vector<std::tuple<double, std::size_t, std::size_t>> gaps;
        for (std::size_t i = 0; i < a.clusters().size(); ++i)
            for (std::size_t j = 0; j < b.clusters().size(); ++j)
            {
                const NodeCluster &ca = a.clusters()[i], &cb = b.clusters()[j];
                gaps.emplace_back((ca.center - X * cb.center).norm() - ca.radius - cb.radius, i, j);
            }
        std::sort(gaps.begin(), gaps.end());
        CombGA two(false);
        two.setSeeding(CombGA::Seeding::CLUSTERS);
        two.setPopulationSize(2);
        two.setGenerations(0);
        const DistanceResult r = solve(two, a, b, X, k);
        auto clusterOf = [](const Body &body, std::uint32_t node)
        {
            const auto &order = body.clusterOrder();
            const auto at = static_cast<std::uint32_t>(std::find(order.begin(), order.end(), node) - order.begin());
            for (std::size_t c = 0; c < body.clusters().size(); ++c)
                if (body.clusters()[c].begin <= at && at < body.clusters()[c].end)
                    return c;
            return body.clusters().size();
        };
        // The two members come from the two nearest cluster pairs; the answer is the better of them.
        const auto got = std::make_tuple(clusterOf(a, r.nodes.a), clusterOf(b, r.nodes.b));
        EXPECT_TRUE(got == std::make_tuple(std::get<1>(gaps[0]), std::get<2>(gaps[0])) ||
                    got == std::make_tuple(std::get<1>(gaps[1]), std::get<2>(gaps[1])))
            << "pose " << k;
        EXPECT_EQ(r.evaluations, 2u);

        const DistanceResult truth = enumerate(a, b, X);
        for (const char *spec : {"seeding=clusters", "seeding=mixed", "restart_stall=3"})
        {
            const DistanceSolverPtr ga = allocSolver("comb-GA-wl");
            const std::string text(spec);
            ASSERT_TRUE(ga->params().setParam(text.substr(0, text.find('=')), text.substr(text.find('=') + 1)));
            const DistanceResult v = solve(*ga, a, b, X, k), again = solve(*ga, a, b, X, k);
            EXPECT_GE(v.distance, truth.distance) << spec;
            EXPECT_NEAR(v.distance, (a.node(v.nodes.a) - X * b.node(v.nodes.b)).norm(), 1e-12) << spec;
            EXPECT_EQ(v.distance, again.distance) << spec;
            EXPECT_EQ(v.evaluations, again.evaluations) << spec;
        }
    }

    // Restarts re-draw a stalled population: more evaluations than the paper's run on the same seed.
    CombGA paper(true), restarting(true);
    restarting.setRestartStall(2);
    const Eigen::Isometry3d X = BumpyScene::pose(1);
    EXPECT_GT(solve(restarting, a, b, X, 3).evaluations, solve(paper, a, b, X, 3).evaluations);

    // Parameters by name: the defaults are the paper's, bad values refused.
    CombGA ga(true);
    std::string value;
    ASSERT_TRUE(ga.params().getParam("seeding", value));
    EXPECT_EQ(value, "random");
    ASSERT_TRUE(ga.params().getParam("restart_stall", value));
    EXPECT_EQ(value, "0");
    EXPECT_FALSE(ga.params().setParam("seeding", "nearest"));
    EXPECT_FALSE(ga.params().setParam("restart_stall", "-1"));
    EXPECT_TRUE(ga.params().setParam("seeding", "mixed"));
    EXPECT_EQ(ga.getSeeding(), CombGA::Seeding::MIXED);
}
