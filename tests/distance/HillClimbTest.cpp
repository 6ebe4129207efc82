#include <gtest/gtest.h>

#include <cstdio>

#include "TestMeshes.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/HillClimb.h"

using namespace meshgap;

namespace
{
    // Local minimum by brute force: no neighbour of either node is strictly closer.
    bool isLocalMinimum(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const NodePair &p)
    {
        const double d2 = (a.node(p.a) - X_AB * b.node(p.b)).squaredNorm();
        for (const std::uint32_t *n = a.graph().beginNeighbours(p.a); n != a.graph().endNeighbours(p.a); ++n)
            if ((a.node(*n) - X_AB * b.node(p.b)).squaredNorm() < d2)
                return false;
        for (const std::uint32_t *n = b.graph().beginNeighbours(p.b); n != b.graph().endNeighbours(p.b); ++n)
            if ((a.node(p.a) - X_AB * b.node(*n)).squaredNorm() < d2)
                return false;
        return true;
    }
}  // namespace

TEST(HillClimb, EndsInALocalMinimumBelowItsStart)
{
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 2.0, 0.5, 5)), b = test::unrefinedBody(test::icosphere(0.8, 2));
    for (std::uint32_t seed = 1; seed <= 50; ++seed)
    {
        const Eigen::Isometry3d X_AB = test::randomPose(seed, 4.0);
        DistanceRequest request;
        request.seed = seed;
        request.start = NodePair{seed % a->numNodes(), (7 * seed) % b->numNodes()};
        DistanceResult r;
        HillClimb().solve(*a, *b, X_AB, request, r);
        EXPECT_LE(r.distance, (a->node(request.start->a) - X_AB * b->node(request.start->b)).norm());
        EXPECT_TRUE(isLocalMinimum(*a, *b, X_AB, r.nodes)) << "seed " << seed;
        EXPECT_NEAR((r.onA - r.onB).norm(), r.distance, 1e-12);
        EXPECT_GT(r.evaluations, 0u);
    }
}

TEST(HillClimb, ConvexBodiesEndWithinOneEdgeOfTheGlobalNodeMinimum)
{
    // Paper III-E says that for convex bodies the local search alone finds the global solution. That holds for the
    // continuous surfaces; over mesh nodes the alternating descent can stop at a pair of mutually nearest nodes one
    // step away from the global pair (measured: about 4 starts in 5 reach it on these icospheres). What does hold,
    // and is checked here from every 7th node pair at several poses against enumeration: the stall is shorter than
    // one mesh edge, and most starts reach the global node minimum.
    const BodyPtr a = test::unrefinedBody(test::icosphere(1.0, 2)), b = test::unrefinedBody(test::icosphere(0.6, 2));
    const double edge = std::max(longestEdge(a->mesh()), longestEdge(b->mesh()));
    int starts = 0, hits = 0;
    double worstGap = 0.0;
    for (std::uint32_t seed = 1; seed <= 6; ++seed)
    {
        Eigen::Isometry3d X_AB = test::randomPose(seed, 1.0);
        X_AB.translation() = X_AB.translation().normalized() * (2.0 + 0.3 * seed);
        DistanceResult best;
        Enumeration().solve(*a, *b, X_AB, DistanceRequest(), best);
        for (std::uint32_t k = 0; k < a->numNodes(); k += 7)
        {
            DistanceRequest request;
            request.start = NodePair{k, (k * 13) % b->numNodes()};
            DistanceResult r;
            HillClimb().solve(*a, *b, X_AB, request, r);
            ++starts;
            hits += r.distance == best.distance;
            worstGap = std::max(worstGap, r.distance - best.distance);
        }
    }
    std::printf("hill climb on convex bodies: %d of %d starts reach the global node minimum; worst gap %.4g "
                "(longest edge %.4g)\n", hits, starts, worstGap, edge);
    EXPECT_LT(worstGap, edge);
    EXPECT_GT(2 * hits, starts);
}

TEST(HillClimb, SameSeedSameAnswer)
{
    const BodyPtr a = test::unrefinedBody(test::box(1.0, 1.0, 1.0, 4)), b = test::unrefinedBody(test::icosphere(0.5, 2));
    const Eigen::Isometry3d X_AB = test::randomPose(3, 3.0);
    DistanceRequest request;
    request.seed = 42;
    DistanceResult r1, r2;
    HillClimb().solve(*a, *b, X_AB, request, r1);
    HillClimb().solve(*a, *b, X_AB, request, r2);
    EXPECT_EQ(r1.nodes, r2.nodes);
    EXPECT_EQ(r1.evaluations, r2.evaluations);
}
