// The self-pair table (SelfPairTable): every cell it calls proven holds no colliding state, checked by the exact
// distance of the pair (refineExact() at random states, at states bisected to within 1e-7 of a contact, and along
// random segments and in random boxes of joint space, corners included, that it says are free), and a scene's verdict with the table is the verdict without it at random states; on
// the test tree (joints of every kind: a continuous joint's cells wrap around) and on MotionBenchMaker's UR5 (from
// ../shared/data, skipped when absent).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/Exception.h"
#include "meshgap/robot/MotionBound.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/SelfPairTable.h"
#include "meshgap/robot/Srdf.h"
#include "robot/TestTree.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        /** \brief Self pair \e p's signed distance at \e q, exact, from the links' meshes (no table, no broad phase). */
        double pairDistance(const RobotScene &scene, std::size_t p, const std::vector<double> &q)
        {
            const std::vector<Eigen::Isometry3d> poses = scene.robot().linkPoses(q);
            const auto [a, b] = scene.selfPairs()[p];
            DistanceRequest request;
            request.computeDepth = false;
            DistanceResult r;
            refineExact(*scene.links()[a].body, *scene.links()[b].body, poses[a].inverse() * poses[b], r, request);
            return r.inCollision ? -1.0 : r.distance;
        }

        /** \brief A state within the robot's limits (an angle without limits within [-pi, pi)). */
        std::vector<double> selfPairRandomState(const RobotModel &robot, std::mt19937 &rng)
        {
            std::vector<double> q(robot.dimension());
            for (std::size_t v = 0; v < q.size(); ++v)
            {
                const double lo = std::isfinite(robot.stateLower(v)) ? robot.stateLower(v) : -M_PI;
                const double hi = std::isfinite(robot.stateUpper(v)) ? robot.stateUpper(v) : M_PI;
                q[v] = std::uniform_real_distribution<double>(lo, hi)(rng);
            }
            return q;
        }

        /** \brief What the checks saw. */
        struct Seen
        {
            std::size_t tabulated{0}, claims{0}, states{0}, colliding{0}, nearContact{0}, boxes{0}, boxClaims{0},
                segments{0}, segmentClaims{0};
        };

        /** \brief For every tabulated pair of \e scene (with \e table): at random states, where the table says
            apart, the exact distance is positive; where the pair collides, the table does not say apart; between a
            claimed state and a colliding one, bisected to 1e-7 of each other, the claim still holds where the
            table makes it. Then random boxes of numbers (apartAlong() with no split: the box around a segment from
            one corner to the opposite one): where claimed, every sampled state in the box, corners included, is
            free. */
        void expectClaimsHold(const RobotScene &scene, const SelfPairTable &table, int states, Seen &seen)
        {
            const RobotModel &robot = scene.robot();
            std::mt19937 rng(3);
            for (std::size_t p = 0; p < table.numPairs(); ++p)
            {
                if (!table.tabulated(p))
                    continue;
                ++seen.tabulated;
                std::vector<double> claimed, hit;
                for (int s = 0; s < states; ++s)
                {
                    const std::vector<double> q = selfPairRandomState(robot, rng);
                    const double d = pairDistance(scene, p, q);
                    const bool says = table.apartAt(p, q.data());
                    ++seen.states;
                    seen.claims += says;
                    seen.colliding += d <= 0.0;
                    if (says)
                    {
                        EXPECT_GT(d, 0.0) << "pair " << p << ", state " << s;
                        claimed = q;
                    }
                    if (d <= 0.0)
                        hit = q;
                    if (!claimed.empty() && !hit.empty())
                    {
                        // Bisect between the two: the last claimed state nearest the contact.
                        std::vector<double> a = claimed, b = hit, m(q.size());
                        for (int k = 0; k < 40; ++k)
                        {
                            for (std::size_t v = 0; v < m.size(); ++v)
                                m[v] = 0.5 * (a[v] + b[v]);
                            (pairDistance(scene, p, m) > 0.0 ? a : b) = m;
                        }
                        if (table.apartAt(p, b.data()))
                            ADD_FAILURE() << "pair " << p << ": a colliding state said apart";
                        seen.nearContact += table.apartAt(p, a.data());
                        hit.clear();
                    }
                }
                for (int s = 0; s < states / 8; ++s)
                {
                    // A segment through a random state, up to a radian long in each number (an angle's across
                    // -pi and pi too): where claimed, free at 24 states along it, its ends included.
                    const std::vector<double> middle = selfPairRandomState(robot, rng);
                    std::vector<double> step(middle.size());
                    for (double &x : step)
                        x = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
                    const double half = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
                    ++seen.segments;
                    if (!table.apartAlong(p, middle.data(), step.data(), half, 5))
                        continue;
                    ++seen.segmentClaims;
                    for (int k = 0; k <= 23; ++k)
                    {
                        std::vector<double> q = middle;
                        for (std::size_t v = 0; v < q.size(); ++v)
                        {
                            // Within its limits (the pair's own numbers are, where the table makes a claim).
                            q[v] += (2.0 * k / 23.0 - 1.0) * half * step[v];
                            if (std::isfinite(robot.stateLower(v)))
                                q[v] = std::clamp(q[v], robot.stateLower(v), robot.stateUpper(v));
                        }
                        EXPECT_GT(pairDistance(scene, p, q), 0.0) << "pair " << p << ", segment " << s << ", " << k;
                    }
                }
                for (int s = 0; s < states / 8; ++s)
                {
                    const std::vector<double> middle = selfPairRandomState(robot, rng);
                    std::vector<double> reach(middle.size());
                    for (double &r : reach)
                        r = std::uniform_real_distribution<double>(0.0, 0.3)(rng);
                    ++seen.boxes;
                    if (!table.apartAlong(p, middle.data(), reach.data(), 1.0, 0))
                        continue;
                    ++seen.boxClaims;
                    for (int k = 0; k < 24; ++k)
                    {
                        std::vector<double> q = middle;
                        for (std::size_t v = 0; v < q.size(); ++v)
                        {
                            // Corners first (every number at one end of its reach), then inside.
                            const double u = k < 8 ? ((k >> (v % 3)) & 1 ? 1.0 : -1.0)
                                                   : std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
                            q[v] = middle[v] + u * reach[v];
                            if (std::isfinite(robot.stateLower(v)))
                                q[v] = std::clamp(q[v], robot.stateLower(v), robot.stateUpper(v));
                        }
                        EXPECT_GT(pairDistance(scene, p, q), 0.0) << "pair " << p << ", box " << s << ", state " << k;
                    }
                }
            }
        }

        /** \brief " first-second fraction" per tabulated pair of \e scene: the fraction of its range proven apart. */
        std::string provenFractions(const RobotScene &scene, const SelfPairTable &table)
        {
            std::ostringstream out;
            for (std::size_t p = 0; p < table.numPairs(); ++p)
                if (table.tabulated(p))
                    out << " " << scene.links()[scene.selfPairs()[p].first].name << "-"
                        << scene.links()[scene.selfPairs()[p].second].name << " " << table.provenFraction(p);
            return out.str();
        }

        /** \brief The scene's verdict with the table is the verdict of a scene without it, at random states (with
            \e bothSides, some colliding and some free). */
        void expectSameVerdicts(const RobotScene &with, const RobotScene &without, int states, bool bothSides = true)
        {
            std::mt19937 rng(7);
            RobotWarmStart w1, w2;
            std::size_t colliding = 0;
            for (int s = 0; s < states; ++s)
            {
                const std::vector<double> q = selfPairRandomState(with.robot(), rng);
                const bool hit = without.inCollision(q.data(), q.size(), w2);
                colliding += hit;
                ASSERT_EQ(with.inCollision(q.data(), q.size(), w1), hit) << "state " << s;
            }
            if (!bothSides)
                return;
            EXPECT_GT(colliding, 0u);
            EXPECT_LT(colliding, std::size_t(states));
        }
    }  // namespace

    TEST(SelfPairTable, TreeCellsProvenApartHoldNoContact)
    {
        const UrdfRobotPtr robot = test::treeWithPayload();
        RobotScene scene(robot, {});
        RobotScene plain(robot, {});
        SelfPairTable::Options options;
        options.rootCells = 4;
        options.levels = 4;
        scene.tabulateSelfPairs(options);
        const SelfPairTable &table = *scene.selfPairTable();
        Seen seen;
        expectClaimsHold(scene, table, test::scaled(400, 100), seen);
        test::Note() << seen.tabulated << " of " << table.numPairs() << " pairs tabulated (proven fractions"
                     << provenFractions(scene, table) << "), " << table.questions() << " questions; " << seen.claims << " of "
                     << seen.states << " states said apart (" << seen.colliding << " colliding), " << seen.nearContact
                     << " within 1e-7 of a contact; " << seen.boxClaims << " of " << seen.boxes << " boxes, "
                     << seen.segmentClaims << " of " << seen.segments << " segments";
        EXPECT_GT(seen.tabulated, 0u);
        EXPECT_GT(seen.claims, seen.states / 4);
        EXPECT_GT(seen.colliding, 0u);
        EXPECT_GT(seen.boxClaims, 0u);
        EXPECT_GT(seen.segmentClaims, 0u);
        expectSameVerdicts(scene, plain, test::scaled(2000, 300));
    }

    TEST(SelfPairTable, PairsAFreeFrameMovesHaveNoGrid)
    {
        // A planar base carrying a revolute arm, a floating drone and a planar slider: every self pair is moved by a
        // free frame (the arm is adjacent to its base), so none has a grid, and the verdict is the plain scene's.
        const UrdfRobotPtr robot = UrdfRobot::load(test::MOBILE_URDF);
        RobotScene scene(robot, {});
        RobotScene plain(robot, {});
        scene.tabulateSelfPairs();
        const SelfPairTable &table = *scene.selfPairTable();
        const MotionBound bound(*robot);
        std::vector<std::size_t> numbers;
        std::vector<unsigned char> arcs;
        ASSERT_GT(table.numPairs(), 0u);
        for (std::size_t p = 0; p < table.numPairs(); ++p)
        {
            const auto [a, b] = scene.selfPairs()[p];
            EXPECT_FALSE(bound.pairNumbers(a, b, numbers, arcs)) << "pair " << p;
            EXPECT_FALSE(table.tabulated(p)) << "pair " << p;
            EXPECT_EQ(table.provenFraction(p), 0.0);
        }
        expectSameVerdicts(scene, plain, test::scaled(500, 100), false);
    }

    TEST(SelfPairTable, BadOptionsAreRefused)
    {
        RobotScene scene(test::treeWithPayload(), {});
        SelfPairTable::Options options;
        options.rootCells = 2;
        EXPECT_THROW(SelfPairTable(scene, options), Exception);
        options.rootCells = 8;
        options.levels = 12;
        EXPECT_THROW(SelfPairTable(scene, options), Exception);
    }

    TEST(SelfPairTable, Ur5CellsProvenApartHoldNoContact)
    {
        const fs::path folder = fs::path(MESHGAP_SHARED_DATA_DIR) / "mbm" / "ur5";
        if (!fs::exists(folder / "ur5.urdf"))
            GTEST_SKIP() << "MotionBenchMaker's UR5 is not in " << folder.string();
        UrdfOptions options;
        options.packagePath = {folder.string()};
        const UrdfRobotPtr robot = UrdfRobot::load((folder / "ur5.urdf").string(), options);
        readSrdf(*robot, (folder / "ur5.srdf").string());
        RobotScene scene(robot, {});
        RobotScene plain(robot, {});
        // The tools' table; under test::scale() < 1 (the instrumented run) halved three times, not five.
        SelfPairTable::Options cells;
        if (test::scale() < 1.0)
            cells.levels = 3;
        const auto start = std::chrono::steady_clock::now();
        scene.tabulateSelfPairs(cells);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const SelfPairTable &table = *scene.selfPairTable();
        Seen seen;
        expectClaimsHold(scene, table, test::scaled(300, 40), seen);
        test::Note() << seen.tabulated << " of " << table.numPairs() << " pairs tabulated in " << seconds << " s, "
                     << table.questions() << " questions:" << provenFractions(scene, table) << "; " << seen.claims << " of "
                     << seen.states << " states said apart (" << seen.colliding << " colliding); " << seen.boxClaims
                     << " of " << seen.boxes << " boxes, " << seen.segmentClaims << " of " << seen.segments
                     << " segments";
        EXPECT_GT(seen.tabulated, 3u);
        EXPECT_GT(seen.claims, seen.states / 2);
        expectSameVerdicts(scene, plain, test::scaled(2000, 300));
    }
}  // namespace meshgap
