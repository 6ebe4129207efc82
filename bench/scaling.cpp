// How preprocessing, memory and query time grow with mesh size, meshgap against FCL 0.7 (BVHModel<OBBRSS>), and
// whether any query path allocates.
//
// A concave part (maps/slotted_wall's C-shaped payload, 1,310 triangles, or --mesh FILE) is refined by longest-edge
// bisection (refineMesh(), the surface unchanged) to about 1k, 4k, 16k, 64k and 256k triangles (--max: the largest).
// At each size, two copies, one fixed and one moving (the robot), are built as meshgap bodies with the mesh as it is
// (gridSize 0: every vertex is a node) and as FCL models. Preprocessing: surface graph, mesh distances (dense all
// pairs under the default 512 MiB budget, else on demand), triangle BVH, Body::build (graph, BVH, node maps,
// clusters; mesh distances are built on first use and listed on their own), FCL's BVH. Memory: heap bytes still in
// use after the structure is built (glibc mallinfo2() in-use bytes, before and after, temporaries excluded).
// Queries: the robot along a short motion (--poses poses; two parts interlocked, never touching), interleaved per pose:
// meshgap cold certified (no SceneWarmStart), warm certified (carried), fast (exact = false), collision-only,
// FCL distance and FCL collision. Then every meshgap query kind is run once more over the motion with an allocation
// counter on (global operator new / new[] and malloc / calloc / realloc replaced in this executable), after a warm-up
// pass, and the allocations per query are reported; --trace-alloc lists each distinct allocating call chain (five
// frames, names by addr2line) and how often it allocated per query.
//
// Also times the warm-fast solver (WarmFast.h) on the same body pair and motion, in a table of its own.
//
// Fast mode beyond the dense budget answers mesh distances by Dijkstra on demand and takes seconds per query at 256k
// triangles, so there it is timed on the first --fast-on-demand poses only (the table says so). About 4 minutes.
//
// --map DIR (a maps/ folder: NAME_a.obj, NAME_b.obj, NAME.poses) scales a scene instead, such as maps/twisted, the
// exact layer's stress scene: its B is the part refined to each size (the robot, and the preprocessing table's body),
// its A the obstacle, refined to the same multiple of its own size, and its .poses, evenly subsampled to --poses,
// the motion.
//
//   build/bench/meshgap_bench_scaling [--max 262144] [--poses 100] [--fast-on-demand 10] [--csv FILE] [--mesh FILE]
//                                     [--map DIR] [--trace-alloc]

#include <dlfcn.h>
#include <execinfo.h>
#include <malloc.h>
#include <ompl/util/Console.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>

#include "CliMain.h"
#include "FclOracle.h"
#include "meshgap/distance/WarmFast.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshDistances.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/Refine.h"
#include "meshgap/mesh/SurfaceGraph.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/Scene.h"

// ---- allocation counting (this executable only) ----

namespace
{
    std::atomic<bool> counting{false}, tracing{false};
    std::atomic<std::size_t> allocations{0};

    /** \brief A distinct allocating call chain (return addresses above the allocator) and how often it allocated;
        a fixed table, so recording allocates nothing. */
    struct Site
    {
        static constexpr int DEPTH = 5;
        void *frames[DEPTH];
        std::size_t count;
    };
    Site sites[64];
    std::atomic<int> numSites{0};
    thread_local bool inTrace = false;

    void noteAllocation()
    {
        if (!counting.load(std::memory_order_relaxed))
            return;
        allocations.fetch_add(1, std::memory_order_relaxed);
        if (!tracing.load(std::memory_order_relaxed) || inTrace)
            return;
        inTrace = true;
        void *frames[Site::DEPTH + 2];
        const int n = ::backtrace(frames, Site::DEPTH + 2);  // [0] this function, [1] the replaced allocator
        Site key{};
        for (int i = 2; i < n; ++i)
            key.frames[i - 2] = frames[i];
        int i = 0;
        for (; i < numSites; ++i)
            if (std::equal(key.frames, key.frames + Site::DEPTH, sites[i].frames))
                break;
        if (i == numSites && i < 64)
        {
            sites[i] = key;
            ++numSites;
        }
        if (i < 64)
            ++sites[i].count;
        inTrace = false;
    }

    /** \brief Print the recorded call chains, innermost first, with function names from addr2line. */
    void printSites(std::size_t queries)
    {
        for (int i = 0; i < numSites; ++i)
        {
            std::fprintf(stderr, "  %.2f per query:", double(sites[i].count) / double(queries));
            for (void *frame : sites[i].frames)
            {
                Dl_info info;
                if (!frame || !::dladdr(frame, &info) || !info.dli_fname)
                    continue;
                const auto offset =
                    static_cast<std::size_t>(static_cast<char *>(frame) - static_cast<char *>(info.dli_fbase));
                char command[1024];
                std::snprintf(command, sizeof command, "addr2line -f -C -e '%s' 0x%zx | head -1", info.dli_fname,
                              offset - 1);
                std::string name;
                if (FILE *pipe = ::popen(command, "r"))
                {
                    char line[4096];
                    if (std::fgets(line, sizeof line, pipe))
                        name = line;
                    ::pclose(pipe);
                }
                while (!name.empty() && name.back() == '\n')
                    name.pop_back();
                // Keep the function's qualified name, not its (long) argument list.
                const std::size_t paren = name.find('(');
                if (paren != std::string::npos && name.compare(0, 8, "meshgap:") == 0)
                    name = name.substr(0, paren);
                if (name.size() > 110)
                    name = name.substr(0, 110) + "...";
                std::fprintf(stderr, "\n      <- %s", name.c_str());
            }
            std::fprintf(stderr, "\n");
        }
        numSites = 0;
    }

}  // namespace

#include "alloc/CountingAllocator.h"

void meshgapNoteAllocation()
{
    noteAllocation();
}

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    /** \brief Heap bytes in use (every arena, and mmapped chunks). */
    std::size_t heapInUse()
    {
        const struct mallinfo2 m = ::mallinfo2();
        return m.uordblks + m.hblkhd;
    }

    double seconds(std::chrono::steady_clock::time_point t0)
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    /** \brief Time and retained heap bytes of building something with \e f (which keeps what it builds). */
    template <typename F>
    std::pair<double, double> measure(F &&f)
    {
        ::malloc_trim(0);
        const std::size_t before = heapInUse();
        const auto t0 = std::chrono::steady_clock::now();
        f();
        const double t = seconds(t0);
        return {t, double(heapInUse()) - double(before)};
    }

    /** \brief Refine \e mesh to about \e target triangles (within 25%, a few tries adjusting h). */
    Mesh refineTo(const Mesh &mesh, std::size_t target)
    {
        if (mesh.triangles.size() * 4 >= target * 3)
            return mesh;
        double h = longestEdge(mesh) * std::sqrt(double(mesh.triangles.size()) / double(target));
        Mesh out;
        for (int attempt = 0; attempt < 6; ++attempt)
        {
            out = refineMesh(mesh, h);
            const double ratio = double(out.triangles.size()) / double(target);
            if (ratio > 0.8 && ratio < 1.25)
                break;
            h *= std::sqrt(ratio);
        }
        return out;
    }

    struct Stats
    {
        double median{0}, p90{0};
    };
    Stats stats(std::vector<double> v)
    {
        std::sort(v.begin(), v.end());
        return {v[v.size() / 2] * 1e6, v[v.size() * 9 / 10] * 1e6};
    }

    template <typename F>
    double timed(F &&f)
    {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        return seconds(t0);
    }

    std::string mib(double bytes)
    {
        char b[32];
        std::snprintf(b, sizeof b, "%.2f", bytes / (1 << 20));
        return b;
    }
}  // namespace

static int run(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "built without FCL\n");
    return 1;
#else
    std::string meshFile = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall_b.obj";
    std::string csvFile, mapDir;
    std::size_t maxTriangles = 262144, numPoses = 100, fastOnDemand = 10;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_scaling");
    cli.add_options()("help,h", "print this help")(
        "mesh", po::value(&meshFile), ("the part to refine (default: " + meshFile + ")").c_str())(
        "map", po::value(&mapDir), "a maps/ folder (e.g. maps/twisted): B refined, A the obstacle, .poses the motion")(
        "max", po::value(&maxTriangles), "largest size (triangles): 1024, 4096, ... up to this (default 262144)")(
        "poses", po::value(&numPoses), "poses along the motion")(
        "fast-on-demand", po::value(&fastOnDemand),
        "fast mode with on-demand mesh distances (slow): time it on the first N poses only")("csv", po::value(&csvFile),
                                                                                             "also write CSV here")(
        "trace-alloc", "list the allocating call chains of each query kind (needs addr2line)");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    for (const auto &[flag, count] : {std::pair{"--poses", numPoses}, std::pair{"--fast-on-demand", fastOnDemand}})
        if (count < 1)
            throw meshgap::Exception(flag, "must be at least 1 (each column's median needs a query)");
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    const bool trace = vm.count("trace-alloc") > 0;
    if (trace)
    {
        void *frames[4];
        ::backtrace(frames, 4);  // loads the unwinder now, not inside a counted loop
    }
    std::optional<Mesh> baseWorld;  // --map: the obstacle, refined alongside the part
    std::vector<Eigen::Isometry3d> mapPoses;
    if (!mapDir.empty())
    {
        fs::path dir = fs::path(mapDir).lexically_normal();
        if (dir.filename().empty())
            dir = dir.parent_path();
        const std::string name = dir.filename().string();
        meshFile = (dir / (name + "_b.obj")).string();
        baseWorld = loadMesh((dir / (name + "_a.obj")).string());
        mapPoses = readPoses((dir / (name + ".poses")).string());
        if (mapPoses.empty())
        {
            std::fprintf(stderr, "error: %s: no poses\n", (dir / (name + ".poses")).c_str());
            return 1;
        }
    }
    const Mesh base = loadMesh(meshFile);
    const Eigen::Vector3d extent = base.bounds().sizes();

    // The motion: two of the C-shaped parts interlocked, openings facing each other (the robot turned half a turn
    // about z, one arm in the other's opening, their bounding boxes overlapping: the broad phase cannot decide),
    // the robot sliding along x over 0.3 of the part's x extent and turning 6 degrees about z and 10 about y as it
    // goes. Made for the C (the default --mesh): another mesh may collide (see the disagreements and the minimum
    // distance printed).
    std::vector<Eigen::Isometry3d> poses;
    const Eigen::Vector3d centre = base.bounds().center();
    for (std::size_t i = 0; i < numPoses && baseWorld; ++i)  // --map: its .poses, evenly subsampled
        poses.push_back(mapPoses[numPoses > 1 ? i * (mapPoses.size() - 1) / (numPoses - 1) : 0]);
    for (std::size_t i = 0; i < numPoses && !baseWorld; ++i)
    {
        const double t = numPoses > 1 ? double(i) / double(numPoses - 1) : 0.0;
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.translation() = centre + Eigen::Vector3d((0.7 + 0.3 * (t - 0.5)) * extent.x(), 0.3 * extent.y(), 0.0);
        X.rotate(Eigen::AngleAxisd(M_PI + 0.1 * (t - 0.5), Eigen::Vector3d::UnitZ()) *
                 Eigen::AngleAxisd(0.17 * (t - 0.5), Eigen::Vector3d::UnitY()));
        X.translate(-centre);
        poses.push_back(X);
    }

    std::unique_ptr<std::ofstream> csv;
    if (!csvFile.empty())
    {
        csv = std::make_unique<std::ofstream>(csvFile);
        *csv << "triangles,nodes,distances,graph_s,graph_bytes,distances_s,distances_bytes,bvh_s,bvh_bytes,body_s,"
                "body_bytes,fcl_build_s,fcl_bytes,cold_us,cold_p90_us,warm_us,warm_p90_us,fast_us,fast_p90_us,"
                "collision_us,collision_p90_us,fcl_distance_us,fcl_distance_p90_us,fcl_collision_us,"
                "fcl_collision_p90_us,allocs_cold,allocs_warm,allocs_fast,allocs_collision,min_distance,disagreements,"
                "obstacle_triangles\n";
    }
    std::printf(
        "Preprocessing (%s; seconds, and MiB of heap retained):\n\n"
        "| triangles | nodes | surface graph | mesh distances | triangle BVH | Body::build (without distances) | "
        "FCL BVH (OBBRSS) |\n|---|---|---|---|---|---|---|\n",
        baseWorld ? ("the map's B, the robot; its A, the obstacle, refined alongside: " + mapDir).c_str()
                  : "one body, used as both robot and obstacle");
    std::fflush(stdout);
    struct Row
    {
        std::size_t triangles;
        std::string text;
    };
    std::vector<Row> queryRows;
    std::vector<std::string> warmFastRows;
    for (std::size_t target = 1024; target <= maxTriangles; target *= 4)
    {
        const Mesh mesh = refineTo(base, target);
        const std::size_t nodes = mesh.vertices.size();

        std::shared_ptr<const SurfaceGraph> graph;
        MeshDistancesPtr distances;
        std::unique_ptr<TriangleBvh> bvh;
        BodyPtr body;
        std::shared_ptr<test::FclModel> fcl;
        const auto g = measure([&] { graph = std::make_shared<const SurfaceGraph>(mesh); });
        const auto d = measure([&] { distances = MeshDistances::build(graph); });
        const bool dense = distances->isDense();
        distances.reset();
        const auto b = measure([&] { bvh = std::make_unique<TriangleBvh>(mesh); });
        bvh.reset();
        BodyOptions options;
        options.gridSize = 0;
        const auto bb = measure([&] { body = Body::build(mesh, options); });
        const auto bd = measure([&] { body->distances(); });  // the body's own, for fast mode
        (void)bd;
        const auto f = measure([&] { fcl = test::fclModel(mesh); });
        std::printf(
            "| %zu | %zu | %.3f s, %s MiB | %.3f s, %s MiB (%s) | %.3f s, %s MiB | %.3f s, %s MiB | %.3f s, %s MiB |\n",
            mesh.triangles.size(), nodes, g.first, mib(g.second).c_str(), d.first, mib(d.second).c_str(),
            dense ? "dense" : "on demand", b.first, mib(b.second).c_str(), bb.first, mib(bb.second).c_str(), f.first,
            mib(f.second).c_str());
        std::fflush(stdout);

        // Queries: the same body fixed (obstacle, world frame = its frame) and moving (robot); with --map, the map's
        // A (refined to the same multiple of its own size) fixed.
        BodyConstPtr obstacle = body;
        std::shared_ptr<test::FclModel> fclObstacle = fcl;
        std::size_t obstacleTriangles = mesh.triangles.size();
        bool obstacleDense = dense;
        if (baseWorld)
        {
            const Mesh world =
                refineTo(*baseWorld, static_cast<std::size_t>(double(target) * double(baseWorld->triangles.size()) /
                                                              double(base.triangles.size())));
            BodyPtr worldBody = Body::build(world, options);
            obstacleDense = worldBody->distances().isDense();  // built here, not in the fast column's times
            obstacle = worldBody;
            fclObstacle = test::fclModel(world);
            obstacleTriangles = world.triangles.size();
        }
        const Scene scene(body, {obstacle});
        SceneRequest certified, fast;
        fast.exact = false;
        std::vector<double> tCold, tWarm, tFast, tColl, tFclD, tFclC, tWarmFast;
        const WarmFast warmFast;  // the warm-started fast solver, the same pair as the scene's
        WarmFastState warmFastState;
        std::size_t warmFastBelow = 0;
        SceneWarmStart warm, fastWarm;
        double minDistance = std::numeric_limits<double>::infinity();
        std::size_t disagreements = 0;
        for (const Eigen::Isometry3d &X : poses)
        {
            SceneResult cold, hot, quick;
            double dF = 0;
            bool cF = false, cM = false;
            tFclD.push_back(timed([&] { dF = test::fclDistance(fclObstacle, fcl, X); }));
            tFclC.push_back(timed([&] { cF = test::fclCollide(fclObstacle, fcl, X); }));
            tCold.push_back(timed(
                [&]
                { scene.distance(X, certified, cold); }));
            tWarm.push_back(timed([&] { scene.distance(X, certified, warm, hot); }));
            if ((dense && obstacleDense) || &X - poses.data() < static_cast<std::ptrdiff_t>(fastOnDemand))
                tFast.push_back(timed([&] { scene.distance(X, fast, fastWarm, quick); }));
            tColl.push_back(timed([&] { cM = scene.inCollision(X); }));
            DistanceResult wf;
            tWarmFast.push_back(timed([&] { warmFast.solveWarm(*body, *body, X, warmFastState, 1, wf); }));
            warmFastBelow += !cF && wf.distance < dF - 1e-9 * (1.0 + dF);
            minDistance = std::min(minDistance, dF);
            disagreements += cF != cM || cF != cold.inCollision || cF != hot.inCollision ||
                             (!cF && (std::abs(cold.distance - dF) > 1e-6 * dF + 1e-9 ||
                                      std::abs(hot.distance - dF) > 1e-6 * dF + 1e-9));
        }
        // Allocations per query, after the pass above warmed every cache.
        auto allocsPerQuery = [&](const char *what, auto &&query, std::size_t count)
        {
            count = std::min(count, poses.size());
            allocations = 0;
            tracing = trace;
            counting = true;
            for (std::size_t i = 0; i < count; ++i)
                query(poses[i]);
            counting = false;
            tracing = false;
            const double perQuery = double(allocations.load()) / double(count);
            if (trace)
            {
                std::fprintf(stderr, "%zu triangles, %s: %.2f allocations per query\n", mesh.triangles.size(), what,
                             perQuery);
                printSites(count);
            }
            return perQuery;
        };
        SceneResult r;
        const double aCold = allocsPerQuery(
            "cold",
            [&](const Eigen::Isometry3d &X)
            { scene.distance(X, certified, r); },
            poses.size());
        const double aWarm = allocsPerQuery(
            "warm", [&](const Eigen::Isometry3d &X) { scene.distance(X, certified, warm, r); }, poses.size());
        const double aFast = allocsPerQuery(
            "fast", [&](const Eigen::Isometry3d &X) { scene.distance(X, fast, fastWarm, r); },
            dense && obstacleDense ? poses.size() : fastOnDemand);
        const double aColl = allocsPerQuery(
            "collision", [&](const Eigen::Isometry3d &X) { (void)scene.inCollision(X); }, poses.size());
        DistanceResult wfResult;
        const double aWarmFast = allocsPerQuery(
            "warm-fast", [&](const Eigen::Isometry3d &X) { warmFast.solveWarm(*body, *body, X, warmFastState, 1, wfResult); },
            poses.size());

        const Stats c = stats(tCold), w = stats(tWarm), q = stats(tFast), k = stats(tColl), fd = stats(tFclD),
                    fc = stats(tFclC);
        char text[512];
        std::snprintf(text, sizeof text,
                      "| %zu%s | %.1f / %.1f (**%.2f**) | %.1f / %.1f (**%.2f**) | %.1f / %.1f (%.2f)%s | %.1f / %.1f "
                      "(**%.2f**) | "
                      "%.1f / %.1f | %.1f / %.1f | %g / %g / %g / %g | %zu |",
                      mesh.triangles.size(), baseWorld ? (" / " + std::to_string(obstacleTriangles)).c_str() : "",
                      c.median, c.p90, c.median / fd.median, w.median, w.p90, w.median / fd.median, q.median, q.p90,
                      q.median / fd.median,
                      tFast.size() < poses.size() ? (" [first " + std::to_string(tFast.size()) + "]").c_str() : "",
                      k.median, k.p90, k.median / fc.median, fd.median, fd.p90, fc.median, fc.p90, aCold, aWarm, aFast,
                      aColl, disagreements);
        queryRows.push_back({mesh.triangles.size(), text});
        {
            const Stats wfs = stats(tWarmFast);
            char row[256];
            std::snprintf(row, sizeof row, "| %zu | %s | %.1f / %.1f (**%.2f**) | %.0f | %.1f | %g | %zu |",
                          mesh.triangles.size(), dense ? "dense" : "on demand", wfs.median, wfs.p90,
                          wfs.median / fd.median, 1e6 * *std::max_element(tWarmFast.begin(), tWarmFast.end()),
                          fd.median, aWarmFast, warmFastBelow);
            warmFastRows.push_back(row);
        }
        std::fprintf(stderr, "%s\n", text);
        if (csv)
            *csv << mesh.triangles.size() << "," << nodes << "," << (dense ? "dense" : "on_demand") << "," << g.first
                 << "," << g.second << "," << d.first << "," << d.second << "," << b.first << "," << b.second << ","
                 << bb.first << "," << bb.second << "," << f.first << "," << f.second << "," << c.median << "," << c.p90
                 << "," << w.median << "," << w.p90 << "," << q.median << "," << q.p90 << "," << k.median << ","
                 << k.p90 << "," << fd.median << "," << fd.p90 << "," << fc.median << "," << fc.p90 << "," << aCold
                 << "," << aWarm << "," << aFast << "," << aColl << "," << minDistance << "," << disagreements << ","
                 << obstacleTriangles << "\n";
        std::fprintf(stderr, "%zu triangles: min distance along the motion %g (FCL)\n", mesh.triangles.size(),
                     minDistance);
    }
    std::printf(
        "\nQueries along a %zu-pose motion (µs per query, median / p90, ratio of medians to FCL distance; "
        "collision-only to FCL collision); allocations per query after warm-up (cold / warm / fast / "
        "collision-only):\n\n| %s | cold certified | warm certified | fast | collision-only | FCL distance | "
        "FCL collision | allocations per query | disagreements |\n|---|---|---|---|---|---|---|---|---|\n",
        poses.size(), baseWorld ? "triangles (robot / obstacle)" : "triangles");
    for (const Row &row : queryRows)
        std::printf("%s\n", row.text.c_str());
    std::printf("\nwarm-fast (WarmFast.h: hill climb from the last pair, bounded global search, surface patch; an upper "
                "bound) along the same motion: µs per query, median / p90 (ratio of medians to FCL distance), the "
                "slowest query, allocations per query after warm-up, answers below FCL's distance:\n\n| triangles | "
                "mesh distances | warm-fast | max µs | FCL distance median | allocations per query | below exact "
                "|\n|---|---|---|---|---|---|---|\n");
    for (const std::string &row : warmFastRows)
        std::printf("%s\n", row.c_str());
    return 0;
#endif
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
