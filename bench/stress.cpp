// Stress: one ClearanceChecker queried from several threads, 10^6 queries in all (validity, certified clearance
// and, one in --fast-every, fast clearance), with the resident memory read at every tenth. The query path should
// not allocate per call, and no cache may grow without bound: after the first tenth (warm starts and thread-local
// state made) the resident set should stay flat. Prints a CSV row per tenth and the growth; exits 1 if the growth
// after the first tenth exceeds --max-growth-kib.
//
//   build/bench/meshgap_bench_stress [--queries 1000000] [--threads 2] [--fast-every 100] [--max-growth-kib 1024]

#include <atomic>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>
#include <thread>
#include <unistd.h>

#include "CliMain.h"
#include "TestMeshes.h"
#include "meshgap/ompl/ClearanceChecker.h"

using namespace meshgap;
namespace ob = ompl::base;

namespace
{
    double residentKiB()
    {
        std::ifstream statm("/proc/self/statm");
        long pages = 0, resident = 0;
        statm >> pages >> resident;
        return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / 1024.0;
    }

    // A small scene with the same structure as a real one: a concave robot (two boxes in an L) among a floor, a
    // pillar and a sphere; queries in a volume where about a third of the poses collide.
    ScenePtr makeScene()
    {
        const Mesh robot = test::merged(test::box(0.6, 0.15, 0.15, 2),
                                        test::transformed(test::box(0.15, 0.6, 0.15, 2), test::translation(0.45, 0.45, 0)));
        Mesh world = test::transformed(test::box(3.0, 3.0, 0.1, 3), test::translation(0, 0, -1.2));
        world = test::merged(world, test::transformed(test::box(0.3, 0.3, 1.0, 2), test::translation(0.8, -0.5, 0)));
        world = test::merged(world, test::transformed(test::icosphere(0.6, 2), test::translation(-1.0, 0.9, 0.2)));
        return Scene::fromMeshes(robot, world);
    }
}  // namespace

static int run(int argc, char **argv)
{
    namespace po = boost::program_options;
    std::size_t queries = 1000000, fastEvery = 100;
    int threads = 2;
    double maxGrowth = 1024.0;
    po::options_description options("meshgap_bench_stress");
    options.add_options()("help,h", "this text")("queries", po::value(&queries), "queries in all")(
        "threads", po::value(&threads), "threads sharing one checker")(
        "fast-every", po::value(&fastEvery), "one query in this many is a fast (comb-GA-wl) clearance; 0: none")(
        "max-growth-kib", po::value(&maxGrowth), "exit 1 if the resident set grows more after the first tenth");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, options, vm))
        return 0;
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ompl::RNG::setSeed(7);  // before any sampler exists

    auto space = std::make_shared<ob::SE3StateSpace>();
    ob::RealVectorBounds bounds(3);
    bounds.setLow(-2.0);
    bounds.setHigh(2.0);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    const ScenePtr scene = makeScene();
    ClearanceChecker certified(si, scene, ClearanceChecker::Mode::CERTIFIED);
    ClearanceChecker fast(si, scene, ClearanceChecker::Mode::FAST);

    // A fixed pool of states (allocated once) visited in a different order by each thread.
    std::vector<ob::State *> pool(4096);
    ob::StateSamplerPtr sampler = si->allocStateSampler();
    for (ob::State *&s : pool)
    {
        s = si->allocState();
        sampler->sampleUniform(s);
    }

    std::printf("tenth,queries,seconds,resident_kib\n");
    const auto t0 = std::chrono::steady_clock::now();
    std::atomic<std::size_t> done{0};
    std::atomic<std::size_t> collisions{0};
    double afterFirstTenth = 0.0, last = 0.0;
    const std::size_t tenth = std::max<std::size_t>(1, queries / 10);
    for (int k = 1; k <= 10; ++k)
    {
        std::vector<std::thread> workers;
        for (int t = 0; t < threads; ++t)
            workers.emplace_back([&, t] {
                const std::size_t stride = 2 * static_cast<std::size_t>(t) + 1;  // odd: visits the whole pool
                std::size_t mine = 0;  // added to the shared count once, so the threads share nothing while querying
                for (std::size_t q = static_cast<std::size_t>(t); q < tenth; q += static_cast<std::size_t>(threads))
                {
                    const ob::State *s = pool[(q * stride + static_cast<std::size_t>(k)) % pool.size()];
                    // The kind of query from this thread's own count, so every thread asks the same mix (from q,
                    // with an even number of threads, one thread would ask every distance and another none).
                    const std::size_t i = q / static_cast<std::size_t>(threads);
                    double d = 0.0;
                    if (fastEvery > 0 && i % fastEvery == 0)
                        d = fast.clearance(s);
                    else if (i % 2 == 0)
                        mine += !certified.isValid(s, d);
                    else
                        mine += !certified.isValid(s);
                    (void)d;
                }
                collisions += mine;
            });
        for (std::thread &w : workers)
            w.join();
        done += tenth;
        last = residentKiB();
        if (k == 1)
            afterFirstTenth = last;
        std::printf("%d,%zu,%.2f,%.0f\n", k, done.load(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), last);
        std::fflush(stdout);
    }
    const CheckerStats s = certified.stats();
    const double growth = last - afterFirstTenth;
    std::fprintf(stderr,
                 "%zu queries on %d threads, %zu in collision; certified checker: %llu validity calls, %llu warm-start "
                 "hits; resident set after the first tenth %.0f KiB, at the end %.0f KiB: growth %.0f KiB\n",
                 done.load(), threads, collisions.load(), static_cast<unsigned long long>(s.validityCalls),
                 static_cast<unsigned long long>(s.warmStartHits), afterFirstTenth, last, growth);
    for (ob::State *st : pool)
        si->freeState(st);
    return growth > maxGrowth ? 1 : 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
