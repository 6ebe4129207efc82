// The tools on a problem in MoveIt's files (--urdf, --srdf, --scene, --request): meshgap_distance's answer worked out
// by hand (the scene's allowed collision matrix honoured), meshgap_plan's path from the request's start to its goal,
// meshgap_benchmark's .log, and one clear error and a non-zero exit per bad command line.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "CliRun.h"

namespace fs = std::filesystem;

namespace
{
    using meshgap::test::CliRun;
    using meshgap::test::runExecutable;

    const std::string CLI_ARM = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/problems/arm2.urdf";
    const std::string CLI_ARM_SRDF = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/problems/arm2.srdf";

    /** \brief A box of edge 0.2 centred at (1.2, 0, 0.2): at the start (every joint 0) the fore link (x up to 0.9)
        is 0.2 from it, the nearest link. */
    const char *const CLI_SCENE =
        "world:\n  collision_objects:\n    - id: block\n      primitives:\n        - type: box\n"
        "          dimensions: [0.2, 0.2, 0.2]\n      primitive_poses:\n"
        "        - position: [1.2, 0, 0.2]\n          orientation: [0, 0, 0, 1]\n";
    const char *const CLI_REQUEST =
        "start_state:\n  joint_state:\n    name: [yaw, elbow]\n    position: [0, 0]\n"
        "goal_constraints:\n  - joint_constraints:\n      - joint_name: yaw\n"
        "        position: 1.5\n      - joint_name: elbow\n        position: -0.5\n";

    class MoveItCli : public meshgap::test::FolderTest
    {
    protected:
        MoveItCli() : FolderTest("meshgap_moveit_cli_") {}
        void SetUp() override
        {
            FolderTest::SetUp();
            scene_ = file("scene.yaml", CLI_SCENE);
            request_ = file("request.yaml", CLI_REQUEST);
        }

        /** \brief The four flags. */
        std::string flags() const
        {
            return "--urdf " + CLI_ARM + " --srdf " + CLI_ARM_SRDF + " --scene " + scene_ + " --request " + request_;
        }

        std::string scene_, request_;
    };

    double valueAfter(const std::string &text, const std::string &key)
    {
        const auto at = text.find(key);
        return at == std::string::npos ? NAN : std::stod(text.substr(at + key.size()));
    }
}  // namespace

TEST_F(MoveItCli, DistanceHonoursTheAllowedCollisionMatrix)
{
    // fore against the block, 0.2.
    const CliRun r = runExecutable("meshgap_distance", flags());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NEAR(valueAfter(r.out, "state 1: clearance"), 0.2, 1e-9) << r.out;
    EXPECT_NE(r.out.find("closest pair   link 'fore' and obstacle 0"), std::string::npos) << r.out;
    // fore and the block allowed by the scene's matrix: upper (x up to 0.5) against the block, 0.6.
    scene_ = file("allowed.yaml", std::string(CLI_SCENE) +
                                      "allowed_collision_matrix:\n  entry_names: [fore, block]\n"
                                      "  entry_values: [[false, true], [true, false]]\n");
    const CliRun allowed = runExecutable("meshgap_distance", flags());
    ASSERT_EQ(allowed.status, 0) << allowed.err;
    EXPECT_NEAR(valueAfter(allowed.out, "state 1: clearance"), 0.6, 1e-9) << allowed.out;
    EXPECT_NE(allowed.out.find("closest pair   link 'upper' and obstacle 0"), std::string::npos) << allowed.out;
}

TEST_F(MoveItCli, PlanGoesFromTheRequestsStartToItsGoal)
{
    const std::string path = (dir_ / "p.path").string();
    const CliRun r = runExecutable("meshgap_plan", flags() + " --time 5 -q --out " + path, 120);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("dense path free yes"), std::string::npos) << r.out;
    std::ifstream in(path);
    std::string first, line, last;
    std::getline(in, first);
    while (std::getline(in, line))
        if (!line.empty())
            last = line;
    double a, b;
    std::istringstream(first) >> a >> b;
    EXPECT_NEAR(a, 0.0, 1e-12);
    EXPECT_NEAR(b, 0.0, 1e-12);
    std::istringstream(last) >> a >> b;
    EXPECT_NEAR(a, 1.5, 1e-12);
    EXPECT_NEAR(b, -0.5, 1e-12);
}

TEST_F(MoveItCli, BenchmarkWritesItsLog)
{
    const std::string out = (dir_ / "logs").string();
    const CliRun r = runExecutable("meshgap_benchmark", flags() + " --planner rrtconnect --checker certified "
                                                                  "--runs 1 --time 2 --seed 1 --out " + out, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(fs::path(out) / "request.RRTConnect.meshgap-certified.log")) << r.err;
}

TEST_F(MoveItCli, BadCommandLinesGetOneClearErrorEach)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--scene " + scene_, "--urdf"},
        {"--cfg x.cfg " + flags(), "either --cfg or --urdf"},
        {"--urdf " + CLI_ARM + " --scene " + file("bad.yaml", "world: [\n"), "bad.yaml:"},
        {"--urdf " + CLI_ARM + " --scene " + scene_ + " --request " +
             file("r.yaml",
                  "start_state: {joint_state: "
                  "{name: [hip], position: [0]}}\n"),
         "no joint 'hip'"}};
    for (const auto &[args, what] : cases)
        for (const char *tool : {"meshgap_distance", "meshgap_plan"})
        {
            const CliRun r = runExecutable(tool, args);
            EXPECT_NE(r.status, 0) << tool << " " << args;
            EXPECT_NE(r.err.find(what), std::string::npos) << tool << ": " << r.err;
        }
}
