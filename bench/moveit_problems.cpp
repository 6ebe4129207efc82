// MotionBenchMaker's problems as shipped (problems.tar.bz2: problems/<scenario>/sceneNNNN.yaml + requestNNNN.yaml,
// MoveIt planning scenes and motion plan requests), every one read by readMoveItProblem() straight from the archive
// (extracted to a temporary folder, not a byte changed), and its start and goal checked: meshgap's exact whole-robot
// collision verdict and clearance, and FCL 0.7's verdict on the same meshes and pairs (as MoveIt checks a state:
// FCL, every link against the world and the self pairs the SRDF and the scene's allowed collision matrix leave).
// Prints one line per scenario (problems read, starts and goals valid by meshgap and by FCL, the least start or goal
// clearance, reading time) and the total; exit status 0 when every problem reads and every start and goal is valid.
//
//   build/bench/meshgap_bench_moveit_problems [--data ../shared/data/mbm/ur5] [--robot ur5] [--limit N]

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <unistd.h>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotScene.h"
#ifdef MESHGAP_HAVE_FCL
#include "FclOracle.h"
#endif

using namespace meshgap;
namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace
{
    /** \brief One scenario's tally. */
    struct Tally
    {
        std::size_t problems{0}, valid{0}, fclValid{0};
        double least{std::numeric_limits<double>::infinity()}, seconds{0.0};
    };

#ifdef MESHGAP_HAVE_FCL
    using Models = std::vector<std::shared_ptr<test::FclModel>>;
#else
    using Models = std::vector<int>;
#endif

    /** \brief FCL's verdict at \e q (the models of the links and of the obstacles): a link against an obstacle it
        is checked against, or a self pair. */
    bool fclCollides(const RobotScene &scene, const Models &links, const Models &obstacles,
                     const std::vector<double> &q)
    {
#ifdef MESHGAP_HAVE_FCL
        const std::vector<Eigen::Isometry3d> poses = scene.robot().linkPoses(q);
        for (std::size_t l = 0; l < links.size(); ++l)
            for (std::size_t o : scene.linkObstacles(l))
                if (test::fclCollide(obstacles[o], links[l], poses[l]))
                    return true;
        for (const auto &[x, y] : scene.selfPairs())
            if (test::fclCollide(links[x], links[y], poses[x].inverse() * poses[y]))
                return true;
#else
        (void)scene;
        (void)links;
        (void)obstacles;
        (void)q;
#endif
        return false;
    }

    /** \brief Read one problem and check its start and goal into \e tally; false when either collides. */
    bool checkProblem(const MoveItFiles &files, const Models &links, Tally &tally)
    {
        const auto begin = std::chrono::steady_clock::now();
        const RobotProblem p = readMoveItProblem(files);
        tally.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        ++tally.problems;
        if (!p.goal)
            throw Exception(files.request, "no goal");
        const RobotScene scene(p.robot, p.obstacles, p.allowedObstacles);
        Models obstacles;
#ifdef MESHGAP_HAVE_FCL
        for (const BodyConstPtr &o : scene.obstacles())
            obstacles.push_back(test::fclModel(o->surface()));
#endif
        bool valid = true, fclValid = true;
        for (const std::vector<double> *q : {&p.start, &*p.goal})
        {
            RobotResult r;
            scene.distance(*q, RobotRequest(), r);
            tally.least = std::min(tally.least, r.distance);
            valid = valid && !r.inCollision;
            fclValid = fclValid && !fclCollides(scene, links, obstacles, *q);
            if (r.inCollision)
                std::printf("  %s: %s in collision (%g)\n", files.scene.c_str(), q == &p.start ? "start" : "goal",
                            r.distance);
        }
        tally.valid += valid;
        tally.fclValid += fclValid;
        return valid && fclValid;
    }

    int run(int argc, char **argv)
    {
        std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/mbm/ur5", robot = "ur5";
        std::size_t limit = 0;
        po::options_description options("meshgap_bench_moveit_problems [--data DIR] [--robot NAME] [--limit N]");
        options.add_options()("help,h", "print this help")(
            "data", po::value(&data), "folder of ROBOT.urdf, ROBOT.srdf, meshes/ and problems.tar.bz2")(
            "robot", po::value(&robot), "the robot's file stem (default ur5)")(
            "limit", po::value(&limit), "problems per scenario (default: all)")("quiet,q", "errors only");
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, options, vm))
            return 0;
        const fs::path archive = fs::path(data) / "problems.tar.bz2";
        if (!fs::exists(archive))
            throw Exception(archive.string(), "not found: MotionBenchMaker's problems are not there");
        const fs::path dir = fs::temp_directory_path() / ("meshgap_mbm_bench_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        const std::string command = "tar -xjf '" + archive.string() + "' -C '" + dir.string() + "'";
        if (std::system(command.c_str()) != 0)
            throw Exception(archive.string(), "tar cannot extract it");
        MoveItFiles base;
        base.urdf = (fs::path(data) / (robot + ".urdf")).string();
        base.srdf = (fs::path(data) / (robot + ".srdf")).string();
        base.robot = readMoveItRobot(base);  // once: every problem takes a copy
        Models links;
#ifdef MESHGAP_HAVE_FCL
        for (const RobotLink &link : base.robot->links())
            links.push_back(test::fclModel(link.body->surface()));
#endif
        std::map<std::string, Tally> tallies;
        bool ok = true;
        for (const fs::directory_entry &folder : fs::directory_iterator(dir / "problems"))
            for (std::size_t n = 1; limit == 0 || n <= limit; ++n)
            {
                char stem[16];
                std::snprintf(stem, sizeof stem, "%04zu.yaml", n);
                MoveItFiles files = base;
                files.scene = (folder.path() / ("scene" + std::string(stem))).string();
                files.request = (folder.path() / ("request" + std::string(stem))).string();
                if (!fs::exists(files.scene))
                    break;
                ok = checkProblem(files, links, tallies[folder.path().filename().string()]) && ok;
            }
        fs::remove_all(dir);
        Tally total;
        std::printf("| scenario | problems read | start and goal valid (meshgap) | (FCL) | least clearance | read s |\n"
                    "|---|---|---|---|---|---|\n");
        for (const auto &[name, t] : tallies)
        {
            std::printf("| %s | %zu | %zu | %zu | %.4g | %.2f |\n", name.c_str(), t.problems, t.valid, t.fclValid,
                        t.least, t.seconds);
            total.problems += t.problems;
            total.valid += t.valid;
            total.fclValid += t.fclValid;
            total.least = std::min(total.least, t.least);
            total.seconds += t.seconds;
        }
        std::printf("| all | %zu | %zu | %zu | %.4g | %.2f |\n", total.problems, total.valid, total.fclValid,
                    total.least, total.seconds);
        return ok ? 0 : 3;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
