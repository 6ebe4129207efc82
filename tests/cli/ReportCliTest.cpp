// meshgap_report (and so the plan report meshgap_plan --report writes): the data the page reads back out of the
// HTML file. The robot poses and clearances, decoded from their base64 float32 arrays, against Scene::distance at
// those poses; the scene, decoded from its base64 glTF, imported with assimp (every obstacle and the robot, whole).
// The page itself is tested in headless Chromium (tests/python/test_report.py).

#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <assimp/Importer.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "CliRun.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    std::string base64Decode(const std::string &text)
    {
        std::string out;
        unsigned value = 0;
        int bits = 0;
        for (const char c : text)
        {
            const char *at = std::strchr("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/", c);
            if (c == '=' || at == nullptr || c == '\0')
                break;
            value = (value << 6) | unsigned(at - "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/");
            bits += 6;
            if (bits >= 8)
            {
                bits -= 8;
                out += char((value >> bits) & 0xff);
            }
        }
        return out;
    }

    /** \brief The string value of "key": "..." in the page's data. */
    std::string field(const std::string &html, const std::string &key)
    {
        const std::string open = "\"" + key + "\": \"";
        const std::size_t at = html.find(open);
        if (at == std::string::npos)
            return "";
        const std::size_t begin = at + open.size();
        return html.substr(begin, html.find('"', begin) - begin);
    }

    std::vector<float> floats(const std::string &html, const std::string &key)
    {
        const std::string bytes = base64Decode(field(html, key));
        std::vector<float> v(bytes.size() / sizeof(float));
        std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
        return v;
    }
}  // namespace

TEST(ReportCli, PageDataIsTheSceneAndTheExactClearanceAlongThePath)
{
    const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
    const ProblemConfig config = readProblemConfig(cfg);
    const fs::path dir = fs::temp_directory_path() / ("meshgap_report_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    // Start to goal in a straight line: through the wall, so both free and colliding states.
    std::ofstream(dir / "line.path") << formatPose(config.start) << "\n" << formatPose(*config.goal) << "\n";
    const std::string html = (dir / "report.html").string();
    const test::CliRun run = test::runExecutable(
        "meshgap_report", "--cfg " + cfg + " --path " + (dir / "line.path").string() + " --out " + html + " -q");
    // The report is written, and the tool says the path collides: one warning line, exit status 2.
    ASSERT_EQ(run.status, 2) << run.out << run.err;
    EXPECT_EQ(test::countLines(run.err, "warning: "), 1) << run.err;
    EXPECT_NE(run.err.find("the path collides"), std::string::npos) << run.err;
    std::stringstream text;
    text << std::ifstream(html).rdbuf();
    const std::string page = text.str();
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(page.find("THREE.OrbitControls"), std::string::npos);
    EXPECT_NE(page.find("GLTFLoader"), std::string::npos);

    const std::vector<float> poses = floats(page, "poses"), clearance = floats(page, "clearance"),
                             onA = floats(page, "onA");
    const std::string collide = base64Decode(field(page, "inCollision"));
    const std::size_t n = clearance.size();
    ASSERT_GT(n, 10u);
    ASSERT_EQ(poses.size(), 7 * n);
    ASSERT_EQ(onA.size(), 3 * n);
    ASSERT_EQ(collide.size(), n);
    EXPECT_NE(run.out.find("(" + std::to_string(n) + " dense states"), std::string::npos) << run.out;

    const ScenePtr scene = Scene::fromMeshes(loadRobotMesh(config.robot, config.planar), loadMesh(config.world));
    std::size_t colliding = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const float *p = &poses[7 * i];
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::Quaterniond(p[6], p[3], p[4], p[5]).normalized().toRotationMatrix();
        X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
        if (i == 0)
        {
            EXPECT_LT((X.translation() - config.start.translation()).norm(), 1e-3);
        }
        if (i + 1 == n)
        {
            EXPECT_LT((X.translation() - config.goal->translation()).norm(), 1e-3);
        }
        SceneWarmStart warm;
        SceneResult r;
        scene->distance(X, SceneRequest(), warm, r);
        // The page has float32 poses: the clearance moves by about the pose's rounding times the lever arm.
        EXPECT_NEAR(clearance[i], r.distance, 1e-3 * (1.0 + std::abs(r.distance))) << i;
        EXPECT_EQ(collide[i] != 0, r.inCollision) << i;
        colliding += r.inCollision;
    }
    EXPECT_GT(colliding, 0u);
    EXPECT_LT(colliding, n);

    const std::string glb = base64Decode(field(page, "glb"));
    Assimp::Importer importer;
    const aiScene *imported = importer.ReadFileFromMemory(glb.data(), glb.size(), 0, "glb");
    ASSERT_NE(imported, nullptr) << importer.GetErrorString();
    ASSERT_EQ(imported->mNumMeshes, scene->obstacles().size() + 1);
    const aiMesh &robot = *imported->mMeshes[imported->mNumMeshes - 1];
    EXPECT_EQ(std::string(robot.mName.C_Str()), "robot");
    EXPECT_EQ(robot.mNumFaces, scene->robot().surface().triangles.size());
    for (std::size_t i = 0; i < scene->obstacles().size(); ++i)
        EXPECT_EQ(imported->mMeshes[i]->mNumFaces, scene->obstacles()[i]->surface().triangles.size()) << i;
    fs::remove_all(dir);
}

// A single body is reported as a robot of one link: its .cfg and the same body given as a one-body robot problem
// (robot.1 = the same mesh, start.1.*, goal.1.*) give the same page data for the same path (poses, dense states,
// clearance, witnesses, the scene), so the single-body report takes the robot route.
TEST(ReportCli, ASingleBodyIsReportedAsARobotOfOneLink)
{
    const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
    const ProblemConfig config = readProblemConfig(cfg);
    const fs::path dir = fs::temp_directory_path() / ("meshgap_report_one_link_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "line.path") << formatPose(config.start) << "\n" << formatPose(*config.goal) << "\n";
    {
        std::ifstream in(cfg);
        std::ofstream out(dir / "one_body.cfg");
        for (std::string line; std::getline(in, line);)
        {
            if (line.rfind("robot =", 0) == 0)
                line = "robot.1 = " + config.robot;
            else if (line.rfind("world =", 0) == 0)
                line = "world = " + config.world;
            else if (line.rfind("start.", 0) == 0 || line.rfind("goal.", 0) == 0)
                line.insert(line.find('.') + 1, "1.");
            out << line << "\n";
        }
    }
    std::string pages[2];
    for (int k = 0; k < 2; ++k)
    {
        const std::string html = (dir / (std::to_string(k) + ".html")).string();
        const test::CliRun run =
            test::runExecutable("meshgap_report", "--cfg " + (k == 0 ? cfg : (dir / "one_body.cfg").string()) +
                                                      " --path " + (dir / "line.path").string() + " --out " + html +
                                                      " -q");
        ASSERT_EQ(run.status, 2) << run.out << run.err;  // the straight line goes through the wall
        std::stringstream text;
        text << std::ifstream(html).rdbuf();
        pages[k] = text.str();
    }
    for (const char *key : {"poses", "arcLength", "clearance", "inCollision", "onA", "onB", "glb"})
    {
        EXPECT_FALSE(field(pages[0], key).empty()) << key;
        EXPECT_EQ(field(pages[0], key), field(pages[1], key)) << key;
    }
    EXPECT_EQ(pages[0].find("\"links\""), std::string::npos);  // one link: no per-link arrays
    fs::remove_all(dir);
}

TEST(ReportCli, BadInputWritesNothing)
{
    const std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/hand_bowl/hand_bowl.cfg";
    const fs::path dir = fs::temp_directory_path() / ("meshgap_report_bad_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "short.path") << "1 2 3 0 0 0 1\n4 5 6\n";
    std::ofstream(dir / "norm.path") << "1 2 3 0 0 0 1\n4 5 6 0 0 0 1.5\n";  // a quaternion not of unit length
    const std::string out = (dir / "r.html").string();
    for (const std::string &args :
         {"--cfg " + cfg + " --path " + (dir / "short.path").string() + " --out " + out,
          "--cfg " + cfg + " --path " + (dir / "norm.path").string() + " --out " + out,
          "--cfg " + cfg + " --path " + (dir / "none.path").string() + " --out " + out,
          "--cfg " + cfg + " --path " + (dir / "short.path").string() + " --out " + out + " --dense 0",
          "--cfg " + cfg + " --out " + out})
    {
        const test::CliRun run = test::runExecutable("meshgap_report", args);
        EXPECT_EQ(run.status, 1) << args << run.err;
        EXPECT_EQ(test::countLines(run.err, "error: "), 1) << run.err;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // the two paths only
    fs::remove_all(dir);
}
