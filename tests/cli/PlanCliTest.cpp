// meshgap_plan as a user runs it: errors, and a real planning run whose path FCL checks state by state.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <sys/wait.h>
#include <unistd.h>

#include "CliRun.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "support/MeshWriter.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    using PlanRun = test::CliRun;

    const std::string PLAN_CLI_MAPS = std::string(MESHGAP_SOURCE_DIR) + "/maps";
}  // namespace

TEST(PlanCli, BadInputGivesOneErrorAndExitOne)
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--cfg /nonexistent/p.cfg", "/nonexistent/p.cfg"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner nope", "rrtconnect"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --checker sloppy", "--checker"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --mode fast",
         "--mode: renamed: use --checker certified|fast"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --objective speed", "max_min_clearance"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --objective length --weight 3", "--weight"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --objective weighted --weight -1", "--weight"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --param rrtstar.speed=3",
         "use_k_nearest"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --param rrtstar.range=far", "'far'"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --param range", "PLANNER.NAME=VALUE"},
        // The old form NAME=VALUE names the new one; a parameter of another planner is refused.
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --param range=3",
         "is not PLANNER.NAME=VALUE (e.g. --param rrtstar.range=5)"},
        {"--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --param rrtconnect.range=3",
         "the planner is rrtstar"},
        {"", "--cfg"},
    };
    for (const auto &[args, mention] : cases)
    {
        const PlanRun r = test::runPlan(args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
    }
}

TEST(PlanCli, ParamReachesThePlanner)
{
    // RRT* says which neighbourhood it uses as it starts: k nearest by default, a radius with use_k_nearest=0.
    const std::string args = "--cfg " + PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg --planner rrtstar --time 0.2";
    const PlanRun byDefault = test::runPlan(args), radius = test::runPlan(args + " --param rrtstar.use_k_nearest=0");
    // 0 (exact) or 2 (no exact solution in the time: a slow build, e.g. under a sanitizer), never 1 (bad input).
    for (const PlanRun *r : {&byDefault, &radius})
        ASSERT_TRUE(r->status == 0 || r->status == 2) << r->status << "\n" << r->err;
    const std::string both = byDefault.out + byDefault.err, radiusBoth = radius.out + radius.err;
    EXPECT_NE(both.find("k-nearest"), std::string::npos) << both;
    EXPECT_EQ(radiusBoth.find("k-nearest"), std::string::npos) << radiusBoth;
    EXPECT_NE(radiusBoth.find("rewiring radius"), std::string::npos) << radiusBoth;
}

// A start (or goal) in collision: exit 1, and the message says which, the obstacle, and the signed distance.
TEST(PlanCli, StartOrGoalInCollisionIsNamed)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_plan_collide_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeObj(test::box(1, 1, 1), (dir / "robot.obj").string());
    writeObj(test::merged(test::transformed(test::box(1, 1, 1), test::translation(10, 0, 0)),
                          test::transformed(test::box(1, 1, 1), test::translation(-10, 0, 0))),
             (dir / "world.obj").string());
    for (const auto &[label, start, goal] : {std::make_tuple("start", "10.5", "0"), std::make_tuple("goal", "0", "-9")})
    {
        std::ofstream(dir / "p.cfg") << "[problem]\nrobot = robot.obj\nworld = world.obj\nstart.x = " << start
                                     << "\nstart.y = 0\nstart.z = 0\ngoal.x = " << goal
                                     << "\ngoal.y = 0\ngoal.z = 0\nvolume.min.x = -20\nvolume.min.y = -20\n"
                                        "volume.min.z = -20\nvolume.max.x = 20\nvolume.max.y = 20\nvolume.max.z = 20\n";
        const PlanRun r = test::runPlan("--cfg " + (dir / "p.cfg").string() + " --time 1");
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_NE(r.err.find(std::string(label) + " is in collision with obstacle " + (label == std::string("start") ? "0" : "1")),
                  std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("signed distance"), std::string::npos) << r.err;
    }
    fs::remove_all(dir);
}

#ifdef MESHGAP_HAVE_FCL
namespace
{
    /** \brief The clearance CSV \e csv of a single body's path of \e states states: the dense path (more states),
        from start to goal (fraction 0 to 1), every state FCL's free state at its clearance (about 60 checked). */
    template <typename Model>
    void expectCsvIsFcls(const std::string &csv, const Model &fw, const Model &fr, std::size_t states)
    {
        std::ifstream in(csv);
        std::string line;
        std::getline(in, line);
        EXPECT_EQ(line, "index,arc_length,fraction,x,y,z,qx,qy,qz,qw,clearance,in_collision");
        std::vector<std::vector<double>> rows;
        while (std::getline(in, line))
        {
            std::vector<double> row;
            std::stringstream fields(line);
            for (std::string field; std::getline(fields, field, ',');)
                row.push_back(std::stod(field));
            ASSERT_EQ(row.size(), 12u) << line;
            rows.push_back(row);
        }
        fs::remove(csv);
        ASSERT_GT(rows.size(), states);
        EXPECT_EQ(rows.front()[2], 0.0);
        EXPECT_DOUBLE_EQ(rows.back()[2], 1.0);
        for (std::size_t i = 0; i < rows.size(); i += 1 + rows.size() / 60)
        {
            const auto &row = rows[i];
            Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
            P.linear() = Eigen::Quaterniond(row[9], row[6], row[7], row[8]).normalized().toRotationMatrix();
            P.translation() = Eigen::Vector3d(row[3], row[4], row[5]);
            EXPECT_EQ(row[11], 0.0) << "dense state " << i;
            const double exact = test::fclDistance(fw, fr, P);
            EXPECT_NEAR(row[10], exact, 1e-6 * (1 + exact)) << "dense state " << i;
        }
    }
}  // namespace

TEST(PlanCli, PlansAPathWhoseEveryStateFclCallsFree)
{
    const std::string cfg = PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg";
    const std::string out = (fs::temp_directory_path() / ("meshgap_plan_" + std::to_string(::getpid()) + ".path")).string();
    const std::string csv = out + ".csv", summary = out + ".txt";
    const PlanRun r = test::runPlan("--cfg " + cfg + " --planner rrtconnect --time 120 --seed 3 --out " + out +
                                    " --clearance-csv " + csv + " --summary " + summary);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("exact solution  yes"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("dense path free yes"), std::string::npos) << r.out;
    std::ifstream summaryIn(summary);
    std::stringstream summaryText;
    summaryText << summaryIn.rdbuf();
    EXPECT_NE(r.out.find(summaryText.str()), std::string::npos) << "the summary file is what was printed";
    fs::remove(summary);
    const ProblemConfig p = readProblemConfig(cfg);
    const auto fw = test::fclModel(loadMesh(p.world)), fr = test::fclModel(loadRobotMesh(p.robot));
    const std::vector<Eigen::Isometry3d> path = readPoses(out);
    ASSERT_GE(path.size(), 2u);
    EXPECT_TRUE(path.front().isApprox(p.start, 1e-9));
    EXPECT_TRUE(path.back().isApprox(*p.goal, 1e-9));
    for (std::size_t i = 0; i < path.size(); ++i)
        EXPECT_FALSE(test::fclCollide(fw, fr, path[i])) << "state " << i;
    fs::remove(out);

    // The clearance CSV: the dense path, from start to goal, every state free by FCL and its clearance FCL's.
    expectCsvIsFcls(csv, fw, fr, path.size());
}

// The same problem given as a robot of one body (robot.1 = the same mesh, start.1.*, goal.1.*) takes the robot
// runner: its clearance CSV has the single body's columns, and FCL's clearance at every state it checks.
TEST(PlanCli, AOneBodyRobotWritesTheSingleBodyClearanceCsv)
{
    const std::string cfg = PLAN_CLI_MAPS + "/hand_bowl/hand_bowl.cfg";
    const ProblemConfig p = readProblemConfig(cfg);
    const fs::path dir = fs::temp_directory_path() / ("meshgap_plan_one_body_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    {
        std::ifstream in(cfg);
        std::ofstream out(dir / "one_body.cfg");
        for (std::string line; std::getline(in, line);)
        {
            if (line.rfind("robot =", 0) == 0)
                line = "robot.1 = " + p.robot;
            else if (line.rfind("world =", 0) == 0)
                line = "world = " + p.world;
            else if (line.rfind("start.", 0) == 0 || line.rfind("goal.", 0) == 0)
                line.insert(line.find('.') + 1, "1.");
            out << line << "\n";
        }
    }
    const std::string out = (dir / "p.path").string(), csv = (dir / "p.csv").string();
    const PlanRun r = test::runPlan("--cfg " + (dir / "one_body.cfg").string() + " --time 120 --seed 3 --out " + out +
                                    " --clearance-csv " + csv);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("(robot problem)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("clearance CSV   " + csv), std::string::npos) << r.out;
    const auto fw = test::fclModel(loadMesh(p.world)), fr = test::fclModel(loadRobotMesh(p.robot));
    const std::vector<Eigen::Isometry3d> path = readPoses(out);
    ASSERT_GE(path.size(), 2u);
    EXPECT_TRUE(path.front().isApprox(p.start, 1e-9));
    EXPECT_TRUE(path.back().isApprox(*p.goal, 1e-9));
    expectCsvIsFcls(csv, fw, fr, path.size());
    fs::remove_all(dir);
}
#endif
