// meshgap_plan and meshgap_distance on robot problems (a URDF arm with its payload, several bodies): the path file
// holds the problem's own state numbers, the distance tool's per-state answer matches distances worked out by hand,
// and each bad input gets one clear error and a non-zero exit.

#include <gtest/gtest.h>

#include <algorithm>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>

#include "CliRun.h"
#include "TestScale.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/robot/RobotScene.h"
#include "support/RobotDistance.h"

namespace fs = std::filesystem;

namespace
{
    using meshgap::test::CliRun;

    const std::string ROBOT_RES = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot";
    const std::string CUBE = ROBOT_RES + "/meshgap_test_description/meshes/cube.obj";
    const std::string ROBOT_CLI_MAPS = std::string(MESHGAP_SOURCE_DIR) + "/maps";

    /** \brief A folder of its own per test process. */
    class RobotCli : public meshgap::test::FolderTest
    {
    protected:
        RobotCli() : FolderTest("meshgap_robot_cli_") {}

        /** \brief Two unit cubes as bodies (centred by OMPL.app's rule: [-0.5, 0.5]^3 about their state), the world
            one unit cube at x in [2, 3], y and z in [0, 1]. */
        std::string twoCubes()
        {
            return file("two.cfg", "[problem]\nrobot.1 = " + CUBE + "\nrobot.2 = " + CUBE + "\nworld = " +
                                       file("world.obj", "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\nv 2 0 1\nv 3 0 1\n"
                                                         "v 3 1 1\nv 2 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\n"
                                                         "f 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n") +
                                       "\nstart.1.x = 0\nstart.1.y = 0\nstart.1.z = 0.5\nstart.2.x = 0\n"
                                       "start.2.y = 1.8\nstart.2.z = 0.5\n");
        }

    };

    /** \brief The number after \e key on the line of \e text that starts with \e key. */
    double valueAfterOnItsLine(const std::string &text, const std::string &key)
    {
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line))
        {
            const auto at = line.find(key);
            if (at != std::string::npos)
                return std::stod(line.substr(at + key.size()));
        }
        return NAN;
    }

    std::vector<std::vector<double>> readPathRows(const std::string &path)
    {
        std::ifstream in(path);
        std::vector<std::vector<double>> rows;
        std::string line;
        while (std::getline(in, line))
        {
            std::istringstream fields(line);
            std::vector<double> row;
            double x;
            while (fields >> x)
                row.push_back(x);
            rows.push_back(row);
        }
        return rows;
    }

    /** \brief The lines of \e text split at commas (no quoted fields expected). */
    std::vector<std::vector<std::string>> csvTable(const std::string &text)
    {
        std::vector<std::vector<std::string>> table;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line))
        {
            std::vector<std::string> fields(1);
            for (char c : line)
                if (c == ',')
                    fields.emplace_back();
                else
                    fields.back() += c;
            table.push_back(fields);
        }
        return table;
    }
}  // namespace

TEST_F(RobotCli, DistanceGivesTheWholeRobotsClearanceItsPairAndEveryLink)
{
    // Body 1 spans x in [-0.5, 0.5], 1.5 from the world cube; body 2 (y in [1.3, 2.3]) is 0.8 from body 1 and
    // sqrt(1.5^2 + 0.3^2) from the world cube: the minimum is the pair of bodies, 0.8, and each body's clearance too.
    const CliRun r = meshgap::test::runExecutable("meshgap_distance", "--cfg " + twoCubes() + " --exact");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NEAR(valueAfterOnItsLine(r.out, "state 1: clearance"), 0.8, 1e-9) << r.out;
    EXPECT_NE(r.out.find("closest pair   links 'robot.1' and 'robot.2'"), std::string::npos) << r.out;
    EXPECT_NEAR(valueAfterOnItsLine(r.out, "link robot.1"), 0.8, 1e-9) << r.out;
    EXPECT_NEAR(valueAfterOnItsLine(r.out, "link robot.2"), 0.8, 1e-9) << r.out;
    // Body 2 moved away (y = 5): body 1's 1.5 to the world cube is the minimum.
    const CliRun far = meshgap::test::runExecutable(
        "meshgap_distance", "--cfg " + twoCubes() + " --pose '0 0 0.5 0 0 0 1 0 5 0.5 0 0 0 1'");
    ASSERT_EQ(far.status, 0) << far.err;
    EXPECT_NEAR(valueAfterOnItsLine(far.out, "state 1: clearance"), 1.5, 1e-9) << far.out;
    EXPECT_NE(far.out.find("closest pair   link 'robot.1' and obstacle 0"), std::string::npos) << far.out;
    EXPECT_NEAR(valueAfterOnItsLine(far.out, "link robot.2"), std::hypot(1.5, 3.5), 1e-9) << far.out;
}

TEST_F(RobotCli, DistancePosesWritesCsvRowsThatAreTheLibrarysExactAnswers)
{
    // The arm with its payload (links against the fixture, and self pairs) at states from start to goal and past
    // them: some free, some in collision.
    const std::string cfg = ROBOT_CLI_MAPS + "/arm_fixture/arm_fixture.cfg";
    const meshgap::RobotProblem problem = meshgap::readRobotProblem(cfg);
    const meshgap::RobotScene scene(problem.robot, problem.obstacles);
    std::vector<std::vector<double>> states;
    std::ostringstream text;
    text.precision(17);
    for (int k = -4; k <= 14; ++k)
    {
        std::vector<double> q = problem.start;
        const auto &arm = static_cast<const meshgap::UrdfRobot &>(*problem.robot);
        for (std::size_t j = 0; j < q.size(); ++j)
        {
            q[j] += (k / 10.0) * ((*problem.goal)[j] - problem.start[j]);
            q[j] = std::clamp(q[j], arm.stateLower(j), arm.stateUpper(j));  // past start or goal, within the limits
        }
        states.push_back(q);
        for (std::size_t j = 0; j < q.size(); ++j)
            text << (j ? " " : "") << q[j];
        text << "\n";
    }
    const CliRun d = meshgap::test::runExecutable("meshgap_distance", "--cfg " + cfg + " --exact --poses " +
                                                                         file("arm.path", text.str()));
    ASSERT_EQ(d.status, 0) << d.err;
    const auto table = csvTable(d.out);
    ASSERT_EQ(table.size(), states.size() + 1) << d.out;
    std::string header = meshgap::cli::ROBOT_CSV_COLUMNS;
    for (const meshgap::RobotLink &link : scene.links())
        header += ",clearance_" + link.name;
    EXPECT_EQ(d.out.substr(0, d.out.find('\n')), header);
    const std::size_t columns = 13 + scene.links().size();
    int colliding = 0;
    for (std::size_t i = 0; i < states.size(); ++i)
    {
        const std::vector<std::string> &row = table[i + 1];
        ASSERT_EQ(row.size(), columns) << "row " << i;
        // The oracle: a fresh (cold) whole-robot query, every pair answered exactly.
        meshgap::RobotRequest request;
        request.everyPair = true;
        meshgap::RobotResult r;
        scene.distance(states[i], request, r);
        double least = INFINITY;
        for (const meshgap::RobotPairAnswer &pair : r.pairs)
        {
            ASSERT_EQ(pair.status, meshgap::RobotPairAnswer::Status::EXACT);
            least = std::min(least, pair.distance);
        }
        EXPECT_EQ(std::stoul(row[0]), i);
        EXPECT_NEAR(std::stod(row[1]), least, 1e-9) << "row " << i;
        EXPECT_EQ(row[2], r.inCollision ? "1" : "0") << "row " << i;
        EXPECT_EQ(row[3], "1") << "row " << i;
        EXPECT_EQ(row[4], scene.links()[r.link].name) << "row " << i;
        EXPECT_EQ(row[5], r.selfPair ? scene.links()[r.other].name : "") << "row " << i;
        EXPECT_EQ(row[6], r.selfPair ? "" : std::to_string(r.other)) << "row " << i;
        const Eigen::Vector3d onA(std::stod(row[7]), std::stod(row[8]), std::stod(row[9]));
        const Eigen::Vector3d onB(std::stod(row[10]), std::stod(row[11]), std::stod(row[12]));
        EXPECT_LT((onA - r.onA).norm(), 1e-9) << "row " << i;
        EXPECT_LT((onB - r.onB).norm(), 1e-9) << "row " << i;
        if (!r.inCollision)
        {
            EXPECT_NEAR((onA - onB).norm(), least, 1e-9) << "row " << i;  // the witnesses attain it
        }
        for (std::size_t l = 0; l < scene.links().size(); ++l)
            EXPECT_NEAR(std::stod(row[13 + l]), r.linkClearance[l], 1e-9) << "row " << i << " link " << l;
        colliding += r.inCollision ? 1 : 0;
    }
    EXPECT_GT(colliding, 0);
    EXPECT_LT(colliding, int(states.size()));
}

TEST_F(RobotCli, PlanWritesThePathInTheProblemsStateNumbers)
{
    const std::string path = (dir_ / "swap.path").string();
    const CliRun r = meshgap::test::runExecutable(
        "meshgap_plan", "--cfg " + ROBOT_CLI_MAPS + "/swap_se2/swap_se2.cfg --seed 3 --time 20 -q --out " + path, 120);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("dense path free yes"), std::string::npos) << r.out;
    // Two bodies moving at once: every motion certified by default (no resolution lets them pass through).
    EXPECT_NE(r.out.find("motion certified"), std::string::npos) << r.out;
    const auto rows = readPathRows(path);
    ASSERT_GE(rows.size(), 2u);
    for (const auto &row : rows)
        ASSERT_EQ(row.size(), 6u);  // x y theta of each body
    // The cfg's start and goal (maps/swap_se2/swap_se2.cfg): the bodies swap (-3.3, -1.2) and (3.3, 1.2).
    const std::vector<double> start = {-3.3, -1.2, 0, 3.3, 1.2, 0}, goal = {3.3, 1.2, 0, -3.3, -1.2, 0};
    for (std::size_t k = 0; k < 6; ++k)
    {
        EXPECT_NEAR(rows.front()[k], start[k], 1e-12) << k;
        EXPECT_NEAR(rows.back()[k], goal[k], 1e-12) << k;
    }
    // meshgap_distance reads the path back: every state free.
    const CliRun d = meshgap::test::runExecutable(
        "meshgap_distance", "--cfg " + ROBOT_CLI_MAPS + "/swap_se2/swap_se2.cfg --exact --poses " + path);
    ASSERT_EQ(d.status, 0) << d.err;
    const auto table = csvTable(d.out);
    ASSERT_EQ(table.size(), rows.size() + 1) << d.out;
    for (std::size_t i = 1; i < table.size(); ++i)
        EXPECT_EQ(table[i][2], "0") << "state " << i - 1 << " in collision:\n" << d.out;
}

TEST_F(RobotCli, PlanWritesTheReportWithEveryLink)
{
    const std::string report = (dir_ / "arm.html").string();
    const CliRun r = meshgap::test::runExecutable(
        "meshgap_plan",
        "--cfg " + ROBOT_CLI_MAPS + "/arm_fixture/arm_fixture.cfg --seed 1 --time 20 -q --report " + report, 120);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("report written  " + report), std::string::npos) << r.out;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
    std::ifstream in(report);
    const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // arm4.urdf's links with geometry, and the payload the cfg attaches, by name in the page's link list.
    for (const char *link : {"base", "column", "upper", "fore", "hand", "payload"})
        EXPECT_NE(page.find(std::string("\"") + link + "\""), std::string::npos) << link;
}

TEST_F(RobotCli, PlanOptimizesTheWholeRobotsClearanceAndNamesTheLimitingPair)
{
    // RRTConnect's certified answer, then the clearance optimiser until it converges (the time limit only ends a run
    // that fails anyway; under the sanitizers' scale, its first 4 rounds, which already raise it well over twice):
    // the dense path's exact minimum clearance rises, and the summary names the pair that limits it before and after.
    const int rounds = meshgap::test::scale() < 1.0 ? 4 : 1000;
    const CliRun r =
        meshgap::test::runExecutable("meshgap_plan",
                                     "--cfg " + ROBOT_CLI_MAPS +
                                         "/arm_fixture/arm_fixture.cfg --seed 5 --time 300 -q --optimize clearance "
                                         "--optimize-time 300 --optimize-rounds " +
                                         std::to_string(rounds),
                                     900);
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(", ([0-9]+) rounds \\("))) << r.out;
    EXPECT_LE(std::stoi(m[1]), rounds) << r.out;
    const double before = valueAfterOnItsLine(r.out, "opt before"), after = valueAfterOnItsLine(r.out, "opt after");
    EXPECT_GT(after, 2.0 * before) << r.out;
    EXPECT_NEAR(valueAfterOnItsLine(r.out, "min clearance"), after, 1e-12 * after) << r.out;
    EXPECT_NE(r.out.find("dense path free yes"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("opt repair      none"), std::string::npos) << r.out;
    for (const char *key : {"opt before", "opt after"})
    {
        const std::size_t at = r.out.find(key);
        ASSERT_NE(at, std::string::npos) << r.out;
        const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
        EXPECT_NE(line.find("(exact, over the dense path; link '"), std::string::npos) << line;
    }
}

TEST_F(RobotCli, PlanWithTheMaxMinObjectiveCostsItsLeastClearanceFromBoundedQueries)
{
    const CliRun r =
        meshgap::test::runExecutable("meshgap_plan",
                                     "--cfg " + ROBOT_CLI_MAPS +
                                         "/arm_fixture/arm_fixture.cfg --seed 1 --time 2 -q --planner rrtstar "
                                         "--objective max_min_clearance",
                                     300);
    ASSERT_NE(r.status, 1) << r.out << r.err;  // solved, or approximately within the 2 s
    EXPECT_NE(r.out.find("objective       max_min_clearance"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cost queries"), std::string::npos) << r.out;
    // The cost is the least clearance at the objective's grid states: at least the dense path's exact minimum
    // less what lies between its states, never below 0 on a free path.
    EXPECT_GT(valueAfterOnItsLine(r.out, "cost"), 0.0) << r.out;
    const CliRun weight = meshgap::test::runExecutable(
        "meshgap_plan", "--cfg " + ROBOT_CLI_MAPS + "/arm_fixture/arm_fixture.cfg --objective clearance --weight 2",
        60);
    EXPECT_EQ(weight.status, 1);
    EXPECT_NE(weight.err.find("--weight: applies to --objective weighted only"), std::string::npos) << weight.err;
}

TEST_F(RobotCli, BadInputGetsOneClearErrorEach)
{
    struct Case
    {
        std::string tool, args, expected;
    };
    const std::string arm = "robot.urdf = " + ROBOT_RES + "/problems/arm2.urdf\nworld = " + CUBE + "\n";
    const std::vector<Case> cases = {
        {"meshgap_distance", "--cfg " + twoCubes() + " --pose '1 2 3'", "--pose: a state of this problem has 14"},
        {"meshgap_distance", "--cfg " + twoCubes() + " --poses " + file("bad.path", "0 0 0.5 0 0 0 1\n"),
         "bad.path:1: a state of this problem has 14 numbers"},
        {"meshgap_plan",
         "--cfg " + file("claw.cfg", "[problem]\n" + arm + "attach = " + CUBE +
                                         " claw 0 0 0 0 0 0 1\nstart.joints = 0 0\ngoal.joints = 1 0\n"),
         "claw.cfg:4: attach: the robot has no link 'claw'"},
        {"meshgap_distance", "--cfg " + file("wrong.cfg", "[problem]\n" + arm + "start.joints = 0 0 0\n"),
         "wrong.cfg:4: start.joints has 3 numbers"},
        {"meshgap_plan",
         "--cfg " + file("missing.cfg", "[problem]\nrobot.urdf = " + ROBOT_RES + "/missing_mesh.urdf\nworld = " + CUBE +
                                            "\nstart.joints = 0\ngoal.joints = 0\n"),
         "missing.cfg:2: robot.urdf:"}};
    for (const Case &c : cases)
    {
        const CliRun r = meshgap::test::runExecutable(c.tool, c.args);
        EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_EQ(meshgap::test::countLines(r.err, "error"), 1) << r.err;
        EXPECT_TRUE(r.out.empty() || r.out.find("path written") == std::string::npos) << r.out;
    }
}
