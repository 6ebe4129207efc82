// The glTF 2.0 export: a small scene written with writeGlb(sceneExportParts(...)) and read back by assimp's glTF
// importer; every mesh is there, in order, with its triangles, placed where the scene put it.

#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <filesystem>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "support/SceneExport.h"
#include "support/Shapes.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    std::string temporaryFile(const std::string &name)
    {
        return (fs::temp_directory_path() / ("meshgap_" + std::to_string(::getpid()) + "_" + name)).string();
    }

    Eigen::Vector3d vertexOf(const aiMesh &mesh, unsigned int i)
    {
        return Eigen::Vector3d(mesh.mVertices[i].x, mesh.mVertices[i].y, mesh.mVertices[i].z);
    }
}  // namespace

TEST(SceneExport, SegmentBoxIsAClosedOutwardBoxAroundTheSegment)
{
    const Eigen::Vector3d a(1, 2, 3), b(4, 6, 3);  // length 5
    const Mesh box = segmentBox(a, b, 0.1);
    EXPECT_EQ(box.vertices.size(), 8u);
    EXPECT_EQ(box.triangles.size(), 12u);
    EXPECT_EQ(countComponents(box), 1u);
    // Outward winding gives a positive volume: width^2 * (length + width).
    EXPECT_NEAR(signedVolume(box), 0.1 * 0.1 * 5.1, 1e-12);
    EXPECT_LT((vertexMean(box) - 0.5 * (a + b)).norm(), 1e-12);
    // A zero-length segment is a small cube, not a degenerate box.
    EXPECT_NEAR(signedVolume(segmentBox(a, a, 0.2)), 0.008, 1e-12);
    EXPECT_THROW(segmentBox(a, b, 0.0), Exception);
}

TEST(SceneExport, GlbReadsBackWithEveryMeshAndTriangle)
{
    // Two obstacles (the world splits into its parts) and a box robot at three poses, the last one colliding.
    const Mesh world =
        test::merged(test::box(1, 1, 1), test::transformed(test::icosphere(1.0, 2), test::translation(8, 0, 0)));
    const ScenePtr scene = Scene::fromMeshes(test::box(0.5, 0.25, 0.25), world);
    ASSERT_EQ(scene->obstacles().size(), 2u);
    const std::vector<Eigen::Isometry3d> poses = {test::translation(3, 0, 0), test::translation(3, 2, 0.5),
                                                  test::translation(1.2, 0, 0)};
    std::vector<SceneResult> results;
    const std::vector<ColoredMesh> parts = sceneExportParts(*scene, poses, SceneExportOptions(), &results);
    ASSERT_EQ(parts.size(), 2u + 2u * poses.size());
    ASSERT_EQ(results.size(), poses.size());
    EXPECT_FALSE(results[0].inCollision);
    EXPECT_TRUE(results[2].inCollision);
    // The closest-point segment at the first pose runs from the robot's face x = 2.5 to the box's face x = 1.
    EXPECT_NEAR(results[0].distance, 1.5, 1e-12);

    const std::string file = temporaryFile("scene.glb");
    writeGlb(parts, file);
    ASSERT_TRUE(fs::exists(file));
    Assimp::Importer importer;
    const aiScene *read = importer.ReadFile(file, 0);
    ASSERT_NE(read, nullptr) << importer.GetErrorString();
    ASSERT_EQ(read->mNumMeshes, parts.size());
    for (unsigned int i = 0; i < read->mNumMeshes; ++i)
    {
        const aiMesh &m = *read->mMeshes[i];
        SCOPED_TRACE(parts[i].name);
        EXPECT_EQ(std::string(m.mName.C_Str()), parts[i].name);
        EXPECT_EQ(m.mNumFaces, parts[i].mesh.triangles.size());
        EXPECT_EQ(m.mNumVertices, parts[i].mesh.vertices.size());
        for (unsigned int f = 0; f < m.mNumFaces; ++f)
            ASSERT_EQ(m.mFaces[f].mNumIndices, 3u);
        // Vertices where the scene put them (single precision in the file).
        for (unsigned int v = 0; v < m.mNumVertices; ++v)
            ASSERT_LT((vertexOf(m, v) - parts[i].mesh.vertices[v]).norm(), 1e-5);
    }
    // Robot k is the robot's surface moved to pose k; its segment's centre is the witness points' midpoint.
    for (std::size_t k = 0; k < poses.size(); ++k)
    {
        const aiMesh &robot = *read->mMeshes[2 + 2 * k], &segment = *read->mMeshes[3 + 2 * k];
        EXPECT_LT((vertexOf(robot, 0) - poses[k] * scene->robot().surface().vertices[0]).norm(), 1e-5);
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (unsigned int v = 0; v < segment.mNumVertices; ++v)
            mean += vertexOf(segment, v) / segment.mNumVertices;
        EXPECT_LT((mean - 0.5 * (results[k].onA + results[k].onB)).norm(), 1e-5);
    }
    fs::remove(file);
}

TEST(SceneExport, BadInputNamesTheFileAndLeavesNothing)
{
    const std::string file = temporaryFile("bad.glb");
    ColoredMesh bad{"bad", test::box(1, 1, 1)};
    bad.mesh.triangles.push_back({0, 1, 99});
    EXPECT_THROW(writeGlb({bad}, file), Exception);
    EXPECT_THROW(writeGlb({}, file), Exception);
    EXPECT_FALSE(fs::exists(file));
    EXPECT_THROW(writeGlb({ColoredMesh{"box", test::box(1, 1, 1)}}, "/nonexistent/dir/x.glb"), Exception);
}
