// Per-query cost of every meshgap query against FCL 0.7 (BVHModel<OBBRSS>, robot against the whole world, as
// OMPL.app builds it), on OMPL.app problems that ship a solution path, on meshgap's maps, and on any pair of mesh
// files:
//   - --data DIR: every NAME.cfg found under DIR (recursively) with a solution path next to it: NAME.path, or else
//     NAME*.path (a path belongs to the cfg with the longest name it starts with, so cubicles_opt.path is not
//     cubicles'). SE(3) paths are "x y z qx qy qz qw" per line, SE(2) ones (a cfg without start.z) "x y theta";
//   - --maps DIR: every NAME.cfg found under DIR with NAME.poses next to it (maps/: B's body-frame poses, then the
//     cfg's goal);
//   - --problems a,b,c: only these (by name, from either folder; an unknown name lists the valid ones). Default:
//     every problem found.
//   - --robot FILE --world FILE[,FILE...]: any mesh files assimp reads (loadMesh(), as the tools load them), the
//     robot in its own frame, the world files merged into one world and split into its connected parts (one
//     obstacle each, as Scene::fromMeshes() does). Poses are drawn in the world's bounding box grown by the robot's
//     radius (its farthest vertex from its origin). --data and --maps are then not searched unless given.
// Streams of poses (--streams; problems default to path,random, mesh pairs to all four):
//   - "path": problems: the solution path interpolated to --states states (SE(3): linear translation, slerp
//     rotation); mesh pairs: random waypoints (uniform position in the box, uniform rotation, one per 200 states)
//     interpolated the same way, a planner's motion checks along a path;
//   - "random": --random poses uniform in the cfg's volume (mesh pairs: the box) with a uniform rotation;
//   - "mixed": --states poses, path states (half as many, a path of their own) interleaved one for one with random
//     ones, as a planner's motion checks between its samples;
//   - "alternating": --states poses from two paths queried alternately, as RRTConnect's two trees ask them: mesh
//     pairs, two random paths in the two halves of the box along its longest side; problems, the solution path's
//     first and second halves (the start's side and the goal's).
// Per state, interleaved so machine load hits every column alike: FCL distance, FCL collision, meshgap cold
// certified (Scene::distance without a warm start), warm certified (one warm start carried from state to state),
// cold and warm with the depth skipped (SceneRequest::computeDepth false, the warm one with its own warm start: the
// verdict alone in collision, as FCL's 0), fast (SceneRequest::exact = false with --fast-solver, its own carried warm
// start), collision-only (Scene::inCollision), collision-only warm (Scene::inCollision with its own warm start), and
// enumeration (the exact node-level minimum over every obstacle, on every --enum-every'th state). --skip leaves
// columns (cold, warm, cold-nodepth, warm-nodepth, fast, collision, collision-warm, enumeration) or streams out; the
// two FCL columns are the reference and always run. What is built on a body's first use is built before the timed
// queries (the penetration depth's node layer and surface grid; fast mode's and enumeration's mesh distances), so the
// columns time queries, not one-time builds (meshgap_bench_build --nodes times those). Mesh pairs leave fast and enumeration out by default (their node-level data costs seconds to build
// on large meshes): --columns fast,enumeration brings them back.
//
// Reported per stream, for all queries and split by FCL's verdict (free, colliding): the median (p50) and 99th
// percentile (p99) in microseconds and their ratios to FCL's p50 and p99 of the same queries (distance columns to
// FCL distance, collision-only to FCL collision); warm p99 / cold p99; the warm start's memory (the most its
// SceneWarmStart::memoryBytes() reached along the stream). Disagreements: collision verdicts of every column against
// FCL's collision, split into containment (meshgap: collision, FCL: free, and one closed body holds a vertex of the
// other: insideClosedBody(), so wholly inside it) and other; certified distances against FCL's distance where both
// say free, beyond 1e-8 relative (+ 1e-12 absolute); warm (and warm without depth) against cold (same verdict,
// signed distances within 1e-12 relative where the depth is computed: the warm start must never change the
// answer). --check: exit status 2 when any disagreement other than containment was found. --clock thread-cpu times
// the thread's own run (blind to waits for a core on a shared machine, which otherwise make the p99). Every time is
// net of the clock's own cost (the median of an empty call timed alike, printed with the table): the thread's CPU
// clock costs about as much as a collision-only query.
//
// Mesh pairs also report load and build: meshgap's loadMesh() of each file, the merge and split of the world, and
// Body::build() of every part (the Scene that the queries then use), against FCL's load of the same files through
// assimp as OMPL.app does it (FclLoad.h) and its BVHModel<OBBRSS> build; median of --load-repeats runs each.
//
//   build/bench/meshgap_bench_queries [--data ../shared/data/omplapp] [--maps maps] [--problems a,b,c]
//                                     [--robot FILE --world FILE[,FILE...]] [--streams path,random,...]
//                                     [--skip fast,enumeration,random,...] [--columns fast,enumeration]
//                                     [--states 1000] [--random 1000] [--enum-every 10] [--seed 1] [--csv FILE]
//                                     [--load-repeats 3] [--clock wall|thread-cpu] [--check]

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <time.h>

#include "CliMain.h"
#include "FclLoad.h"
#include "FclOracle.h"
#include "PathInterpolation.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    Eigen::Isometry3d randomPose(const Eigen::AlignedBox3d &volume, std::mt19937_64 &rng)
    {
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::normal_distribution<double> g;
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        const Eigen::Vector3d f(u(rng), u(rng), u(rng));
        X.translation() = volume.min() + f.cwiseProduct(volume.sizes());
        const Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));  // uniform on SO(3)
        X.linear() = q.normalized().toRotationMatrix();
        return X;
    }

    std::vector<Eigen::Isometry3d> randomPoses(const Eigen::AlignedBox3d &volume, std::size_t count, std::uint32_t seed)
    {
        std::mt19937_64 rng(seed);
        std::vector<Eigen::Isometry3d> out;
        for (std::size_t i = 0; i < count; ++i)
            out.push_back(randomPose(volume, rng));
        return out;
    }

    /** \brief \e count states along random waypoints in \e volume (one waypoint per 200 states, at least two),
        interpolated evenly (bench::interpolatePath()): small steps, as a planner's motion checks. */
    std::vector<Eigen::Isometry3d> randomPath(const Eigen::AlignedBox3d &volume, std::size_t count, std::uint32_t seed)
    {
        return bench::interpolatePath(randomPoses(volume, std::max<std::size_t>(2, count / 200 + 1), seed), count);
    }

    /** \brief a[0], b[0], a[1], b[1], ... (the longer one's rest at the end). */
    std::vector<Eigen::Isometry3d> interleave(const std::vector<Eigen::Isometry3d> &a,
                                              const std::vector<Eigen::Isometry3d> &b)
    {
        std::vector<Eigen::Isometry3d> out;
        for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i)
        {
            if (i < a.size())
                out.push_back(a[i]);
            if (i < b.size())
                out.push_back(b[i]);
        }
        return out;
    }

    /** \brief The two halves of \e box along its longest side. */
    std::pair<Eigen::AlignedBox3d, Eigen::AlignedBox3d> halves(const Eigen::AlignedBox3d &box)
    {
        Eigen::Index axis;
        box.sizes().maxCoeff(&axis);
        Eigen::AlignedBox3d low = box, high = box;
        low.max()[axis] = high.min()[axis] = box.center()[axis];
        return {low, high};
    }

    struct Stats
    {
        std::size_t n{0};
        double p50{0}, p99{0};
    };

    /** \brief p50 and p99 (µs) of the times \e t whose verdict is \e want (1: colliding, 0: free, -1: every one). */
    Stats stats(const std::vector<double> &t, const std::vector<char> &colliding, int want)
    {
        std::vector<double> v;
        for (std::size_t i = 0; i < t.size(); ++i)
            if (want < 0 || colliding[i] == want)
                v.push_back(t[i]);
        if (v.empty())
            return {};
        std::sort(v.begin(), v.end());
        return {v.size(), v[v.size() / 2] * 1e6, v[std::min(v.size() - 1, v.size() * 99 / 100)] * 1e6};
    }

    /** \brief --clock thread-cpu: time the calling thread ran (CLOCK_THREAD_CPUTIME_ID), blind to the time the
        thread waited for a core on a loaded machine; otherwise wall time (steady_clock). */
    bool threadCpuClock = false;

    double threadSeconds()
    {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    }

    /** \brief The clock's own cost per timed call, in seconds (measureClockCost()): timed() leaves it out. */
    double clockCost = 0.0;

    /** \brief \e f's time by the chosen clock, less the clock's own cost (clockCost; never below 0). */
    template <typename F>
    double timed(F &&f)
    {
        double elapsed;
        if (threadCpuClock)
        {
            const double t0 = threadSeconds();
            f();
            elapsed = threadSeconds() - t0;
        }
        else
        {
            const auto t0 = std::chrono::steady_clock::now();
            f();
            elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        return std::max(0.0, elapsed - clockCost);
    }

    double median(std::vector<double> v)
    {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    }

    /** \brief Sets clockCost: the median time of an empty call, timed as timed() times a query. Reading the
        thread's CPU clock is a system call (about 0.6 µs here, against 0.03 for the wall clock), as long as a
        collision-only query: left in, it would bring every ratio of sub-microsecond times towards 1. */
    void measureClockCost()
    {
        clockCost = 0.0;
        std::vector<double> t(2001);
        for (double &x : t)
            x = timed([] { asm volatile("" ::: "memory"); });
        clockCost = median(t);
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
        Eigen::Vector3d c = report.omplAppCenter.value();
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

    /** \brief Certified distances agree with FCL's where both say free: within 1e-8 relative (+ 1e-12 absolute). */
    bool sameDistance(double a, double b)
    {
        return std::abs(a - b) <= 1e-8 * std::max(std::abs(a), std::abs(b)) + 1e-12;
    }

    /** \brief Warm and cold answers agree: the same verdict, signed distances within 1e-12 relative (\e depth: also
        in collision). */
    bool sameAnswer(const SceneResult &a, const SceneResult &b, bool depth = true)
    {
        if (a.inCollision != b.inCollision)
            return false;
        if (a.inCollision && !depth)
            return true;
        return a.distance == b.distance ||
               std::abs(a.distance - b.distance) <= 1e-12 * std::max(std::abs(a.distance), std::abs(b.distance));
    }

    const char *const COLUMNS[] = {"FCL distance",   "FCL collision",  "cold certified", "warm certified",
                                   "cold, no depth", "warm, no depth", "fast",           "collision-only",
                                   "collision-only, warm", "enumeration"};
    /** \brief --skip / --columns names of the columns, in COLUMNS' order (the FCL columns are the reference: never
        skipped). */
    const char *const SKIP_NAMES[] = {"",          "",          "cold",          "warm",           "cold-nodepth",
                                      "warm-nodepth", "fast",     "collision",     "collision-warm", "enumeration"};
    enum Column
    {
        FCL_D,
        FCL_C,
        COLD,
        WARM,
        COLD_ND,
        WARM_ND,
        FAST,
        COLL,
        WCOLL,
        ENUM,
        NUM_COLUMNS
    };
    bool collisionColumn(int c)
    {
        return c == FCL_C || c == COLL || c == WCOLL;
    }
    const char *const STREAMS[] = {"path", "random", "mixed", "alternating"};

    struct Stream
    {
        std::string name, note;
        std::vector<Eigen::Isometry3d> poses;
    };

    /** \brief One robot and world, their scene and the streams of poses to query. */
    struct Case
    {
        std::string name;
        Mesh robot, world;
        ScenePtr scene;
        std::vector<Stream> streams;
    };

    struct Options
    {
        bool active[NUM_COLUMNS];
        std::set<std::string> streams;
        std::size_t states{1000}, random{1000}, enumEvery{10}, loadRepeats{3};
        std::uint32_t seed{1};
        std::size_t certificates{4};  ///< per warm start, as ClearanceChecker keeps them
        std::string fastSolver{"comb-GA-wl"};
    };

    /** \brief The streams \e options asks for, for a problem (its solution path) or a mesh pair (path empty:
        random waypoints in \e volume). */
    std::vector<Stream> makeStreams(const Options &options, const Eigen::AlignedBox3d &volume,
                                    const std::vector<Eigen::Isometry3d> &path, const std::string &pathNote)
    {
        const std::uint32_t seed = options.seed;
        const std::size_t half = (options.states + 1) / 2;
        const bool pair = path.empty();
        std::vector<Stream> out;
        if (options.streams.count("path"))
            out.push_back({"path", pair ? "random waypoints" : pathNote,
                           pair ? randomPath(volume, options.states, seed + 1) :
                                  bench::interpolatePath(path, options.states)});
        if (options.streams.count("random"))
            out.push_back({"random", "random", randomPoses(volume, options.random, seed)});
        if (options.streams.count("mixed"))
            out.push_back({"mixed", "path + random",
                           interleave(pair ? randomPath(volume, half, seed + 2) : bench::interpolatePath(path, half),
                                      randomPoses(volume, options.states / 2, seed + 3))});
        if (options.streams.count("alternating"))
        {
            std::vector<Eigen::Isometry3d> a, b;
            if (pair)
            {
                const auto [low, high] = halves(volume);
                a = randomPath(low, half, seed + 4);
                b = randomPath(high, options.states / 2, seed + 5);
            }
            else
            {
                const std::vector<Eigen::Isometry3d> all = bench::interpolatePath(path, options.states);
                a.assign(all.begin(), all.begin() + long(half));
                b.assign(all.rbegin(), all.rend() - long(half));  // from the goal back, as the goal's tree grows
            }
            out.push_back({"alternating", pair ? "two regions" : "start and goal halves", interleave(a, b)});
        }
        return out;
    }

    /** \brief One closed body holds a vertex of the other (so, with no surface contact, wholly inside it), by the
        winding number summed over every triangle (containsPoint(), the definition, not the BVH's ray casting that
        the queries use). */
    bool contained(const Scene &scene, const Eigen::Isometry3d &X_WR)
    {
        const Body &robot = scene.robot();
        const Eigen::Vector3d onRobot = X_WR * robot.surface().vertices[robot.surface().triangles[0][0]];
        const Eigen::Isometry3d X_RW = X_WR.inverse();
        for (const BodyConstPtr &o : scene.obstacles())
            if (containsPoint(*o, onRobot) ||
                containsPoint(robot, X_RW * o->surface().vertices[o->surface().triangles[0][0]]))
                return true;
        return false;
    }

    /** \brief What one stream measured. */
    struct Tally
    {
        std::vector<double> t[NUM_COLUMNS];
        std::vector<char> colliding, enumColliding;  ///< FCL's verdict per query (enumColliding: ENUM's queries)
        std::size_t containment[NUM_COLUMNS] = {}, other[NUM_COLUMNS] = {}, distances[NUM_COLUMNS] = {};
        std::size_t posesContainment{0}, posesOther{0}, warmCold{0}, noDepthCold{0}, fclSelf{0}, fastBelowExact{0},
            warmBytes{0};
    };

    /** \brief The warm starts and requests carried along one stream. */
    struct Carried
    {
        explicit Carried(std::size_t certificates)
          : warm(certificates), noDepthWarm(certificates), fastWarm(certificates), collisionWarm(certificates)
        {
        }
        SceneWarmStart warm, noDepthWarm, fastWarm, collisionWarm;
        SceneRequest certified, noDepth, fast;
    };

    using FclModelPtr = std::shared_ptr<test::FclModel>;

    /** \brief Every active column at pose \e i of the stream, timed, and its answers checked against FCL's. */
    void measure(const Case &c, const FclModelPtr &fw, const FclModelPtr &fr, const Eigen::Isometry3d &X,
                 std::size_t i, const Options &options, Carried &k, Tally &tally)
    {
        const Scene &scene = *c.scene;
        const bool *active = options.active;
        double dF = 0;
        bool cF = false, verdict[NUM_COLUMNS] = {};
        SceneResult r[NUM_COLUMNS];
        tally.t[FCL_D].push_back(timed([&] { dF = test::fclDistance(fw, fr, X); }));
        tally.t[FCL_C].push_back(timed([&] { cF = test::fclCollide(fw, fr, X); }));
        if (active[COLD])
            tally.t[COLD].push_back(timed([&] { scene.distance(X, k.certified, r[COLD]); }));
        if (active[WARM])
            tally.t[WARM].push_back(timed([&] { scene.distance(X, k.certified, k.warm, r[WARM]); }));
        if (active[COLD_ND])
            tally.t[COLD_ND].push_back(timed([&] { scene.distance(X, k.noDepth, r[COLD_ND]); }));
        if (active[WARM_ND])
            tally.t[WARM_ND].push_back(timed([&] { scene.distance(X, k.noDepth, k.noDepthWarm, r[WARM_ND]); }));
        if (active[FAST])
            tally.t[FAST].push_back(timed([&] { scene.distance(X, k.fast, k.fastWarm, r[FAST]); }));
        if (active[COLL])
            tally.t[COLL].push_back(timed([&] { verdict[COLL] = scene.inCollision(X); }));
        if (active[WCOLL])
            tally.t[WCOLL].push_back(timed([&] { verdict[WCOLL] = scene.inCollision(X, k.collisionWarm); }));
        tally.colliding.push_back(cF);
        tally.fclSelf += (dF <= 0) != cF;
        if (active[WARM])
            tally.warmBytes = std::max(tally.warmBytes, k.warm.memoryBytes());
        bool poseContained = false, poseOther = false;
        int holds = -1;  // contained(), asked once per pose and only on a verdict difference
        for (int col = COLD; col < ENUM; ++col)
        {
            if (!active[col])
                continue;
            if (col != COLL && col != WCOLL)
                verdict[col] = r[col].inCollision;
            if (verdict[col] != cF)
            {
                // Only a collision FCL does not see can be a containment (FCL tests surfaces only).
                if (verdict[col] && holds < 0)
                    holds = contained(scene, X);
                const bool inside = verdict[col] && holds > 0;
                ++(inside ? tally.containment : tally.other)[col];
                (inside ? poseContained : poseOther) = true;
            }
            if (col != FAST && col != COLL && col != WCOLL && !cF && !verdict[col])
                tally.distances[col] += !sameDistance(r[col].distance, dF);
        }
        tally.posesContainment += poseContained;
        tally.posesOther += poseOther;
        if (active[COLD] && active[WARM])
            tally.warmCold += !sameAnswer(r[WARM], r[COLD]);
        if (active[COLD] && active[WARM_ND])
            tally.noDepthCold += !sameAnswer(r[WARM_ND], r[COLD], false);
        if (active[COLD] && active[COLD_ND])
            tally.noDepthCold += !sameAnswer(r[COLD_ND], r[COLD], false);
        if (active[FAST] && active[COLD] && !r[COLD].inCollision && !r[FAST].inCollision)
            tally.fastBelowExact += r[FAST].distance < r[COLD].distance - 1e-9 * (1 + r[COLD].distance);
        if (active[ENUM] && i % options.enumEvery == 0)
        {
            static const Enumeration enumeration;
            double best = std::numeric_limits<double>::infinity();
            tally.t[ENUM].push_back(timed(
                [&]
                {
                    for (const BodyConstPtr &o : scene.obstacles())
                    {
                        DistanceResult e;
                        enumeration.solve(*o, scene.robot(), X, DistanceRequest(), e);
                        best = std::min(best, e.distance);
                    }
                }));
            tally.enumColliding.push_back(cF);
            // A node pair is a pair of surface points: never below the exact distance.
            if (!cF && best < dF - 1e-9 * (1 + dF))
                ++tally.distances[ENUM];
        }
    }

    /** \brief Disagreements other than containment (what --check fails on). */
    std::size_t wrongCount(const Tally &t)
    {
        std::size_t n = t.posesOther + t.warmCold + t.noDepthCold + t.fclSelf + t.fastBelowExact;
        for (int c = 0; c < NUM_COLUMNS; ++c)
            n += t.distances[c];
        return n;
    }

    std::string disagreements(const Tally &t)
    {
        std::size_t distances = 0;
        for (int c = COLD; c < ENUM; ++c)
            distances += t.distances[c];
        std::string out = "verdicts: containment " + std::to_string(t.posesContainment) + ", other " +
                          std::to_string(t.posesOther) + "; distances " + std::to_string(distances);
        if (t.t[COLD].size() && t.t[WARM].size())
            out += ", warm≠cold " + std::to_string(t.warmCold);
        if (t.t[COLD].size() && (t.t[WARM_ND].size() || t.t[COLD_ND].size()))
            out += ", no-depth≠cold " + std::to_string(t.noDepthCold);
        if (t.fclSelf)
            out += ", FCL distance vs collide " + std::to_string(t.fclSelf);
        if (t.fastBelowExact)
            out += ", fast below exact " + std::to_string(t.fastBelowExact);
        if (t.distances[ENUM])
            out += ", enumeration below exact " + std::to_string(t.distances[ENUM]);
        return out;
    }

    const char *const VERDICTS[] = {"all", "free", "colliding"};
    int verdictWanted(int v)
    {
        return v == 0 ? -1 : v == 1 ? 0 : 1;
    }

    /** \brief The table's rows and the CSV's for one stream: all queries, then the free and the colliding ones. */
    void report(const Case &c, const Stream &stream, const Options &options, const Tally &tally, std::ostream *csv)
    {
        const std::size_t colliding = std::size_t(std::count(tally.colliding.begin(), tally.colliding.end(), 1));
        for (int v = 0; v < 3; ++v)
        {
            Stats s[NUM_COLUMNS];
            for (int col = 0; col < NUM_COLUMNS; ++col)
                s[col] = stats(tally.t[col], col == ENUM ? tally.enumColliding : tally.colliding, verdictWanted(v));
            if (s[FCL_D].n == 0)
                continue;
            const double warmOverCold = s[COLD].n && s[WARM].n ? s[WARM].p99 / s[COLD].p99 : 0.0;
            std::printf("| %s | %s (%s) | %zu | %s (%zu) |", c.name.c_str(), stream.name.c_str(), stream.note.c_str(),
                        stream.poses.size(), VERDICTS[v], s[FCL_D].n);
            for (int col = 0; col < NUM_COLUMNS; ++col)
            {
                if (!options.active[col])
                    continue;
                const Stats &ref = collisionColumn(col) ? s[FCL_C] : s[FCL_D];
                if (s[col].n == 0)
                    std::printf(" - |");
                else if (col == FCL_D || col == FCL_C)
                    std::printf(" %.1f / %.1f |", s[col].p50, s[col].p99);
                else
                    std::printf(" %.1f / %.1f (**%.2f** / %.2f) |", s[col].p50, s[col].p99, s[col].p50 / ref.p50,
                                s[col].p99 / ref.p99);
            }
            char ratio[32] = "-";
            if (warmOverCold)
                std::snprintf(ratio, sizeof ratio, "%.2f", warmOverCold);
            if (v == 0)
                std::printf(" %s | %s | %s |\n", ratio,
                            tally.warmBytes ? (std::to_string(tally.warmBytes) + " B").c_str() : "-",
                            disagreements(tally).c_str());
            else
                std::printf(" %s | | |\n", ratio);
            if (!csv)
                continue;
            for (int col = 0; col < NUM_COLUMNS; ++col)
            {
                if (!options.active[col])
                    continue;
                const Stats &ref = collisionColumn(col) ? s[FCL_C] : s[FCL_D];
                *csv << '"' << c.name << "\"," << stream.name << "," << stream.poses.size() << "," << colliding << ","
                     << c.world.triangles.size() << "," << c.robot.triangles.size() << ","
                     << c.scene->obstacles().size() << "," << VERDICTS[v] << ",\"" << COLUMNS[col] << "\"," << s[col].n
                     << "," << s[col].p50 << "," << s[col].p99 << "," << (s[col].n ? s[col].p50 / ref.p50 : 0.0) << ","
                     << (s[col].n ? s[col].p99 / ref.p99 : 0.0) << ",";
                if (col == WARM && warmOverCold)
                    *csv << warmOverCold;
                *csv << ",";
                if (v == 0)
                    *csv << tally.containment[col] << "," << tally.other[col] << "," << tally.distances[col];
                else
                    *csv << ",,";
                *csv << ",";
                if (v == 0 && col == WARM)
                    *csv << tally.warmCold;
                if (v == 0 && (col == WARM_ND || col == COLD_ND))
                    *csv << tally.noDepthCold;
                *csv << ",";
                if (v == 0 && col == WARM && tally.warmBytes)
                    *csv << tally.warmBytes;
                *csv << "\n";
            }
        }
        std::fflush(stdout);
    }

    /** \brief Query every stream of \e c; returns the disagreements other than containment. */
    std::size_t run(const Case &c, const Options &options, std::ostream *csv)
    {
        if (options.active[COLD] || options.active[WARM])
        {
            // What penetration depth reads (the node layer, the surface grid) is built on a body's first colliding
            // query: keep that one-time build out of the depth columns' times, as the load and build are.
            for (const BodyConstPtr &o : c.scene->obstacles())
                o->surfaceGrid(), o->numNodes();
            c.scene->robot().surfaceGrid(), c.scene->robot().numNodes();
        }
        if (options.active[FAST] || options.active[ENUM])
        {
            for (const BodyConstPtr &o : c.scene->obstacles())
                o->distances();  // built on first use: keep that out of the fast column's times
            c.scene->robot().distances();
        }
        const FclModelPtr fw = test::fclModel(c.world), fr = test::fclModel(c.robot);
        std::size_t wrong = 0;
        for (const Stream &stream : c.streams)
        {
            if (stream.poses.empty())
                continue;
            Tally tally;
            Carried k(options.certificates);
            k.noDepth.computeDepth = false;
            k.fast.exact = false;
            k.fast.solver = options.fastSolver;
            for (std::size_t i = 0; i < stream.poses.size(); ++i)
                measure(c, fw, fr, stream.poses[i], i, options, k, tally);
            report(c, stream, options, tally, csv);
            wrong += wrongCount(tally);
        }
        return wrong;
    }

    /** \brief A problem as a case: its world, its robot in OMPL.app's frame, its streams. */
    Case problemCase(const Source &source, const Options &options)
    {
        const Problem problem = load(source);
        Case c;
        c.name = problem.name;
        c.world = loadMesh(problem.config.world);
        c.robot = loadRobotMesh(problem.config.robot, problem.config.planar);
        c.scene = Scene::fromMeshes(c.robot, c.world);
        const Eigen::AlignedBox3d volume = problem.config.volume ? *problem.config.volume : c.world.bounds();
        c.streams = makeStreams(options, volume, problem.path, problem.pathNote);
        return c;
    }

    /** \brief Load and build times (seconds) of one input, meshgap's and FCL's, each split into the load (the
        files read) and the build (meshgap: merge, split, Body::build() of every part, the scene; FCL: BVHModel). */
    struct LoadCost
    {
        std::string input;
        std::size_t triangles{0}, parts{0};
        double load{0}, build{0}, fclLoad{0}, fclBuild{0};
    };

    /** \brief A mesh pair as a case, with the load and build of each input timed (median of options.loadRepeats)
        against FCL's. */
    Case pairCase(const std::string &robotFile, const std::vector<std::string> &worldFiles, const Options &options,
                  std::vector<LoadCost> &costs)
    {
        Case c;
        std::vector<double> t[2][4];  // [robot, world][load, build, FCL load, FCL build]
        BodyConstPtr robotBody;
        std::vector<BodyConstPtr> obstacles;
        for (std::size_t run = 0; run < std::max<std::size_t>(1, options.loadRepeats); ++run)
        {
            std::vector<Mesh> parts;
            t[0][0].push_back(timed([&] { c.robot = loadMesh(robotFile); }));
            t[0][1].push_back(timed([&] { robotBody = Body::build(c.robot); }));
            t[1][0].push_back(timed(
                [&]
                {
                    for (const std::string &file : worldFiles)
                        parts.push_back(loadMesh(file));
                }));
            t[1][1].push_back(timed(
                [&]
                {
                    c.world = parts.size() == 1 ? std::move(parts[0]) : mergeMeshes(parts, joinNames(worldFiles));
                    c.world.validate();
                    obstacles.clear();
                    for (Mesh &part : splitComponents(c.world))
                        obstacles.push_back(Body::build(std::move(part)));
                    c.scene = std::make_shared<Scene>(robotBody, obstacles);  // the broad phase's R-tree
                }));
            for (int input = 0; input < 2; ++input)
            {
                std::vector<fcl::Vector3d> points;
                t[input][2].push_back(
                    timed([&] { points = bench::fclReadTriangles(input == 0 ? std::vector{robotFile} : worldFiles); }));
                t[input][3].push_back(timed([&] { bench::fclBuild(points); }));
            }
        }
        std::vector<std::string> stems;
        for (const std::string &file : worldFiles)
            stems.push_back(fs::path(file).stem().string());
        std::string world = stems[0];
        for (std::size_t i = 1; i < stems.size(); ++i)
            world += "+" + stems[i];
        c.name = fs::path(robotFile).stem().string() + " vs " + world;
        costs.push_back({"robot " + robotFile, c.robot.triangles.size(), 1, median(t[0][0]), median(t[0][1]),
                         median(t[0][2]), median(t[0][3])});
        costs.push_back({"world " + joinNames(worldFiles), c.world.triangles.size(), obstacles.size(),
                         median(t[1][0]), median(t[1][1]), median(t[1][2]), median(t[1][3])});
        double radius = 0;
        for (const Eigen::Vector3d &v : c.robot.vertices)
            radius = std::max(radius, v.norm());
        Eigen::AlignedBox3d box = c.world.bounds();
        box.min().array() -= radius;
        box.max().array() += radius;
        c.streams = makeStreams(options, box, {}, "");
        return c;
    }
}  // namespace

namespace
{
    /** \brief --skip, --columns and --streams into \e options (mesh pairs: \e pairs). */
    void chooseColumns(const std::string &skipList, const std::string &columnList, const std::string &streamList,
                       bool pairs, Options &options)
    {
        std::fill(options.active, options.active + NUM_COLUMNS, true);
        if (pairs)
            options.active[FAST] = options.active[ENUM] = false;
        const std::string valid =
            "cold, warm, cold-nodepth, warm-nodepth, fast, collision, collision-warm, enumeration";
        auto column = [&](const std::string &option, const std::string &name)
        {
            for (int c = COLD; c < NUM_COLUMNS; ++c)
                if (name == SKIP_NAMES[c])
                    return c;
            throw Exception(option, "unknown column '" + name + "' (valid: " + valid +
                                        (option == "--skip" ? ", path, random, mixed, alternating" : "") +
                                        "; the FCL columns are the reference and always run)");
        };
        for (const std::string &name : splitList(columnList))
            options.active[column("--columns", name)] = true;
        options.streams = pairs ? std::set<std::string>(std::begin(STREAMS), std::end(STREAMS)) :
                                  std::set<std::string>{"path", "random"};
        if (!streamList.empty())
        {
            options.streams.clear();
            for (const std::string &name : splitList(streamList))
            {
                if (std::find(std::begin(STREAMS), std::end(STREAMS), name) == std::end(STREAMS))
                    throw Exception("--streams",
                                    "unknown stream '" + name + "' (valid: path, random, mixed, alternating)");
                options.streams.insert(name);
            }
        }
        for (const std::string &name : splitList(skipList))
        {
            if (std::find(std::begin(STREAMS), std::end(STREAMS), name) != std::end(STREAMS))
                options.streams.erase(name);
            else
                options.active[column("--skip", name)] = false;
        }
        if (options.enumEvery == 0)
            options.active[ENUM] = false;
        if (options.states < 2 && (options.streams.count("path") || options.streams.count("mixed") ||
                                   options.streams.count("alternating")))
            throw Exception("--states", std::to_string(options.states) +
                                            " is too few: a path needs at least 2 states (--skip path,mixed,"
                                            "alternating for random poses alone)");
    }

    /** \brief The problems found under \e data and \e maps, or those \e problemList names. */
    std::vector<Source> chooseProblems(const std::string &data, const std::string &maps, const std::string &problemList)
    {
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
        if (problemList.empty())
            return sources;
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
                                                  (names.empty() ? std::string("none found") : joinNames(names)) + ")");
            }
            chosen.push_back(sources[std::size_t(it - names.begin())]);
        }
        return chosen;
    }

    void printLoadTable(const std::vector<LoadCost> &costs, std::ostream *csv)
    {
        std::printf("Load and build in ms (median of the runs): meshgap's loadMesh, then merge + split + Body::build of "
                    "every part; FCL's assimp read (OMPL.app's flags), then BVHModel<OBBRSS> build.\n\n| input | "
                    "triangles (parts) | meshgap load + build | FCL load + build | meshgap / FCL: load, build, "
                    "**total** |\n|---|---|---|---|---|\n");
        for (const LoadCost &l : costs)
        {
            const double total = (l.load + l.build) / (l.fclLoad + l.fclBuild);
            std::printf("| %s | %zu (%zu) | %.2f + %.2f | %.2f + %.2f | %.2f, %.2f, **%.2f** |\n", l.input.c_str(),
                        l.triangles, l.parts, l.load * 1e3, l.build * 1e3, l.fclLoad * 1e3, l.fclBuild * 1e3,
                        l.load / l.fclLoad, l.build / l.fclBuild, total);
            if (csv)
                *csv << "\"" << l.input << "\"," << l.triangles << "," << l.parts << "," << l.load * 1e6 << ","
                     << l.build * 1e6 << "," << l.fclLoad * 1e6 << "," << l.fclBuild * 1e6 << "," << total << "\n";
        }
        std::printf("\n");
    }

    void printHeader(const Options &options, std::ostream *csv)
    {
        if (csv)
            *csv << "problem,set,states,colliding,world_triangles,robot_triangles,obstacles,verdict,method,queries,"
                    "p50_us,p99_us,ratio_p50,ratio_p99,warm_p99_over_cold_p99,verdict_containment,verdict_other,"
                    "distance_disagreements,warm_cold_disagreements,warm_start_bytes\n";
        std::printf("Times per query in µs (%s, less the clock's own cost, %.3f µs a timed call: an empty call's "
                    "median): p50 / p99 (**p50 / FCL's p50** / p99 / FCL's p99 over the same queries: distance "
                    "columns against FCL distance, collision-only against FCL collision); rows split by FCL's "
                    "verdict.\n\n| problem | stream | poses | verdict (queries) |",
                    threadCpuClock ? "the thread's CPU time" : "wall time", clockCost * 1e6);
        std::string rule = "|---|---|---|---|";
        for (int c = 0; c < NUM_COLUMNS; ++c)
            if (options.active[c])
            {
                std::printf(" %s |", COLUMNS[c]);
                rule += "---|";
            }
        std::printf(" warm p99 / cold p99 | warm start | disagreements |\n%s---|---|---|\n", rule.c_str());
        std::fflush(stdout);
    }
}  // namespace

int main(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "built without FCL\n");
    return 1;
#else
    try
    {
        std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp", maps, csvFile, loadCsvFile, problemList,
                    skipList, columnList, streamList, robotFile, worldList;
        maps = std::string(MESHGAP_SOURCE_DIR) + "/maps";
        Options options;
        bool check = false;
        std::string clock = "wall";
        namespace po = boost::program_options;
        po::options_description cli("meshgap_bench_queries");
        cli.add_options()("help,h", "print this help")(
            "data", po::value(&data), "folder searched for OMPL.app problems (NAME.cfg + NAME*.path); '' for none")(
            "maps", po::value(&maps), "folder searched for maps (NAME.cfg + NAME.poses); '' for none")(
            "problems", po::value(&problemList), "comma-separated problem names (default: every one found)")(
            "robot", po::value(&robotFile), "a robot mesh file (its own frame), queried against --world")(
            "world", po::value(&worldList), "comma-separated world mesh files, merged and split into parts")(
            "streams", po::value(&streamList),
            "comma-separated streams: path, random, mixed, alternating (default: path,random for problems, all "
            "four for --robot)")("skip", po::value(&skipList),
                                 "comma-separated columns or streams to leave out: cold, warm, cold-nodepth, "
                                 "warm-nodepth, fast, "
                                 "collision, collision-warm, enumeration, path, random, mixed, alternating")(
            "columns", po::value(&columnList), "comma-separated columns to run that are off by default (fast, "
                                               "enumeration with --robot)")(
            "states", po::value(&options.states), "states per path (and per mixed and alternating stream)")(
            "random", po::value(&options.random), "random poses per problem")(
            "enum-every", po::value(&options.enumEvery), "run enumeration on every N-th state (0: never)")(
            "seed", po::value(&options.seed), "seed of the random poses and waypoints")(
            "certificates", po::value(&options.certificates),
            "certificates each warm start keeps (SceneWarmStart; default 4, as ClearanceChecker's)")(
            "csv", po::value(&csvFile), "also write every row as CSV here")(
            "load-csv", po::value(&loadCsvFile), "with --robot: also write the load and build rows as CSV here")(
            "load-repeats", po::value(&options.loadRepeats), "with --robot: load and build runs (median reported)")(
            "check", po::bool_switch(&check), "exit with status 2 if any disagreement other than containment")(
            "clock", po::value(&clock),
            "wall (default) or thread-cpu: the thread's own run time, blind to waiting for a core on a loaded "
            "machine (each reading a system call of a few hundred ns, left out of every time as for the wall clock)")(
            "fast-solver", po::value(&options.fastSolver),
            "the fast column's node-level solver (default comb-GA-wl; warm-fast follows the path warm-started)");
        po::variables_map vm;
        if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
            return 0;
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

        if (clock != "wall" && clock != "thread-cpu")
            throw Exception("--clock", "unknown clock '" + clock + "' (valid: wall, thread-cpu)");
        threadCpuClock = clock == "thread-cpu";
        measureClockCost();
        const bool pairs = vm.count("robot") || vm.count("world");
        if (pairs && (robotFile.empty() || splitList(worldList).empty()))
            throw Exception(robotFile.empty() ? "--robot" : "--world",
                            "missing: a mesh pair needs --robot FILE and --world FILE[,FILE...]");
        if (pairs)
        {
            data = vm.count("data") ? data : "";
            maps = vm.count("maps") ? maps : "";
        }
        if (!vm.count("data") && !data.empty() && !fs::is_directory(data))
        {
            // The default folder is optional (a clone without ../shared): the maps alone, said so.
            std::fprintf(stderr, "no OMPL.app problems: %s is not a folder (--data names another)\n", data.c_str());
            data.clear();
        }
        if (!loadCsvFile.empty() && !pairs)
            throw Exception("--load-csv", "load and build are measured on --robot and --world only");
        chooseColumns(skipList, columnList, streamList, pairs, options);
        std::vector<Source> sources;
        if (!pairs || !data.empty() || !maps.empty())
            sources = chooseProblems(data, maps, problemList);
        if (sources.empty() && !pairs)
            throw Exception("meshgap_bench_queries", "no problem found under '" + data + "' or '" + maps + "'");

        std::unique_ptr<std::ofstream> csv, loadCsv;
        for (auto [file, stream] : {std::make_pair(&csvFile, &csv), std::make_pair(&loadCsvFile, &loadCsv)})
            if (!file->empty())
            {
                *stream = std::make_unique<std::ofstream>(*file);
                if (!**stream)
                    throw Exception(*file, "cannot open for writing");
            }
        std::vector<Case> pairCases;
        if (pairs)
        {
            std::vector<LoadCost> costs;
            pairCases.push_back(pairCase(robotFile, splitList(worldList), options, costs));
            if (loadCsv)
                *loadCsv << "input,triangles,parts,meshgap_load_us,meshgap_build_us,fcl_load_us,fcl_build_us,ratio\n";
            printLoadTable(costs, loadCsv.get());
        }
        printHeader(options, csv.get());
        std::size_t wrong = 0;
        for (const Case &c : pairCases)
            wrong += run(c, options, csv.get());
        for (const Source &source : sources)
            wrong += run(problemCase(source, options), options, csv.get());
        for (auto *stream : {csv.get(), loadCsv.get()})
            if (stream && !stream->flush())
                throw Exception(stream == csv.get() ? csvFile : loadCsvFile, "write failed");
        std::printf("\ndisagreements with FCL other than containment: %zu\n", wrong);
        return check && wrong ? 2 : 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
#endif
}
