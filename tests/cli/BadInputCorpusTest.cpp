// Every file of the bad-input corpus (tests/resources/bad) through every executable that reads that kind of file
// (meshgap_makemap reads none):
// one line "error: ..." naming the file and the problem, exit status 1, nothing on stdout, no crash, no hang.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <vector>

#include "CliRun.h"

using namespace meshgap;
using meshgap::test::CliRun;
namespace fs = std::filesystem;

namespace
{
    const std::string RES = MESHGAP_TEST_RESOURCES_DIR;

    // What the one error line must say, beyond the file's name: the problem, in the user's words. Files the loader
    // accepts with a warning (degenerate.obj: its zero-area triangles are dropped) are not in the corpus's table.
    const std::map<std::string, std::vector<std::string>> PROBLEM = {
        {"badindex.obj", {"badindex.obj", "index"}},
        {"corrupt.dae", {"corrupt.dae", "cannot read"}},
        {"corrupt.ply", {"corrupt.ply", "out of range"}},
        {"corrupt.stl", {"corrupt.stl", "cannot read"}},
        {"empty.obj", {"empty.obj", "no triangles"}},
        {"garbage.obj", {"garbage.obj", "no triangles"}},
        {"hang_header.ply", {"hang_header.ply", "corrupt PLY header"}},  // Debian's assimp hangs on it
        {"huge.obj", {"huge.obj", "infinite"}},
        {"inf.obj", {"inf.obj", "infinite"}},
        {"nan.obj", {"nan.obj", "NaN"}},
        {"points.ply", {"points.ply", "triangles"}},
        {"truncated.dae", {"truncated.dae", "cannot read"}},
        {"truncated.obj", {"truncated.obj", "index"}},
        {"truncated.ply", {"truncated.ply", "no triangles"}},
        {"truncated.stl", {"truncated.stl", "cannot read"}},
        {"bad_mesh.cfg", {"corrupt.ply"}},
        {"goal_outside.cfg", {"goal_outside.cfg", "goal", "volume"}},
        {"missing_key.cfg", {"missing_key.cfg", "world"}},
        {"missing_mesh.cfg", {"missing_mesh.cfg", "robot.obj", "does not exist"}},
        {"nan_value.cfg", {"nan_value.cfg", "start.z", "not a finite number"}},
        {"start_outside.cfg", {"start_outside.cfg", "start", "volume"}},
        {"truncated.cfg", {"truncated.cfg", "start.y"}},
        {"unknown_key.cfg", {"unknown_key.cfg", "start.w"}},
        {"wrong_type.cfg", {"wrong_type.cfg", "goal.y", "three"}},
    };

    bool isConfig(const fs::path &p) { return p.extension() == ".cfg"; }

    // The command lines that read \e file: a mesh as either body of meshgap_distance; a problem through
    // meshgap_distance, meshgap_plan and meshgap_benchmark.
    std::vector<std::pair<std::string, std::string>> commandsFor(const fs::path &file)
    {
        const std::string f = "'" + file.string() + "'";
        if (isConfig(file))
            return {{"meshgap_distance", "--cfg " + f},
                    {"meshgap_plan", "--cfg " + f + " --time 1"},
                    {"meshgap_benchmark", "--cfg " + f + " --planner rrtconnect --runs 1 --time 1 --out " +
                                              (fs::temp_directory_path() / "meshgap_bad_corpus_logs").string()}};
        return {{"meshgap_distance", RES + "/cube.obj " + f}, {"meshgap_distance", f + " " + RES + "/cube.obj"}};
    }

    void expectOneClearError(const std::string &what, const CliRun &r, const std::vector<std::string> &mentions)
    {
        ASSERT_NE(r.status, -1) << what << ": crashed\n" << r.err;
        ASSERT_NE(r.status, 124) << what << ": did not finish in time";
        EXPECT_EQ(r.status, 1) << what << "\n" << r.err;
        EXPECT_EQ(test::countLines(r.err, "error: "), 1) << what << "\n" << r.err;
        for (const std::string &m : mentions)
            EXPECT_NE(r.err.find(m), std::string::npos) << what << ": the error does not say '" << m << "'\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << what << ": wrote results\n" << r.out;
    }
}  // namespace

TEST(BadInputCorpus, EveryFileHasAnExpectedProblemAndEveryProblemAFile)
{
    std::size_t files = 0;
    for (const auto &entry : fs::directory_iterator(RES + "/bad"))
    {
        const std::string name = entry.path().filename().string();
        if (name == "degenerate.obj")
            continue;
        ++files;
        EXPECT_TRUE(PROBLEM.count(name)) << name << " is in the corpus but not in this test's table";
    }
    EXPECT_EQ(files, PROBLEM.size()) << "a file named in this test's table is missing from " << RES << "/bad";
}

TEST(BadInputCorpus, EveryExecutableGivesOneErrorNamingFileAndProblem)
{
    for (const auto &[name, mentions] : PROBLEM)
    {
        const fs::path file = fs::path(RES) / "bad" / name;
        if (!fs::exists(file))
            continue;  // reported by the test above
        for (const auto &[executable, args] : commandsFor(file))
            expectOneClearError(executable + " " + args, test::runExecutable(executable, args, 120), mentions);
    }
}
