// meshgap_plan --optimize clearance: bad options refused with one error, and a run whose optimised path FCL finds
// free at every state of its dense interpolation, no less clear than the optimiser says; with the default sampled
// motion validator on a planar problem of thin barriers, the planner's path has motions the certified validator
// refuses, and the optimised path has none; a goal no certified motion reaches gives one error naming the motion.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>

#include "CliRun.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/RobotMesh.h"
#include "support/MeshWriter.h"
#include "support/PathFile.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{

    const std::string SLOTTED = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
}  // namespace

TEST(PlanOptimizeCli, BadOptionsGiveOneErrorAndExitOne)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--optimize length", "clearance"},
        {"--optimize-time 2", "--optimize-time: applies to --optimize only"},
        {"--optimize-rounds 2", "--optimize-rounds: applies to --optimize only"},
        {"--optimize clearance --optimize-rounds 0", "--optimize-rounds: must be at least 1"},
        {"--optimize clearance --optimize-rounds -3", "--optimize-rounds"},
        {"--optimize clearance --optimize-time -1", "positive"},
        {"--optimize clearance --optimize-time nan", "positive"},
        {"--optimize clearance --checker fast", "--checker certified"},
        {"--sampler bogus", "narrow_passage"},
    };
    for (const auto &[args, mention] : cases)
    {
        const test::CliRun r = test::runPlan("--cfg " + SLOTTED + " --time 0.1 " + args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
        EXPECT_EQ(r.out.find("optimizer"), std::string::npos) << "nothing planned: " << r.out;
    }
}

#ifdef MESHGAP_HAVE_FCL
TEST(PlanOptimizeCli, OptimisedPathIsFreeAndAsClearAsSaid)
{
    const std::string out =
        (fs::temp_directory_path() / ("meshgap_plan_opt_" + std::to_string(::getpid()) + ".path")).string();
    const test::CliRun r = test::runPlan("--cfg " + SLOTTED +
                                         " --motion clearance --time 300 --seed 2 --optimize clearance "
                                         "--optimize-time 1 --out " +
                                         out);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    std::smatch m;
    const std::string text = r.out;
    ASSERT_TRUE(std::regex_search(text, m, std::regex("opt clearance +([-0-9.e+]+) -> ([-0-9.e+]+)"))) << r.out;
    const double before = std::stod(m[1]), after = std::stod(m[2]);
    EXPECT_GE(after, before) << r.out;
    ASSERT_TRUE(std::regex_search(text, m, std::regex("opt length +([-0-9.e+]+) -> ([-0-9.e+]+)"))) << r.out;
    EXPECT_LE(std::stod(m[2]), 3.0 * std::stod(m[1]) * (1 + 1e-9)) << "the default length cap";

    // FCL over the written path, interpolated at 1/200 of each motion: free, and at least the optimiser's minimum
    // (its measure is an upper estimate of the true minimum, within a tolerance of 1e-3 of the input's least clear
    // state).
    const ProblemConfig p = readProblemConfig(SLOTTED);
    OmplProblem problem = setupProblem(p, ClearanceChecker::Mode::CERTIFIED);
    const auto &space = *problem.setup->getStateSpace();
    const auto fw = test::fclModel(loadMesh(p.world)), fr = test::fclModel(loadRobotMesh(p.robot));
    const std::vector<Eigen::Isometry3d> poses = readPoses(out);
    fs::remove(out);
    ASSERT_GE(poses.size(), 2u);
    ompl::base::State *a = space.allocState(), *b = space.allocState(), *s = space.allocState();
    double least = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < poses.size(); ++i)
    {
        stateFromPose(space, poses[i], a);
        stateFromPose(space, poses[i + 1], b);
        for (int k = 0; k <= 200; ++k)
        {
            space.interpolate(a, b, k / 200.0, s);
            const Eigen::Isometry3d X = poseFromState(space, s);
            ASSERT_FALSE(test::fclCollide(fw, fr, X)) << "motion " << i << " at " << k / 200.0;
            least = std::min(least, test::fclDistance(fw, fr, X));
        }
    }
    space.freeState(a);
    space.freeState(b);
    space.freeState(s);
    EXPECT_GE(least, after - 0.01 * after) << r.out;
}
#endif

namespace
{
    /** \brief A planar problem: four barriers 0.05 thick across [-5, 5]^2, each with a gap of 1 (alternately high
        and low), thin posts between them, and an L-shaped robot; written to a fresh folder. */
    class BarriersProblem : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / ("meshgap_barriers_" + std::to_string(::getpid()));
            fs::create_directories(dir_);
            Mesh world;
            for (const auto &[x, gap] : {std::pair<double, double>{-3, 2.5}, {-1, -2.5}, {1, 2.5}, {3, -2.5}})
            {
                const double low = gap - 0.5, high = gap + 0.5;
                world = test::merged(world, test::transformed(test::box(0.025, (low + 5) / 2, 0.5),
                                                              test::translation(x, (low - 5) / 2, 0.5)));
                world = test::merged(world, test::transformed(test::box(0.025, (5 - high) / 2, 0.5),
                                                              test::translation(x, (high + 5) / 2, 0.5)));
            }
            for (const auto &[x, y] : {std::pair<double, double>{-2, 0}, {0, 0}, {2, 0}, {-2, -3}, {0, 3}, {2, -3}})
                world =
                    test::merged(world, test::transformed(test::box(0.3, 0.025, 0.5), test::translation(x, y, 0.5)));
            const Mesh robot =
                test::merged(test::transformed(test::box(0.3, 0.05, 0.25), test::translation(0, 0, 0.5)),
                             test::transformed(test::box(0.05, 0.15, 0.25), test::translation(-0.25, 0.15, 0.5)));
            writeObj(world, (dir_ / "barriers_env.obj").string());
            writeObj(robot, (dir_ / "barriers_robot.obj").string());
            cfg_ = (dir_ / "barriers.cfg").string();
            std::ofstream(cfg_) << "[problem]\nname = barriers\nrobot = barriers_robot.obj\nworld = barriers_env.obj\n"
                                   "start.x = -4.3\nstart.y = -3.5\nstart.theta = 0\n"
                                   "goal.x = 4.3\ngoal.y = 3.5\ngoal.theta = 1.5707963267948966\n"
                                   "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n";
        }
        void TearDown() override { fs::remove_all(dir_); }

        /** \brief Motions of the path file \e file the certified validator refuses. */
        int refusedMotions(const OmplProblem &problem, const std::string &file) const
        {
            const auto si = problem.setup->getSpaceInformation();
            const ompl::geometric::PathGeometric path = readPathFile(file, si);
            ClearanceMotionValidator validator(si, problem.checker);
            int refused = 0;
            for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
                refused += !validator.checkMotion(path.getState(i), path.getState(i + 1));
            return refused;
        }

        fs::path dir_;
        std::string cfg_;
    };
}  // namespace

TEST_F(BarriersProblem, DefaultMotionSettingsGiveACertifiedClearerPath)
{
    const ProblemConfig config = readProblemConfig(cfg_);
    ASSERT_TRUE(config.planar);
    OmplProblem problem = setupProblem(config, ClearanceChecker::Mode::CERTIFIED);
    problem.setup->getSpaceInformation()->setup();
    // The planner's own path (default --motion discrete): some of its motions are refused by the certified validator.
    const std::string raw = (dir_ / "raw.path").string(), optimised = (dir_ / "optimised.path").string();
    const test::CliRun r0 = test::runPlan("--cfg " + cfg_ + " --seed 3 --quiet --out " + raw);
    ASSERT_EQ(r0.status, 0) << r0.out << r0.err;
    ASSERT_GT(refusedMotions(problem, raw), 0) << "the scene should make the sampled validator pass a motion the "
                                                  "certified one refuses";

    const test::CliRun r =
        test::runPlan("--cfg " + cfg_ + " --seed 3 --quiet --optimize clearance --optimize-time 5 --out " + optimised);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    std::smatch m;
    const std::string text = r.out;
    ASSERT_TRUE(std::regex_search(text, m, std::regex("opt repair +([0-9]+) motions refused"))) << r.out;
    EXPECT_EQ(std::stoi(m[1]), refusedMotions(problem, raw)) << r.out;
    ASSERT_TRUE(std::regex_search(text, m, std::regex("opt clearance +([-0-9.e+]+) -> ([-0-9.e+]+)"))) << r.out;
    const double before = std::stod(m[1]), after = std::stod(m[2]);
    EXPECT_GT(after, before) << r.out;
    EXPECT_EQ(refusedMotions(problem, optimised), 0) << r.out;

    // The optimised path, densely by the exact test (and by FCL): free, and no less clear than the optimiser says.
    const auto si = problem.setup->getSpaceInformation();
    const ompl::geometric::PathGeometric path = readPathFile(optimised, si);
    const auto &space = *si->getStateSpace();
    ompl::base::State *s = si->allocState();
    double least = std::numeric_limits<double>::infinity();
#ifdef MESHGAP_HAVE_FCL
    const auto fw = test::fclModel(loadMesh(config.world)), fr = test::fclModel(loadRobotMesh(config.robot, true));
#endif
    for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
        for (int k = 0; k <= 200; ++k)
        {
            space.interpolate(path.getState(i), path.getState(i + 1), k / 200.0, s);
            const Eigen::Isometry3d X = poseFromState(space, s);
            ASSERT_FALSE(problem.scene->inCollision(X)) << "motion " << i << " at " << k / 200.0;
            least = std::min(least, problem.checker->clearance(s));
#ifdef MESHGAP_HAVE_FCL
            ASSERT_FALSE(test::fclCollide(fw, fr, X)) << "motion " << i << " at " << k / 200.0 << " (FCL)";
#endif
        }
    si->freeState(s);
    EXPECT_GE(least, after - 0.01 * after) << r.out;
}

TEST(PlanOptimizeCli, NamesTheMotionItCannotCertify)
{
    // The goal inside a closed square ring of walls 0.02 thick, a robot 0.1 wide: the sampled validator's states
    // step over a wall, the certified validator never does, so no certified path reaches the goal.
    const fs::path dir = fs::temp_directory_path() / ("meshgap_ring_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Mesh world;
    for (const auto &[x, y, hx, hy] : {std::array<double, 4>{3, 3.51, 0.53, 0.01},
                                       {3, 2.49, 0.53, 0.01},
                                       {3.51, 3, 0.01, 0.53},
                                       {2.49, 3, 0.01, 0.53}})
        world = test::merged(world, test::transformed(test::box(hx, hy, 0.5), test::translation(x, y, 0.5)));
    writeObj(world, (dir / "ring_env.obj").string());
    writeObj(test::transformed(test::box(0.05, 0.05, 0.25), test::translation(0, 0, 0.5)),
             (dir / "ring_robot.obj").string());
    const std::string cfg = (dir / "ring.cfg").string(), raw = (dir / "raw.path").string();
    std::ofstream(cfg) << "[problem]\nname = ring\nrobot = ring_robot.obj\nworld = ring_env.obj\n"
                          "start.x = -3\nstart.y = -3\nstart.theta = 0\ngoal.x = 3\ngoal.y = 3\ngoal.theta = 0\n"
                          "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n";
    const test::CliRun r0 = test::runPlan("--cfg " + cfg + " --seed 1 --quiet --out " + raw);
    ASSERT_EQ(r0.status, 0) << r0.out << r0.err;
    const test::CliRun r = test::runPlan("--cfg " + cfg + " --seed 1 --quiet --optimize clearance --optimize-time 1");
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_EQ(test::countLines(r.err, "error: --optimize clearance: "), 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_NE(r.out.find("optimizer       failed: "), std::string::npos) << r.out;
    std::smatch m;
    const std::string err = r.err;
    ASSERT_TRUE(std::regex_search(err, m, std::regex("motion ([0-9]+)→([0-9]+) "))) << r.err;
    const std::size_t i = std::stoul(m[1]), j = std::stoul(m[2]);
    EXPECT_EQ(j, i + 1);
    // The motion named is one of the planner's path (the same seed) that the certified validator refuses.
    OmplProblem problem = setupProblem(readProblemConfig(cfg), ClearanceChecker::Mode::CERTIFIED);
    const auto si = problem.setup->getSpaceInformation();
    si->setup();
    const ompl::geometric::PathGeometric path = readPathFile(raw, si);
    ASSERT_LT(j, path.getStateCount());
    EXPECT_FALSE(ClearanceMotionValidator(si, problem.checker).checkMotion(path.getState(i), path.getState(j)));
    fs::remove_all(dir);
}
