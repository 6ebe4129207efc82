// Enumeration on the OMPL.app problems at their start poses: node counts, time (median of repeated runs), the share
// of node pairs evaluated after exact pruning, and the node distance against FCL's exact mesh distance, both on the
// meshes as they are and refined to the default grid size.
//
//   build/bench/meshgap_bench_enumeration [--data ../shared/data/omplapp] [--repeats 15]

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <ompl/util/Console.h>

#include "CliMain.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#ifdef MESHGAP_HAVE_FCL
#include "FclOracle.h"
#endif

using namespace meshgap;
namespace fs = std::filesystem;

static int run(int argc, char **argv)
{
    std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp";
    int repeats = 15;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_enumeration");
    cli.add_options()("help,h", "print this help")("data", po::value(&data),
                                                   ("folder with OMPL.app .cfg files (default: " + data + ")").c_str())(
        "repeats", po::value(&repeats), "timed runs per problem (median reported)");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    if (!fs::exists(data))
    {
        std::fprintf(stderr, "no OMPL.app data at %s\n", data.c_str());
        return 1;
    }
    std::vector<fs::path> cfgs;
    for (const auto &entry : fs::directory_iterator(data))
        if (entry.path().extension() == ".cfg")
            cfgs.push_back(entry.path());
    std::sort(cfgs.begin(), cfgs.end());

    std::printf("| problem | grid | world nodes | robot nodes | pairs evaluated | enumeration median | node distance | "
                "exact (FCL) | node / exact - 1 |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const fs::path &cfg : cfgs)
    {
        const ProblemConfig problem = readProblemConfig(cfg.string());
        const Mesh world = loadMesh(problem.world), robot = loadRobotMesh(problem.robot);
        double exact = std::nan("");
#ifdef MESHGAP_HAVE_FCL
        exact = test::fclDistance(test::fclModel(world), test::fclModel(robot), problem.start);
#endif
        for (bool refine : {false, true})
        {
            BodyOptions options;
            options.gridSize = refine ? -1.0 : 0.0;
            const BodyPtr a = Body::build(world, options), b = Body::build(robot, options);
            std::vector<double> times;
            DistanceResult r;
            for (int k = 0; k < repeats; ++k)
            {
                Enumeration().solve(*a, *b, problem.start, DistanceRequest(), r);
                times.push_back(r.seconds);
            }
            std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
            const double all = double(a->numNodes()) * b->numNodes();
            std::printf("| %s | %s | %u | %u | %.2f%% of %.3g | %.3f ms | %.6g | %.6g | %+.1f%% |\n",
                        problem.name.c_str(), refine ? "auto (1/25 size)" : "none", a->numNodes(), b->numNodes(),
                        100.0 * r.evaluations / all, all, times[times.size() / 2] * 1e3, r.distance, exact,
                        100.0 * (r.distance / exact - 1.0));
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
