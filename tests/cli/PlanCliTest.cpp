// meshgap_plan as a user runs it: errors, and a real planning run whose path FCL checks state by state.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "FclOracle.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    struct PlanRun
    {
        int status;
        std::string out, err;
    };

    PlanRun plan(const std::string &args)
    {
        static int calls = 0;
        const std::string stem = (fs::temp_directory_path() / ("meshgap_plan_" + std::to_string(::getpid()) + "_" +
                                                               std::to_string(++calls))).string();
        const std::string command = std::string(MESHGAP_BINARY_DIR) + "/planners/meshgap_plan " + args + " >" + stem +
                                    ".out 2>" + stem + ".err";
        const int raw = std::system(command.c_str());
        auto slurp = [](const std::string &path) {
            std::ifstream in(path);
            std::stringstream s;
            s << in.rdbuf();
            fs::remove(path);
            return s.str();
        };
        return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(stem + ".out"), slurp(stem + ".err")};
    }

    const std::string MAPS = std::string(MESHGAP_SOURCE_DIR) + "/maps";
}  // namespace

TEST(PlanCli, BadInputGivesOneErrorAndExitOne)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--cfg /nonexistent/p.cfg", "/nonexistent/p.cfg"},
        {"--cfg " + MAPS + "/hand_bowl/hand_bowl.cfg --planner nope", "rrtconnect"},
        {"--cfg " + MAPS + "/hand_bowl/hand_bowl.cfg --mode sloppy", "--mode"},
        {"--cfg " + MAPS + "/hand_bowl/hand_bowl.cfg --objective speed", "speed"},
        {"", "--cfg"},
    };
    for (const auto &[args, mention] : cases)
    {
        const PlanRun r = plan(args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
    }
}

#ifdef MESHGAP_HAVE_FCL
TEST(PlanCli, PlansAPathWhoseEveryStateFclCallsFree)
{
    const std::string cfg = MAPS + "/hand_bowl/hand_bowl.cfg";
    const std::string out = (fs::temp_directory_path() / ("meshgap_plan_" + std::to_string(::getpid()) + ".path")).string();
    const PlanRun r = plan("--cfg " + cfg + " --planner rrtconnect --time 20 --seed 3 --out " + out);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("exact solution yes"), std::string::npos) << r.out;
    const ProblemConfig p = readProblemConfig(cfg);
    const auto fw = test::fclModel(loadMesh(p.world)), fr = test::fclModel(loadRobotMesh(p.robot));
    const std::vector<Eigen::Isometry3d> path = readPoses(out);
    ASSERT_GE(path.size(), 2u);
    EXPECT_TRUE(path.front().isApprox(p.start, 1e-9));
    EXPECT_TRUE(path.back().isApprox(*p.goal, 1e-9));
    for (std::size_t i = 0; i < path.size(); ++i)
        EXPECT_FALSE(test::fclCollide(fw, fr, path[i])) << "state " << i;
    fs::remove(out);
}
#endif
