// Reliability of the paper's global searches across geometry: for every paper scene-pose in maps/
// (battery_fixture positions 1 and 2, hand_bowl, handshake) and for --poses poses of every OMPL.app problem in
// --data (the world as one body, the robot shifted by its OMPL.app centre, as `meshgap_distance --cfg` does; poses
// interpolated along the problem's .path, or from start to goal without one), run enumeration (the node-level
// minimum: its evaluations are the "pruned" cost; nodes A x nodes B is the unpruned one) and --runs seeds of each
// --algorithms solver. Success = the solver's distance equals enumeration's (1e-12 relative). Also the node
// minimum's excess over the exact surface distance (refineExact, cold).
//
// The node meshes: --sizing none (the meshes as given: the maps' paper node counts; OMPL.app meshes unrefined),
// uniform (BodyOptions' default grid, 1/25 of the body's size) or adaptive (adaptiveNodeSizes(), NodeSizing.h).
// An algorithm NAME:PARAM=VALUE sets a parameter of the solver (e.g. comb-GA-wl:seeding=clusters, CombGA.h).
// --population / --generations override comb-GA's Table I values, --scale-population sets N_pop from the node count
// (see bench/paper/README.md, "Reliability").
//
//   build/bench/meshgap_bench_reliability [--maps maps] [--data ../shared/data/omplapp] [--runs 20] [--poses 20]
//       [--sizing none|uniform|adaptive] [--algorithms comb-GA-wl,comb-SA-wl] [--problems a,b] [--csv FILE]
//
// Markdown rows on stdout (one per scene-pose and algorithm, then one per problem summing its poses), progress on
// stderr.

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "CliMain.h"
#include "PathInterpolation.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/distance/CombGA.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    using Clock = std::chrono::steady_clock;

    double median(std::vector<double> v)
    {
        if (v.empty())
            return std::nan("");
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    }

    struct Case
    {
        std::string problem;  ///< scene or OMPL.app problem
        std::string label;    ///< "pos 1", "pose 7/20", ...
        Eigen::Isometry3d X_AB;
    };

    /** \brief Totals over the poses of one problem, per algorithm. */
    struct Totals
    {
        std::size_t runs{0}, successes{0}, posesAllSuccessful{0}, poses{0};
        double evaluations{0.0}, enumEvaluations{0.0}, unpruned{0.0};
        double worstRate{1.0};
    };
}  // namespace

static int run(int argc, char **argv)
{
    std::string maps = std::string(MESHGAP_SOURCE_DIR) + "/maps";  // the repository's, set when configured
    std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp", sizing = "none", csvFile;
    std::string algorithmsText = "comb-GA-wl,comb-SA-wl", problemsText, scenesText = "battery_fixture,hand_bowl,handshake";
    int runs = 20, posesPerProblem = 20;
    unsigned int population = 0, generations = 0;
    double scalePopulation = 0.0;
    AdaptiveSizing rule;
    std::uint64_t seed = 1;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_reliability");
    cli.add_options()("help,h", "print this help")(
        "maps", po::value(&maps), ("maps folder (default: " + maps + ")").c_str())(
        "data", po::value(&data), "OMPL.app problems folder (skipped when absent)")(
        "runs", po::value(&runs), "seeds per scene-pose and algorithm")("seed", po::value(&seed), "first seed")(
        "poses", po::value(&posesPerProblem), "poses per OMPL.app problem")(
        "sizing", po::value(&sizing), "node meshes: none, uniform or adaptive")(
        "algorithms", po::value(&algorithmsText),
        "solvers, comma separated, each NAME[:PARAM=VALUE...] (e.g. comb-GA-wl:seeding=clusters)")(
        "scenes", po::value(&scenesText), "map scenes (empty: none)")(
        "problems", po::value(&problemsText), "OMPL.app problems (default: every .cfg; 'none': none)")(
        "population", po::value(&population), "comb-GA population (0: the default)")(
        "generations", po::value(&generations), "comb-GA G_max (0: the default)")(
        "scale-population", po::value(&scalePopulation),
        "comb-GA population = max(default, ceil(c * sqrt(nodes A x nodes B) / 100)) for c > 0")(
        "feature-fraction", po::value(&rule.featureFraction), "adaptive: h = this x local feature size")(
        "min-fraction", po::value(&rule.minFraction), "adaptive: smallest h / body size")(
        "max-fraction", po::value(&rule.maxFraction), "adaptive: largest h / body size")(
        "grading", po::value(&rule.grading), "adaptive: size growth per unit mesh distance")(
        "csv", po::value(&csvFile), "also write one CSV row per scene-pose and algorithm");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    if (sizing != "none" && sizing != "uniform" && sizing != "adaptive")
        throw Exception("--sizing", "'" + sizing + "' is not one of none, uniform, adaptive");
    if (runs < 1 || posesPerProblem < 1)
        throw Exception("--runs / --poses", "must be at least 1");
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    BodyOptions options;
    if (sizing == "none")
        options.gridSize = 0.0;
    else if (sizing == "adaptive")
    {
        options.sizing = GridSizing::ADAPTIVE;
        options.adaptive = rule;
    }
    const std::vector<std::string> algorithms = splitList(algorithmsText);
    std::vector<DistanceSolverPtr> solvers;
    for (const std::string &spec : algorithms)
    {
        // NAME[:PARAM=VALUE...], e.g. comb-GA-wl:seeding=clusters (the solver's ParamSet).
        std::vector<std::string> parts;
        std::stringstream ss(spec);
        for (std::string part; std::getline(ss, part, ':');)
            parts.push_back(part);
        solvers.push_back(allocSolver(parts[0]));
        for (std::size_t k = 1; k < parts.size(); ++k)
        {
            const std::size_t eq = parts[k].find('=');
            if (eq == std::string::npos ||
                !solvers.back()->params().setParam(parts[k].substr(0, eq), parts[k].substr(eq + 1)))
                throw std::runtime_error("--algorithms: '" + parts[k] + "' is not a valid PARAM=VALUE of " + parts[0]);
        }
    }

    // The bodies and poses of every problem.
    struct Problem
    {
        std::string name;
        Mesh a, b;
        std::vector<Case> cases;
    };
    std::vector<Problem> problems;
    for (const std::string &scene : splitList(scenesText))
    {
        const fs::path dir = fs::path(maps) / scene;
        Problem p{
            scene, loadMesh((dir / (scene + "_a.obj")).string()), loadMesh((dir / (scene + "_b.obj")).string()), {}};
        const auto poses = readPoses((dir / (scene + ".poses")).string());
        for (std::size_t k = 0; k < poses.size(); ++k)
            p.cases.push_back({scene, "pos " + std::to_string(k + 1), poses[k]});
        problems.push_back(std::move(p));
    }
    std::vector<std::string> names;
    if (problemsText != "none" && fs::is_directory(data))
    {
        if (problemsText.empty())
        {
            for (const auto &entry : fs::directory_iterator(data))
                if (entry.path().extension() == ".cfg")
                    names.push_back(entry.path().stem().string());
            std::sort(names.begin(), names.end());
        }
        else
            names = splitList(problemsText);
    }
    else if (problemsText != "none")
        std::fprintf(stderr, "no OMPL.app problems: %s is not a folder\n", data.c_str());
    std::vector<std::pair<std::string, std::string>> seen;  // (world, robot) already in the list
    for (const std::string &name : names)
    {
        const fs::path cfgPath = fs::path(data) / (name + ".cfg");
        const ProblemConfig cfg = readProblemConfig(cfgPath.string());
        if (std::find(seen.begin(), seen.end(), std::make_pair(cfg.world, cfg.robot)) != seen.end())
        {
            std::fprintf(stderr, "skipping %s: same meshes as a problem above\n", name.c_str());
            continue;
        }
        seen.emplace_back(cfg.world, cfg.robot);
        Problem p{name, loadMesh(cfg.world), loadRobotMesh(cfg.robot, cfg.planar), {}};
        std::vector<Eigen::Isometry3d> path;
        const fs::path pathFile = fs::path(data) / (name + ".path");
        if (fs::exists(pathFile))
            path = readPoses(pathFile.string());
        else
        {
            path.push_back(cfg.start);
            if (cfg.goal)
                path.push_back(*cfg.goal);
        }
        const auto poses = bench::interpolatePath(path, static_cast<std::size_t>(posesPerProblem));
        for (std::size_t k = 0; k < poses.size(); ++k)
            p.cases.push_back({name, "pose " + std::to_string(k + 1) + "/" + std::to_string(poses.size()), poses[k]});
        problems.push_back(std::move(p));
    }

    std::unique_ptr<std::ofstream> csv;
    if (!csvFile.empty())
    {
        csv = std::make_unique<std::ofstream>(csvFile);
        *csv << "sizing,problem,pose,nodes_a,nodes_b,population,algorithm,runs,successes,mean_evaluations,"
                "max_evaluations,enum_evaluations,unpruned,median_ms,node_distance,exact_distance\n";
    }
    if (sizing == "adaptive")
        std::printf("Adaptive rule: h = clamp(%g x feature size, %g x body size, %g x body size), grading %g.\n", rule.featureFraction,
                    rule.minFraction, rule.maxFraction, rule.grading);
    std::printf("Sizing: %s; %d seeds (%llu..%llu) per scene-pose and algorithm.\n\n", sizing.c_str(), runs,
                static_cast<unsigned long long>(seed), static_cast<unsigned long long>(seed + runs - 1));
    std::printf("| problem | pose | nodes A / B | node min / exact | algorithm | success | mean evaluations | "
                "/ pruned enumeration | / unpruned | median ms |\n|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    const auto start = Clock::now();
    std::vector<std::string> summaryRows;
    const DistanceSolverPtr enumeration = allocSolver("enumeration");
    for (const Problem &problem : problems)
    {
        const auto buildStart = Clock::now();
        const BodyPtr a = Body::build(problem.a, options), b = Body::build(problem.b, options);
        a->distances();
        b->distances();
        const double unpruned = double(a->numNodes()) * double(b->numNodes());
        unsigned int pop = population;
        if (scalePopulation > 0.0)
            pop = std::max(CombGA::DEFAULT_POPULATION,
                           static_cast<unsigned int>(std::ceil(scalePopulation * std::sqrt(unpruned) / 100.0)));
        for (std::size_t s = 0; s < solvers.size(); ++s)
            if (auto *ga = dynamic_cast<CombGA *>(solvers[s].get()))
            {
                ga->setPopulationSize(pop ? pop : CombGA::DEFAULT_POPULATION);
                ga->setGenerations(generations ? generations : CombGA::DEFAULT_GENERATIONS);
            }
        std::fprintf(stderr, "[%7.1f s] %s: A %u nodes, B %u nodes (%s), built in %.2f s\n",
                     std::chrono::duration<double>(Clock::now() - start).count(), problem.name.c_str(), a->numNodes(),
                     b->numNodes(), sizing.c_str(), std::chrono::duration<double>(Clock::now() - buildStart).count());
        std::vector<Totals> totals(solvers.size());
        for (const Case &c : problem.cases)
        {
            DistanceResult reference;
            enumeration->solve(*a, *b, c.X_AB, DistanceRequest(), reference);
            DistanceResult exact;
            refineExact(*a, *b, c.X_AB, exact);
            char nodeVsExact[96];
            if (exact.inCollision)
                std::snprintf(nodeVsExact, sizeof nodeVsExact, "%.4g / collision", reference.distance);
            else
                std::snprintf(nodeVsExact, sizeof nodeVsExact, "%.4g / %.4g (+%.1f%%)", reference.distance,
                              exact.distance, 100.0 * (reference.distance / exact.distance - 1.0));
            for (std::size_t s = 0; s < solvers.size(); ++s)
            {
                std::size_t successes = 0;
                double evaluations = 0.0, maxEvaluations = 0.0;
                std::vector<double> times;
                for (int i = 0; i < runs; ++i)
                {
                    DistanceRequest request;
                    request.seed = seed + static_cast<std::uint64_t>(i);
                    DistanceResult r;
                    solvers[s]->solve(*a, *b, c.X_AB, request, r);
                    successes += r.distance == reference.distance ||
                                 std::abs(r.distance - reference.distance) <= 1e-12 * std::abs(reference.distance);
                    evaluations += double(r.evaluations);
                    maxEvaluations = std::max(maxEvaluations, double(r.evaluations));
                    times.push_back(r.seconds);
                }
                const double mean = evaluations / runs;
                Totals &t = totals[s];
                t.runs += runs;
                t.successes += successes;
                t.poses += 1;
                t.posesAllSuccessful += successes == std::size_t(runs);
                t.worstRate = std::min(t.worstRate, double(successes) / runs);
                t.evaluations += mean;
                t.enumEvaluations += double(reference.evaluations);
                t.unpruned += unpruned;
                std::printf("| %s | %s | %u / %u | %s | %s | %zu/%d | %.4g | %.3g | %.3g | %.3f |\n",
                            problem.name.c_str(), c.label.c_str(), a->numNodes(), b->numNodes(), nodeVsExact,
                            algorithms[s].c_str(), successes, runs, mean, mean / double(reference.evaluations),
                            mean / unpruned, 1e3 * median(times));
                std::fflush(stdout);
                if (csv)
                    *csv << sizing << "," << problem.name << "," << c.label << "," << a->numNodes() << ","
                         << b->numNodes() << "," << (pop ? pop : CombGA::DEFAULT_POPULATION) << "," << algorithms[s]
                         << "," << runs << "," << successes << "," << mean << "," << maxEvaluations << ","
                         << reference.evaluations << "," << unpruned << "," << 1e3 * median(times) << ","
                         << reference.distance << "," << (exact.inCollision ? -1.0 : exact.distance) << "\n";
            }
        }
        for (std::size_t s = 0; s < solvers.size(); ++s)
        {
            const Totals &t = totals[s];
            char row[512];
            std::snprintf(row, sizeof row, "| %s | %zu | %u / %u | %s | %.1f%% | %.1f%% | %zu/%zu | %.3g | %.3g |",
                          problem.name.c_str(), t.poses, a->numNodes(), b->numNodes(), algorithms[s].c_str(),
                          100.0 * double(t.successes) / double(t.runs), 100.0 * t.worstRate, t.posesAllSuccessful,
                          t.poses, t.evaluations / t.enumEvaluations, t.evaluations / t.unpruned);
            summaryRows.push_back(row);
        }
    }
    std::printf("\nPer problem (success over all its poses and seeds; worst pose; poses where every seed succeeded; "
                "mean evaluations summed over the poses against enumeration's, pruned and unpruned):\n\n"
                "| problem | poses | nodes A / B | algorithm | success | worst pose | poses at 100%% | / pruned | "
                "/ unpruned |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string &row : summaryRows)
        std::printf("%s\n", row.c_str());
    std::fprintf(stderr, "total %.1f s\n", std::chrono::duration<double>(Clock::now() - start).count());
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
