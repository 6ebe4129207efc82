// The warm-started fast solver (WarmFast.h, "warm-fast") along paths, against the exact certified query on the
// same scene: the OMPL.app problems that ship a .path (cubicles, Easy, Twistycool) and the maps (.poses in order,
// then the cfg's goal), interpolated to --states states as bench/queries.cpp does, queried in order.
//
// Per state, interleaved: FCL distance (robot against the whole world), the warm certified query
// (Scene::distance, exact, one SceneWarmStart carried along), and warm-fast over the scene's obstacles (one
// WarmFastState per obstacle, obstacles visited nearest bounding sphere first and skipped once their sphere gap is
// at or above the best answer so far; a skipped obstacle's state stays valid: its drift is measured from the pose
// of its last query), alone and followed by the exact collision test (Scene::inCollision, which fast mode needs for
// its verdict). Reported: medians in µs and their ratios, the fast distance's error against the certified one on
// collision-free states (median, 90th percentile, max, and how many below it: must be 0), global searches, and the
// mean times (global searches included). --problems picks problems and maps by name (e.g. for a profile).
//
//   build/bench/meshgap_bench_warm_fast [--states 1000] [--data ../shared/data/omplapp] [--maps maps]
//       [--global-every 64] [--global-evaluations 40000] [--gap 0.5] [--budget-mib 512] [--sizing uniform|adaptive]
//       [--global-search multistart|comb-GA-wl] [--global-seeding random|clusters] [--problems a,b] [--csv FILE]

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <sstream>

#include "CliMain.h"
#include "FclOracle.h"
#include "PathInterpolation.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/WarmFast.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    template <typename F>
    double timed(F &&f)
    {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    double quantile(std::vector<double> v, double q)
    {
        if (v.empty())
            return std::nan("");
        std::sort(v.begin(), v.end());
        return v[std::min(v.size() - 1, static_cast<std::size_t>(q * double(v.size())))];
    }

    struct Sphere
    {
        Eigen::Vector3d center;
        double radius;
    };
    Sphere boundingSphere(const Body &body)
    {
        const Eigen::Vector3d c = body.surface().bounds().center();
        double r = 0.0;
        for (const Eigen::Vector3d &v : body.surface().vertices)
            r = std::max(r, (v - c).norm());
        return {c, r};
    }

    struct Problem
    {
        std::string name;
        ProblemConfig config;
        std::vector<Eigen::Isometry3d> path;
    };
}  // namespace

static int run(int argc, char **argv)
{
    // The defaults are the shared OMPL.app problems and the repository's maps, set when configured.
    std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp",
                maps = std::string(MESHGAP_SOURCE_DIR) + "/maps", csvFile, sizing = "uniform", problemsText,
                globalSeeding = "random", globalSearch = "multistart";
    std::size_t states = 1000;
    unsigned int globalEvery = WarmFast::DEFAULT_GLOBAL_EVERY, globalEvaluations = WarmFast::DEFAULT_GLOBAL_EVALUATIONS;
    double gap = WarmFast::DEFAULT_GAP_TOLERANCE, budgetMiB = 512;
    bool noPatch = false;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_warm_fast");
    cli.add_options()("help,h", "print this help")("data", po::value(&data), "folder with OMPL.app problems")(
        "maps", po::value(&maps), ("folder with meshgap's maps (default: " + maps + ")").c_str())(
        "states", po::value(&states), "states per path")(
        "global-every", po::value(&globalEvery), "warm-fast global_every")(
        "global-evaluations", po::value(&globalEvaluations), "warm-fast global_evaluations")(
        "global-seeding", po::value(&globalSeeding), "warm-fast global_seeding: random or clusters")(
        "global-search", po::value(&globalSearch), "warm-fast global_search: multistart or comb-GA-wl")("gap", po::value(&gap),
                                                                           "warm-fast gap_tolerance")(
        "budget-mib", po::value(&budgetMiB), "dense mesh-distance budget per body (MiB)")(
        "sizing", po::value(&sizing), "node meshes: uniform or adaptive")(
        "no-patch", po::bool_switch(&noPatch), "warm-fast without surface_patch (node distances)")(
        "problems", po::value(&problemsText), "only these problems and maps, comma separated (default: all)")(
        "csv", po::value(&csvFile), "CSV output");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    if (sizing != "uniform" && sizing != "adaptive")
        throw Exception("--sizing", "'" + sizing + "' is not uniform or adaptive");
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    BodyOptions options;
    options.distances.memoryBudgetBytes = static_cast<std::size_t>(budgetMiB * 1024 * 1024);
    if (sizing == "adaptive")
        options.sizing = GridSizing::ADAPTIVE;
    WarmFast solver;
    solver.setGlobalEvery(globalEvery);
    if (globalEvaluations == 0)
        throw Exception("--global-evaluations", "must be positive");
    solver.setGlobalEvaluations(globalEvaluations);
    if (!solver.params().setParam("global_seeding", globalSeeding))
        throw Exception("--global-seeding", "'" + globalSeeding + "' is not random or clusters");
    if (!solver.params().setParam("global_search", globalSearch))
        throw Exception("--global-search", "'" + globalSearch + "' is not multistart or comb-GA-wl");
    solver.setGapTolerance(gap);
    solver.setSurfacePatch(!noPatch);

    std::vector<Problem> problems;
    auto wanted = [&](const std::string &name)
    {
        if (problemsText.empty())
            return true;
        std::stringstream ss(problemsText);
        for (std::string item; std::getline(ss, item, ',');)
            if (item == name)
                return true;
        return false;
    };
    for (const char *name : {"cubicles", "Easy", "Twistycool"})
    {
        if (!wanted(name))
            continue;
        const fs::path cfg = fs::path(data) / (std::string(name) + ".cfg"),
                       path = fs::path(data) / (std::string(name) + ".path");
        if (!fs::exists(cfg) || !fs::exists(path))
        {
            std::fprintf(stderr, "skipping %s: %s or its .path not found\n", name, cfg.c_str());
            continue;
        }
        problems.push_back({name, readProblemConfig(cfg.string()), readPoses(path.string())});
    }
    if (fs::is_directory(maps))
    {
        std::vector<fs::path> dirs;
        for (const auto &entry : fs::directory_iterator(maps))
            if (entry.is_directory())
                dirs.push_back(entry.path());
        std::sort(dirs.begin(), dirs.end());
        for (const fs::path &dir : dirs)
        {
            const std::string name = dir.filename().string();
            if (!wanted(name))
                continue;
            const fs::path cfg = dir / (name + ".cfg"), poses = dir / (name + ".poses");
            if (!fs::exists(cfg) || !fs::exists(poses))
                continue;
            Problem p{name, readProblemConfig(cfg.string()), {}};
            LoadReport report;
            loadRobotMesh(p.config.robot, &report);
            for (Eigen::Isometry3d X : readPoses(poses.string()))
            {
                X.translate(report.omplAppCenter.value());
                p.path.push_back(X);
            }
            if (p.config.goal)
                p.path.push_back(*p.config.goal);
            problems.push_back(std::move(p));
        }
    }

    std::unique_ptr<std::ofstream> csv;
    if (!csvFile.empty())
    {
        csv = std::make_unique<std::ofstream>(csvFile);
        *csv << "problem,states,free,obstacles,fcl_us,warm_certified_us,warm_fast_us,warm_fast_max_us,warm_fast_collision_us,"
                "fast_to_certified,fast_collision_to_certified,fast_to_fcl,error_median,error_p90,error_max,"
                "below_exact,global_searches,warm_certified_mean_us,warm_fast_mean_us\n";
    }
    std::printf("warm-fast: global_every %u, global search %s of at most %u evaluations (seeding %s), gap_tolerance %g; sizing %s; dense budget %g MiB. Median µs per query "
                "(ratio to the warm certified query).\n\n",
                globalEvery, globalSearch.c_str(), globalEvaluations, globalSeeding.c_str(), gap, sizing.c_str(),
                budgetMiB);
    std::printf("| problem | states (free) | obstacles | nodes robot | FCL distance | warm certified | warm-fast | warm-fast max | "
                "warm-fast + exact collision | fast / FCL | error median / p90 / max | below exact | global "
                "searches | mean µs certified / warm-fast |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    for (const Problem &problem : problems)
    {
        const Mesh world = loadMesh(problem.config.world), robot = loadRobotMesh(problem.config.robot);
        const ScenePtr scene = Scene::fromMeshes(robot, world, options);
        for (const BodyConstPtr &o : scene->obstacles())
            o->distances();
        scene->robot().distances();
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        const std::size_t n = scene->obstacles().size();
        std::vector<Sphere> spheres;
        for (const BodyConstPtr &o : scene->obstacles())
            spheres.push_back(boundingSphere(*o));
        const Sphere robotSphere = boundingSphere(scene->robot());
        const std::vector<Eigen::Isometry3d> poses = bench::interpolatePath(problem.path, states);

        std::vector<WarmFastState> fastStates(n);
        std::vector<std::pair<double, std::size_t>> order(n);
        SceneWarmStart warm;
        SceneRequest certified;
        std::vector<double> tF, tW, tFast, tColl, errors;
        std::size_t below = 0, free = 0, triangleTests = 0, evaluations = 0;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const Eigen::Isometry3d &X = poses[i];
            SceneResult exact;
            double dF = 0.0, fast = std::numeric_limits<double>::infinity();
            bool colliding = false;
            tF.push_back(timed([&] { dF = test::fclDistance(fw, fr, X); }));
            tW.push_back(timed([&] { scene->distance(X, certified, warm, exact); }));
            const double tf = timed(
                [&]
                {
                    const Eigen::Vector3d c = X * robotSphere.center;
                    for (std::size_t o = 0; o < n; ++o)
                        order[o] = {(spheres[o].center - c).norm() - spheres[o].radius - robotSphere.radius, o};
                    std::sort(order.begin(), order.end());
                    for (const auto &[bound, o] : order)
                    {
                        if (bound >= fast)
                            break;
                        DistanceResult r;
                        solver.solveWarm(*scene->obstacles()[o], scene->robot(), X, fastStates[o], 1 + i, r);
                        fast = std::min(fast, r.distance);
                        triangleTests += r.triangleTests;
                        evaluations += r.evaluations;
                    }
                });
            tFast.push_back(tf);
            tColl.push_back(tf + timed([&] { colliding = scene->inCollision(X); }));
            (void)dF;
            if (!exact.inCollision && !colliding)
            {
                ++free;
                errors.push_back(fast / exact.distance - 1.0);
                below += fast < exact.distance - 1e-9 * (1.0 + exact.distance);
            }
        }
        std::size_t globals = 0;
        for (const WarmFastState &s : fastStates)
            globals += s.globalSearches;
        const double mF = 1e6 * quantile(tF, 0.5), mW = 1e6 * quantile(tW, 0.5), mFast = 1e6 * quantile(tFast, 0.5),
                     mColl = 1e6 * quantile(tColl, 0.5);
        const double e50 = quantile(errors, 0.5), e90 = quantile(errors, 0.9),
                     emax = errors.empty() ? std::nan("") : *std::max_element(errors.begin(), errors.end());
        const double maxFast = 1e6 * *std::max_element(tFast.begin(), tFast.end());
        // Means: a planner pays the mean, global searches included (the medians leave them out).
        auto mean = [](const std::vector<double> &t) { return 1e6 * std::accumulate(t.begin(), t.end(), 0.0) / t.size(); };
        const double meanW = mean(tW), meanFast = mean(tFast);
        std::printf("| %s | %zu (%zu) | %zu | %u | %.1f | %.1f | %.1f (**%.2f**) | %.0f | %.1f (**%.2f**) | %.2f | "
                    "%.2f%% / %.2f%% / %.1f%% | %zu | %zu | %.1f / %.1f (%.2f) |\n",
                    problem.name.c_str(), poses.size(), free, n, scene->robot().numNodes(), mF, mW, mFast, mFast / mW,
                    maxFast,
                    mColl, mColl / mW, mFast / mF, 100 * e50, 100 * e90, 100 * emax, below, globals, meanW, meanFast,
                    meanFast / meanW);
        std::fprintf(stderr, "%s: warm-fast per query: %.1f triangle tests, %.1f evaluations (global searches included)\n",
                     problem.name.c_str(), double(triangleTests) / poses.size(), double(evaluations) / poses.size());
        std::fflush(stdout);
        if (csv)
            *csv << problem.name << "," << poses.size() << "," << free << "," << n << "," << mF << "," << mW << ","
                 << mFast << "," << maxFast << "," << mColl << "," << mFast / mW << "," << mColl / mW << "," << mFast / mF << "," << e50
                 << "," << e90 << "," << emax << "," << below << "," << globals << "," << meanW << "," << meanFast
                 << "\n";
    }
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
