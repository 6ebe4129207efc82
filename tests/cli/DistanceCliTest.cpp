// The distance executable as a user runs it: exit codes, one clear error line, CSV and JSON output.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "TestMeshes.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    struct CliRun
    {
        int status;  // exit status, or -1 if killed by a signal
        std::string out, err;
    };

    CliRun run(const std::string &args)
    {
        // Unique per process and call: ctest runs several of these tests at once.
        static int calls = 0;
        const std::string stem = (fs::temp_directory_path() / ("meshgap_cli_" + std::to_string(::getpid()) + "_" +
                                                               std::to_string(++calls))).string();
        const std::string out = stem + ".out", err = stem + ".err";
        const std::string command = std::string(MESHGAP_BINARY_DIR) + "/planners/meshgap_distance " + args + " >" +
                                    out + " 2>" + err;
        const int raw = std::system(command.c_str());
        auto slurp = [](const std::string &path) {
            std::ifstream in(path);
            std::stringstream s;
            s << in.rdbuf();
            return s.str();
        };
        CliRun result{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
        fs::remove(out);
        fs::remove(err);
        return result;
    }

    int countLines(const std::string &text, const std::string &prefix)
    {
        std::istringstream in(text);
        std::string line;
        int n = 0;
        while (std::getline(in, line))
            n += line.rfind(prefix, 0) == 0;
        return n;
    }

    const std::string RES = MESHGAP_TEST_RESOURCES_DIR;
}  // namespace

TEST(DistanceCli, BadInputGivesOneErrorNamingTheFileAndExitOne)
{
    std::vector<std::pair<std::string, std::string>> cases = {
        {RES + "/cube.obj /nonexistent/mesh.obj", "/nonexistent/mesh.obj"},
        {"--cfg /nonexistent/problem.cfg", "/nonexistent/problem.cfg"},
        {RES + "/cube.obj " + RES + "/cube.obj --algorithm comb-XX", "comb-XX"},
        {RES + "/cube.obj " + RES + "/cube.obj --pose '1 2 3'", "--pose"},
        {RES + "/cube.obj " + RES + "/cube.obj --grid -3", "--grid"},
        {RES + "/cube.obj", "two mesh files"},
    };
    for (const auto &entry : fs::directory_iterator(RES + "/bad"))
        if (entry.path().extension() != ".cfg" && entry.path().filename() != "degenerate.obj")
            cases.emplace_back(RES + "/cube.obj " + entry.path().string(), entry.path().filename().string());
    for (const auto &[args, mention] : cases)
    {
        const CliRun r = run(args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_EQ(countLines(r.err, "error: "), 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST(DistanceCli, UnknownAlgorithmListsTheValidOnes)
{
    const CliRun r = run(RES + "/cube.obj " + RES + "/cube.obj --algorithm nope");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("enumeration"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("hill-climb"), std::string::npos) << r.err;
}

TEST(DistanceCli, PosesGiveCsvRowsThatMatchTheGeometry)
{
    // Two unit cubes (from cube.obj, [0,1]^3) side by side with gaps 0.5, 1.5, 2.5 along x.
    const std::string poses = (fs::temp_directory_path() / ("meshgap_cli_" + std::to_string(::getpid()) + ".path")).string();
    std::ofstream(poses) << "1.5 0 0 0 0 0 1\n2.5 0 0 0 0 0 1\n# comment\n3.5 0 0 0 0 0 1\n";
    const CliRun r = run(RES + "/cube.obj " + RES + "/cube.obj --grid 0 --poses " + poses);
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

TEST(DistanceCli, JsonAndTextAgree)
{
    const std::string meshes = RES + "/cube.obj " + RES + "/cube.obj --pose '3 0 0 0 0 0 1' --grid 0";
    const CliRun text = run(meshes), json = run(meshes + " --json");
    ASSERT_EQ(text.status, 0) << text.err;
    ASSERT_EQ(json.status, 0) << json.err;
    EXPECT_NE(text.out.find("distance       2\n"), std::string::npos) << text.out;
    EXPECT_NE(json.out.find("\"distance\": 2,"), std::string::npos) << json.out;
    EXPECT_NE(text.out.find("witness on A   1 "), std::string::npos) << text.out;
}

TEST(DistanceCli, CfgStartPoseGivesTheEnumerationMinimum)
{
    const fs::path cfg = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp" / "Easy.cfg";
    if (!fs::exists(cfg))
        GTEST_SKIP() << "OMPL.app problems not found at " << cfg << "; skipping";
    const CliRun r = run("--cfg " + cfg.string() + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const ProblemConfig problem = readProblemConfig(cfg.string());
    DistanceResult expected;
    Enumeration().solve(*Body::build(loadMesh(problem.world)), *Body::build(loadRobotMesh(problem.robot)),
                        problem.start, DistanceRequest(), expected);
    char number[64];
    std::snprintf(number, sizeof number, "\"distance\": %.17g,", expected.distance);
    EXPECT_NE(r.out.find(number), std::string::npos) << r.out << " expected " << number;
}
