// OMPL.app's own problems (read from ../shared/data, skipped when absent): meshgap must load their meshes and place
// their robot exactly as OMPL.app does, or the problems' own solution paths collide (shared/DESIGN.md).

#include <gtest/gtest.h>

#include <filesystem>

#include "FclOracle.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    struct AppProblem
    {
        std::string name;
        ProblemConfig config;
        std::vector<Eigen::Isometry3d> path;
    };

    std::vector<AppProblem> problemsWithPaths()
    {
        std::vector<AppProblem> problems;
        const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
        for (const char *name : {"Easy", "cubicles", "Twistycool"})
            if (fs::exists(dir / (std::string(name) + ".cfg")) && fs::exists(dir / (std::string(name) + ".path")))
                problems.push_back({name, readProblemConfig((dir / (std::string(name) + ".cfg")).string()),
                                    readPoses((dir / (std::string(name) + ".path")).string())});
        return problems;
    }
}  // namespace

#ifdef MESHGAP_HAVE_FCL
TEST(OmplAppProblems, SolutionPathsAreCollisionFreeWithOurMeshesAndConventions)
{
    const auto problems = problemsWithPaths();
    if (problems.empty())
        GTEST_SKIP() << "OMPL.app problems not found under " << MESHGAP_SHARED_DATA_DIR << "; skipping";
    std::size_t uncenteredCollisions = 0;
    for (const AppProblem &p : problems)
    {
        const Mesh world = loadMesh(p.config.world), robot = loadRobotMesh(p.config.robot);
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        for (std::size_t i = 0; i < p.path.size(); ++i)
            EXPECT_FALSE(test::fclCollide(fw, fr, p.path[i])) << p.name << " state " << i;
        EXPECT_FALSE(test::fclCollide(fw, fr, p.config.start)) << p.name << " start";
        // Control: without OMPL.app's centre shift the same check must fail somewhere, or it checks nothing.
        const auto raw = test::fclModel(loadMesh(p.config.robot));
        for (const Eigen::Isometry3d &X : p.path)
            uncenteredCollisions += test::fclCollide(fw, raw, X);
    }
    EXPECT_GT(uncenteredCollisions, 0u);
}

TEST(OmplAppProblems, EnumerationAtStartIsNeverBelowTheExactDistance)
{
    const auto problems = problemsWithPaths();
    if (problems.empty())
        GTEST_SKIP() << "OMPL.app problems not found under " << MESHGAP_SHARED_DATA_DIR << "; skipping";
    for (const AppProblem &p : problems)
    {
        const Mesh world = loadMesh(p.config.world), robot = loadRobotMesh(p.config.robot);
        const BodyPtr a = Body::build(world), b = Body::build(robot);  // default grid size
        DistanceResult r;
        Enumeration().solve(*a, *b, p.config.start, DistanceRequest(), r);
        const double exact = test::fclDistance(test::fclModel(world), test::fclModel(robot), p.config.start);
        EXPECT_GE(r.distance, exact - 1e-9 * world.size()) << p.name;
        // Refinement brings nodes within a grid size of every surface point, so the node distance is close.
        EXPECT_LE(r.distance, exact + a->gridSize() + b->gridSize()) << p.name;
    }
}
#endif

TEST(OmplAppProblems, MeshesLoadWithPlausibleCounts)
{
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    if (!fs::exists(dir))
        GTEST_SKIP() << "OMPL.app problems not found at " << dir << "; skipping";
    for (const auto &entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".dae")
        {
            LoadReport report;
            const Mesh m = loadMesh(entry.path().string(), &report);
            EXPECT_GT(m.triangles.size(), 0u);
            // Welding never makes more vertices than assimp returned; SketchUp's doubled faces are dropped.
            EXPECT_LE(m.vertices.size(), report.rawVertices) << entry.path();
            EXPECT_EQ(m.triangles.size() + report.clean.degenerate + report.clean.duplicates, report.rawTriangles);
        }
}
