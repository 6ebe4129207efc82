// Cost of the paper's mesh distance tables (Section II-A.2): build time and memory of the dense all-pairs table
// for box meshes of about 1k, 4k and 16k nodes, and the per-query cost of the on-demand strategy, which should stay
// flat as the mesh grows (a short query searches a small region whatever the mesh size). Prints Markdown tables.

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "CliMain.h"
#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshDistances.h"
#include "meshgap/mesh/SurfaceGraph.h"

namespace
{
    using Clock = std::chrono::steady_clock;

    double seconds(Clock::time_point since)
    {
        return std::chrono::duration<double>(Clock::now() - since).count();
    }

    /** \brief Peak resident set size of this process so far, in MiB (VmHWM from /proc/self/status). */
    double peakRssMiB()
    {
        std::ifstream status("/proc/self/status");
        std::string line;
        while (std::getline(status, line))
            if (line.rfind("VmHWM:", 0) == 0)
                return std::stod(line.substr(6)) / 1024.0;  // reported in kB
        return -1.0;
    }

    double median(std::vector<double> v)
    {
        std::sort(v.begin(), v.end());
        return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    }

    int run(int argc, char **argv)
    {
        namespace po = boost::program_options;
        std::vector<int> denseSubdivisions{13, 26, 52}, onDemandSubdivisions{13, 26, 52, 204};
        unsigned int threads = 0;
        int runs = 3;
        std::size_t singleRunAbove = 8000;
        int queries = 20000;
        po::options_description desc(
            "meshgap_bench_mesh_distances: dense table build and on-demand query cost on "
            "test::box(1, 1, 1, n) meshes (6 n^2 + 2 nodes)");
        auto add = desc.add_options();
        add("help,h", "this help");
        add("dense", po::value(&denseSubdivisions)->multitoken(), "box subdivisions n for the dense builds (13 26 52)");
        add("on-demand", po::value(&onDemandSubdivisions)->multitoken(),
            "box subdivisions n for the on-demand queries (13 26 52 204)");
        add("threads", po::value(&threads), "build threads, 0 = hardware concurrency (0)");
        add("runs", po::value(&runs), "dense builds per mesh, median reported (3)");
        add("single-run-above", po::value(&singleRunAbove), "meshes with more nodes are built once (8000)");
        add("queries", po::value(&queries), "on-demand queries per mesh and kind (20000)");
        po::variables_map vm;
        if (!meshgap::cli::parseCommandLine(argc, argv, desc, vm))
            return 0;

        std::cout << "Dense all-pairs table (D double + P uint32):\n\n"
                  << "| mesh | nodes | edges | build runs | build time (s, median) | table bytes | table MiB | "
                     "peak RSS MiB |\n"
                  << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (int n : denseSubdivisions)
        {
            const auto graph = std::make_shared<const meshgap::SurfaceGraph>(meshgap::test::box(1, 1, 1, n));
            meshgap::MeshDistancesOptions options;
            options.memoryBudgetBytes = std::size_t(8) << 30;
            options.threads = threads;
            const int r = graph->numNodes() > singleRunAbove ? 1 : runs;
            std::vector<double> times;
            for (int k = 0; k < r; ++k)
            {
                const auto start = Clock::now();
                const auto md = meshgap::MeshDistances::build(graph, options);
                times.push_back(seconds(start));
                if (!md->isDense())
                    throw meshgap::Exception("bench", "expected a dense table");
            }
            const std::size_t bytes = meshgap::MeshDistances::denseTableBytes(graph->numNodes());
            std::printf("| box n=%d | %u | %zu | %d | %.3f | %zu | %.1f | %.1f |\n", n, graph->numNodes(),
                        graph->numEdges(), r, median(times), bytes, bytes / 1048576.0, peakRssMiB());
            std::fflush(stdout);
        }

        std::cout << "\nOn-demand queries (bounded Dijkstra, per-thread workspace):\n\n"
                  << "| mesh | nodes | distance to a neighbour (us/query) | distance to a node 3 edges away "
                     "(us/query) | nodesWithin r = 3 edges (us/query, mean nodes) |\n"
                  << "|---|---:|---:|---:|---:|\n";
        for (int n : onDemandSubdivisions)
        {
            const auto graph = std::make_shared<const meshgap::SurfaceGraph>(meshgap::test::box(1, 1, 1, n));
            meshgap::MeshDistancesOptions options;
            options.memoryBudgetBytes = 0;
            const auto md = meshgap::MeshDistances::build(graph, options);
            const std::uint32_t nodes = graph->numNodes();
            const double edge = 2.0 / n;
            std::mt19937 rng(1);
            std::uniform_int_distribution<std::uint32_t> pick(0, nodes - 1);
            std::vector<std::uint32_t> us(queries), near(queries), far(queries);
            std::vector<std::uint32_t> path;
            for (int q = 0; q < queries; ++q)
            {
                us[q] = pick(rng);
                near[q] = *graph->beginNeighbours(us[q]);
                std::uint32_t w = us[q];  // a short walk away, staying off the way back
                for (int step = 0; step < 3; ++step)
                    w = graph->beginNeighbours(w)[step % graph->degree(w)];
                far[q] = w;
            }
            double sink = 0.0;
            auto start = Clock::now();
            for (int q = 0; q < queries; ++q)
                sink += md->distance(us[q], near[q]);
            const double nearUs = seconds(start) / queries * 1e6;
            start = Clock::now();
            for (int q = 0; q < queries; ++q)
                sink += md->distance(us[q], far[q]);
            const double farUs = seconds(start) / queries * 1e6;
            std::size_t found = 0;
            start = Clock::now();
            for (int q = 0; q < queries; ++q)
            {
                md->nodesWithin(us[q], 3.0 * edge, path);
                found += path.size();
            }
            const double withinUs = seconds(start) / queries * 1e6;
            std::printf("| box n=%d | %u | %.2f | %.2f | %.2f (%.1f) |\n", n, nodes, nearUs, farUs, withinUs,
                        double(found) / queries);
            if (sink < 0.0)
                std::printf("(impossible)\n");
            std::fflush(stdout);
        }
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
