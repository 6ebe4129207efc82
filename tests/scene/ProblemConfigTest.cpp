#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "meshgap/Exception.h"
#include "meshgap/scene/ProblemConfig.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    class ProblemConfigTest : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / ("meshgap_cfg_" + std::to_string(::getpid()));
            fs::create_directories(dir_ / "meshes");
            std::ofstream(dir_ / "meshes" / "r.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
            std::ofstream(dir_ / "meshes" / "w.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        }
        void TearDown() override { fs::remove_all(dir_); }

        std::string write(const std::string &text)
        {
            const std::string path = (dir_ / "p.cfg").string();
            std::ofstream(path) << text;
            return path;
        }

        // The message of the exception thrown reading \e text.
        std::string error(const std::string &text)
        {
            try
            {
                readProblemConfig(write(text));
            }
            catch (const Exception &e)
            {
                return e.what();
            }
            return "";
        }

        fs::path dir_;
    };

    const std::string GOOD = "[problem]\nname = demo\nrobot = meshes/r.obj\nworld = meshes/w.obj\n"
                             "start.x = 1\nstart.y = 2\nstart.z = 3\nstart.theta = 1.5707963267948966\n"
                             "start.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 1\n"
                             "goal.x = 4\ngoal.y = 5\ngoal.z = 6\ngoal.theta = 0\ngoal.axis.x = 1\ngoal.axis.y = 0\n"
                             "goal.axis.z = 0\nvolume.min.x = -1\nvolume.min.y = -1\nvolume.min.z = -1\n"
                             "volume.max.x = 10\nvolume.max.y = 10\nvolume.max.z = 10\n"
                             "[benchmark]\ntime_limit=5.0\n[planner]\nrrtstar=\nrrtstar.name=RRT*\nprm=\n";
}  // namespace

TEST_F(ProblemConfigTest, ReadsAGoodFile)
{
    const ProblemConfig c = readProblemConfig(write(GOOD));
    EXPECT_EQ(c.name, "demo");
    EXPECT_EQ(fs::path(c.robot), (dir_ / "meshes" / "r.obj").lexically_normal());
    EXPECT_TRUE(c.start.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
    EXPECT_TRUE((c.start.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
    ASSERT_TRUE(c.goal.has_value());
    EXPECT_TRUE(c.goal->translation().isApprox(Eigen::Vector3d(4, 5, 6)));
    ASSERT_TRUE(c.volume.has_value());
    EXPECT_EQ(c.volume->max(), Eigen::Vector3d(10, 10, 10));
    ASSERT_EQ(c.planners.size(), 3u);
    EXPECT_EQ(c.planners[1].first, "rrtstar.name");
    EXPECT_EQ(c.planners[1].second, "RRT*");
    EXPECT_EQ(c.benchmark[0].second, "5.0");
}

TEST_F(ProblemConfigTest, ErrorsNameFileLineAndProblem)
{
    const std::string file = (dir_ / "p.cfg").string();
    auto replaced = [](std::string s, const std::string &from, const std::string &to) {
        return s.replace(s.find(from), from.size(), to);
    };
    std::string e = error(replaced(GOOD, "start.y = 2", "start.y = two"));
    EXPECT_NE(e.find(file + ":6"), std::string::npos) << e;
    EXPECT_NE(e.find("start.y"), std::string::npos) << e;
    e = error(replaced(GOOD, "name = demo", "colour = red"));
    EXPECT_NE(e.find(file + ":2"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown key 'colour'"), std::string::npos) << e;
    e = error(replaced(GOOD, "robot = meshes/r.obj\n", ""));
    EXPECT_NE(e.find("missing required key 'robot'"), std::string::npos) << e;
    e = error(replaced(GOOD, "meshes/w.obj", "meshes/nothere.obj"));
    EXPECT_NE(e.find("nothere.obj"), std::string::npos) << e;
    EXPECT_NE(e.find(file + ":4"), std::string::npos) << e;
    e = error(replaced(GOOD, "[benchmark]", "[colours]"));
    EXPECT_NE(e.find("unknown section"), std::string::npos) << e;
    e = error(replaced(GOOD, "name = demo", "name demo"));
    EXPECT_NE(e.find("expected 'key = value'"), std::string::npos) << e;
    e = error(replaced(GOOD, "start.x = 1", "start.x = nan"));
    EXPECT_NE(e.find("start.x"), std::string::npos) << e;
    e = error(replaced(GOOD, "volume.max.x = 10\n", ""));
    EXPECT_NE(e.find("volume"), std::string::npos) << e;
    e = error(replaced(GOOD, "start.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 1",
                       "start.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 0"));
    EXPECT_NE(e.find("zero vector"), std::string::npos) << e;
    EXPECT_NE(error("").find("missing required key"), std::string::npos);
}

// OMPL.app's 2D problems (e.g. resources/2D/Maze_planar.cfg): no start.z, theta is the yaw, a 2D volume.
const std::string PLANAR = "[problem]\nname = maze\nrobot = meshes/r.obj\nworld = meshes/w.obj\n"
                           "start.x = 0.01\nstart.y = -0.15\nstart.theta = 0.0\n"
                           "goal.x = 41.01\ngoal.y = -0.15\ngoal.theta = 0.802851455917\n"
                           "volume.min.x = -55.0\nvolume.min.y = -54.0\nvolume.max.x = 55.0\nvolume.max.y = 56.0\n"
                           "[benchmark]\ntime_limit=20.0\n[planner]\nest=\n";

TEST_F(ProblemConfigTest, ReadsAPlanarFile)
{
    const ProblemConfig c = readProblemConfig(write(PLANAR));
    EXPECT_TRUE(c.planar);
    EXPECT_FALSE(readProblemConfig(write(GOOD)).planar);
    EXPECT_TRUE(c.start.translation().isApprox(Eigen::Vector3d(0.01, -0.15, 0)));
    ASSERT_TRUE(c.goal.has_value());
    EXPECT_TRUE(c.goal->translation().isApprox(Eigen::Vector3d(41.01, -0.15, 0)));
    // The yaw: a rotation about z by goal.theta.
    EXPECT_TRUE(c.goal->linear().isApprox(
        Eigen::AngleAxisd(0.802851455917, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
    ASSERT_TRUE(c.volume.has_value());
    EXPECT_EQ(c.volume->min(), Eigen::Vector3d(-55, -54, 0));
    EXPECT_EQ(c.volume->max(), Eigen::Vector3d(55, 56, 0));
}

TEST_F(ProblemConfigTest, PlanarErrorsNameTheLine)
{
    const std::string file = (dir_ / "p.cfg").string();
    auto replaced = [](std::string s, const std::string &from, const std::string &to) {
        return s.replace(s.find(from), from.size(), to);
    };
    std::string e = error(replaced(PLANAR, "goal.y = -0.15\n", "goal.y = -0.15\ngoal.z = 3\n"));
    EXPECT_NE(e.find(file + ":10"), std::string::npos) << e;
    EXPECT_NE(e.find("planar"), std::string::npos) << e;
    e = error(replaced(PLANAR, "start.theta = 0.0\n", "start.theta = 0.0\nstart.axis.z = 1\n"));
    EXPECT_NE(e.find(file + ":8"), std::string::npos) << e;
    e = error(replaced(PLANAR, "volume.max.y = 56.0\n", ""));
    EXPECT_NE(e.find("four keys"), std::string::npos) << e;
    e = error(replaced(PLANAR, "start.y = -0.15\n", ""));
    EXPECT_NE(e.find("missing required key 'start.y'"), std::string::npos) << e;
}

TEST(ProblemConfig, MissingFile)
{
    EXPECT_THROW(readProblemConfig("/nonexistent/x.cfg"), Exception);
}

TEST(ProblemConfig, ReadsEveryOmplAppProblem)
{
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    if (!fs::exists(dir))
        GTEST_SKIP() << "OMPL.app problems not found at " << dir << "; skipping";
    int read = 0;
    for (const auto &entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".cfg")
        {
            const ProblemConfig c = readProblemConfig(entry.path().string());
            EXPECT_TRUE(c.volume.has_value()) << entry.path();
            EXPECT_TRUE(c.goal.has_value()) << entry.path();
            EXPECT_FALSE(c.planners.empty()) << entry.path();
            // OMPL.app's control problems name their model; its geometric ones do not.
            EXPECT_EQ(c.control, entry.path().stem() == "BugTrap_dcar" ? "dynamic_car" : "") << entry.path();
            ++read;
        }
    EXPECT_GE(read, 5);
}

// OMPL.app's "control" key: a known model is kept, an unknown one named with its line and the known ones.
TEST_F(ProblemConfigTest, ControlModelIsReadAndAnUnknownOneRefused)
{
    std::string text = GOOD;
    text.insert(text.find("start.x"), "control = kinematic_car\n");
    EXPECT_EQ(readProblemConfig(write(text)).control, "kinematic_car");
    EXPECT_EQ(readProblemConfig(write(GOOD)).control, "");
    std::string bad = GOOD;
    bad.insert(bad.find("start.x"), "control = hovercraft\n");
    const std::string message = error(bad);
    EXPECT_NE(message.find("p.cfg:5"), std::string::npos) << message;
    EXPECT_NE(message.find("unknown control model 'hovercraft'"), std::string::npos) << message;
    EXPECT_NE(message.find("dynamic_car"), std::string::npos) << message;
}
