// The distance executable as a user runs it: exit codes, one clear error line, CSV and JSON output.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

#include "CliRun.h"
#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    using test::CliRun;
    using test::countLines;

    CliRun run(const std::string &args) { return test::runExecutable("meshgap_distance", args); }

    const std::string CLI_RES = MESHGAP_TEST_RESOURCES_DIR;
}  // namespace

TEST(DistanceCli, BadInputGivesOneErrorNamingTheFileAndExitOne)
{
    std::vector<std::pair<std::string, std::string>> cases = {
        {CLI_RES + "/cube.obj /nonexistent/mesh.obj", "/nonexistent/mesh.obj"},
        {"--cfg /nonexistent/problem.cfg", "/nonexistent/problem.cfg"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm comb-XX", "comb-XX"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --pose '1 2 3'", "--pose"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --grid -3", "--grid"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --sizing bogus", "bogus"},
        {CLI_RES + "/cube.obj", "two mesh files"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --cold", "--cold"},  // the scene's answer only
        // A single body's state through the one-link robot: the count, and a quaternion that is no rotation.
        {"--cfg " + std::string(MESHGAP_SOURCE_DIR) + "/maps/twisted/twisted.cfg --pose '1 2 3'",
         "--pose: a state of "
         "this problem has 7"},
        {"--cfg " + std::string(MESHGAP_SOURCE_DIR) + "/maps/twisted/twisted.cfg --pose '1 2 3 0 0 0 0'",
         "--pose: SE(3) state: the quaternion"},
        // Solver parameters: ALGORITHM.NAME=VALUE, as meshgap_plan's and meshgap_benchmark's PLANNER.NAME=VALUE.
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm comb-GA-wl --param comb-GA-wl.population=1",
         "not a valid parameter of comb-GA-wl"},  // comb-GA needs at least 2: the value reached the solver
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm comb-GA-wl --param population=10",
         "is not ALGORITHM.NAME=VALUE"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm comb-GA-wl --param comb-SA-wl.population=10",
         "the algorithm is comb-GA-wl"},
        {CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm comb-GA-wl --set population=10",
         "--set: renamed: use --param ALGORITHM.NAME=VALUE"},
    };
    for (const auto &entry : fs::directory_iterator(CLI_RES + "/bad"))
        if (entry.path().extension() != ".cfg" && entry.path().filename() != "degenerate.obj")
            cases.emplace_back(CLI_RES + "/cube.obj " + entry.path().string(), entry.path().filename().string());
    for (const auto &[args, mention] : cases)
    {
        const CliRun r = run(args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_EQ(countLines(r.err, "error: "), 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST(DistanceCli, ParamReachesTheSolver)
{
    // comb-GA-wl with a population of 2 and no generations evaluates far fewer pairs than with its defaults (Table I).
    const std::string args = CLI_RES + "/cube.obj " + CLI_RES +
                             "/cube.obj --pose '3 0 0 0 0 0 1' --algorithm comb-GA-wl "
                             "--seed 1 --json --grid 0";
    const CliRun byDefault = run(args),
                 small = run(args + " --param comb-GA-wl.population=2 --param comb-GA-wl.generations=0");
    ASSERT_EQ(byDefault.status, 0) << byDefault.err;
    ASSERT_EQ(small.status, 0) << small.err;
    auto evaluations = [](const std::string &json)
    {
        const std::size_t at = json.find("\"evaluations\": ");
        return at == std::string::npos ? -1L : std::stol(json.substr(at + 15));
    };
    EXPECT_GT(evaluations(small.out), 0) << small.out;
    EXPECT_LT(evaluations(small.out), evaluations(byDefault.out)) << small.out << "\n" << byDefault.out;
}

TEST(DistanceCli, UnknownAlgorithmListsTheValidOnes)
{
    const CliRun r = run(CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --algorithm nope");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("enumeration"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hill-climb"), std::string::npos) << r.err;
}

TEST(DistanceCli, PosesGiveCsvRowsThatMatchTheGeometry)
{
    // Two unit cubes (from cube.obj, [0,1]^3) side by side with gaps 0.5, 1.5, 2.5 along x.
    const std::string poses = (fs::temp_directory_path() / ("meshgap_cli_" + std::to_string(::getpid()) + ".path")).string();
    std::ofstream(poses) << "1.5 0 0 0 0 0 1\n2.5 0 0 0 0 0 1\n# comment\n3.5 0 0 0 0 0 1\n";
    const CliRun r = run(CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --grid 0 --poses " + poses);
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream in(r.out);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("index,distance,evaluations,time_us", 0), 0u) << line;
    const double gaps[] = {0.5, 1.5, 2.5};
    for (int i = 0; i < 3; ++i)
    {
        ASSERT_TRUE(std::getline(in, line));
        std::istringstream row(line);
        std::string index, distance;
        std::getline(row, index, ',');
        std::getline(row, distance, ',');
        EXPECT_EQ(std::stoi(index), i);
        EXPECT_NEAR(std::stod(distance), gaps[i], 1e-12) << line;
    }
    EXPECT_FALSE(std::getline(in, line));
    fs::remove(poses);
}

TEST(DistanceCli, ExactAndCollisionColumns)
{
    // Cube [0,1]^3 against the same cube turned 45 degrees about z: B's corner edge (0,0,z) stays put and its
    // corner (0,1,z) swings to (-c, c, z), c = sqrt(1/2), B's leading (leftmost) vertical edge. Moved by
    // (x0 + c, 0.5 - c, 0) that edge stands at x = x0, y = 0.5, facing A's face x = 1 edge-on: the exact gap is
    // x0 - 1 (node pairs: at least that). x0 = 1.5, then 0.9
    // (the edge cuts into A: collision).
    const double c = std::sqrt(0.5);
    const std::string poses = (fs::temp_directory_path() / ("meshgap_cli_x" + std::to_string(::getpid()) + ".path")).string();
    std::ofstream(poses) << std::setprecision(17) << 1.5 + c << " " << 0.5 - c << " 0 0 0 " << std::sin(M_PI / 8)
                         << " " << std::cos(M_PI / 8) << "\n"
                         << 0.9 + c << " " << 0.5 - c << " 0 0 0 " << std::sin(M_PI / 8) << " " << std::cos(M_PI / 8)
                         << "\n";
    for (const char *extra : {"", " --exact"})
    {
        const CliRun r = run(CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --grid 0 --poses " + poses + extra);
        ASSERT_EQ(r.status, 0) << r.err;
        std::istringstream in(r.out);
        std::string header, row;
        std::getline(in, header);
        EXPECT_NE(header.find(",in_collision,certified,node_distance"), std::string::npos) << header;
        std::vector<std::vector<std::string>> rows;
        while (std::getline(in, row))
        {
            std::vector<std::string> cells;
            std::istringstream split(row);
            std::string cell;
            while (std::getline(split, cell, ','))
                cells.push_back(cell);
            rows.push_back(cells);
        }
        ASSERT_EQ(rows.size(), 2u);
        const std::size_t collision = rows[0].size() - 3, certified = rows[0].size() - 2;
        EXPECT_EQ(rows[0][collision], "0") << extra;
        EXPECT_EQ(rows[1][collision], "1") << extra;  // decided exactly even without --exact
        EXPECT_EQ(rows[0][certified], *extra ? "1" : "0");
        // In collision the distance is signed, with or without --exact: negative. Here (no refinement) no corner of
        // one cube is inside the other: depth 0, the smallest negative normal double.
        EXPECT_LT(std::stod(rows[1][1]), 0.0) << extra;
        EXPECT_GT(std::stod(rows[1][1]), -1e-300) << extra;
        if (*extra)
        {
            // B's corner (0,0) turned by 45 degrees about z sits at x = 1.5 (its leading edge): gap 0.5 to x = 1.
            EXPECT_NEAR(std::stod(rows[0][1]), 0.5, 1e-12);
        }
        else
        {
            EXPECT_GE(std::stod(rows[0][1]), 0.5);  // a node answer is never below the exact one
        }
    }
    fs::remove(poses);
}

TEST(DistanceCli, CollisionDistanceIsMinusThePenetrationDepth)
{
    // The collision pose above (B's leading edge 0.1 inside A's face x = 1), refined to grid 0.1: nodes along that
    // edge are 0.1 deep, the deepest of either cube inside the other: distance -0.1, with or without --exact.
    const double c = std::sqrt(0.5);
    std::ostringstream pose;
    pose << std::setprecision(17) << 0.9 + c << " " << 0.5 - c << " 0 0 0 " << std::sin(M_PI / 8) << " "
         << std::cos(M_PI / 8);
    for (const char *extra : {"", " --exact"})
    {
        const CliRun r =
            run(CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --grid 0.1 --json --pose '" + pose.str() + "'" + extra);
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string key = "\"distance\": ";
        const std::size_t at = r.out.find(key);
        ASSERT_NE(at, std::string::npos) << r.out;
        EXPECT_NEAR(std::stod(r.out.substr(at + key.size())), -0.1, 1e-12) << r.out;
        EXPECT_NE(r.out.find("\"in_collision\": true"), std::string::npos) << r.out;
    }
}

TEST(DistanceCli, JsonAndTextAgree)
{
    const std::string meshes = CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --pose '3 0 0 0 0 0 1' --grid 0";
    const CliRun text = run(meshes), json = run(meshes + " --json");
    ASSERT_EQ(text.status, 0) << text.err;
    ASSERT_EQ(json.status, 0) << json.err;
    EXPECT_NE(text.out.find("distance       2 (node to node"), std::string::npos) << text.out;
    EXPECT_NE(json.out.find("\"distance\": 2,"), std::string::npos) << json.out;
    EXPECT_NE(text.out.find("witness on A   1 "), std::string::npos) << text.out;
}

TEST(DistanceCli, CfgStartPoseGivesTheEnumerationMinimum)
{
    const fs::path cfg = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp" / "Easy.cfg";
    if (!fs::exists(cfg))
        GTEST_SKIP() << "OMPL.app problems not found at " << cfg << "; skipping";
    const CliRun r = run("--cfg " + cfg.string() + " --algorithm enumeration --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const ProblemConfig problem = readProblemConfig(cfg.string());
    DistanceResult expected;
    Enumeration().solve(*Body::build(loadMesh(problem.world)), *Body::build(loadRobotMesh(problem.robot)),
                        problem.start, DistanceRequest(), expected);
    char number[64];
    std::snprintf(number, sizeof number, "\"distance\": %.17g,", expected.distance);
    EXPECT_NE(r.out.find(number), std::string::npos) << r.out << " expected " << number;
}

namespace
{
    /** \brief The CSV rows of a --poses run, cells split at commas, after checking the header starts with
        \e headerStart. */
    std::vector<std::vector<std::string>> csvRows(const std::string &out, const std::string &headerStart)
    {
        std::istringstream in(out);
        std::string line;
        std::getline(in, line);
        EXPECT_EQ(line.rfind(headerStart, 0), 0u) << line;
        std::vector<std::vector<std::string>> rows;
        while (std::getline(in, line))
        {
            std::vector<std::string> cells;
            std::istringstream split(line);
            std::string cell;
            while (std::getline(split, cell, ','))
                cells.push_back(cell);
            rows.push_back(cells);
        }
        return rows;
    }
}  // namespace

TEST(DistanceCli, CfgPosesGiveTheSceneAnswerWarmOrCold)
{
    // --cfg without --algorithm answers as the checker does, for a single body as for a robot (a robot of one link,
    // the robot problems' CSV): the scene (handshake's world, a hand, splits into its six parts), exact and
    // certified, one warm start carried from pose to pose, or a fresh one with --cold. Poses: the cfg's start, the
    // goal and the straight line between them, which runs through the world (colliding stretch). Oracle: FCL's
    // distance and collision on the same meshes; warm and cold must agree to 1e-12; --json gives the same numbers,
    // --no-depth the same verdicts with the contact distance in collision.
    const fs::path cfg = fs::path(MESHGAP_SOURCE_DIR) / "maps" / "handshake" / "handshake.cfg";
    const ProblemConfig problem = readProblemConfig(cfg.string());
    ASSERT_TRUE(problem.goal.has_value());
    std::vector<Eigen::Isometry3d> poses;
    for (int k = 0; k <= 8; ++k)
    {
        Eigen::Isometry3d X = problem.start;
        X.translation() += (k / 8.0) * (problem.goal->translation() - problem.start.translation());
        poses.push_back(X);
    }
    const std::string file =
        (fs::temp_directory_path() / ("meshgap_cli_s" + std::to_string(::getpid()) + ".path")).string();
    {
        std::ofstream out(file);
        out << std::setprecision(17);
        for (const Eigen::Isometry3d &X : poses)
        {
            const Eigen::Quaterniond q(X.linear());
            out << X.translation().x() << " " << X.translation().y() << " " << X.translation().z() << " " << q.x()
                << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
        }
    }
    const std::string header = "index,distance,in_collision,certified,link,other_link,obstacle,witness_a_x,";
    const CliRun warm = run("--cfg " + cfg.string() + " --poses " + file + " -q");
    const CliRun cold = run("--cfg " + cfg.string() + " --poses " + file + " --cold -q");
    const CliRun json = run("--cfg " + cfg.string() + " --poses " + file + " --json -q");
    const CliRun noDepth = run("--cfg " + cfg.string() + " --poses " + file + " --no-depth -q");
    fs::remove(file);
    ASSERT_EQ(json.status, 0) << json.err;
    ASSERT_EQ(noDepth.status, 0) << noDepth.err;
    std::vector<double> jsonDistances;
    const std::regex field("\"distance\": ([-+0-9.eE]+),");
    for (auto it = std::sregex_iterator(json.out.begin(), json.out.end(), field); it != std::sregex_iterator(); ++it)
        jsonDistances.push_back(std::stod((*it)[1]));
    EXPECT_EQ(json.out.front(), '[') << json.out;
    ASSERT_EQ(jsonDistances.size(), poses.size()) << json.out;
    const auto flat = csvRows(noDepth.out, header);
    ASSERT_EQ(flat.size(), poses.size());
    ASSERT_EQ(warm.status, 0) << warm.err;
    ASSERT_EQ(cold.status, 0) << cold.err;
    EXPECT_NE(warm.err.find("median"), std::string::npos) << warm.err;  // time per query, on stderr
    EXPECT_NE(cold.err.find("cold"), std::string::npos) << cold.err;
    const auto w = csvRows(warm.out, header), c = csvRows(cold.out, header);
    ASSERT_EQ(w.size(), poses.size());
    ASSERT_EQ(c.size(), poses.size());
    const std::size_t collision = 2, certified = 3;
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
        SCOPED_TRACE("pose " + std::to_string(i));
        ASSERT_EQ(w[i].size(), 14u);  // the columns, then clearance_robot: the robot's one link
        EXPECT_EQ(w[i][4], "robot");
        EXPECT_EQ(w[i][5], "");  // against an obstacle, not another link
        EXPECT_EQ(w[i][collision], c[i][collision]);
        const double dw = std::stod(w[i][1]), dc = std::stod(c[i][1]);
        EXPECT_LE(std::abs(dw - dc), 1e-12 * std::max(std::abs(dw), std::abs(dc)));
        EXPECT_EQ(jsonDistances[i], dw);
        EXPECT_EQ(std::stod(w[i][13]), dw);  // the one link's clearance is the robot's
        EXPECT_EQ(w[i][certified], "1");
        EXPECT_EQ(c[i][certified], "1");
        EXPECT_EQ(flat[i][collision], w[i][collision]);
        if (w[i][collision] == "1")
        {
            EXPECT_EQ(std::stod(flat[i][1]), CONTACT_DISTANCE);  // the verdict alone
        }
        else
        {
            EXPECT_EQ(flat[i][1], w[i][1]);
            const Eigen::Vector3d onA(std::stod(w[i][7]), std::stod(w[i][8]), std::stod(w[i][9]));
            const Eigen::Vector3d onB(std::stod(w[i][10]), std::stod(w[i][11]), std::stod(w[i][12]));
            EXPECT_NEAR((onA - onB).norm(), dw, 1e-9 * dw);
        }
        colliding += w[i][collision] == "1";
#ifdef MESHGAP_HAVE_FCL
        static const auto world = test::fclModel(loadMesh(problem.world)),
                          robot = test::fclModel(loadRobotMesh(problem.robot));
        const bool hit = test::fclCollide(world, robot, poses[i]);
        EXPECT_EQ(w[i][collision] == "1", hit);
        if (!hit)
        {
            const double d = test::fclDistance(world, robot, poses[i]);
            EXPECT_NEAR(dw, d, 1e-6 * d);
        }
        else
            EXPECT_LT(dw, 0.0);  // signed: negative in collision
#endif
    }
    EXPECT_GT(colliding, 0u);  // the straight line runs through the other hand
    EXPECT_LT(colliding, poses.size());
}

TEST(DistanceCli, AdaptiveSizingGivesTheEnumerationMinimumOverAdaptiveNodes)
{
    const std::string pose = "3.1 0.2 0.3 0.1 0.2 0.3 0.927";
    const CliRun r = run(CLI_RES + "/cube.obj " + CLI_RES + "/cube.obj --sizing adaptive --json --pose '" + pose + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("adaptive node sizing"), std::string::npos) << r.err;
    BodyOptions options;
    options.sizing = GridSizing::ADAPTIVE;
    const Mesh cube = loadMesh(CLI_RES + "/cube.obj");
    const BodyPtr body = Body::build(cube, options);
    EXPECT_GT(body->numNodes(), cube.vertices.size());  // the rule refined it
    std::istringstream in(pose);
    double x, y, z, qx, qy, qz, qw;
    in >> x >> y >> z >> qx >> qy >> qz >> qw;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    X.translation() = Eigen::Vector3d(x, y, z);
    DistanceResult expected;
    Enumeration().solve(*body, *body, X, DistanceRequest(), expected);
    char number[64];
    std::snprintf(number, sizeof number, "\"distance\": %.17g,", expected.distance);
    EXPECT_NE(r.out.find(number), std::string::npos) << r.out << " expected " << number;
}
