#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "TestMeshes.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/RecentInsideTests.h"
#include "meshgap/geometry/TriangleDistance.h"

using namespace meshgap;

namespace
{
    /** \brief The distance from \e p to the surface of \e body: the minimum over every triangle. */
    double surfaceDistanceByEveryTriangle(const Body &body, const Eigen::Vector3d &p)
    {
        const Mesh &m = body.surface();
        double d = std::numeric_limits<double>::infinity();
        Eigen::Vector3d on;
        for (const Triangle &t : m.triangles)
            d = std::min(d, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], on));
        return d;
    }
}  // namespace

TEST(RecentInsideTests, EveryAnswerIsTheRayCastsAndNearPointsReuseIt)
{
    // Random walks (seeded, steps of 0.04) through and around a U of three overlapping shells (walls 0.4 thick,
    // winding 2 where they overlap) and a sphere: every answer must be insideClosedBody()'s, and a good share must
    // come from the points kept. Walls this thin catch a ball taken larger than the distance to the surface.
    const BodyPtr u = Body::build(test::uShape()), ball = Body::build(test::icosphere(0.6, 2));
    for (const Body *body : {u.get(), ball.get()})
    {
        std::mt19937 rng(11);
        std::normal_distribution<double> step(0.0, 0.04);
        std::uniform_real_distribution<double> start(-1.6, 1.6);
        RecentInsideTests<8> recent(1e-12);
        std::size_t points = 0, rayCasts = 0, inside = 0;
        for (int walk = 0; walk < 20; ++walk)
        {
            Eigen::Vector3d p(start(rng), start(rng), 0.5 * start(rng));
            for (int k = 0; k < 100; ++k, ++points)
            {
                p += Eigen::Vector3d(step(rng), step(rng), step(rng));
                const bool truth = insideClosedBody(*body, p);
                ASSERT_EQ(recent.inside(*body, p, surfaceDistanceByEveryTriangle(*body, p), rayCasts), truth)
                    << "walk " << walk << " step " << k << " at " << p.transpose();
                inside += truth;
            }
        }
        EXPECT_GT(inside, points / 20) << "the walks must spend time inside";
        EXPECT_LT(rayCasts, points / 2) << "most answers should come from the points kept";
        EXPECT_GT(rayCasts, points / 50) << "and some points must need a ray cast";
    }
}
