// The hostile-input corpus (tests/resources/hostile): robot problems whose URDF urdfdom reads with a logged error and
// drops a part of (a typo in an origin, a box of two numbers, an unknown shape, a mesh without a file, NaN), robots
// without geometry, numbers beyond what double geometry answers, folders and devices named as files; and the hostile
// command lines (a pose at 1e300, states outside the joint limits, a FIFO as --cfg, an infinite time limit, a negative
// count). Each must end in one line "error: ..." naming the file (and line) and the problem, exit status 1, nothing on
// stdout, no signal, no hang. The valid input the same readers refused (the README's robot problem as written, a fixed
// robot, an SRDF naming the payload) must be read, and the tools must say when their output contradicts their input.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "CliRun.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotBatch.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/ProblemConfig.h"

using meshgap::test::CliRun;
namespace fs = std::filesystem;

namespace
{
    const std::string HOSTILE = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/hostile";
    const std::string HOSTILE_CORPUS_MAPS = std::string(MESHGAP_SOURCE_DIR) + "/maps";

    /** \brief Every problem file of the corpus, and what its one error line must say beyond its own name. */
    const std::map<std::string, std::vector<std::string>> HOSTILE_PROBLEM = {
        {"bare.cfg", {"bare.urdf", "robot 'bare' has no collision geometry"}},
        {"origin_typo.cfg",
         {"origin_typo.urdf:8", "link 'b'", "<origin xyz=\"0.25 0 O\">", "'O', not a finite number"}},
        {"box_two_numbers.cfg", {"box_two_numbers.urdf:8", "link 'b'", "size needs 3 numbers, found 2"}},
        {"capsule.cfg", {"capsule.urdf:8", "<capsule", "unknown shape"}},
        {"mesh_no_filename.cfg", {"mesh_no_filename.urdf:8", "<mesh>", "without a filename"}},
        {"mesh_is_folder.cfg", {"mesh_is_folder.urdf", "link 'b'", "is a folder, not a file"}},
        {"nan_origin.cfg", {"nan_origin.urdf:8", "<origin", "'nan', not a finite number"}},
        {"nan_size.cfg", {"nan_size.urdf:8", "<box", "'nan', not a finite number"}},
        {"nan_scale.cfg", {"nan_scale.urdf:8", "scale has 'nan'"}},
        {"huge_box.cfg", {"huge_box.urdf:8", "<box size=\"1e300", "beyond 1e12"}},
        {"huge_joint_origin.cfg", {"huge_joint_origin.urdf:11", "joint 'j'", "beyond 1e12"}},
        {"huge_start.cfg", {"huge_start.cfg:5", "start.x", "beyond 1e12"}},
        {"folder_mesh.cfg", {"folder_mesh.cfg:3", "is a folder"}},
        {"devnull_mesh.cfg", {"devnull_mesh.cfg:4", "/dev/null", "is not a regular file"}},
        {"robot_devnull_world.cfg", {"robot_devnull_world.cfg:4", "/dev/null", "is not a regular file"}},
        {"robot_folder_payload.cfg", {"robot_folder_payload.cfg:5", "attach", "is a folder"}},
    };

    /** \brief Files of the corpus that are no entry: what the entries use, and the valid problem the hostile states
        and paths are given to. */
    const std::set<std::string> SUPPORT = {"far_block.obj", "valid_arm.cfg", "valid_arm.urdf",
                                           "joint_outside_limits.path", "colliding_arm.cfg", "valid_arm.path",
                                           "huge_time_limit.cfg"};

    /** \brief The command lines that read a problem file \e cfg. */
    std::vector<std::pair<std::string, std::string>> hostileCommandsFor(const std::string &cfg)
    {
        const std::string f = "'" + cfg + "'";
        return {{"meshgap_distance", "--cfg " + f},
                {"meshgap_plan", "--cfg " + f + " --time 1"},
                {"meshgap_benchmark", "--cfg " + f + " --planner rrtconnect --runs 1 --time 1 --out " +
                                          (fs::temp_directory_path() / "meshgap_hostile_corpus_logs").string()}};
    }

    void expectOneClearHostileError(const std::string &what, const CliRun &r, const std::vector<std::string> &mentions)
    {
        ASSERT_NE(r.status, -1) << what << ": crashed (a signal)\n" << r.err;
        ASSERT_NE(r.status, 124) << what << ": did not finish in time";
        EXPECT_EQ(r.status, 1) << what << "\n" << r.err;
        EXPECT_EQ(meshgap::test::countLines(r.err, "error: "), 1) << what << "\n" << r.err;
        for (const std::string &m : mentions)
            EXPECT_NE(r.err.find(m), std::string::npos) << what << ": the error does not say '" << m << "'\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << what << ": wrote results\n" << r.out;
    }

    /** \brief A folder of its own per test process, removed at the end. */
    class HostileCli : public meshgap::test::FolderTest
    {
    protected:
        HostileCli() : FolderTest("meshgap_hostile_") {}

    };
}  // namespace

TEST(HostileInputCorpus, EveryFileIsAnEntryOrSupport)
{
    std::size_t entries = 0;
    for (const auto &entry : fs::directory_iterator(HOSTILE))
    {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() == ".urdf" && !SUPPORT.count(name))
        {
            // A hostile URDF is read through the problem of the same stem.
            EXPECT_TRUE(HOSTILE_PROBLEM.count(entry.path().stem().string() + ".cfg")) << name << " has no problem file";
            continue;
        }
        if (SUPPORT.count(name))
            continue;
        ++entries;
        EXPECT_TRUE(HOSTILE_PROBLEM.count(name)) << name << " is in the corpus but not in this test's table";
    }
    EXPECT_EQ(entries, HOSTILE_PROBLEM.size()) << "a file named in this test's table is missing from " << HOSTILE;
}

TEST(HostileInputCorpus, EveryToolGivesOneErrorNamingFileAndProblem)
{
    for (const auto &[name, mentions] : HOSTILE_PROBLEM)
    {
        const fs::path cfg = fs::path(HOSTILE) / name;
        if (!fs::exists(cfg))
            continue;  // reported by the test above
        std::vector<std::string> all = mentions;
        all.push_back(name);
        for (const auto &[executable, args] : hostileCommandsFor(cfg.string()))
            expectOneClearHostileError(executable + " " + args, meshgap::test::runExecutable(executable, args, 120),
                                       all);
    }
}

TEST(HostileInputCorpus, HostileCommandLinesGetOneErrorEach)
{
    const std::string arm = "--cfg '" + HOSTILE + "/valid_arm.cfg'";
    const std::string cube = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/cube.obj";
    const std::string logs = (fs::temp_directory_path() / "meshgap_hostile_corpus_logs").string();
    const std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> lines = {
        // States outside the joint limits, as start.joints refuses them.
        {"meshgap_distance", arm + " --pose 1.5", {"--pose", "joint 'j' = 1.5 is outside its limits [-1, 1]"}},
        {"meshgap_distance", arm + " --poses '" + HOSTILE + "/joint_outside_limits.path'",
         {"joint_outside_limits.path:4", "joint 'j' = 1.5 is outside its limits"}},
        {"meshgap_distance", arm + " --pose 1e300", {"--pose", "state number 0 (", ") = 1e+300", "beyond 1e12"}},
        // Folders and devices as meshes say what they are.
        {"meshgap_distance", "'" + HOSTILE + "' '" + cube + "'", {HOSTILE, "is a folder, not a file"}},
        {"meshgap_distance", "/dev/null '" + cube + "'", {"/dev/null", "is not a regular file"}},
        {"meshgap_distance", "--cfg '" + HOSTILE + "'", {HOSTILE, "is a folder, not a file"}},
        // Time limits that are no limit.
        {"meshgap_benchmark", arm + " --planner rrtconnect --runs 1 --time inf --out " + logs,
         {"--time", "positive and finite"}},
        {"meshgap_benchmark", arm + " --planner rrtconnect --runs 1 --time 1e30 --out " + logs,
         {"--time", "at most 1e6 seconds"}},
        {"meshgap_plan", arm + " --time 1e30", {"--time", "at most 1e6 seconds"}},
        {"meshgap_benchmark", "--cfg '" + HOSTILE + "/huge_time_limit.cfg' --planner rrtconnect --out " + logs,
         {"huge_time_limit.cfg", "[benchmark] time_limit", "at most 1e6 seconds"}},
        // Negative counts, which the option parser would wrap round to some 4 billion, and sizes out of range.
        {"meshgap_plan", arm + " --time 1 --seed -3", {"--seed", "'-3' is not a non-negative integer"}},
        {"meshgap_plan", arm + " --time 1 --dense -1", {"--dense", "'-1' is not a non-negative integer"}},
        {"meshgap_plan", arm + " --time 1 --optimize clearance --optimize-rounds -2",
         {"--optimize-rounds", "'-2' is not a non-negative integer"}},
        {"meshgap_benchmark", arm + " --planner rrtconnect --runs -1 --time 1 --out " + logs,
         {"--runs", "'-1' is not a non-negative integer"}},
        {"meshgap_benchmark", arm + " --planner rrtconnect --runs 1 --seed -1 --time 1 --out " + logs,
         {"--seed", "'-1' is not a non-negative integer"}},
        {"meshgap_report", arm + " --dense -1 --path '" + HOSTILE + "/valid_arm.path' --out " + logs + ".html",
         {"--dense", "'-1' is not a non-negative integer"}},
        {"meshgap_distance", "--seed -2 -a comb-GA-wl '" + cube + "' '" + cube + "'",
         {"--seed", "'-2' is not a non-negative integer"}},
        {"meshgap_distance", "--memory-budget -5 -a comb-GA-wl '" + cube + "' '" + cube + "'",
         {"--memory-budget", "-5 is not a size in MiB"}},
        {"meshgap_distance", "--memory-budget nan -a comb-GA-wl '" + cube + "' '" + cube + "'",
         {"--memory-budget", "nan is not a size in MiB"}},
    };
    for (const auto &[executable, args, mentions] : lines)
        expectOneClearHostileError(executable + " " + args, meshgap::test::runExecutable(executable, args, 120),
                                   mentions);
}

TEST(HostileInputCorpus, PoseBeyondDoubleGeometryIsRefusedNotAnsweredWrong)
{
    const std::string cfg = HOSTILE_CORPUS_MAPS + "/hand_bowl/hand_bowl.cfg";
    const std::string args = "--cfg '" + cfg + "' --pose '1e300 0 0 0 0 0 1'";
    expectOneClearHostileError("meshgap_distance " + args, meshgap::test::runExecutable("meshgap_distance", args, 120),
                               {"--pose", "state number 0 (robot.x) = 1e+300", "beyond 1e12"});
}

TEST_F(HostileCli, FifoAsProblemFileIsRefusedWithoutBlocking)
{
    const std::string fifo = (dir_ / "problem.cfg").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const char *executable : {"meshgap_distance", "meshgap_plan", "meshgap_report"})
    {
        const std::string args = std::string("--cfg '") + fifo + "'" +
                                 (std::string(executable) == "meshgap_report" ? " --path x --out y.html" : "");
        expectOneClearHostileError(std::string(executable) + " " + args,
                                   meshgap::test::runExecutable(executable, args, 20), {fifo, "is not a regular file"});
    }
}

// The README's robot problem, exactly as the README writes it (read from README.md, so the two cannot drift), with
// the files it names: the inline '#' comments are comments, robot.package_path may name folders that do not exist,
// and the SRDF may name the attached payload.
TEST_F(HostileCli, ReadmeRobotProblemRunsAsWritten)
{
    std::ifstream readme(std::string(MESHGAP_SOURCE_DIR) + "/README.md");
    std::stringstream text;
    text << readme.rdbuf();
    const std::string all = text.str();
    const std::size_t section = all.find("## Robot problems");
    ASSERT_NE(section, std::string::npos) << "README.md has no section '## Robot problems'";
    const std::size_t begin = all.find("```ini\n", section);
    ASSERT_NE(begin, std::string::npos);
    const std::size_t end = all.find("```", begin + 7);
    const std::string example = all.substr(begin + 7, end - begin - 7);
    ASSERT_NE(example.find("robot.urdf = arm4.urdf "), std::string::npos) << example;
    ASSERT_NE(example.find("# "), std::string::npos) << "the example has no inline comment any more:\n" << example;

    const fs::path arm = fs::path(HOSTILE_CORPUS_MAPS) / "arm_fixture";
    fs::copy_file(arm / "arm4.urdf", dir_ / "arm4.urdf");
    fs::copy_file(arm / "arm_fixture_world.obj", dir_ / "fixture.obj");
    fs::copy_file(arm / "arm_fixture_payload.obj", dir_ / "payload.obj");
    file("arm4.srdf", "<robot name=\"arm4\">\n"
                      "  <disable_collisions link1=\"payload\" link2=\"fore\" reason=\"Never\"/>\n"
                      "</robot>\n");
    const std::string cfg = file("readme.cfg", example);

    const CliRun d = meshgap::test::runExecutable("meshgap_distance", "--cfg '" + cfg + "'", 120);
    ASSERT_EQ(d.status, 0) << d.err;
    EXPECT_NE(d.out.find("link payload"), std::string::npos) << d.out;
    const CliRun p = meshgap::test::runExecutable("meshgap_plan", "--cfg '" + cfg + "' --time 2 --seed 1", 120);
    EXPECT_TRUE(p.status == 0 || p.status == 2) << p.err;  // 2: no exact solution in the time; never an error
    EXPECT_EQ(meshgap::test::countLines(p.err, "error: "), 0) << p.err;

    // The SRDF's pair is allowed: the payload is never checked against the forearm.
    const meshgap::RobotProblem problem = meshgap::readRobotProblem(cfg);
    const meshgap::RobotModel &robot = *problem.robot;
    EXPECT_TRUE(robot.isAllowed(robot.findLink("payload"), robot.findLink("fore")));
    EXPECT_FALSE(robot.isAllowed(robot.findLink("payload"), robot.findLink("upper")));
}

// A robot without movable joints is a valid robot: its clearance can be asked; planning says there is nothing to
// plan.
TEST_F(HostileCli, FixedRobotIsReadAndPlanningSaysWhyNot)
{
    file("fixed.urdf", "<robot name=\"fixed\">\n"
                       "  <link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link>\n"
                       "  <link name=\"b\"><collision><geometry><sphere radius=\"0.5\"/></geometry></collision>"
                       "</link>\n"
                       "  <joint name=\"j\" type=\"fixed\"><origin xyz=\"0 0 2\"/><parent link=\"a\"/>"
                       "<child link=\"b\"/></joint>\n</robot>\n");
    fs::copy_file(fs::path(HOSTILE) / "far_block.obj", dir_ / "far_block.obj");
    const std::string cfg = file("fixed.cfg", "[problem]\nrobot.urdf = fixed.urdf\nworld = far_block.obj\n");
    const CliRun d = meshgap::test::runExecutable("meshgap_distance", "--cfg '" + cfg + "'", 120);
    ASSERT_EQ(d.status, 0) << d.err;
    // The box [-0.5, 0.5]^3 and the block's face x = 5: 4.5 apart; the sphere about (0, 0, 2) is further.
    EXPECT_NE(d.out.find("clearance 4.5 "), std::string::npos) << d.out;
    expectOneClearHostileError("meshgap_plan --cfg fixed.cfg",
                               meshgap::test::runExecutable("meshgap_plan", "--cfg '" + cfg + "' --time 1", 120),
                               {"fixed.cfg", "no movable joint", "nothing to plan"});
}

// meshgap_report on a path that collides with its world: the report is written, but the tool says so (a warning
// line and exit status 2), as meshgap_plan does for a path that is not an exact solution.
TEST_F(HostileCli, ReportOfACollidingPathSaysSo)
{
    const std::string out = (dir_ / "report.html").string();
    const CliRun r = meshgap::test::runExecutable(
        "meshgap_report", "--cfg '" + HOSTILE + "/colliding_arm.cfg' --path '" + HOSTILE + "/valid_arm.path' --out '" +
                              out + "'",
        120);
    ASSERT_NE(r.status, -1) << r.err;
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(meshgap::test::countLines(r.err, "warning: "), 1) << r.err;
    EXPECT_NE(r.err.find("valid_arm.path: the path collides"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out));
    // The same path in a world it does not touch: exit 0, no warning.
    const CliRun free = meshgap::test::runExecutable(
        "meshgap_report", "--cfg '" + HOSTILE + "/valid_arm.cfg' --path '" + HOSTILE + "/valid_arm.path' --out '" +
                              out + "'",
        120);
    EXPECT_EQ(free.status, 0) << free.err;
    EXPECT_EQ(free.err.find("warning"), std::string::npos) << free.err;
}

// -q means quiet: no log and no warnings (a mesh that is not a closed surface warns without it).
TEST(HostileInputCorpus, QuietPrintsNoWarnings)
{
    const std::string open = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/odd/single_triangle.obj";
    const std::string cube = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/cube.obj";
    const std::string args = "'" + cube + "' '" + open + "' --pose '3 0 0 0 0 0 1'";
    const CliRun loud = meshgap::test::runExecutable("meshgap_distance", args, 120);
    ASSERT_EQ(loud.status, 0) << loud.err;
    ASSERT_NE(loud.err.find("not a closed surface"), std::string::npos) << "the warning this test silences\n"
                                                                        << loud.err;
    const CliRun quiet = meshgap::test::runExecutable("meshgap_distance", args + " -q", 120);
    ASSERT_EQ(quiet.status, 0) << quiet.err;
    EXPECT_TRUE(quiet.err.empty()) << quiet.err;
    EXPECT_NE(quiet.out.find("distance       2 "), std::string::npos) << quiet.out;  // the same answer
}

// The exact solver searches surfaces, not nodes: its answer has no node pair, and JSON says null rather than [0, 0].
TEST(HostileInputCorpus, ExactSolverReportsNoNodePair)
{
    const std::string cube = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/cube.obj";
    const std::string args = "'" + cube + "' '" + cube + "' --pose '3 0 0 0 0 0 1' --algorithm exact -q";
    const CliRun json = meshgap::test::runExecutable("meshgap_distance", args + " --json", 120);
    ASSERT_EQ(json.status, 0) << json.err;
    EXPECT_NE(json.out.find("\"nodes\": null"), std::string::npos) << json.out;
    EXPECT_NE(json.out.find("\"distance\": 2,"), std::string::npos) << json.out;
    const CliRun text = meshgap::test::runExecutable("meshgap_distance", args, 120);
    EXPECT_NE(text.out.find("node pair      none"), std::string::npos) << text.out;
    // Enumeration has one.
    const CliRun nodes = meshgap::test::runExecutable(
        "meshgap_distance", "'" + cube + "' '" + cube + "' --pose '3 0 0 0 0 0 1' --json -q", 120);
    EXPECT_TRUE(std::regex_search(nodes.out, std::regex("\"nodes\": \\[[0-9]+, [0-9]+\\]"))) << nodes.out;
}

// The library behind every state query (RobotScene's, so Python's RobotScene.distance, link_poses and in_collision
// too) refuses a state outside the joint limits as start.joints does, naming the joint; a state at a limit, give or
// take an interpolation's roundoff, is taken.
TEST(HostileInputCorpus, QueriesRefuseStatesOutsideTheJointLimits)
{
    const meshgap::RobotProblem problem = meshgap::readRobotProblem(HOSTILE + "/valid_arm.cfg");
    const meshgap::RobotScene scene(problem.robot, problem.obstacles);
    auto errorAt = [&](double q)
    {
        try
        {
            meshgap::RobotResult r;
            scene.distance(std::vector<double>{q}, meshgap::RobotRequest(), r);
        }
        catch (const meshgap::Exception &e)
        {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(errorAt(1.5).find("joint 'j' = 1.5 is outside its limits [-1, 1]"), std::string::npos) << errorAt(1.5);
    EXPECT_NE(errorAt(-1.001).find("outside its limits"), std::string::npos);
    EXPECT_EQ(errorAt(1.0 + 1e-15), "");
    EXPECT_EQ(errorAt(-1.0), "");
    EXPECT_THROW(problem.robot->linkPoses(std::vector<double>{2.0}), meshgap::Exception);
}

// A robot without geometry is refused where it is read (and where a scene is made of it), never a crash later.
TEST(HostileInputCorpus, RobotWithoutGeometryIsRefusedByTheLibrary)
{
    try
    {
        meshgap::readRobotProblem(HOSTILE + "/bare.cfg");
        ADD_FAILURE() << "bare.cfg was read";
    }
    catch (const meshgap::Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("no collision geometry"), std::string::npos) << e.what();
    }
}

// A batch names the row of the state it refuses (its row in the whole batch, whatever the blocks and threads).
TEST(HostileInputCorpus, BatchNamesTheRowOfAStateOutsideTheLimits)
{
    const meshgap::RobotProblem problem = meshgap::readRobotProblem(HOSTILE + "/valid_arm.cfg");
    const meshgap::RobotScene scene(problem.robot, problem.obstacles);
    std::vector<double> states(1000, 0.25);
    states[700] = 3.0;
    std::vector<meshgap::RobotResult> results;
    std::vector<char> collides;
    for (unsigned threads : {1u, 2u})
    {
        try
        {
            meshgap::robotDistanceBatch(scene, states.data(), states.size(), meshgap::RobotRequest(), threads,
                                        results);
            ADD_FAILURE() << "a state outside the limits was answered";
        }
        catch (const meshgap::Exception &e)
        {
            EXPECT_EQ(std::string(e.what()).rfind("states[700]: ", 0), 0u) << e.what();
            EXPECT_NE(std::string(e.what()).find("joint 'j' = 3 is outside its limits"), std::string::npos);
        }
        EXPECT_THROW(meshgap::robotInCollisionBatch(scene, states.data(), states.size(), true, threads, collides),
                     meshgap::Exception);
    }
}

// Huge values (a 1 MB cfg value, key or line, a 1 MB YAML scalar or URDF attribute, a mesh path of 5000 characters)
// are not echoed whole: each error stays short and still names the file (and line) and the problem.
TEST_F(HostileCli, HugeValuesAreNotEchoedWhole)
{
    constexpr std::size_t BOUND = 1000;
    const std::string mb(1 << 20, '7'), longPath = (dir_ / (std::string(5000, 'm') + ".obj")).string();
    const std::string cube = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/cube.obj";
    const std::string arm = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/problems/arm2.urdf";
    const std::string single = "[problem]\nrobot = " + cube + "\nworld = " + cube + "\nstart.y = 0\nstart.z = 0\n";
    fs::copy_file(fs::path(HOSTILE) / "valid_arm.urdf", dir_ / "valid_arm.urdf");
    fs::copy_file(fs::path(HOSTILE) / "far_block.obj", dir_ / "far_block.obj");
    const std::string robot = "[problem]\nrobot.urdf = valid_arm.urdf\nworld = far_block.obj\n";  // + start.joints
    const std::string urdf = HOSTILE + "/valid_arm.urdf";
    auto messageOf = [](const std::function<void()> &read)
    {
        try
        {
            read();
        }
        catch (const meshgap::Exception &e)
        {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    auto yaml = [&](const std::string &name, const std::string &text)
    {
        return messageOf(
            [&]
            {
                meshgap::MoveItFiles files;
                files.urdf = arm;
                files.scene = file(name, text);
                meshgap::readMoveItProblem(files);
            });
    };
    auto urdfWith = [&](const std::string &name, const std::string &from, const std::string &to)
    {
        std::ifstream in(urdf);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        text.replace(text.find(from), from.size(), to);
        file(name, text);
        return messageOf(
            [&]
            {
                meshgap::readRobotProblem(file(
                    "urdf.cfg", "[problem]\nrobot.urdf = " + name + "\nworld = far_block.obj\nstart.joints = 0\n"));
            });
    };
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {messageOf([&] { meshgap::readProblemConfig(file("value.cfg", single + "start.x = " + mb + "x\n")); }),
         {"value.cfg:6", "start.x", "is not a finite number", "(1048577 characters)"}},
        {messageOf([&] { meshgap::readProblemConfig(file("key.cfg", single + mb + " = 1\n")); }),
         {"key.cfg:6", "unknown key", "in [problem]"}},
        {messageOf([&] { meshgap::readProblemConfig(file("line.cfg", single + mb + "\n")); }),
         {"line.cfg:6", "expected 'key = value'"}},
        {messageOf([&] { meshgap::readProblemConfig(file("section.cfg", "[" + mb + "]\n")); }),
         {"section.cfg:1", "unknown section"}},
        {messageOf([&] { meshgap::readRobotProblem(file("joints.cfg", robot + "start.joints = " + mb + "x\n")); }),
         {"joints.cfg:4", "start.joints", "not a finite number"}},
        {messageOf(
             [&] { meshgap::readRobotProblem(file("attach.cfg", robot + "start.joints = 0\nattach = " + mb + "\n")); }),
         {"attach.cfg:5", "attach", "found"}},
        {messageOf(
             [&]
             {
                 meshgap::readProblemConfig(file("path.cfg", "[problem]\nrobot = " + longPath + "\nworld = " + cube +
                                                                 "\nstart.x = 0\nstart.y = 0\nstart.z = 0\n"));
             }),
         {"path.cfg:2", "robot mesh", "mmm.obj", "cannot be read"}},
        {messageOf([&] { meshgap::loadMesh(longPath); }), {"mmm.obj", "(5"}},
        {yaml("type.yaml", "world:\n  collision_objects:\n    - id: a\n      primitives:\n        - type: " + mb +
                               "x\n          dimensions: [1, 1, 1]\n      primitive_poses: [{}]\n"),
         {"type.yaml:5", "primitives[0].type", "unknown primitive type", "(1048577 characters)"}},
        {yaml("number.yaml", "robot_state:\n  joint_state:\n    name: [yaw]\n    position: [" + mb + "x]\n"),
         {"number.yaml:4", "position[0]", "is not a number"}},
        {yaml("joint.yaml", "robot_state:\n  joint_state:\n    name: [" + mb + "]\n    position: [0]\n"),
         {"joint.yaml:4", "has no joint"}},
        {yaml("id.yaml", "world:\n  collision_objects:\n    - id: " + mb +
                             "\n      primitives: [{type: box}]\n"
                             "      primitive_poses: [{}]\n"),
         {"id.yaml:4", "dimensions", "0 numbers; a box takes 3"}},
        {urdfWith("attribute.urdf", "xyz=\"0.25 0 0\"", "xyz=\"0.25 0 " + mb + "x\""),
         {"attribute.urdf:8", "link 'b'", "not a finite number"}},
        {urdfWith("name.urdf", "<child link=\"b\"/>", "<child link=\"" + mb + "\"/>"), {"name.urdf", "characters)"}},
    };
    for (const auto &[message, mentions] : cases)
    {
        SCOPED_TRACE(message.substr(0, 2 * BOUND));
        EXPECT_LT(message.size(), BOUND);
        for (const std::string &m : mentions)
            EXPECT_NE(message.find(m), std::string::npos) << "the error does not say '" << m << "'";
    }

    // The tools print the same short line.
    const CliRun r = meshgap::test::runExecutable("meshgap_distance", "'" + longPath + "' '" + cube + "'", 120);
    expectOneClearHostileError("meshgap_distance LONG_PATH cube.obj", r, {"mmm.obj"});
    EXPECT_LT(r.err.size(), BOUND) << r.err.substr(0, 2 * BOUND);
}
