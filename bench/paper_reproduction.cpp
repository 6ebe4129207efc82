// The experiments of the paper's Section IV (shared/paper/combinatorial-min-distance.md, Tables III, V, VI and the
// time histories of Figs. 7, 8, 10, 11, 13, 14) on the three generated scenes in maps/: for each scene and pose,
// enumeration (the node-level minimum, timed as the median of 5 runs) and N independent runs of comb-GA-wl,
// comb-GA-nl, comb-SA-wl and comb-SA-nl with Table I's parameters (the solvers' defaults), seeds S..S+N-1.
//
// Prints a Markdown summary table on stdout, progress on stderr, and writes into --out:
//   results.csv                    one row per scene, pose and algorithm (enumeration included), and one for the
//                                  --climbs hill climbs from random starts (the local minima at node level)
//   history_<scene>_pos<k>.csv     per-iteration best distance of every algorithm: the median run's and the
//                                  per-iteration median and 10th/90th percentiles across all runs
// bench/plot_paper.py turns these into the figures.
//
//   build/bench/meshgap_bench_paper_reproduction [--maps maps] [--runs 100] [--seed 1] [--out paper_results]
//       [--climbs 10000] [--scenes battery_fixture,hand_bowl,handshake]
//       [--algorithms comb-GA-wl,comb-GA-nl,comb-SA-wl,comb-SA-nl]

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#ifdef MESHGAP_HAVE_FCL
#include "FclOracle.h"
#endif

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    using Clock = std::chrono::steady_clock;

    /** \brief What one run of one algorithm gave. */
    struct Run
    {
        double distance;
        std::size_t evaluations;
        std::size_t iterations;
        std::size_t localSteps;
        std::size_t convergedAt;
        double seconds;
        bool success;       ///< the enumeration minimum (within 1e-12 relative)
        bool globalRegion;  ///< both nodes near the enumeration's (see inGlobalRegion())
        bool globalBasin;   ///< a hill climb from the answer reaches the enumeration minimum
        std::vector<double> history;
    };

    /** \brief One row of results.csv and of the Markdown table. */
    struct Summary
    {
        std::string scene;
        int pose{0};
        std::string algorithm;
        std::size_t runs{0};
        std::uint32_t nodesA{0}, nodesB{0};
        double exact{std::nan("")};
        double enumDistance{0.0}, enumMs{0.0};
        double successRate{0.0}, regionRate{0.0}, basinRate{0.0};
        double meanDistance{0.0}, bestDistance{0.0}, medianDistance{0.0}, worstDistance{0.0};
        double meanEvaluations{0.0}, meanKflops{0.0}, meanLocalSteps{0.0}, meanIterations{0.0};
        double convergedMean{0.0}, convergedMedian{0.0}, convergedMax{0.0};
        double medianMs{0.0}, meanMs{0.0};
        std::size_t distinctMinima{0};  ///< multistart hill climb only: distinct node pairs it ended at
    };

    double elapsed(Clock::time_point since)
    {
        return std::chrono::duration<double>(Clock::now() - since).count();
    }

    double median(std::vector<double> v)
    {
        if (v.empty())
            return std::nan("");
        std::sort(v.begin(), v.end());
        const std::size_t n = v.size();
        return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    }

    /** \brief The q-quantile of \e v (linear interpolation between order statistics). */
    double quantile(std::vector<double> v, double q)
    {
        std::sort(v.begin(), v.end());
        const double pos = q * static_cast<double>(v.size() - 1);
        const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
        const std::size_t hi = std::min(lo + 1, v.size() - 1);
        return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
    }

    /** \brief Fraction of a body's largest mesh distance max(D) that bounds the global region. */
    constexpr double REGION_FRACTION = 0.1;

    /** \brief The paper's "global region" column, made precise: each node of \e found is within REGION_FRACTION
        max(D) of mesh distance (on its own body, so in the same connected component) of the enumeration's node. */
    bool inGlobalRegion(const Body &a, const Body &b, const NodePair &found, const NodePair &reference)
    {
        const MeshDistances &da = a.distances(), &db = b.distances();
        return da.distance(found.a, reference.a) <= REGION_FRACTION * da.maxDistance() &&
               db.distance(found.b, reference.b) <= REGION_FRACTION * db.maxDistance();
    }

    bool sameDistance(double d, double reference)
    {
        return d == reference || std::abs(d - reference) <= 1e-12 * std::abs(reference);
    }

    /** \brief Index of the median run: runs sorted by final distance, ties by evaluations, element (N - 1) / 2. */
    std::size_t medianRun(const std::vector<Run> &runs)
    {
        std::vector<std::size_t> order(runs.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t p, std::size_t q)
                         {
                             if (runs[p].distance != runs[q].distance)
                                 return runs[p].distance < runs[q].distance;
                             return runs[p].evaluations < runs[q].evaluations;
                         });
        return order[(order.size() - 1) / 2];
    }

    Summary summarize(const std::vector<Run> &runs)
    {
        Summary s;
        s.runs = runs.size();
        std::vector<double> distances, converged, ms;
        for (const Run &r : runs)
        {
            s.successRate += r.success ? 1.0 : 0.0;
            s.regionRate += r.globalRegion ? 1.0 : 0.0;
            s.basinRate += r.globalBasin ? 1.0 : 0.0;
            s.meanDistance += r.distance;
            s.meanEvaluations += static_cast<double>(r.evaluations);
            s.meanLocalSteps += static_cast<double>(r.localSteps);
            s.meanIterations += static_cast<double>(r.iterations);
            s.meanMs += 1e3 * r.seconds;
            distances.push_back(r.distance);
            converged.push_back(static_cast<double>(r.convergedAt));
            ms.push_back(1e3 * r.seconds);
        }
        const double n = static_cast<double>(runs.size());
        s.successRate /= n;
        s.regionRate /= n;
        s.basinRate /= n;
        s.meanDistance /= n;
        s.meanEvaluations /= n;
        s.meanLocalSteps /= n;
        s.meanIterations /= n;
        s.meanMs /= n;
        s.meanKflops = s.meanEvaluations * DistanceResult::FLOPS_PER_EVALUATION / 1e3;
        s.bestDistance = *std::min_element(distances.begin(), distances.end());
        s.worstDistance = *std::max_element(distances.begin(), distances.end());
        s.medianDistance = median(distances);
        for (double c : converged)
            s.convergedMean += c / n;
        s.convergedMedian = median(converged);
        s.convergedMax = *std::max_element(converged.begin(), converged.end());
        s.medianMs = median(ms);
        return s;
    }

    /** \brief Appends one algorithm's rows to a history CSV: every iteration's best distance of the median run and
        the median, 10th and 90th percentiles over all runs (histories are padded with their last value when runs
        stopped early, which only an evaluation cap can cause). */
    void writeHistory(std::ofstream &out, const std::string &algorithm, const std::vector<Run> &runs)
    {
        std::size_t length = 0;
        for (const Run &r : runs)
            length = std::max(length, r.history.size());
        const Run &mid = runs[medianRun(runs)];
        std::vector<double> column(runs.size());
        for (std::size_t it = 0; it < length; ++it)
        {
            for (std::size_t k = 0; k < runs.size(); ++k)
            {
                const auto &h = runs[k].history;
                column[k] = h.empty() ? runs[k].distance : h[std::min(it, h.size() - 1)];
            }
            const double midValue =
                mid.history.empty() ? mid.distance : mid.history[std::min(it, mid.history.size() - 1)];
            char line[256];
            std::snprintf(line, sizeof(line), "%s,%zu,%.10g,%.10g,%.10g,%.10g\n", algorithm.c_str(), it, midValue,
                          median(column), quantile(column, 0.1), quantile(column, 0.9));
            out << line;
        }
    }

    std::string csvHeader()
    {
        return "scene,pose,algorithm,nodes_a,nodes_b,runs,exact_distance,enumeration_distance,enumeration_ms,"
               "success_rate,global_region_rate,global_basin_rate,best_distance,mean_distance,median_distance,worst_"
               "distance,"
               "mean_evaluations,mean_kflops,mean_local_steps,mean_iterations,converged_mean,converged_median,"
               "converged_max,median_ms,mean_ms,distinct_minima\n";
    }

    std::string csvRow(const Summary &s)
    {
        char line[1024];
        std::snprintf(line, sizeof(line),
                      "%s,%d,%s,%u,%u,%zu,%.10g,%.17g,%.6g,%.4f,%.4f,%.4f,%.17g,%.17g,%.17g,%.17g,%.6g,%.6g,%.6g,%.6g,"
                      "%.4g,%.4g,%.4g,%.6g,%.6g,%s\n",
                      s.scene.c_str(), s.pose, s.algorithm.c_str(), s.nodesA, s.nodesB, s.runs, s.exact, s.enumDistance,
                      s.enumMs, s.successRate, s.regionRate, s.basinRate, s.bestDistance, s.meanDistance,
                      s.medianDistance, s.worstDistance, s.meanEvaluations, s.meanKflops, s.meanLocalSteps,
                      s.meanIterations, s.convergedMean, s.convergedMedian, s.convergedMax, s.medianMs, s.meanMs,
                      s.distinctMinima == 0 ? "" : std::to_string(s.distinctMinima).c_str());
        return line;
    }

    void printTableHeader()
    {
        std::printf(
            "| scene | pos | algorithm | success | global region | global basin | mean distance | worst distance | "
            "mean evaluations | mean kflops | convergedAt mean / median / max | median time per run |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    }

    void printTableRow(const Summary &s)
    {
        if (s.algorithm == "enumeration")
        {
            std::printf("| %s | %d | enumeration | exact | | | %.6g | | %.4g | %.4g | | %.3f ms |\n", s.scene.c_str(),
                        s.pose, s.enumDistance, s.meanEvaluations, s.meanKflops, s.enumMs);
            return;
        }
        std::printf(
            "| %s | %d | %s | %.0f%% | %.0f%% | %.0f%% | %.6g | %.6g | %.4g | %.4g | %.3g / %.3g / %.3g | %.3f ms |\n",
            s.scene.c_str(), s.pose, s.algorithm.c_str(), 100.0 * s.successRate, 100.0 * s.regionRate,
            100.0 * s.basinRate, s.meanDistance, s.worstDistance, s.meanEvaluations, s.meanKflops, s.convergedMean,
            s.convergedMedian, s.convergedMax, s.medianMs);
    }
}  // namespace

static int run(int argc, char **argv)
{
    std::string maps = std::string(MESHGAP_SOURCE_DIR) + "/maps";  // the repository's, set when configured
    std::string out = "paper_results";
    std::string scenesText = "battery_fixture,hand_bowl,handshake";
    std::string algorithmsText = "comb-GA-wl,comb-GA-nl,comb-SA-wl,comb-SA-nl";
    int runsCount = 100;
    int climbs = 10000;
    std::uint64_t seed = 1;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_paper_reproduction");
    cli.add_options()("help,h", "this help")(
        "maps", po::value(&maps), ("folder with the scenes (default: " + maps + ")").c_str())(
        "runs", po::value(&runsCount), "independent runs per algorithm and pose")(
        "climbs", po::value(&climbs), "hill climbs from random starts per pose, to map the local minima (0: none)")(
        "seed", po::value(&seed), "seed of the first run; run i uses seed + i")(
        "out", po::value(&out), "folder for results.csv and history_*.csv")(
        "scenes", po::value(&scenesText), "comma-separated scene names")("algorithms", po::value(&algorithmsText),
                                                                         "comma-separated algorithm names");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    if (runsCount < 1 || climbs < 0)
        throw Exception("--runs / --climbs", "--runs must be at least 1 and --climbs not negative");
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const std::vector<std::string> scenes = splitList(scenesText), algorithms = splitList(algorithmsText);
    std::vector<DistanceSolverPtr> solvers;
    for (const std::string &name : algorithms)
        solvers.push_back(allocSolver(name));
    fs::create_directories(out);
    std::ofstream results(fs::path(out) / "results.csv");
    results << csvHeader();

    const auto startAll = Clock::now();
    std::vector<Summary> summaries;
    for (const std::string &scene : scenes)
    {
        const fs::path dir = fs::path(maps) / scene;
        const Mesh meshA = loadMesh((dir / (scene + "_a.obj")).string());
        const Mesh meshB = loadMesh((dir / (scene + "_b.obj")).string());
        const std::vector<Eigen::Isometry3d> poses = readPoses((dir / (scene + ".poses")).string());
        BodyOptions options;
        options.gridSize = 0.0;  // the meshes exactly as generated (the paper's node counts)
        const auto buildStart = Clock::now();
        const BodyPtr a = Body::build(meshA, options), b = Body::build(meshB, options);
        // D and P are built on first use; build them here so that no run's time includes them.
        a->distances();
        b->distances();
        std::fprintf(stderr, "[%7.1f s] %s: A %u nodes, B %u nodes, %zu pose(s); bodies and mesh distances %.2f s\n",
                     elapsed(startAll), scene.c_str(), a->numNodes(), b->numNodes(), poses.size(), elapsed(buildStart));
#ifdef MESHGAP_HAVE_FCL
        const auto fclA = test::fclModel(meshA), fclB = test::fclModel(meshB);
#endif
        for (std::size_t p = 0; p < poses.size(); ++p)
        {
            const Eigen::Isometry3d &X_AB = poses[p];
            const int pose = static_cast<int>(p) + 1;
            double exact = std::nan("");
#ifdef MESHGAP_HAVE_FCL
            exact = test::fclDistance(fclA, fclB, X_AB);
#endif
            // Enumeration: the reference, timed as the median of 5 runs.
            const DistanceSolverPtr enumeration = allocSolver("enumeration");
            DistanceResult reference;
            std::vector<double> enumTimes;
            for (int k = 0; k < 5; ++k)
            {
                DistanceRequest request;
                enumeration->solve(*a, *b, X_AB, request, reference);
                enumTimes.push_back(reference.seconds);
            }
            Summary enumSummary;
            enumSummary.scene = scene;
            enumSummary.pose = pose;
            enumSummary.algorithm = "enumeration";
            enumSummary.runs = 5;
            enumSummary.nodesA = a->numNodes();
            enumSummary.nodesB = b->numNodes();
            enumSummary.exact = exact;
            enumSummary.enumDistance = reference.distance;
            enumSummary.enumMs = 1e3 * median(enumTimes);
            enumSummary.successRate = enumSummary.regionRate = enumSummary.basinRate = 1.0;
            enumSummary.bestDistance = enumSummary.meanDistance = enumSummary.medianDistance =
                enumSummary.worstDistance = reference.distance;
            enumSummary.meanEvaluations = static_cast<double>(reference.evaluations);
            enumSummary.meanKflops = static_cast<double>(reference.flops()) / 1e3;
            enumSummary.medianMs = enumSummary.meanMs = enumSummary.enumMs;
            std::fprintf(stderr, "[%7.1f s] %s pos %d: enumeration %.9g (exact %.9g) in %.3f ms\n", elapsed(startAll),
                         scene.c_str(), pose, reference.distance, exact, enumSummary.enumMs);

            std::ofstream history(fs::path(out) / ("history_" + scene + "_pos" + std::to_string(pose) + ".csv"));
            history << "algorithm,iteration,median_run,median_all,p10_all,p90_all\n";
            std::vector<Summary> poseSummaries{enumSummary};
            const DistanceSolverPtr climber = allocSolver("hill-climb");

            // The landscape at node level: hill climbs (III-E) from random node pairs, the paper's "multi point
            // local search". Each one ends at a local minimum; count the distinct ones and how often the global
            // one is reached.
            if (climbs > 0)
            {
                const auto climbStart = Clock::now();
                std::vector<Run> runs;
                runs.reserve(climbs);
                std::set<std::pair<std::uint32_t, std::uint32_t>> minima;
                for (int i = 0; i < climbs; ++i)
                {
                    DistanceRequest request;
                    request.seed = seed + static_cast<std::uint64_t>(i);
                    DistanceResult r;
                    climber->solve(*a, *b, X_AB, request, r);
                    minima.insert({r.nodes.a, r.nodes.b});
                    const bool success = sameDistance(r.distance, reference.distance);
                    runs.push_back({r.distance,
                                    r.evaluations,
                                    r.iterations,
                                    r.localSteps,
                                    r.convergedAt,
                                    r.seconds,
                                    success,
                                    inGlobalRegion(*a, *b, r.nodes, reference.nodes),
                                    success,
                                    {}});
                }
                Summary s = summarize(runs);
                s.scene = scene;
                s.pose = pose;
                s.algorithm = "hill-climb";
                s.nodesA = a->numNodes();
                s.nodesB = b->numNodes();
                s.exact = exact;
                s.enumDistance = reference.distance;
                s.enumMs = enumSummary.enumMs;
                s.distinctMinima = minima.size();
                poseSummaries.push_back(s);
                std::fprintf(stderr,
                             "[%7.1f s] %s pos %d: hill-climb %d climbs in %.1f s: %zu distinct local minima, %.2f%% "
                             "reach the global one\n",
                             elapsed(startAll), scene.c_str(), pose, climbs, elapsed(climbStart), minima.size(),
                             100.0 * s.successRate);
            }
            for (const DistanceSolverPtr &solver : solvers)
            {
                const auto algStart = Clock::now();
                std::vector<Run> runs;
                runs.reserve(runsCount);
                for (int i = 0; i < runsCount; ++i)
                {
                    DistanceRequest request;
                    request.seed = seed + static_cast<std::uint64_t>(i);
                    request.recordHistory = true;
                    DistanceResult r;
                    solver->solve(*a, *b, X_AB, request, r);
                    // The answer lies in the basin of the global minimum when a hill climb started from it
                    // reaches the enumeration minimum.
                    DistanceRequest climb;
                    climb.start = r.nodes;
                    DistanceResult climbed;
                    climber->solve(*a, *b, X_AB, climb, climbed);
                    runs.push_back({r.distance, r.evaluations, r.iterations, r.localSteps, r.convergedAt, r.seconds,
                                    sameDistance(r.distance, reference.distance),
                                    inGlobalRegion(*a, *b, r.nodes, reference.nodes),
                                    sameDistance(climbed.distance, reference.distance), std::move(r.history)});
                }
                Summary s = summarize(runs);
                s.scene = scene;
                s.pose = pose;
                s.algorithm = solver->getName();
                s.nodesA = a->numNodes();
                s.nodesB = b->numNodes();
                s.exact = exact;
                s.enumDistance = reference.distance;
                s.enumMs = enumSummary.enumMs;
                poseSummaries.push_back(s);
                writeHistory(history, solver->getName(), runs);
                std::fprintf(stderr,
                             "[%7.1f s] %s pos %d: %-10s %d runs in %.1f s: success %.0f%%, mean %.6g, worst %.6g, "
                             "%.0f kflops\n",
                             elapsed(startAll), scene.c_str(), pose, solver->getName().c_str(), runsCount,
                             elapsed(algStart), 100.0 * s.successRate, s.meanDistance, s.worstDistance, s.meanKflops);
            }
            for (const Summary &s : poseSummaries)
            {
                results << csvRow(s);
                summaries.push_back(s);
            }
            results.flush();
        }
    }

    std::printf(
        "Runs per algorithm and pose: %d (seeds %llu..%llu). Success: the enumeration minimum; global region: "
        "both nodes within %.0f%% of max(D) (mesh distance) of the enumeration's nodes; global basin: a hill "
        "climb from the answer reaches the enumeration minimum.\n\n",
        runsCount, static_cast<unsigned long long>(seed),
        static_cast<unsigned long long>(seed + static_cast<std::uint64_t>(runsCount) - 1), 100.0 * REGION_FRACTION);
    printTableHeader();
    for (const Summary &s : summaries)
        if (s.algorithm != "hill-climb")
            printTableRow(s);
    if (climbs > 0)
    {
        // The paper's alternative to the GA is a multi point local search (IV-A): its success at comb-GA-wl's mean
        // cost is 1 - (1 - p)^k, with p the share of climbs that reach the global minimum and k the number of
        // climbs comb-GA-wl's mean evaluations pay for.
        std::printf(
            "\nLocal minima at node level: %d hill climbs (III-E) from random node pairs per pose.\n\n"
            "| scene | pos | distinct local minima found | climbs reaching the enumeration minimum | "
            "ending in the global region | mean evaluations per climb | multistart success at comb-GA-wl's "
            "mean evaluations |\n|---|---|---|---|---|---|---|\n",
            climbs);
        for (const Summary &s : summaries)
        {
            if (s.algorithm != "hill-climb")
                continue;
            std::string equalBudget = "";
            for (const Summary &g : summaries)
                if (g.scene == s.scene && g.pose == s.pose && g.algorithm == "comb-GA-wl")
                {
                    const double k = g.meanEvaluations / s.meanEvaluations;
                    char text[64];
                    std::snprintf(text, sizeof(text), "%.1f%% (%.0f climbs)",
                                  100.0 * (1.0 - std::pow(1.0 - s.successRate, k)), k);
                    equalBudget = text;
                }
            std::printf("| %s | %d | %zu | %.2f%% | %.2f%% | %.1f | %s |\n", s.scene.c_str(), s.pose, s.distinctMinima,
                        100.0 * s.successRate, 100.0 * s.regionRate, s.meanEvaluations, equalBudget.c_str());
        }
    }
    std::fprintf(stderr, "[%7.1f s] done; CSVs in %s\n", elapsed(startAll), out.c_str());
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
