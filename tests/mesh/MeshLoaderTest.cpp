#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>
#include <unistd.h>

#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    const std::string LOADER_RES = MESHGAP_TEST_RESOURCES_DIR;

    void expectUnitCube(const std::string &file)
    {
        LoadReport report;
        LoadOptions centre;
        centre.omplAppCenter = true;
        const Mesh m = loadMesh(LOADER_RES + "/" + file, &report, centre);
        EXPECT_EQ(m.vertices.size(), 8u) << file;
        EXPECT_EQ(m.triangles.size(), 12u) << file;
        EXPECT_EQ(report.components, 1u) << file;
        EXPECT_EQ(countComponents(m), 1u) << file;
        EXPECT_EQ(m.bounds().min(), Eigen::Vector3d(0, 0, 0)) << file;
        EXPECT_EQ(m.bounds().max(), Eigen::Vector3d(1, 1, 1)) << file;
        ASSERT_TRUE(report.omplAppCenter) << file;
        EXPECT_TRUE(report.omplAppCenter->isApprox(Eigen::Vector3d(0.5, 0.5, 0.5), 1e-6)) << file;
        // Outward winding survives: positive enclosed volume of 1.
        double volume = 0.0;
        for (const Triangle &t : m.triangles)
            volume += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
        EXPECT_NEAR(volume, 1.0, 1e-12) << file;
    }
}  // namespace

TEST(MeshLoader, EveryFormatGivesTheWeldedCube)
{
    expectUnitCube("cube.obj");         // quads: triangulated
    expectUnitCube("cube_ascii.stl");   // a vertex per facet corner: welded
    expectUnitCube("cube_binary.stl");
    expectUnitCube("cube.ply");
}

TEST(MeshLoader, OmplAppsNormalsStepChangesOnlyTheCentre)
{
    // Without LoadOptions::omplAppCenter assimp skips GenNormals and JoinIdenticalVertices and the weld joins the
    // copies alone: every mesh file of the tests, maps/ and (when present) ../shared/data must load to the same
    // vertices, in the same order, the same triangles and the same report counts either way.
    std::vector<fs::path> files;
    for (const fs::path &root :
         {fs::path(LOADER_RES), fs::path(MESHGAP_SOURCE_DIR) / "maps", fs::path(MESHGAP_SHARED_DATA_DIR)})
    {
        if (!fs::exists(root))
            continue;
        for (const auto &entry : fs::recursive_directory_iterator(root))
        {
            std::string ext = entry.path().extension().string();
            for (char &c : ext)
                c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            const bool bad = entry.path().parent_path().filename() == "bad";
            if (entry.is_regular_file() && !bad && (ext == ".obj" || ext == ".stl" || ext == ".dae" || ext == ".ply"))
                files.push_back(entry.path());
        }
    }
    ASSERT_GE(files.size(), 10u);
    LoadOptions centre;
    centre.omplAppCenter = true;
    for (const fs::path &file : files)
    {
        LoadReport plain, omplApp;
        const Mesh a = loadMesh(file.string(), &plain), b = loadMesh(file.string(), &omplApp, centre);
        EXPECT_FALSE(plain.omplAppCenter) << file;
        EXPECT_TRUE(omplApp.omplAppCenter) << file;
        EXPECT_EQ(a.vertices, b.vertices) << file;
        EXPECT_EQ(a.triangles, b.triangles) << file;
        EXPECT_EQ(plain.rawTriangles, omplApp.rawTriangles) << file;
        EXPECT_EQ(plain.skippedPrimitives, omplApp.skippedPrimitives) << file;
        EXPECT_EQ(plain.clean.degenerate, omplApp.clean.degenerate) << file;
        EXPECT_EQ(plain.clean.duplicates, omplApp.clean.duplicates) << file;
        EXPECT_EQ(plain.components, omplApp.components) << file;
        EXPECT_EQ(plain.edges.boundaryEdges, omplApp.edges.boundaryEdges) << file;
        EXPECT_EQ(plain.edges.nonManifoldEdges, omplApp.edges.nonManifoldEdges) << file;
        EXPECT_GE(plain.rawVertices, omplApp.rawVertices) << file;  // the copies the join step merged
    }
}

TEST(MeshLoader, ColladaNodeTransformAndUpAxisAreApplied)
{
    const Mesh m = loadMesh(LOADER_RES + "/cube.dae");
    std::ifstream in(LOADER_RES + "/cube.dae.expected");
    std::vector<Eigen::Vector3d> expected;
    double x, y, z;
    while (in >> x >> y >> z)
        expected.emplace_back(x, y, z);
    ASSERT_EQ(expected.size(), 8u);
    ASSERT_EQ(m.vertices.size(), 8u);
    for (const Eigen::Vector3d &e : expected)
    {
        double nearest = std::numeric_limits<double>::infinity();
        for (const Eigen::Vector3d &v : m.vertices)
            nearest = std::min(nearest, (v - e).norm());
        EXPECT_LT(nearest, 1e-5) << e.transpose();
    }
}

TEST(MeshLoader, SeparatePartsAreSeparateComponents)
{
    LoadReport report;
    const Mesh m = loadMesh(LOADER_RES + "/two_parts.obj", &report);
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 8u);
    EXPECT_EQ(report.components, 2u);
}

TEST(MeshLoader, DegenerateTrianglesAreDroppedNotFatal)
{
    LoadReport report;
    const Mesh m = loadMesh(LOADER_RES + "/bad/degenerate.obj", &report);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_EQ(report.clean.degenerate, 2u);
    EXPECT_EQ(m.vertices.size(), 8u);
}

TEST(MeshLoader, BadFilesThrowOneErrorNamingTheFile)
{
    const std::map<std::string, std::string> expectedWords = {
        {"nan.obj", "NaN"}, {"inf.obj", "NaN or infinite"}, {"empty.obj", ""}, {"points.ply", "triangles"},
        {"badindex.obj", ""}, {"garbage.obj", ""}, {"truncated.stl", ""}, {"corrupt.dae", ""}};
    int tried = 0;
    for (const auto &entry : std::filesystem::directory_iterator(LOADER_RES + "/bad"))
    {
        const std::string name = entry.path().filename().string();
        if (name == "degenerate.obj" || entry.path().extension() == ".cfg")
            continue;
        ++tried;
        try
        {
            loadMesh(entry.path().string());
            ADD_FAILURE() << name << " loaded without error";
        }
        catch (const Exception &e)
        {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(entry.path().string() + ": ", 0), 0u) << what;
            const auto it = expectedWords.find(name);
            if (it != expectedWords.end())
            {
                EXPECT_NE(what.find(it->second), std::string::npos) << what;
            }
        }
    }
    EXPECT_GE(tried, 8);
    try
    {
        loadMesh("/nonexistent/thing.stl");
        FAIL();
    }
    catch (const Exception &e)
    {
        EXPECT_STREQ(e.what(), "/nonexistent/thing.stl: no such file");
    }
}

TEST(MeshLoader, ACoordinateBeyondTheLimitIsNamedAndOneWithinLoads)
{
    // Powers of two, exact in the float assimp reads: 2^42 (4.4e12) beyond MAX_MAGNITUDE, 2^39 (5.5e11) within.
    const std::string dir = (std::filesystem::temp_directory_path() /
                             ("meshgap_limit_" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(dir);
    auto write = [&](const std::string &name, const std::string &text)
    {
        std::ofstream(dir + "/" + name) << text;
        return dir + "/" + name;
    };
    const std::string beyond = write("beyond.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -4398046511104\n"
                                                   "f 1 2 3\nf 1 2 4\n");
    const std::string within = write("within.obj", "v 0 0 0\nv 549755813888 0 0\nv 0 1000000 0\nf 1 2 3\n");
    int errors = 0;
    try
    {
        loadMesh(beyond);
    }
    catch (const Exception &e)
    {
        ++errors;
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(beyond + ": ", 0), 0u) << what;
        EXPECT_NE(what.find("z = -4398046511104"), std::string::npos) << what;
        EXPECT_NE(what.find("beyond 1e12"), std::string::npos) << what;
    }
    EXPECT_EQ(errors, 1);
    const Mesh m = loadMesh(within);
    ASSERT_EQ(m.vertices.size(), 3u);
    EXPECT_EQ(m.bounds().max().x(), 549755813888.0);
    std::filesystem::remove_all(dir);
}
