// Per-query cost of every meshgap query against FCL 0.7 (BVHModel<OBBRSS>, robot against the whole world, as
// OMPL.app builds it), on any OMPL.app problem that ships a solution path and on meshgap's maps:
//   - --data DIR: every NAME.cfg found under DIR (recursively) with a solution path next to it: NAME.path, or else
//     NAME*.path (a path belongs to the cfg with the longest name it starts with, so cubicles_opt.path is not
//     cubicles'). SE(3) paths are "x y z qx qy qz qw" per line, SE(2) ones (a cfg without start.z) "x y theta";
//   - --maps DIR: every NAME.cfg found under DIR with NAME.poses next to it (maps/: B's body-frame poses, then the
//     cfg's goal);
//   - --problems a,b,c: only these (by name, from either folder; an unknown name lists the valid ones). Default:
//     every problem found.
// Sets of poses per problem:
//   - "path": the path interpolated to --states states (SE(3): linear translation, slerp rotation) and queried in
//     order, as a planner's motion checks ask them;
//   - "random": --random poses uniform in the cfg's volume with a uniform rotation (fixed seed).
// Per state, interleaved so machine load hits every column alike: FCL distance, FCL collision, meshgap cold
// certified (Scene::distance without a warm start), warm certified (one warm start carried from state
// to state), fast (SceneRequest::exact = false with --fast-solver, its own carried warm start), collision-only
// (Scene::inCollision), collision-only warm (Scene::inCollision with its own warm start carried from state to state:
// collision fronts), and enumeration (the exact node-level minimum over every obstacle, on every --enum-every'th
// state). --skip leaves columns (cold, warm, fast, collision, collision-warm, enumeration) or sets (path, random) out;
// the two FCL columns are the reference and always run. Median and 90th percentile in microseconds, the ratio of the
// medians to FCL's (distance columns to FCL distance, collision-only to FCL collision), and disagreements counted:
// collision verdicts of every column against FCL's collision; certified distances against FCL's distance, where both
// say free, beyond 1e-6 relative + 1e-9 absolute; warm against cold (same verdict, signed distances within 1e-12
// relative: the warm start must never change the answer).
//
//   build/bench/meshgap_bench_queries [--data ../shared/data/omplapp] [--maps maps] [--problems a,b,c]
//                                     [--skip fast,enumeration,random,...] [--states 1000] [--random 1000]
//                                     [--enum-every 10] [--seed 1] [--csv FILE]

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "CliMain.h"
#include "FclOracle.h"
#include "PathInterpolation.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
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

    /** \brief Memory held by one warm start (its triangle pairs and certificates): the table's "warm start" column
        and the CSV's warm_start_bytes. */
    std::optional<std::size_t> warmStartBytes(const SceneWarmStart &warm)
    {
        return warm.memoryBytes();
    }

    /** \brief One SE(2) state per line, "x y theta" (OMPL.app's 2D .path), as a pose in the plane z = 0. */
    std::vector<Eigen::Isometry3d> readPlanarPath(const std::string &path)
    {
        std::ifstream in(path);
        if (!in)
            throw Exception(path, "cannot open");
        std::vector<Eigen::Isometry3d> out;
        std::string line;
        for (std::size_t number = 1; std::getline(in, line); ++number)
        {
            if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#')
                continue;
            std::istringstream fields(line);
            double x, y, theta;
            std::string extra;
            if (!(fields >> x >> y >> theta) || (fields >> extra) || !std::isfinite(x) || !std::isfinite(y) ||
                !std::isfinite(theta))
                throw Exception(path + ":" + std::to_string(number), "not an SE(2) state \"x y theta\"");
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.translation() = Eigen::Vector3d(x, y, 0.0);
            X.linear() = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
            out.push_back(X);
        }
        return out;
    }

    /** \brief A problem found on disk, loaded only if selected. */
    struct Source
    {
        std::string name;
        fs::path cfg, path;  ///< path: the .path (OMPL.app) or the .poses (maps)
        bool isMap{false};
    };

    struct Problem
    {
        std::string name;
        ProblemConfig config;
        std::vector<Eigen::Isometry3d> path;  ///< OMPL.app states, before interpolation
        std::string pathNote;
    };

    std::vector<fs::path> filesUnder(const std::string &dir, const std::string &extension)
    {
        std::vector<fs::path> out;
        if (dir.empty())
            return out;
        if (!fs::is_directory(dir))
            throw Exception(dir, "not a folder");
        for (const auto &entry : fs::recursive_directory_iterator(dir))
            if (entry.is_regular_file() && entry.path().extension() == extension)
                out.push_back(entry.path());
        std::sort(out.begin(), out.end());
        return out;
    }

    /** \brief OMPL.app problems under \e dir: each NAME.cfg with a solution path beside it, NAME.path or else the
        first NAME*.path (sorted) not claimed by a cfg with a longer name in the same folder. */
    std::vector<Source> findOmplAppProblems(const std::string &dir)
    {
        const std::vector<fs::path> cfgs = filesUnder(dir, ".cfg"), paths = filesUnder(dir, ".path");
        std::vector<Source> out;
        for (const fs::path &cfg : cfgs)
        {
            const std::string stem = cfg.stem().string();
            std::optional<fs::path> chosen;
            for (const fs::path &p : paths)
            {
                const std::string ps = p.stem().string();
                if (p.parent_path() != cfg.parent_path() || ps.compare(0, stem.size(), stem) != 0)
                    continue;
                // Claimed by a longer cfg name in the same folder (cubicles_opt.path is not cubicles').
                bool claimed = false;
                for (const fs::path &other : cfgs)
                {
                    const std::string os = other.stem().string();
                    claimed = claimed || (other.parent_path() == cfg.parent_path() && os.size() > stem.size() &&
                                          ps.compare(0, os.size(), os) == 0);
                }
                if (claimed)
                    continue;
                if (ps == stem)
                {
                    chosen = p;
                    break;
                }
                if (!chosen)
                    chosen = p;
            }
            if (chosen)
                out.push_back({stem, cfg, *chosen, false});
        }
        return out;
    }

    /** \brief Maps under \e dir: each NAME.cfg with NAME.poses beside it. */
    std::vector<Source> findMaps(const std::string &dir)
    {
        std::vector<Source> out;
        for (const fs::path &cfg : filesUnder(dir, ".cfg"))
        {
            const fs::path poses = cfg.parent_path() / (cfg.stem().string() + ".poses");
            if (fs::exists(poses))
                out.push_back({cfg.stem().string(), cfg, poses, true});
        }
        return out;
    }

    Problem load(const Source &source)
    {
        Problem p{source.name, readProblemConfig(source.cfg.string()), {}, {}};
        if (!source.isMap)
        {
            p.path = p.config.planar ? readPlanarPath(source.path.string()) : readPoses(source.path.string());
            p.pathNote = source.path.filename().string();
            return p;
        }
        // .poses place B's own frame; OMPL.app states place B shifted by its centre c: state = pose * translate(c).
        p.pathNote = source.path.filename().string() + " then goal";
        LoadReport report;
        loadRobotMesh(p.config.robot, p.config.planar, &report);
        Eigen::Vector3d c = report.omplAppCenter;
        if (p.config.planar)
            c.z() = 0.0;
        for (Eigen::Isometry3d X : readPoses(source.path.string()))
        {
            X.translate(c);
            p.path.push_back(X);
        }
        if (p.config.goal)
            p.path.push_back(*p.config.goal);
        return p;
    }

    bool sameDistance(double a, double b)
    {
        return std::abs(a - b) <= 1e-6 * std::abs(b) + 1e-9;
    }

    /** \brief Warm and cold answers agree: the same verdict, signed distances within 1e-12 relative. */
    bool sameAnswer(const SceneResult &a, const SceneResult &b)
    {
        return a.inCollision == b.inCollision &&
               (a.distance == b.distance ||
                std::abs(a.distance - b.distance) <= 1e-12 * std::max(std::abs(a.distance), std::abs(b.distance)));
    }

    const char *const COLUMNS[] = {"FCL distance", "FCL collision",  "cold certified",       "warm certified",
                                   "fast",         "collision-only", "collision-only, warm", "enumeration"};
    /** \brief --skip names of the columns, in COLUMNS' order (the FCL columns are the reference: never skipped). */
    const char *const SKIP_NAMES[] = {"", "", "cold", "warm", "fast", "collision", "collision-warm", "enumeration"};
    enum Column
    {
        FCL_D,
        FCL_C,
        COLD,
        WARM,
        FAST,
        COLL,
        WCOLL,
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
    try
    {
        std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp", maps, csvFile, problemList, skipList,
                    fastSolver = "comb-GA-wl";
        maps = std::string(MESHGAP_SOURCE_DIR) + "/maps";
        std::size_t states = 1000, random = 1000, enumEvery = 10;
        std::uint32_t seed = 1;
        namespace po = boost::program_options;
        po::options_description cli("meshgap_bench_queries");
        cli.add_options()("help,h", "print this help")(
            "data", po::value(&data), "folder searched for OMPL.app problems (NAME.cfg + NAME*.path); '' for none")(
            "maps", po::value(&maps), "folder searched for maps (NAME.cfg + NAME.poses); '' for none")(
            "problems", po::value(&problemList), "comma-separated problem names (default: every one found)")(
            "skip", po::value(&skipList),
            "comma-separated columns or sets to leave out: cold, warm, fast, collision, "
            "enumeration, path, random")("states", po::value(&states), "interpolated states per path")(
            "random", po::value(&random), "random poses per problem")("enum-every", po::value(&enumEvery),
                                                                      "run enumeration on every N-th state (0: never)")(
            "seed", po::value(&seed), "seed of the random poses")("csv", po::value(&csvFile), "also write CSV here")(
            "fast-solver", po::value(&fastSolver),
            "the fast column's node-level solver (default comb-GA-wl; warm-fast follows the path warm-started)");
        po::variables_map vm;
        if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
            return 0;
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

        bool active[NUM_COLUMNS];
        std::fill(active, active + NUM_COLUMNS, true);
        bool runPath = true, runRandom = true;
        for (const std::string &name : splitList(skipList))
        {
            bool known = name == "path" || name == "random";
            runPath = runPath && name != "path";
            runRandom = runRandom && name != "random";
            for (int c = COLD; c < NUM_COLUMNS; ++c)
                if (name == SKIP_NAMES[c])
                {
                    active[c] = false;
                    known = true;
                }
            if (!known)
                throw Exception("--skip",
                                "unknown column or set '" + name +
                                    "' (valid: cold, warm, fast, collision, collision-warm, enumeration, path, random; "
                                    "the FCL columns are the reference and always run)");
        }
        if (enumEvery == 0)
            active[ENUM] = false;
        if (runPath && states < 2)
            throw Exception("--states", std::to_string(states) + " is too few: a path needs at least 2 states");

        std::vector<Source> sources = findOmplAppProblems(data), found = findMaps(maps);
        sources.insert(sources.end(), found.begin(), found.end());
        std::vector<std::string> names;
        for (const Source &s : sources)
            names.push_back(s.name);
        for (std::size_t i = 0; i < names.size(); ++i)
            for (std::size_t j = i + 1; j < names.size(); ++j)
                if (names[i] == names[j])
                    throw Exception(sources[j].cfg.string(), "a second problem named '" + names[i] +
                                                                 "' (the first: " + sources[i].cfg.string() + ")");
        if (!problemList.empty())
        {
            std::vector<Source> chosen;
            for (const std::string &name : splitList(problemList))
            {
                const auto it = std::find(names.begin(), names.end(), name);
                if (it == names.end())
                {
                    std::string where;
                    if (!data.empty())
                        where += " a .cfg and a .path under '" + data + "'";
                    if (!maps.empty())
                        where += std::string(where.empty() ? "" : " or") + " a .cfg and a .poses under '" + maps + "'";
                    throw Exception("--problems", "no problem '" + name + "' with" + where + " (valid: " +
                                                      (names.empty() ? std::string("none found") : joinNames(names)) +
                                                      ")");
                }
                chosen.push_back(sources[std::size_t(it - names.begin())]);
            }
            sources = chosen;
        }
        if (sources.empty())
            throw Exception("meshgap_bench_queries", "no problem found under '" + data + "' or '" + maps + "'");

        std::unique_ptr<std::ofstream> csv;
        if (!csvFile.empty())
        {
            csv = std::make_unique<std::ofstream>(csvFile);
            if (!*csv)
                throw Exception(csvFile, "cannot open for writing");
            *csv << "problem,set,states,colliding,world_triangles,robot_triangles,obstacles,method,queries,median_us,"
                    "p90_us,ratio_to_fcl,verdict_disagreements,distance_disagreements,warm_cold_disagreements,"
                    "warm_start_bytes\n";
        }
        std::printf(
            "Times per query in µs: median / p90 (median / FCL's median: distance columns against FCL distance, "
            "collision-only against FCL collision).\n\n| problem | poses | world / robot triangles (obstacles) | "
            "colliding (FCL) |");
        std::string rule = "|---|---|---|---|";
        for (int c = 0; c < NUM_COLUMNS; ++c)
            if (active[c])
            {
                std::printf(" %s |", COLUMNS[c]);
                rule += "---|";
            }
        std::printf(" warm start | disagreements |\n%s---|---|\n", rule.c_str());
        std::fflush(stdout);
        const Enumeration enumeration;
        for (const Source &source : sources)
        {
            const Problem problem = load(source);
            const Mesh world = loadMesh(problem.config.world),
                       robot = loadRobotMesh(problem.config.robot, problem.config.planar);
            const ScenePtr scene = Scene::fromMeshes(robot, world);
            if (active[FAST] || active[ENUM])
            {
                for (const BodyConstPtr &o : scene->obstacles())
                    o->distances();  // built on first use: keep that out of the fast column's times
                scene->robot().distances();
            }
            const auto fw = test::fclModel(world), fr = test::fclModel(robot);
            Eigen::AlignedBox3d volume = problem.config.volume ? *problem.config.volume : world.bounds();

            for (const char *set : {"path", "random"})
            {
                const bool onPath = std::string(set) == "path";
                if (!(onPath ? runPath : runRandom))
                    continue;
                const std::vector<Eigen::Isometry3d> poses =
                    onPath ? bench::interpolatePath(problem.path, states) : randomPoses(volume, random, seed);
                if (poses.empty())
                    continue;
                std::vector<double> t[NUM_COLUMNS];
                std::size_t verdicts[NUM_COLUMNS] = {}, distances[NUM_COLUMNS] = {}, colliding = 0, fastBelowExact = 0,
                            warmCold = 0;
                SceneWarmStart warm, fastWarm, collisionWarm;
                SceneRequest certified, fast;
                fast.exact = false;
                fast.solver = fastSolver;
                for (std::size_t i = 0; i < poses.size(); ++i)
                {
                    const Eigen::Isometry3d &X = poses[i];
                    double dF = 0;
                    bool cF = false, cM = false, cW = false;
                    SceneResult cold, hot, quick;
                    t[FCL_D].push_back(timed([&] { dF = test::fclDistance(fw, fr, X); }));
                    t[FCL_C].push_back(timed([&] { cF = test::fclCollide(fw, fr, X); }));
                    if (active[COLD])
                        t[COLD].push_back(timed([&] { scene->distance(X, certified, cold); }));
                    if (active[WARM])
                        t[WARM].push_back(timed([&] { scene->distance(X, certified, warm, hot); }));
                    if (active[FAST])
                        t[FAST].push_back(timed([&] { scene->distance(X, fast, fastWarm, quick); }));
                    if (active[COLL])
                        t[COLL].push_back(timed([&] { cM = scene->inCollision(X); }));
                    if (active[WCOLL])
                        t[WCOLL].push_back(timed([&] { cW = scene->inCollision(X, collisionWarm); }));
                    colliding += cF;
                    verdicts[FCL_D] += (dF <= 0) != cF;
                    if (active[COLD])
                    {
                        verdicts[COLD] += cold.inCollision != cF;
                        if (!cF && !cold.inCollision)
                            distances[COLD] += !sameDistance(cold.distance, dF);
                    }
                    if (active[WARM])
                    {
                        verdicts[WARM] += hot.inCollision != cF;
                        if (!cF && !hot.inCollision)
                            distances[WARM] += !sameDistance(hot.distance, dF);
                    }
                    if (active[COLD] && active[WARM])
                        warmCold += !sameAnswer(hot, cold);
                    if (active[FAST])
                    {
                        verdicts[FAST] += quick.inCollision != cF;
                        if (active[COLD] && !cold.inCollision && !quick.inCollision)
                            fastBelowExact += quick.distance < cold.distance - 1e-9 * (1 + cold.distance);
                    }
                    if (active[COLL])
                        verdicts[COLL] += cM != cF;
                    if (active[WCOLL])
                        verdicts[WCOLL] += cW != cF;
                    if (active[ENUM] && i % enumEvery == 0)
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
                    const double ref = c == COLL || c == WCOLL ? s[FCL_C].median : s[FCL_D].median;
                    if (c == FCL_D || c == FCL_C)
                        std::snprintf(buf, sizeof buf, "%.1f / %.1f", s[c].median, s[c].p90);
                    else
                        std::snprintf(buf, sizeof buf, "%.1f / %.1f (**%.2f**)", s[c].median, s[c].p90,
                                      s[c].median / ref);
                    std::string out = buf;
                    if (c == ENUM && s[c].n != poses.size())
                        out += " [" + std::to_string(s[c].n) + "]";
                    return out;
                };
                std::string dis = "verdicts " +
                                  std::to_string(verdicts[COLD] + verdicts[WARM] + verdicts[FAST] + verdicts[COLL] +
                                                 verdicts[WCOLL]) +
                                  ", distances " + std::to_string(distances[COLD] + distances[WARM]);
                if (active[COLD] && active[WARM])
                    dis += ", warm≠cold " + std::to_string(warmCold);
                if (verdicts[FCL_D])
                    dis += ", FCL distance vs collide " + std::to_string(verdicts[FCL_D]);
                if (fastBelowExact)
                    dis += ", fast below exact " + std::to_string(fastBelowExact);
                if (distances[ENUM])
                    dis += ", enumeration below exact " + std::to_string(distances[ENUM]);
                const std::optional<std::size_t> warmBytes = warmStartBytes(warm);
                std::printf("| %s (%s) | %zu %s | %zu / %zu (%zu) | %zu |", problem.name.c_str(),
                            onPath ? problem.pathNote.c_str() : "random", poses.size(), set, world.triangles.size(),
                            robot.triangles.size(), scene->obstacles().size(), colliding);
                for (int c = 0; c < NUM_COLUMNS; ++c)
                    if (active[c])
                        std::printf(" %s |", cell(c).c_str());
                std::printf(" %s | %s |\n", warmBytes ? (std::to_string(*warmBytes) + " B").c_str() : "-", dis.c_str());
                std::fflush(stdout);
                if (csv)
                    for (int c = 0; c < NUM_COLUMNS; ++c)
                    {
                        if (!active[c])
                            continue;
                        const double ref = c == COLL || c == WCOLL || c == FCL_C ? s[FCL_C].median : s[FCL_D].median;
                        *csv << problem.name << "," << set << "," << poses.size() << "," << colliding << ","
                             << world.triangles.size() << "," << robot.triangles.size() << ","
                             << scene->obstacles().size() << "," << COLUMNS[c] << "," << s[c].n << "," << s[c].median
                             << "," << s[c].p90 << "," << (s[c].n ? s[c].median / ref : 0.0) << "," << verdicts[c]
                             << "," << distances[c] << ",";
                        if (c == WARM && active[COLD])
                            *csv << warmCold;
                        *csv << ",";
                        if (c == WARM && warmBytes)
                            *csv << *warmBytes;
                        *csv << "\n";
                    }
            }
        }
        return 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
#endif
}
