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

// A robot problem (two bodies in the plane) writes the same scene: at each exported state every link, placed at its
// pose, then the segment of the pair that attains the clearance; the first state's links where the problem starts.
TEST(PlanExport, GlbOfARobotsPathHoldsEveryLinkAtEachState)
{
    const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/swap_se2/swap_se2.cfg";
    const std::string file =
        (fs::temp_directory_path() / ("meshgap_plan_export_robot_" + std::to_string(::getpid()) + ".glb")).string();
    const test::CliRun run = test::runExecutable(
        "meshgap_plan", "--cfg " + cfg + " --time 120 --seed 1 --quiet --export-glb " + file + " --export-states 3",
        120);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("scene written   " + file + " (3 robot states)"), std::string::npos) << run.out;

    const fs::path folder = fs::path(cfg).parent_path();
    const std::size_t obstacles = splitComponents(loadMesh((folder / "swap_se2_world.obj").string())).size();
    const Mesh body = loadRobotMesh((folder / "swap_se2_robot.obj").string(), true);
    Assimp::Importer importer;
    const aiScene *scene = importer.ReadFile(file, 0);
    ASSERT_NE(scene, nullptr) << importer.GetErrorString();
    ASSERT_EQ(scene->mNumMeshes, obstacles + 3 * 3);
    for (std::size_t k = 0; k < 3; ++k)
    {
        for (std::size_t i = 0; i < 2; ++i)
        {
            const aiMesh &link = *scene->mMeshes[obstacles + 3 * k + i];
            EXPECT_EQ(std::string(link.mName.C_Str()), "robot " + std::to_string(k) + " robot." + std::to_string(i + 1));
            EXPECT_EQ(link.mNumFaces, body.triangles.size());
        }
        const aiMesh &segment = *scene->mMeshes[obstacles + 3 * k + 2];
        EXPECT_EQ(std::string(segment.mName.C_Str()), "clearance " + std::to_string(k));
        EXPECT_EQ(segment.mNumFaces, 12u);
    }
    // At the first state, body 1 sits at start.1 (-3.3, -1.2, no turn): its vertices' box is the body's, moved there.
    const aiMesh &first = *scene->mMeshes[obstacles];
    Eigen::AlignedBox3d placed;
    for (unsigned v = 0; v < first.mNumVertices; ++v)
        placed.extend(Eigen::Vector3d(first.mVertices[v].x, first.mVertices[v].y, first.mVertices[v].z));
    const Eigen::Vector3d shift(-3.3, -1.2, 0.0);
    EXPECT_LT((placed.min() - (body.bounds().min() + shift)).norm(), 1e-4);
    EXPECT_LT((placed.max() - (body.bounds().max() + shift)).norm(), 1e-4);
    fs::remove(file);
}
