// meshgap_plan --optimize clearance: bad options refused with one error, and a run whose optimised path FCL finds
// free at every state of its dense interpolation, no less clear than the optimiser says.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <regex>

#include "CliRun.h"
#include "FclOracle.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    test::CliRun plan(const std::string &args)
    {
        return test::runExecutable("meshgap_plan", args);
    }

    const std::string SLOTTED = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
}  // namespace

TEST(PlanOptimizeCli, BadOptionsGiveOneErrorAndExitOne)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--optimize length", "clearance"},
        {"--optimize-time 2", "--optimize-time"},
        {"--optimize clearance --optimize-time -1", "positive"},
        {"--optimize clearance --optimize-time nan", "positive"},
        {"--optimize clearance --checker fast", "--checker certified"},
        {"--sampler bogus", "narrow_passage"},
    };
    for (const auto &[args, mention] : cases)
    {
        const test::CliRun r = plan("--cfg " + SLOTTED + " --time 0.1 " + args);
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
    const test::CliRun r = plan("--cfg " + SLOTTED +
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
