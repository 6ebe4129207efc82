// The C++ side of the Python module's batch timing (bench/python_batch.py): Scene::distance over the poses of a
// .path file, in order, with one warm start carried from pose to pose (the "warm certified" column of
// meshgap_bench_queries), repeated; prints the wall time per query of each pass in microseconds, then the median.
//
//   build/bench/meshgap_bench_path_loop [--cfg problem.cfg --poses poses.path] [--repeat 5] [--exact 1]

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <ompl/util/Console.h>

#include "CliMain.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace po = boost::program_options;

static int run(int argc, char **argv)
{
    // The defaults: the repository's hand_bowl map and its poses (set when configured).
    std::string cfg = std::string(MESHGAP_SOURCE_DIR) + "/maps/hand_bowl/hand_bowl.cfg",
                posesFile = std::string(MESHGAP_SOURCE_DIR) + "/maps/hand_bowl/hand_bowl.poses";
    unsigned repeat = 5;
    bool exact = true;
    po::options_description options("meshgap_bench_path_loop [--cfg FILE --poses FILE] [options]");
    options.add_options()("help,h", "print this help")(
        "cfg", po::value(&cfg), ("OMPL.app problem file (default: " + cfg + ")").c_str())(
        "poses", po::value(&posesFile), ("poses, one a line as in a .path file (default: " + posesFile + ")").c_str())(
        "repeat", po::value(&repeat), "timed passes (default 5)")(
        "exact", po::value(&exact), "1: certified distance, 0: the fast one (default 1)");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, options, vm))
        return 0;
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    try
    {
        const ProblemConfig config = readProblemConfig(cfg);
        const ScenePtr scene =
            Scene::fromMeshes(loadRobotMesh(config.robot, config.planar), loadMesh(config.world));
        const std::vector<Eigen::Isometry3d> poses = readPoses(posesFile);
        SceneRequest request;
        request.exact = exact;
        std::vector<double> perQuery, cpuPerQuery;
        double sink = 0.0;
        for (unsigned r = 0; r < repeat; ++r)
        {
            SceneWarmStart warm;
            SceneResult result;
            const auto start = std::chrono::steady_clock::now();
            const std::clock_t cpuStart = std::clock();
            for (const Eigen::Isometry3d &X : poses)
            {
                scene->distance(X, request, warm, result);
                sink += result.distance;
            }
            perQuery.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                               double(poses.size()) * 1e6);
            cpuPerQuery.push_back(double(std::clock() - cpuStart) / CLOCKS_PER_SEC / double(poses.size()) * 1e6);
            std::printf("pass %u: %.3f us/query wall, %.3f us/query CPU\n", r + 1, perQuery.back(),
                        cpuPerQuery.back());
        }
        std::sort(perQuery.begin(), perQuery.end());
        std::sort(cpuPerQuery.begin(), cpuPerQuery.end());
        std::printf("median %.3f us/query wall, cpu %.3f us/query over %zu poses (checksum %.6g)\n",
                    perQuery[perQuery.size() / 2], cpuPerQuery[cpuPerQuery.size() / 2], poses.size(), sink);
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
