// meshgap_plan on control problems: a small kinematic car problem of its own and OMPL.app's BugTrap_dcar; every state
// of the written path is checked free here, by the exact distance from the scene at a pose built from the row.

#include <gtest/gtest.h>

#include <vector>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "CliRun.h"
#include "TestMeshes.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/MeshWriter.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{

    /** \brief The rows of a .path file. */
    std::vector<std::vector<double>> readRows(const std::string &file)
    {
        std::vector<std::vector<double>> rows;
        std::ifstream in(file);
        for (std::string line; std::getline(in, line);)
        {
            std::istringstream words(line);
            std::vector<double> row;
            for (double v; words >> v;)
                row.push_back(v);
            if (!row.empty())
                rows.push_back(row);
        }
        return rows;
    }

    /** \brief Every row of \e pathFile (x y theta, then the model's velocities, \e width numbers) lies in the cfg's
        volume and is free: the certified distance at the pose (x, y, 0) turned by theta about z is positive. The
        first row is the start. */
    void expectPathFree(const std::string &cfg, const std::string &pathFile, std::size_t width)
    {
        const ProblemConfig config = readProblemConfig(cfg);
        const OmplControlProblem problem = setupControlProblem(config, ClearanceChecker::Mode::CERTIFIED);
        const std::vector<std::vector<double>> rows = readRows(pathFile);
        ASSERT_GE(rows.size(), 2u);
        EXPECT_NEAR(rows.front()[0], config.start.translation().x(), 1e-12);
        EXPECT_NEAR(rows.front()[1], config.start.translation().y(), 1e-12);
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
            ASSERT_EQ(rows[i].size(), width) << i;
            EXPECT_TRUE(config.volume->contains(Eigen::Vector3d(rows[i][0], rows[i][1], 0.0))) << i;
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = Eigen::AngleAxisd(rows[i][2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
            X.translation() = Eigen::Vector3d(rows[i][0], rows[i][1], 0.0);
            SceneRequest request;
            SceneResult r;
            problem.scene->distance(X, request, r);
            EXPECT_GT(r.distance, 0.0) << "state " << i << " of " << rows.size();
        }
    }
}  // namespace

TEST(ControlPlanCli, KinematicCarAroundABoxHasAFreePath)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_control_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeObj(test::transformed(test::box(1.0, 1.0, 0.5, 1), test::translation(0, 0, 0.5)), (dir / "w.obj").string());
    writeObj(test::box(0.3, 0.15, 0.2, 1), (dir / "car.obj").string());
    const std::string cfg = (dir / "car.cfg").string();
    std::ofstream(cfg) << "[problem]\nname = box\nrobot = car.obj\nworld = w.obj\ncontrol = kinematic_car\n"
                          "start.x = -3\nstart.y = 0\nstart.theta = 0\ngoal.x = 3\ngoal.y = 0\ngoal.theta = 0\n"
                          "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n";
#ifdef __SANITIZE_ADDRESS__
    // OMPL 1.5.2's SST never frees the motions it prunes (their states and controls): LeakSanitizer would fail the
    // run on OMPL's leak, so the instrumented build plans with the other two.
    const std::vector<std::string> planners = {"kpiece", "rrt"};
#else
    const std::vector<std::string> planners = {"kpiece", "rrt", "sst"};
#endif
    for (const std::string &planner : planners)
    {
        const std::string out = (dir / (planner + ".path")).string();
        const test::CliRun r =
            test::runPlan("--cfg " + cfg + " --planner " + planner + " --time 2 --quiet --seed 3 --out " + out);
        ASSERT_TRUE(r.status == 0 || r.status == 2) << r.err;
        EXPECT_NE(r.out.find("problem         box (control: kinematic_car)"), std::string::npos) << r.out;
        ASSERT_TRUE(r.out.find("solved          yes (exact)") != std::string::npos ||
                    r.out.find("solved          approximate") != std::string::npos)
            << r.out;
        expectPathFree(cfg, out, 3);
        // The car got past the box towards the goal: its last state is nearer the goal than the start was.
        const std::vector<double> last = readRows(out).back();
        EXPECT_LT(std::hypot(last[0] - 3.0, last[1]), 6.0) << planner;
    }
    // Bad input: one error, exit 1.
    const test::CliRun unknown = test::runPlan("--cfg " + cfg + " --planner rrtconnect --time 1");
    EXPECT_EQ(unknown.status, 1);
    EXPECT_NE(unknown.err.find("not a control planner (a control problem is planned by one of: kpiece, rrt, est, "
                               "pdst, sst)"),
              std::string::npos)
        << unknown.err;
    const test::CliRun geometric = test::runPlan("--cfg " + cfg + " --objective length --time 1");
    EXPECT_EQ(geometric.status, 1);
    EXPECT_NE(geometric.err.find("applies to geometric problems only"), std::string::npos) << geometric.err;
    fs::remove_all(dir);
}

TEST(ControlPlanCli, BugTrapDynamicCarWritesAFreePath)
{
    const std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp";
    const std::string cfg = data + "/BugTrap_dcar.cfg";
    if (!fs::exists(cfg))
        GTEST_SKIP() << data << " is absent (OMPL.app's problems)";
    const std::string out = (fs::temp_directory_path() / ("meshgap_dcar_" + std::to_string(::getpid()) + ".path"));
    const test::CliRun r = test::runPlan("--cfg " + cfg + " --planner kpiece --time 5 --quiet --seed 1 --out " + out);
    ASSERT_TRUE(r.status == 0 || r.status == 2) << r.err;
    ASSERT_TRUE(r.out.find("solved          yes (exact)") != std::string::npos ||
                r.out.find("solved          approximate") != std::string::npos)
        << r.out;
    expectPathFree(cfg, out, 5);
    fs::remove(out);
}
