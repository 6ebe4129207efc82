// meshgap_plan --export-glb: a quick plan on maps/slotted_wall, and the .glb it writes imports with assimp, holding
// the world's parts, the robot at each exported state and a closest-point segment per state.

#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <filesystem>

#include "CliRun.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

TEST(PlanExport, GlbOfThePlannedPathImports)
{
    const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
    const std::string file =
        (fs::temp_directory_path() / ("meshgap_plan_export_" + std::to_string(::getpid()) + ".glb")).string();
    const test::CliRun run = test::runExecutable(
        "meshgap_plan", "--cfg " + cfg + " --time 120 --seed 1 --quiet --export-glb " + file + " --export-states 5",
        120);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("scene written"), std::string::npos) << run.out;
    ASSERT_TRUE(fs::exists(file));

    const ProblemConfig config = readProblemConfig(cfg);
    const std::size_t obstacles = splitComponents(loadMesh(config.world)).size();
    const std::size_t robotTriangles = loadRobotMesh(config.robot).triangles.size();
    Assimp::Importer importer;
    const aiScene *scene = importer.ReadFile(file, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    ASSERT_EQ(scene->mNumMeshes, obstacles + 2 * 5);
    for (std::size_t k = 0; k < 5; ++k)
    {
        const aiMesh &robot = *scene->mMeshes[obstacles + 2 * k], &segment = *scene->mMeshes[obstacles + 2 * k + 1];
        EXPECT_EQ(std::string(robot.mName.C_Str()), "robot " + std::to_string(k));
        EXPECT_EQ(robot.mNumFaces, robotTriangles);
        EXPECT_EQ(std::string(segment.mName.C_Str()), "clearance " + std::to_string(k));
        EXPECT_EQ(segment.mNumFaces, 12u);
    }
    fs::remove(file);

    // A bad value is refused before planning.
    const test::CliRun bad =
        test::runExecutable("meshgap_plan", "--cfg " + cfg + " --export-glb " + file + " --export-states 0");
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.err.find("--export-states"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(file));
}
