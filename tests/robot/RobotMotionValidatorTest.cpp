// The certified motion validator for chains: the displacement bound against the vertices' real motion (dense
// forward kinematics), and certified motions checked densely against the exact collision test.
#include <gtest/gtest.h>

#include <ompl/base/SpaceInformation.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <random>

#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "TestMeshes.h"
#include "robot/TestTree.h"
#include "TestNote.h"
#include "TestScale.h"

namespace ob = ompl::base;

namespace meshgap
{
    TEST(RobotMotionValidator, DisplacementBoundHoldsForEveryVertex)
    {
        const UrdfRobotPtr robot = test::treeWithPayload();
        const MotionBound bound(*robot);
        std::mt19937 rng(4);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        double tightest = 0.0;  // the largest ratio of a real displacement to its bound
        std::vector<double> moves;
        for (int trial = 0; trial < 100; ++trial)
        {
            // Joint values within the limits (continuous ones in [-pi, pi): the shorter arc is the straight line).
            const std::vector<double> a = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            const std::vector<double> b = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            bound.linkDisplacements(a, b, moves);
            const std::vector<Eigen::Isometry3d> start = robot->linkPoses(a);
            for (int step = 1; step <= 50; ++step)
            {
                std::vector<double> q(a.size());
                for (std::size_t k = 0; k < q.size(); ++k)
                    q[k] = a[k] + (b[k] - a[k]) * step / 50.0;
                const std::vector<Eigen::Isometry3d> poses = robot->linkPoses(q);
                for (std::size_t i = 0; i < poses.size(); ++i)
                    for (const Eigen::Vector3d &v : robot->links()[i].body->surface().vertices)
                    {
                        const double moved = (poses[i] * v - start[i] * v).norm();
                        ASSERT_LE(moved, moves[i] + 1e-12) << robot->links()[i].name;
                        tightest = std::max(tightest, moved / moves[i]);
                    }
            }
        }
        test::Note() << "largest displacement / bound " << tightest;
        EXPECT_GT(tightest, 0.2);  // a bound, not a wild one
    }

    TEST(RobotMotionValidator, PairBoundHoldsInTheCommonAncestorsFrame)
    {
        const UrdfRobotPtr robot = test::treeWithPayload();
        const MotionBound bound(*robot);
        std::mt19937 rng(9);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        double tightest = 0.0, saving = 0.0;
        std::vector<double> moves;
        std::vector<Eigen::Isometry3d> framesA, framesQ, linksA, linksQ;
        for (int trial = 0; trial < test::scaled(60); ++trial)
        {
            const std::vector<double> a = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            const std::vector<double> b = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            bound.linkDisplacements(a, b, moves);
            robot->linkPoses(a.data(), a.size(), framesA, linksA);
            for (int step = 1; step <= 40; ++step)
            {
                std::vector<double> q(a.size());
                for (std::size_t k = 0; k < q.size(); ++k)
                    q[k] = a[k] + (b[k] - a[k]) * step / 40.0;
                robot->linkPoses(q.data(), q.size(), framesQ, linksQ);
                for (const auto &[first, second] : robot->selfPairs())
                {
                    const std::size_t c =
                        test::commonFrame(*robot, robot->links()[first].frame, robot->links()[second].frame);
                    ASSERT_NE(c, RobotModel::NONE);
                    double moved = 0.0;  // each link's largest vertex move in the common frame, summed
                    for (std::size_t link : {first, second})
                    {
                        const Eigen::Isometry3d XQ = framesQ[c].inverse() * linksQ[link];
                        const Eigen::Isometry3d XA = framesA[c].inverse() * linksA[link];
                        double most = 0.0;
                        for (const Eigen::Vector3d &v : robot->links()[link].body->surface().vertices)
                            most = std::max(most, (XQ * v - XA * v).norm());
                        moved += most;
                    }
                    const double pair = bound.pairDisplacement(first, second, a, b);
                    ASSERT_LE(moved, pair + 1e-12) << robot->links()[first].name << " " << robot->links()[second].name;
                    ASSERT_LE(pair, moves[first] + moves[second] + 1e-12);
                    if (pair > 0)
                        tightest = std::max(tightest, moved / pair);
                    saving = std::max(saving, 1.0 - pair / (moves[first] + moves[second]));
                }
            }
        }
        test::Note() << "largest relative displacement / pair bound " << tightest << ", largest saving over the two "
                     << "links' own bounds " << saving;
    }

    TEST(RobotMotionValidator, BendBoundsTheStrayFromTheChord)
    {
        // Every vertex's path along a straight motion in joint space, against the straight line between its two
        // ends: at t it strays at most t (1 - t) / 2 times the bend (the bend bounds the path's second derivative),
        // in the world for every link and in the nearest common frame for every self pair.
        const UrdfRobotPtr robot = test::treeWithPayload();
        const MotionBound bound(*robot);
        std::mt19937 rng(21);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        MotionBound::Motion motion;
        double tightest = 0.0;
        std::vector<Eigen::Isometry3d> frames0, frames1, framesQ, links0, links1, linksQ;
        // The largest stray of \e link's vertices at fraction t, each placed by X0, X1 and XQ.
        auto stray = [&](std::size_t link, const Eigen::Isometry3d &X0, const Eigen::Isometry3d &X1,
                         const Eigen::Isometry3d &XQ, double t)
        {
            double most = 0.0;
            for (const Eigen::Vector3d &v : robot->links()[link].body->surface().vertices)
                most = std::max(most, (XQ * v - ((1.0 - t) * (X0 * v) + t * (X1 * v))).norm());
            return most;
        };
        for (int trial = 0; trial < test::scaled(60); ++trial)
        {
            // Short motions too, where the chord is a close fit and the bend's terms in S matter most.
            const double reach = trial % 2 ? 1.0 : 0.2;
            std::vector<double> a = {1.5 * u(rng), 2.5 * u(rng), 0.1 + 0.2 * u(rng), 1.5 * u(rng), u(rng)};
            for (std::size_t k = 0; k < a.size(); ++k)
                a[k] = std::clamp(a[k], robot->stateLower(k), robot->stateUpper(k));
            std::vector<double> b = a;
            for (std::size_t k = 0; k < b.size(); ++k)
                b[k] = std::clamp(b[k] + reach * (k == 2 ? 0.1 : 1.0) * u(rng), robot->stateLower(k),
                                  robot->stateUpper(k));
            bound.motion(a, b, motion);
            robot->linkPoses(a.data(), a.size(), frames0, links0);
            robot->linkPoses(b.data(), b.size(), frames1, links1);
            for (int step = 1; step < 24; ++step)
            {
                const double t = step / 24.0, allowed = 0.5 * t * (1.0 - t);
                std::vector<double> q(a.size());
                for (std::size_t k = 0; k < q.size(); ++k)
                    q[k] = a[k] + (b[k] - a[k]) * t;
                robot->linkPoses(q.data(), q.size(), framesQ, linksQ);
                for (std::size_t i = 0; i < robot->links().size(); ++i)
                {
                    const double most = stray(i, links0[i], links1[i], linksQ[i], t);
                    const double limit = allowed * bound.bend(i, bound.numTerms(i), motion);
                    ASSERT_LE(most, limit + 1e-12) << robot->links()[i].name << " at t " << t;
                    if (limit > 1e-9)
                        tightest = std::max(tightest, most / limit);
                }
                for (const auto &[first, second] : robot->selfPairs())
                {
                    const std::size_t c =
                        test::commonFrame(*robot, robot->links()[first].frame, robot->links()[second].frame);
                    const auto [n1, n2] = bound.pairTerms(first, second);
                    for (const auto &[link, n] : {std::pair(first, n1), std::pair(second, n2)})
                    {
                        const double most = stray(link, frames0[c].inverse() * links0[link],
                                                  frames1[c].inverse() * links1[link],
                                                  framesQ[c].inverse() * linksQ[link], t);
                        ASSERT_LE(most, allowed * bound.bend(link, n, motion) + 1e-12)
                            << robot->links()[link].name << " in frame " << robot->frames()[c].name << " at t " << t;
                    }
                }
            }
        }
        test::Note() << "largest stray / bound " << tightest;
        EXPECT_GT(tightest, 0.05);  // a bound, not a wild one
    }

    namespace
    {
        /** \brief Random motions of the test tree among the posts: every one the validator certifies is free at
            states no joint of which is more than 1e-3 from the next, by the exact collision test of a scene of its
            own (no self-pair table). With \e tabulate, the validator's scene has its self pairs tabulated
            (RobotScene::tabulateSelfPairs()). */
        void expectCertifiedMotionsFree(bool tabulate)
        {
            const UrdfRobotPtr robot = test::treeWithPayload();
            const std::vector<BodyConstPtr> obstacles = test::postsAroundTree();
            const auto checked = std::make_shared<RobotScene>(robot, obstacles);
            if (tabulate)
            {
                SelfPairTable::Options options;
                options.rootCells = 4;
                options.levels = 4;
                checked->tabulateSelfPairs(options);
            }
            const RobotSceneConstPtr scene = checked;
            const RobotScene oracle(robot, obstacles);
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-1);
            bounds.setHigh(1);
            auto si = std::make_shared<ob::SpaceInformation>(robotStateSpace(*robot, bounds));
            si->setStateValidityChecker(std::make_shared<RobotChecker>(si, scene));
            const auto validator = std::make_shared<RobotMotionValidator>(si, scene, *robot);
            si->setMotionValidator(validator);
            si->setup();
            ompl::RNG::setSeed(13);
            ob::StateSamplerPtr sampler = si->allocStateSampler();
            ob::State *a = si->allocState(), *b = si->allocState(), *s = si->allocState();
            std::size_t certified = 0, rejected = 0, dense = 0;
            std::vector<double> q;
            RobotWarmStart warm;
            // MESHGAP_ROBOT_MOTIONS sets the count of motions tried (300 by default, scaled by test::scale()).
            const char *count = std::getenv("MESHGAP_ROBOT_MOTIONS");
            const int motions = count ? std::atoi(count) : test::scaled(300, 150);
            for (int m = 0; m < motions; ++m)
            {
                do
                    sampler->sampleUniform(a);
                while (!si->isValid(a));
                sampler->sampleUniformNear(b, a, 0.6);
                if (!validator->checkMotion(a, b))
                {
                    ++rejected;
                    continue;
                }
                ++certified;
                // Dense: no joint changes by more than 1e-3 between checked states.
                const int steps = static_cast<int>(std::ceil(si->distance(a, b) / 1e-3)) + 1;
                for (int i = 0; i <= steps; ++i)
                {
                    si->getStateSpace()->interpolate(a, b, double(i) / steps, s);
                    robotStateToVector(*si->getStateSpace(), s, q);
                    ++dense;
                    ASSERT_FALSE(oracle.inCollision(q.data(), q.size(), warm)) << "motion " << m << " at " << i;
                }
            }
            si->freeState(a);
            si->freeState(b);
            si->freeState(s);
            test::Note() << certified << " certified motions (" << dense << " states checked densely), " << rejected
                         << " rejected";
            EXPECT_GT(certified, 50u);
            EXPECT_GT(rejected, 10u);
        }
    }  // namespace

    TEST(RobotMotionValidator, CertifiedMotionsAreFreeWhenCheckedDensely)
    {
        expectCertifiedMotionsFree(false);
    }

    TEST(RobotMotionValidator, CertifiedMotionsWithTheSelfPairTableAreFreeWhenCheckedDensely)
    {
        expectCertifiedMotionsFree(true);
    }
}  // namespace meshgap
