// The joint-space clearance gradient against central finite differences of the same pair's exact distance.
#include <gtest/gtest.h>

#include <random>

#include "meshgap/robot/JointGradient.h"
#include "TestMeshes.h"
#include "robot/TestTree.h"
#include "TestNote.h"
#include "TestScale.h"

namespace meshgap
{
    TEST(JointGradient, MatchesFiniteDifferencesOfThePairsDistance)
    {
        const UrdfRobotPtr robot = test::treeWithPayload();
        const std::vector<BodyConstPtr> obstacles = test::postsAroundTree();
        const RobotScene scene(robot, obstacles);
        std::mt19937 rng(8);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        RobotRequest every;
        every.everyPair = true;
        std::size_t free = 0, matching = 0;
        const int trials = test::scaled(400);
        for (int trial = 0; trial < trials; ++trial)
        {
            const std::vector<double> q = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            RobotResult r;
            scene.distance(q, RobotRequest(), r);
            std::vector<Eigen::Isometry3d> frames;
            robot->framePoses(q.data(), q.size(), frames);
            Eigen::VectorXd g;
            if (!clearanceGradient(*robot, scene, q, frames, r, g) || r.distance < 1e-4)
                continue;
            ++free;
            // The same pair's distance a step either way.
            const std::size_t pair = r.selfPair ? [&] {
                for (std::size_t p = 0; p < scene.selfPairs().size(); ++p)
                    if (scene.selfPairs()[p] == LinkPair(r.link, r.other))
                        return scene.links().size() + p;
                return std::size_t(0);
            }() : r.link;
            const double h = 1e-6;
            Eigen::VectorXd fd(g.size());
            for (Eigen::Index k = 0; k < g.size(); ++k)
            {
                std::vector<double> plus = q, minus = q;
                plus[k] += h;
                minus[k] -= h;
                RobotResult rp, rm;
                scene.distance(plus, every, rp);
                scene.distance(minus, every, rm);
                fd[k] = (rp.pairs[pair].distance - rm.pairs[pair].distance) / (2 * h);
            }
            matching += (fd - g).norm() <= 1e-4 * std::max(1.0, g.norm()) ? 1 : 0;
        }
        test::Note() << matching << " of " << free << " free states match finite differences";
        EXPECT_GT(free, 40u * trials / 400);
        // A few states sit where the closest features switch (the distance has a kink there).
        EXPECT_GE(matching, free * 9 / 10);
    }
}  // namespace meshgap
