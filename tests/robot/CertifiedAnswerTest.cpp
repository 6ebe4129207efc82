// Certified answers at the price of a sampled search (CertifiedAnswerPlanner, PathCertifier): a motion that OMPL's
// sampled check passes but that collides is refused and replanned into certified motions; every path the planner
// returns, on maps/arm_fixture and on the fanuc carrying a payload through a window, is free when checked at steps of
// at most 1e-4 rad by the exact collision test (every link against the obstacles, every self pair, containment
// included), with the search's sampled check coarse enough that it lets colliding motions through.
#include <gtest/gtest.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/PathCertifier.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/UrdfRobot.h"
#include "TestNote.h"
#include "TestScale.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace
    {
        const std::string ARM_FIXTURE = std::string(MESHGAP_SOURCE_DIR) + "/maps/arm_fixture/arm_fixture.cfg";

        /** \brief OMPL's seed for the generators made from now on (OMPL's complaint that others exist silenced). */
        void seed(std::uint_fast32_t value)
        {
            const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
            ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
            ompl::RNG::setSeed(value);
            ompl::msg::setLogLevel(level);
        }

        /** \brief A robot problem in joint space: its scene, and a SpaceInformation whose validity checker is exact
            and whose motion validator is the certified one. */
        struct ArmSetup
        {
            RobotProblem problem;
            RobotSceneConstPtr scene;
            ob::SpaceInformationPtr si;

            explicit ArmSetup(const std::string &cfg) : problem(readRobotProblem(cfg))
            {
                scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles);
                const auto &urdf = dynamic_cast<const UrdfRobot &>(*problem.robot);
                ob::RealVectorBounds bounds(3);
                bounds.setLow(-1);
                bounds.setHigh(1);
                si = std::make_shared<ob::SpaceInformation>(robotStateSpace(urdf, bounds));
                si->setStateValidityChecker(std::make_shared<RobotChecker>(si, scene));
                si->setMotionValidator(std::make_shared<RobotMotionValidator>(si, scene, urdf));
                si->setup();
            }
        };

        /** \brief States of the straight joint-space motion a -> b (OMPL's interpolation) at most \e step apart in
            every joint that collide (exact test); stops at the first when \e first. */
        std::size_t collidingStates(const ArmSetup &arm, const ob::State *a, const ob::State *b, double step,
                                    bool first)
        {
            const ob::StateSpace &space = *arm.si->getStateSpace();
            std::vector<double> qa, qb, q;
            robotStateToVector(space, a, qa);
            robotStateToVector(space, b, qb);
            double largest = 0.0;
            for (std::size_t k = 0; k < qa.size(); ++k)
                largest = std::max(largest, std::abs(qb[k] - qa[k]));
            const auto n = static_cast<std::size_t>(std::ceil(largest / step)) + 1;
            ob::State *s = arm.si->allocState();
            RobotWarmStart warm;
            std::size_t colliding = 0;
            for (std::size_t i = 0; i <= n && !(first && colliding); ++i)
            {
                space.interpolate(a, b, double(i) / double(n), s);
                robotStateToVector(space, s, q);
                colliding += arm.scene->inCollision(q.data(), q.size(), warm);
            }
            arm.si->freeState(s);
            return colliding;
        }

        /** \brief Colliding states of every motion of \e path at steps of at most 1e-4 rad. */
        std::size_t densePathCollisions(const ArmSetup &arm, const og::PathGeometric &path)
        {
            std::size_t colliding = 0;
            for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                colliding += collidingStates(arm, path.getState(i), path.getState(i + 1), 1e-4, false);
            return colliding;
        }

        /** \brief A motion between two free states that the sampled check at \e resolution passes and that
            collides (a state 1e-3 rad steps find): found by drawing motions with a fixed seed. */
        bool findMissedCollision(const ArmSetup &arm, double resolution, ob::State *a, ob::State *b)
        {
            auto coarse = std::make_shared<ob::SpaceInformation>(arm.si->getStateSpace());
            coarse->setStateValidityChecker(arm.si->getStateValidityChecker());
            coarse->setup();
            const double kept = arm.si->getStateValidityCheckingResolution();
            coarse->setStateValidityCheckingResolution(resolution);  // the shared state space's: restored below
            ob::DiscreteMotionValidator sampled(coarse);
            seed(5);
            ob::StateSamplerPtr sampler = arm.si->allocStateSampler();
            bool found = false;
            for (int trial = 0; trial < 200000 && !found; ++trial)
            {
                sampler->sampleUniform(a);
                sampler->sampleUniformNear(b, a, 0.8);
                if (!arm.si->isValid(a) || !arm.si->isValid(b) || !sampled.checkMotion(a, b))
                    continue;
                found = collidingStates(arm, a, b, 1e-3, true) > 0;
            }
            coarse->setStateValidityCheckingResolution(kept);
            return found;
        }

        /** \brief After a certify() that refused the one motion a-b and repaired it: the path still runs from a to b,
            every motion accepted by the certified validator and free at steps of 1e-4 rad. */
        void expectRepaired(const ArmSetup &arm, const PathCertifier &certifier, const og::PathGeometric &path,
                            const ob::State *a, const ob::State *b)
        {
            EXPECT_EQ(certifier.lastStats().refused, 1u);
            EXPECT_EQ(certifier.lastStats().repaired, 1u);
            ASSERT_GE(path.getStateCount(), 3u);
            EXPECT_EQ(certifier.lastStats().inserted, path.getStateCount() - 2);
            EXPECT_EQ(arm.si->distance(path.getState(0), a), 0.0);
            EXPECT_EQ(arm.si->distance(path.getState(path.getStateCount() - 1), b), 0.0);
            for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                EXPECT_TRUE(arm.si->checkMotion(path.getState(i), path.getState(i + 1))) << "motion " << i;
            EXPECT_EQ(densePathCollisions(arm, path), 0u);
        }
    }  // namespace

    TEST(PathCertifier, ReplansAMotionTheSampledCheckLetsThroughIntoCertifiedMotions)
    {
        const ArmSetup arm(ARM_FIXTURE);
        ob::State *a = arm.si->allocState(), *b = arm.si->allocState();
        ASSERT_TRUE(findMissedCollision(arm, 0.05, a, b)) << "no motion found that the sampled check misses";
        ASSERT_GT(collidingStates(arm, a, b, 1e-4, false), 0u);
        og::PathGeometric path(arm.si, a, b);
        ASSERT_FALSE(arm.si->checkMotion(a, b)) << "the certified validator passes a colliding motion";

        // No repair allowed: the path is refused and left as it was.
        PathCertifier certifier(arm.si);
        certifier.setRepairIterations(0);
        const std::vector<ob::State *> before = path.getStates();
        seed(3);
        EXPECT_FALSE(certifier.certify(path, ob::plannerNonTerminatingCondition()));
        EXPECT_EQ(path.getStates(), before);
        EXPECT_EQ(certifier.lastStats().refused, 1u);
        EXPECT_EQ(certifier.lastStats().repaired, 0u);

        certifier.setRepairIterations(20000);
        ASSERT_TRUE(certifier.certify(path, ob::plannerNonTerminatingCondition()));
        EXPECT_EQ(certifier.lastStats().motions, 1u);
        expectRepaired(arm, certifier, path, a, b);
        test::Note() << "a motion the sampled check at 5 % misses, replanned into " << path.getStateCount() - 1
                     << " certified motions";
        arm.si->freeState(a);
        arm.si->freeState(b);
    }

    namespace
    {
        /** \brief A sampled motion check of its own: the end state and \e n - 1 evenly spaced states between
            (n = 1: the end state alone, which lets every motion between free states through). */
        class EvenlySampledValidator : public ob::MotionValidator
        {
        public:
            EvenlySampledValidator(const ob::SpaceInformationPtr &si, unsigned n) : ob::MotionValidator(si), n_(n)
            {
            }

            bool checkMotion(const ob::State *s1, const ob::State *s2) const override
            {
                ob::State *s = si_->allocState();
                bool free = true;
                for (unsigned k = 1; free && k <= n_; ++k)
                {
                    si_->getStateSpace()->interpolate(s1, s2, double(k) / n_, s);
                    free = si_->isValid(s);
                }
                si_->freeState(s);
                return free;
            }

            bool checkMotion(const ob::State *s1, const ob::State *s2,
                             std::pair<ob::State *, double> &lastValid) const override
            {
                const bool free = checkMotion(s1, s2);
                if (!free && lastValid.first)
                    si_->copyState(lastValid.first, s1);
                lastValid.second = 0.0;
                return free;
            }

        private:
            unsigned n_;
        };

        /** \brief A twin of \e arm's SpaceInformation whose motion check is EvenlySampledValidator(n). */
        ob::SpaceInformationPtr sampledTwin(const ArmSetup &arm, unsigned n)
        {
            auto twin = std::make_shared<ob::SpaceInformation>(arm.si->getStateSpace());
            twin->setStateValidityChecker(arm.si->getStateValidityChecker());
            twin->setMotionValidator(std::make_shared<EvenlySampledValidator>(twin, n));
            twin->setup();
            return twin;
        }

        /** \brief Certify a -> b (a motion that collides) with \e certifier; the path returned runs from a to b,
            every motion of it accepted by the certified validator and free at steps of 1e-4 rad. */
        void expectCertifiedDetour(const ArmSetup &arm, PathCertifier &certifier, const ob::State *a,
                                   const ob::State *b)
        {
            og::PathGeometric path(arm.si, a, b);
            seed(3);
            ASSERT_TRUE(certifier.certify(path, ob::plannerNonTerminatingCondition()));
            expectRepaired(arm, certifier, path, a, b);
        }
    }  // namespace

    TEST(PathCertifier, ProvesADetourFoundWithASampledCheckAndReplansWhatItLetsThrough)
    {
        const ArmSetup arm(ARM_FIXTURE);
        ob::State *a = arm.si->allocState(), *b = arm.si->allocState();
        ASSERT_TRUE(findMissedCollision(arm, 0.05, a, b)) << "no motion found that the sampled check misses";
        ASSERT_FALSE(arm.si->checkMotion(a, b)) << "the certified validator passes a colliding motion";

        // A fine sampled check: the detour it finds is proven, no certified search needed.
        PathCertifier fine(arm.si);
        fine.setSampledSpaceInformation(sampledTwin(arm, 200));
        expectCertifiedDetour(arm, fine, a, b);
        EXPECT_GE(fine.lastStats().sampled, 1u);
        const std::size_t fineStates = fine.lastStats().inserted;

        // A check of the end state alone lets the straight motion through again and again: each motion of its
        // detours that collides is refused and replanned, down to the certified search.
        PathCertifier blind(arm.si);
        blind.setSampledSpaceInformation(sampledTwin(arm, 1));
        expectCertifiedDetour(arm, blind, a, b);
        EXPECT_GT(blind.lastStats().detourRefused, 0u);
        test::Note() << "a motion the sampled check at 5 % misses: a detour of " << fineStates + 1
                     << " motions found at 200 states a motion and proven (" << fine.lastStats().detourRefused
                     << " of its motions refused); with the end state alone, " << blind.lastStats().detourRefused
                     << " motions of the detours refused and replanned, " << blind.lastStats().inserted + 1
                     << " motions in the end";

        auto other = std::make_shared<ob::SpaceInformation>(std::make_shared<ob::RealVectorStateSpace>(2));
        EXPECT_THROW(fine.setSampledSpaceInformation(other), Exception);
        arm.si->freeState(a);
        arm.si->freeState(b);
    }

    namespace
    {
        /** \brief Totals over the seeds of runPlanner(). */
        struct Tally
        {
            unsigned solved{0}, refused{0}, repaired{0}, rejected{0}, collidingPaths{0};
            std::size_t collidingStates{0};
        };

        /** \brief RRTConnect from the problem's start to its goal, seeds 1..seeds: through CertifiedAnswerPlanner
            (its search's sampled check at \e resolution) when \e certify, else alone with the sampled check at
            \e resolution; each path returned checked densely. */
        Tally plan(const ArmSetup &arm, unsigned seeds, double resolution, bool certify)
        {
            Tally t;
            for (unsigned run = 1; run <= seeds; ++run)
            {
                seed(run);
                ob::SpaceInformationPtr si = arm.si;
                const double kept = si->getStateValidityCheckingResolution();
                if (!certify)
                {
                    si = std::make_shared<ob::SpaceInformation>(arm.si->getStateSpace());
                    si->setStateValidityChecker(arm.si->getStateValidityChecker());
                    si->setStateValidityCheckingResolution(resolution);
                    si->setup();
                }
                og::SimpleSetup setup(si);
                ob::ScopedState<> start(si), goal(si);
                robotStateFromVector(*si->getStateSpace(), arm.problem.start, start.get());
                robotStateFromVector(*si->getStateSpace(), *arm.problem.goal, goal.get());
                setup.setStartAndGoalStates(start, goal);
                std::shared_ptr<CertifiedAnswerPlanner> answer;
                if (certify)
                {
                    answer = std::make_shared<CertifiedAnswerPlanner>(
                        si, [](const ob::SpaceInformationPtr &s) { return std::make_shared<og::RRTConnect>(s); });
                    answer->setSearchResolution(resolution);
                    setup.setPlanner(answer);
                }
                else
                    setup.setPlanner(std::make_shared<og::RRTConnect>(si));
                // A generous limit: a run under the sanitizers on a loaded machine is ten times slower, and this is
                // no timing test.
                const bool exact = setup.solve(60.0) == ob::PlannerStatus::EXACT_SOLUTION;
                si->setStateValidityCheckingResolution(kept);  // the state space is shared
                if (!exact)
                    continue;
                ++t.solved;
                const std::size_t colliding = densePathCollisions(arm, setup.getSolutionPath());
                t.collidingStates += colliding;
                t.collidingPaths += colliding > 0;
                if (answer)
                {
                    t.refused += answer->lastStats().refused;
                    t.repaired += answer->lastStats().repaired;
                    t.rejected += answer->lastStats().rejectedPaths;
                    // Every motion of the answer is one the certified validator accepts.
                    const og::PathGeometric &path = setup.getSolutionPath();
                    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                        EXPECT_TRUE(arm.si->checkMotion(path.getState(i), path.getState(i + 1)));
                }
            }
            return t;
        }

        /** \brief Certified answers densely free over \e seeds seeds, at the default search resolution and at a
            coarse one; and the coarse search alone, uncertified, for comparison. */
        void expectCertifiedAnswersFree(const ArmSetup &arm, const std::string &name, unsigned seeds)
        {
            const Tally fine = plan(arm, seeds, 0.0, true), coarse = plan(arm, seeds, 0.1, true);
            const Tally unchecked = plan(arm, seeds, 0.1, false);
            EXPECT_EQ(fine.solved, seeds);
            EXPECT_EQ(coarse.solved, seeds);
            EXPECT_EQ(fine.collidingStates, 0u);
            EXPECT_EQ(coarse.collidingStates, 0u);
            // The coarse search lets colliding motions through (its own paths collide): the certification has work
            // to do.
            EXPECT_GT(unchecked.collidingPaths, 0u);
            EXPECT_GT(coarse.refused, 0u);
            EXPECT_EQ(coarse.refused, coarse.repaired + coarse.rejected);
            test::Note() << name << ", " << seeds << " seeds: certified answers (search at 1 %) " << fine.solved
                         << " solved, " << fine.refused << " motions refused, " << fine.repaired
                         << " replanned; (search at 10 %) " << coarse.solved << " solved, " << coarse.refused
                         << " refused, " << coarse.repaired << " replanned, " << coarse.rejected
                         << " paths searched again; 0 colliding states at 1e-4 rad. The search at 10 % alone: "
                         << unchecked.collidingPaths << " of " << unchecked.solved << " paths collide ("
                         << unchecked.collidingStates << " states)";
        }
    }  // namespace

    TEST(CertifiedAnswerPlanner, EveryArmFixturePathIsFreeAtATenThousandthOfARadian)
    {
        expectCertifiedAnswersFree(ArmSetup(ARM_FIXTURE), "arm_fixture", static_cast<unsigned>(test::scaled(5)));
    }

    TEST(CertifiedAnswerPlanner, EveryFanucPathIsFreeAtATenThousandthOfARadian)
    {
        const std::string folder = std::string(MESHGAP_SHARED_DATA_DIR) + "/robots";
        const std::string urdf = folder + "/moveit_resources_fanuc_description/urdf/fanuc.urdf";
        const std::string srdf = folder + "/moveit_resources_fanuc_moveit_config/config/fanuc.srdf";
        if (!std::filesystem::exists(urdf) || !std::filesystem::exists(srdf))
            GTEST_SKIP() << "the fanuc arm is not in " << folder << " (see ../shared/data/robots/README.md)";
        // arm_fixture's wall, moved so that its window is at the height of the fanuc's forearm, and its C-shaped
        // payload on link_6 (bench/robots.md, "Robots of many bodies: planning").
        const std::filesystem::path dir = std::filesystem::temp_directory_path() / "meshgap_certified_answer_fanuc";
        std::filesystem::create_directories(dir);
        const std::string maps = std::string(MESHGAP_SOURCE_DIR) + "/maps/arm_fixture/";
        std::ifstream in(maps + "arm_fixture_world.obj");
        std::ofstream world(dir / "fixture.obj");
        world.precision(17);
        for (std::string line; std::getline(in, line);)
        {
            double x, y, z;
            std::istringstream values(line.size() > 2 && line.rfind("v ", 0) == 0 ? line.substr(2) : "");
            if (values >> x >> y >> z)
                world << "v " << x - 0.12 << " " << y << " " << z + 0.85 << "\n";
            else
                world << line << "\n";
        }
        world.close();
        std::ofstream cfg(dir / "fanuc_payload.cfg");
        cfg << "[problem]\nrobot.urdf = " << urdf << "\nrobot.srdf = " << srdf << "\nrobot.package_path = " << folder
            << "\nworld = fixture.obj\nattach = " << maps
            << "arm_fixture_payload.obj link_6 0.1 0 0 0 0 0 1\nstart.joints = 0 -0.9 -0.9 0 -1.5 0\n"
            << "goal.joints = 0 0 0 0 0 0\n";
        cfg.close();
        expectCertifiedAnswersFree(ArmSetup((dir / "fanuc_payload.cfg").string()), "fanuc + payload",
                                   static_cast<unsigned>(test::scaled(3)));
    }
}  // namespace meshgap

namespace meshgap
{
    TEST(CertifiedAnswerPlanner, RefusesAMissingOrMisplacedSearchPlannerAndBadSettings)
    {
        const ArmSetup arm(ARM_FIXTURE);
        EXPECT_THROW(CertifiedAnswerPlanner(arm.si, nullptr), Exception);
        EXPECT_THROW(CertifiedAnswerPlanner(arm.si, [](const ob::SpaceInformationPtr &) { return nullptr; }),
                     Exception);
        // A planner on the problem's own SpaceInformation would search with the certified validator.
        EXPECT_THROW(CertifiedAnswerPlanner(arm.si, [&arm](const ob::SpaceInformationPtr &)
                                            { return std::make_shared<og::RRTConnect>(arm.si); }),
                     Exception);
        CertifiedAnswerPlanner planner(arm.si, [](const ob::SpaceInformationPtr &s)
                                       { return std::make_shared<og::RRTConnect>(s); });
        EXPECT_EQ(planner.getName(), "RRTConnect");
        EXPECT_TRUE(planner.params().hasParam("range"));
        EXPECT_THROW(planner.setSearchResolution(-0.1), Exception);
        EXPECT_THROW(planner.setSearchResolution(std::nan("")), Exception);
        EXPECT_THROW(planner.certifier().setRepairRange(0.0), Exception);
        EXPECT_THROW(PathCertifier(nullptr), Exception);
    }
}  // namespace meshgap
