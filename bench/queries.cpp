// Per-query cost of every meshgap query against FCL 0.7 (BVHModel<OBBRSS>, robot against the whole world, as
// OMPL.app builds it), on the OMPL.app problems that ship a solution path and on the maps in maps/:
//   - "path": the problem's .path (maps: the .poses in order, then the cfg's goal) interpolated to --states states
//     (SE(3): linear translation, slerp rotation) and queried in order, as a planner's motion checks ask them;
//   - "random": --random poses uniform in the cfg's volume with a uniform rotation (fixed seed).
// Per state, interleaved so machine load hits every column alike: FCL distance, FCL collision, meshgap cold
// certified (Scene::distance without a warm start), warm certified (one warm start carried from state
// to state), fast (SceneRequest::exact = false, its own carried warm start), collision-only (Scene::inCollision),
// and enumeration (the exact node-level minimum over every obstacle, on every --enum-every'th state). Median and
// 90th percentile in microseconds, the ratio of the medians to FCL's (distance columns to FCL distance,
// collision-only to FCL collision), and disagreements counted (collision verdicts of every column against FCL's
// collision; certified distances against FCL's distance, where both say free, beyond 1e-6 relative + 1e-9 absolute).
//
//   build/bench/meshgap_bench_queries [--states 1000] [--random 1000] [--enum-every 10] [--csv FILE]
//                                     [--data ../shared/data/omplapp] [--maps maps] [--seed 1]

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

#include "FclOracle.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    std::vector<Eigen::Isometry3d> interpolate(const std::vector<Eigen::Isometry3d> &path, std::size_t count)
    {
        if (path.size() < 2)
            return path;
        // Arc length with rotation weighted by the path's extent, so states spread along translation and turns.
        std::vector<double> s{0.0};
        for (std::size_t i = 1; i < path.size(); ++i)
        {
            const double dt = (path[i].translation() - path[i - 1].translation()).norm();
            const double dr =
                Eigen::Quaterniond(path[i].linear()).angularDistance(Eigen::Quaterniond(path[i - 1].linear()));
            s.push_back(s.back() + dt + dr + 1e-12);
        }
        std::vector<Eigen::Isometry3d> out;
        std::size_t seg = 0;
        for (std::size_t k = 0; k < count; ++k)
        {
            const double at = s.back() * double(k) / double(count - 1);
            while (seg + 2 < path.size() && s[seg + 1] < at)
                ++seg;
            const double t = std::clamp((at - s[seg]) / (s[seg + 1] - s[seg]), 0.0, 1.0);
            const Eigen::Quaterniond q0(path[seg].linear()), q1(path[seg + 1].linear());
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q0.slerp(t, q1).toRotationMatrix();
            X.translation() = (1 - t) * path[seg].translation() + t * path[seg + 1].translation();
            out.push_back(X);
        }
        return out;
    }

    std::vector<Eigen::Isometry3d> randomPoses(const Eigen::AlignedBox3d &volume, std::size_t count, std::uint32_t seed)
    {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::normal_distribution<double> g;
        std::vector<Eigen::Isometry3d> out;
        for (std::size_t i = 0; i < count; ++i)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            const Eigen::Vector3d f(u(rng), u(rng), u(rng));
            X.translation() = volume.min() + f.cwiseProduct(volume.sizes());
            Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));  // uniform on SO(3)
            X.linear() = q.normalized().toRotationMatrix();
            out.push_back(X);
        }
        return out;
    }

    struct Stats
    {
        std::size_t n{0};
        double median{0}, p90{0};
    };
    Stats stats(std::vector<double> v)
    {
        if (v.empty())
            return {};
        std::sort(v.begin(), v.end());
        return {v.size(), v[v.size() / 2] * 1e6, v[v.size() * 9 / 10] * 1e6};
    }

    template <typename F>
    double timed(F &&f)
    {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    struct Problem
    {
        std::string name;
        ProblemConfig config;
        std::vector<Eigen::Isometry3d> path;  ///< OMPL.app states, before interpolation
        std::string pathNote;
    };

    bool sameDistance(double a, double b)
    {
        return std::abs(a - b) <= 1e-6 * std::abs(b) + 1e-9;
    }

    const char *const COLUMNS[] = {"FCL distance", "FCL collision",  "cold certified", "warm certified",
                                   "fast",         "collision-only", "enumeration"};
    enum Column
    {
        FCL_D,
        FCL_C,
        COLD,
        WARM,
        FAST,
        COLL,
        ENUM,
        NUM_COLUMNS
    };
}  // namespace

int main(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "built without FCL\n");
    return 1;
#else
    std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp", maps, csvFile;
    {
        const fs::path here = fs::path(__FILE__).parent_path().parent_path() / "maps";
        maps = here.string();
    }
    std::size_t states = 1000, random = 1000, enumEvery = 10;
    std::uint32_t seed = 1;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_queries");
    cli.add_options()("help,h", "print this help")("data", po::value(&data), "folder with OMPL.app problems")(
        "maps", po::value(&maps), "folder with meshgap's maps")("states", po::value(&states),
                                                                "interpolated states per path")(
        "random", po::value(&random), "random poses per problem")("enum-every", po::value(&enumEvery),
                                                                  "run enumeration on every N-th state (0: never)")(
        "seed", po::value(&seed), "seed of the random poses")("csv", po::value(&csvFile), "also write CSV here");
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, cli), vm);
    po::notify(vm);
    if (vm.count("help"))
    {
        std::cout << cli << "\n";
        return 0;
    }
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    std::vector<Problem> problems;
    for (const char *name : {"cubicles", "Easy", "Twistycool"})
    {
        const fs::path cfg = fs::path(data) / (std::string(name) + ".cfg"),
                       path = fs::path(data) / (std::string(name) + ".path");
        if (!fs::exists(cfg) || !fs::exists(path))
        {
            std::fprintf(stderr, "skipping %s: %s or its .path not found\n", name, cfg.c_str());
            continue;
        }
        problems.push_back({name, readProblemConfig(cfg.string()), readPoses(path.string()), "its .path"});
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
            const fs::path cfg = dir / (name + ".cfg"), poses = dir / (name + ".poses");
            if (!fs::exists(cfg) || !fs::exists(poses))
                continue;
            Problem p{name, readProblemConfig(cfg.string()), {}, ".poses then goal"};
            // .poses place B's own frame; OMPL.app states place B shifted by its centre c: state = pose * translate(c).
            LoadReport report;
            loadRobotMesh(p.config.robot, &report);
            for (Eigen::Isometry3d X : readPoses(poses.string()))
            {
                X.translate(report.omplAppCenter);
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
        *csv << "problem,set,states,colliding,world_triangles,robot_triangles,obstacles,method,queries,median_us,"
                "p90_us,ratio_to_fcl,verdict_disagreements,distance_disagreements\n";
    }
    std::printf(
        "Times per query in µs: median / p90 (median / FCL's median: distance columns against FCL distance, "
        "collision-only against FCL collision).\n\n");
    std::printf(
        "| problem | poses | world / robot triangles (obstacles) | colliding (FCL) | FCL distance | FCL collision | "
        "cold certified | warm certified | "
        "fast | collision-only | enumeration | disagreements |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::fflush(stdout);
    const Enumeration enumeration;
    for (const Problem &problem : problems)
    {
        const Mesh world = loadMesh(problem.config.world), robot = loadRobotMesh(problem.config.robot);
        const ScenePtr scene = Scene::fromMeshes(robot, world);
        for (const BodyConstPtr &o : scene->obstacles())
            o->distances();  // built on first use: keep that out of the fast column's times
        scene->robot().distances();
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        Eigen::AlignedBox3d volume = problem.config.volume ? *problem.config.volume : world.bounds();

        for (const char *set : {"path", "random"})
        {
            const bool onPath = std::string(set) == "path";
            const std::vector<Eigen::Isometry3d> poses =
                onPath ? interpolate(problem.path, states) : randomPoses(volume, random, seed);
            if (poses.empty())
                continue;
            std::vector<double> t[NUM_COLUMNS];
            std::size_t verdicts[NUM_COLUMNS] = {}, distances[NUM_COLUMNS] = {}, colliding = 0, fastBelowExact = 0;
            SceneWarmStart warm, fastWarm;
            SceneRequest certified, fast;
            fast.exact = false;
            for (std::size_t i = 0; i < poses.size(); ++i)
            {
                const Eigen::Isometry3d &X = poses[i];
                double dF = 0;
                bool cF = false, cM = false;
                SceneResult cold, hot, quick;
                t[FCL_D].push_back(timed([&] { dF = test::fclDistance(fw, fr, X); }));
                t[FCL_C].push_back(timed([&] { cF = test::fclCollide(fw, fr, X); }));
                t[COLD].push_back(timed(
                    [&]
                    { scene->distance(X, certified, cold); }));
                t[WARM].push_back(timed([&] { scene->distance(X, certified, warm, hot); }));
                t[FAST].push_back(timed([&] { scene->distance(X, fast, fastWarm, quick); }));
                t[COLL].push_back(timed([&] { cM = scene->inCollision(X); }));
                colliding += cF;
                verdicts[FCL_D] += (dF <= 0) != cF;
                verdicts[COLD] += cold.inCollision != cF;
                verdicts[WARM] += hot.inCollision != cF;
                verdicts[FAST] += quick.inCollision != cF;
                verdicts[COLL] += cM != cF;
                if (!cF && !cold.inCollision)
                    distances[COLD] += !sameDistance(cold.distance, dF);
                if (!cF && !hot.inCollision)
                    distances[WARM] += !sameDistance(hot.distance, dF);
                if (!cold.inCollision && !quick.inCollision)
                    fastBelowExact += quick.distance < cold.distance - 1e-9 * (1 + cold.distance);
                if (enumEvery > 0 && i % enumEvery == 0)
                {
                    double best = std::numeric_limits<double>::infinity();
                    t[ENUM].push_back(timed(
                        [&]
                        {
                            for (const BodyConstPtr &o : scene->obstacles())
                            {
                                DistanceResult r;
                                enumeration.solve(*o, scene->robot(), X, DistanceRequest(), r);
                                best = std::min(best, r.distance);
                            }
                        }));
                    // A node pair is a pair of surface points: never below the exact distance.
                    if (!cF && best < dF - 1e-9 * (1 + dF))
                        ++distances[ENUM];
                }
            }
            Stats s[NUM_COLUMNS];
            for (int c = 0; c < NUM_COLUMNS; ++c)
                s[c] = stats(t[c]);
            auto cell = [&](int c)
            {
                char buf[96];
                if (s[c].n == 0)
                    return std::string("-");
                const double ref = c == COLL ? s[FCL_C].median : s[FCL_D].median;
                if (c == FCL_D || c == FCL_C)
                    std::snprintf(buf, sizeof buf, "%.1f / %.1f", s[c].median, s[c].p90);
                else
                    std::snprintf(buf, sizeof buf, "%.1f / %.1f (**%.2f**)", s[c].median, s[c].p90, s[c].median / ref);
                std::string out = buf;
                if (c == ENUM && s[c].n != poses.size())
                    out += " [" + std::to_string(s[c].n) + "]";
                return out;
            };
            std::string dis = "verdicts " +
                              std::to_string(verdicts[COLD] + verdicts[WARM] + verdicts[FAST] + verdicts[COLL]) +
                              ", distances " + std::to_string(distances[COLD] + distances[WARM]);
            if (verdicts[FCL_D])
                dis += ", FCL distance vs collide " + std::to_string(verdicts[FCL_D]);
            if (fastBelowExact)
                dis += ", fast below exact " + std::to_string(fastBelowExact);
            if (distances[ENUM])
                dis += ", enumeration below exact " + std::to_string(distances[ENUM]);
            std::printf("| %s (%s) | %zu %s | %zu / %zu (%zu) | %zu | %s | %s | %s | %s | %s | %s | %s | %s |\n",
                        problem.name.c_str(), onPath ? problem.pathNote.c_str() : "random", poses.size(), set,
                        world.triangles.size(), robot.triangles.size(), scene->obstacles().size(), colliding,
                        cell(FCL_D).c_str(), cell(FCL_C).c_str(), cell(COLD).c_str(), cell(WARM).c_str(),
                        cell(FAST).c_str(), cell(COLL).c_str(), cell(ENUM).c_str(), dis.c_str());
            std::fflush(stdout);
            if (csv)
                for (int c = 0; c < NUM_COLUMNS; ++c)
                {
                    const double ref = c == COLL || c == FCL_C ? s[FCL_C].median : s[FCL_D].median;
                    *csv << problem.name << "," << set << "," << poses.size() << "," << colliding << ","
                         << world.triangles.size() << "," << robot.triangles.size() << "," << scene->obstacles().size()
                         << "," << COLUMNS[c] << "," << s[c].n << "," << s[c].median << "," << s[c].p90 << ","
                         << (s[c].n ? s[c].median / ref : 0.0) << "," << verdicts[c] << "," << distances[c] << "\n";
                }
        }
    }
    return 0;
#endif
}
