// The whole robot's clearance as a ClearanceField (RobotChecker): its gradient in tangent coordinates against central
// finite differences of the closest pair's exact distance (a fixed-base tree with a payload, the same tree on a
// floating base, two bodies in SE(3) and SE(2)); the max-min objective's motion cost against OMPL's (every grid state
// queried exactly); and the clearance optimiser on maps/arm_fixture: the path's exact minimum clearance rises, every
// motion it makes is certified by RobotMotionValidator and free at steps of 1e-4 rad.
#include <gtest/gtest.h>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <random>

#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/ClearancePathOptimizer.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/JointGradient.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/RobotProblem.h"
#include "robot/TestTree.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace
    {
        /** \brief OMPL's seed for the generators made from now on (OMPL's complaint that others exist silenced). */
        void seedOmpl(std::uint_fast32_t value)
        {
            const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
            ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
            ompl::RNG::setSeed(value);
            ompl::msg::setLogLevel(level);
        }

        /** \brief A robot among obstacles in the space robotStateSpace() makes, its checker and the certified
            validator. */
        struct Field
        {
            RobotSceneConstPtr scene;
            ob::SpaceInformationPtr si;
            std::shared_ptr<RobotChecker> checker;

            Field(RobotModelConstPtr robot, std::vector<BodyConstPtr> obstacles, double extent = 1.0)
            {
                scene = std::make_shared<RobotScene>(robot, std::move(obstacles));
                ob::RealVectorBounds bounds(3);
                bounds.setLow(-extent);
                bounds.setHigh(extent);
                si = std::make_shared<ob::SpaceInformation>(robotStateSpace(*robot, bounds));
                checker = std::make_shared<RobotChecker>(si, scene);
                si->setStateValidityChecker(checker);
                si->setMotionValidator(std::make_shared<RobotMotionValidator>(si, scene, *robot));
                si->setup();
            }
        };

        /** \brief The index (RobotResult::pairs order) of the pair \e r names. */
        std::size_t pairIndex(const RobotScene &scene, const RobotResult &r)
        {
            if (!r.selfPair)
                return r.link;
            for (std::size_t p = 0; p < scene.selfPairs().size(); ++p)
                if (scene.selfPairs()[p] == LinkPair(r.link, r.other))
                    return scene.links().size() + p;
            return 0;
        }

        /** \brief Free states (drawn with a fixed seed) whose gradient (ClearanceField::gradient()) matches central
            differences of the closest pair's exact distance along each tangent coordinate (applyStep()); expects
            at least \e least free states and 90 % of them matching. */
        void expectGradientMatches(const Field &f, unsigned seed, std::size_t least)
        {
            meshgap::seedOmpl(seed);
            ob::StateSamplerPtr sampler = f.si->allocStateSampler();
            ob::State *s = f.si->allocState(), *t = f.si->allocState();
            const ob::StateSpace &space = *f.si->getStateSpace();
            RobotRequest every;
            every.everyPair = true;
            std::vector<double> g, step(f.checker->gradientDimension()), q;
            std::size_t free = 0, matching = 0;
            const int trials = test::scaled(300);  // \e least is for all 300
            for (int trial = 0; trial < trials; ++trial)
            {
                sampler->sampleUniform(s);
                ClearanceGradientInfo info;
                const double c = f.checker->gradient(s, g, {}, &info);
                ASSERT_EQ(g.size(), step.size());
                if (!info.hasDirection || c < 1e-3)
                    continue;
                ++free;
                RobotResult r;
                f.checker->distance(s, RobotRequest(), r);
                const std::size_t pair = pairIndex(*f.scene, r);
                const double h = 1e-6;
                double error = 0.0, norm = 0.0;
                for (std::size_t k = 0; k < step.size(); ++k)
                {
                    double d[2];
                    for (int side = 0; side < 2; ++side)
                    {
                        std::fill(step.begin(), step.end(), 0.0);
                        step[k] = side == 0 ? h : -h;
                        f.checker->applyStep(s, step.data(), t);
                        robotStateToVector(space, t, q);
                        RobotResult rt;
                        f.scene->distance(q, every, rt);
                        d[side] = rt.pairs[pair].distance;
                    }
                    const double fd = (d[0] - d[1]) / (2 * h);
                    error += (fd - g[k]) * (fd - g[k]);
                    norm += g[k] * g[k];
                }
                matching += std::sqrt(error) <= 1e-4 * std::max(1.0, std::sqrt(norm)) ? 1 : 0;
            }
            f.si->freeState(s);
            f.si->freeState(t);
            test::Note() << matching << " of " << free << " free states match finite differences";
            EXPECT_GE(free, least * static_cast<std::size_t>(trials) / 300);
            EXPECT_GE(matching, free * 9 / 10);
        }
    }  // namespace

    TEST(RobotClearanceField, GradientMatchesFiniteDifferencesOnAFixedBaseTreeWithAPayload)
    {
        expectGradientMatches(Field(test::treeWithPayload(), test::postsAroundTree()), 3, 40);
    }

    TEST(RobotClearanceField, GradientMatchesFiniteDifferencesOnAFloatingBase)
    {
        UrdfOptions options;
        options.floatingBase = true;
        const UrdfRobotPtr robot = UrdfRobot::load(test::TREE_URDF, options);
        robot->attach("payload", test::box(0.03, 0.02, 0.01), "tool", test::translation(0.0, 0.0, 0.04));
        const Field f(robot, test::postsAroundTree(), 0.5);
        EXPECT_EQ(f.checker->gradientDimension(), robot->dimension() - 1);  // the quaternion's 4 numbers: 3 turns
        expectGradientMatches(f, 4, 25);
    }

    TEST(RobotClearanceField, GradientMatchesFiniteDifferencesOnBodiesInSE3AndSE2)
    {
        const BodyConstPtr plate = Body::build(test::box(0.2, 0.05, 0.1));
        auto robot = std::make_shared<MultiBodyRobot>(
            std::vector<MultiBodyRobot::Part>{{"a", plate, RigidSpace::SE3}, {"b", plate, RigidSpace::SE2}});
        const Field f(robot, test::postsAroundTree(), 0.6);
        EXPECT_EQ(f.checker->gradientDimension(), 6u + 3u);
        expectGradientMatches(f, 5, 40);
    }

    TEST(RobotClearanceField, MaxMinObjectiveCostsWhatOmplsCostsWithEveryGridStateQueried)
    {
        const Field f(test::treeWithPayload(), test::postsAroundTree());
        MaxMinClearanceObjective ours(f.si);
        ob::MaximizeMinClearanceObjective ompls(f.si);
        seedOmpl(6);
        ob::StateSamplerPtr sampler = f.si->allocStateSampler();
        ob::State *a = f.si->allocState(), *b = f.si->allocState();
        int free = 0, compared = 0;
        for (int trial = 0; trial < 600; ++trial)
        {
            // Motions of every length: from a free state a fraction of the way to another.
            sampler->sampleUniform(a);
            sampler->sampleUniform(b);
            if (!f.checker->isValid(a))
                continue;
            f.si->getStateSpace()->interpolate(a, b, (trial % 4 + 1) / 16.0, b);
            // OMPL's: the exact clearance of every grid state after a, and b.
            const double expected = ompls.motionCost(a, b).value();
            const double got = ours.motionCost(a, b).value();
            ++compared;
            if (expected > 0.0)
            {
                ++free;
                EXPECT_NEAR(got, expected, 1e-12 * (1.0 + expected)) << "motion " << trial;
            }
            else
                EXPECT_LE(got, 0.0) << "motion " << trial;  // in collision: a non-positive cost, either way
        }
        f.si->freeState(a);
        f.si->freeState(b);
        EXPECT_GE(free, 20);
        EXPECT_GT(compared, 40);
    }

    TEST(RobotClearanceField, OptimiserRaisesTheArmFixturesExactClearanceWithCertifiedMotions)
    {
        const RobotProblem problem =
            readRobotProblem(std::string(MESHGAP_SOURCE_DIR) + "/maps/arm_fixture/arm_fixture.cfg");
        const Field f(problem.robot, problem.obstacles);
        const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
        ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
        seedOmpl(1);
        og::SimpleSetup setup(f.si);
        ob::ScopedState<> start(f.si), goal(f.si);
        robotStateFromVector(*f.si->getStateSpace(), problem.start, start.get());
        robotStateFromVector(*f.si->getStateSpace(), *problem.goal, goal.get());
        setup.setStartAndGoalStates(start, goal);
        setup.setPlanner(std::make_shared<CertifiedAnswerPlanner>(
            f.si, [](const ob::SpaceInformationPtr &si) { return allocPlanner("rrtconnect", si); }));
        ASSERT_EQ(setup.solve(60.0), ob::PlannerStatus::EXACT_SOLUTION);
        ompl::msg::setLogLevel(level);
        og::PathGeometric &path = setup.getSolutionPath();

        // The dense exact minimum, at steps of at most 1e-4 rad in every joint (1e-4 times test::stride() under
        // test::scale() < 1).
        const auto denseMinimum = [&f](const og::PathGeometric &p, std::size_t &collisions)
        {
            const ob::StateSpace &space = *f.si->getStateSpace();
            std::vector<double> qa, qb, q;
            ob::State *s = f.si->allocState();
            double least = INFINITY;
            collisions = 0;
            for (std::size_t i = 0; i + 1 < p.getStateCount(); ++i)
            {
                robotStateToVector(space, p.getState(i), qa);
                robotStateToVector(space, p.getState(i + 1), qb);
                double largest = 0.0;
                for (std::size_t k = 0; k < qa.size(); ++k)
                    largest = std::max(largest, std::abs(qb[k] - qa[k]));
                const auto n = static_cast<std::size_t>(std::ceil(largest / (1e-4 * test::stride()))) + 1;
                for (std::size_t j = 0; j <= n; ++j)
                {
                    space.interpolate(p.getState(i), p.getState(i + 1), double(j) / double(n), s);
                    const double c = f.checker->clearance(s);
                    collisions += c <= 0.0;
                    least = std::min(least, c);
                }
            }
            f.si->freeState(s);
            return least;
        };
        std::size_t collisions = 0;
        const double before = denseMinimum(path, collisions);
        ASSERT_EQ(collisions, 0u);

        ClearancePathOptimizer optimizer(f.si, f.checker);
        optimizer.setTimeLimit(600.0);
        // No clock: the result depends on the input and the seed alone. Fewer rounds under test::scale() < 1.
        optimizer.setMaxRounds(static_cast<unsigned>(test::scaled(8, 3)));
        const RobotMotionValidator certifier(f.si, f.scene, *problem.robot);
        std::size_t accepted = 0, refused = 0;
        optimizer.setAcceptedMotionCallback(
            [&](const ob::State *a, const ob::State *b)
            {
                ++accepted;
                refused += certifier.checkMotion(a, b) ? 0 : 1;
            });
        optimizer.optimize(path);
        const ClearancePathOptimizer::Stats &s = optimizer.lastStats();
        const double after = denseMinimum(path, collisions);
        test::Note() << "dense exact minimum " << before << " -> " << after << "; optimiser's measure "
                     << s.minClearanceBefore << " -> " << s.minClearanceAfter << ", " << s.rounds << " rounds, "
                     << accepted << " motions accepted";
        EXPECT_EQ(collisions, 0u);
        EXPECT_GT(accepted, 0u);
        EXPECT_EQ(refused, 0u);
        for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
            EXPECT_TRUE(certifier.checkMotion(path.getState(i), path.getState(i + 1))) << "motion " << i;
        EXPECT_GT(after, 2.0 * before);
        EXPECT_GT(s.minClearanceAfter, s.minClearanceBefore);
        EXPECT_FALSE(s.restored);
        // The measure is an upper estimate of the true minimum, close to it: the dense minimum is no lower than
        // it less its tolerance, nor much above it.
        EXPECT_NEAR(after, s.minClearanceAfter, 0.01 * s.minClearanceAfter);
        std::vector<double> q0, q1;
        robotStateToVector(*f.si->getStateSpace(), path.getState(0), q0);
        robotStateToVector(*f.si->getStateSpace(), path.getState(path.getStateCount() - 1), q1);
        EXPECT_EQ(q0, problem.start);
        EXPECT_EQ(q1, *problem.goal);
    }
}  // namespace meshgap
