// meshgap_distance: minimum distance between two bodies at one or many poses.
//
//   meshgap_distance A.obj B.obj --pose "x y z qx qy qz qw" [--algorithm NAME]
//   meshgap_distance --cfg problem.cfg [--pose ...] [--poses path.path] [--cold] [--json]
//   meshgap_distance --cfg problem.cfg --algorithm NAME [--exact] [--pose ...] [--poses path.path] [--json]
//
// With two mesh files, A is fixed (the world frame) and B placed by the pose; the answer is the named node-level
// solver's (--algorithm, default enumeration) on the two whole bodies, refined to the exact distance with --exact.
// With --cfg F (any problem: one rigid body, a URDF robot, several bodies; or the MoveIt flags) and no --algorithm,
// the answer is the checker's, the same for every kind (a single body is a robot of one link, rigidBodyProblem()):
// per state of the problem (its start by default; --pose "v1 v2 ...", or --poses STATES one a line, as a .path of
// the problem: x y theta or x y z qx qy qz qw for a single body) the whole robot's exact signed clearance, the pair
// that attains it (a link and an obstacle, or two links) with its witness points, and every link's clearance; one
// warm start carried from state to state (--cold: none). A text block for one state, CSV with a header for --poses
// (support/RobotDistance.h, ROBOT_CSV_COLUMNS), JSON with --json; with --poses the time per query (median and mean)
// goes to stderr. --cfg with --algorithm (a single body only) puts the named solver to the problem's world (A) and
// robot (B, centred as OMPL.app centres it), the pose then "x y z qx qy qz qw". In collision (always decided exactly)
// the distance is signed: negative, minus a penetration depth estimate (--no-depth: the verdict alone).

#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"
#include "support/MoveItOptions.h"
#include "support/RobotDistance.h"
#include "support/SurfaceText.h"

namespace po = boost::program_options;
using namespace meshgap;

namespace
{
    double gridValue(const std::string &text, const std::string &option)
    {
        if (text == "auto")
            return -1.0;
        double h = 0.0;
        if (parseNumber(text, h) && h >= 0.0 && std::isfinite(h))
            return h;
        throw Exception("--" + option, quote(text) + " is not a grid size (a number >= 0, 0 = no refinement, or auto)");
    }

    BodyPtr makeBody(const Mesh &mesh, const LoadReport &report, double grid, bool adaptive,
                     const MeshDistancesOptions &distances, const char *label)
    {
        BodyOptions options;
        options.gridSize = grid;
        if (adaptive)
            options.sizing = GridSizing::ADAPTIVE;
        options.distances = distances;
        BodyPtr body = Body::build(mesh, options);
        const Eigen::AlignedBox3d box = mesh.bounds();
        OMPL_INFORM("%s: %s: %zu vertices, %zu triangles, components: %zu, %s, box [%g %g %g]..[%g %g %g]", label,
                    mesh.source.c_str(), mesh.vertices.size(), mesh.triangles.size(), report.components,
                    surfaceText(body->edges()).c_str(), box.min().x(), box.min().y(), box.min().z(), box.max().x(),
                    box.max().y(), box.max().z());
        if (body->adaptiveSizing())
            OMPL_INFORM("%s: adaptive node sizing (largest size %g): %zu nodes, %zu triangles, longest edge %g", label,
                        body->gridSize(), body->refinement().nodesAfter, body->refinement().trianglesAfter,
                        body->refinement().longestEdge);
        else if (body->gridSize() > 0.0)
            OMPL_INFORM("%s: refined to grid size %g: %zu nodes, %zu triangles, longest edge %g", label,
                        body->gridSize(), body->refinement().nodesAfter, body->refinement().trianglesAfter,
                        body->refinement().longestEdge);
        return body;
    }

    std::string vec(const Eigen::Vector3d &v, const char *sep)
    {
        char buffer[128];
        std::snprintf(buffer, sizeof buffer, "%.10g%s%.10g%s%.10g", v.x(), sep, v.y(), sep, v.z());
        return buffer;
    }

    /** \brief The text answer's last line when a body of the answer is not closed. */
    const char *const OPEN_BODY_LINE =
        "open body      yes (not a closed surface: nothing counts as inside it; README, \"Open meshes\")\n";

    const char *penetrationText(Penetration kind)
    {
        switch (kind)
        {
            case Penetration::DEEPEST_NODE:
                return "in collision: minus the depth of the deepest node inside the other body";
            case Penetration::NO_NODE_INSIDE:
                return "in collision: no node inside the other body, depth 0";
            case Penetration::OPEN_BODIES:
                return "in collision: open bodies have no depth";
            default:
                return "in collision: depth not computed";
        }
    }

    /** \brief The exact solver searches the surfaces, not the nodes: its answer has no node pair. */
    bool hasNodePair(const std::string &algorithm)
    {
        return algorithm != "exact";
    }

    std::string json(const DistanceResult &r, const std::string &algorithm)
    {
        std::ostringstream out;
        out.precision(17);
        out << "{\"algorithm\": \"" << algorithm << "\", \"distance\": " << r.distance << ", \"nodes\": ";
        if (hasNodePair(algorithm))
            out << "[" << r.nodes.a << ", " << r.nodes.b << "]";
        else
            out << "null";
        out << ", \"witness_a\": [" << vec(r.onA, ", ") << "], \"witness_b\": ["
            << vec(r.onB, ", ") << "], \"evaluations\": " << r.evaluations << ", \"time_us\": " << r.seconds * 1e6
            << ", \"node_optimal\": " << (r.nodeOptimal ? "true" : "false") << ", \"in_collision\": "
            << (r.inCollision ? "true" : "false") << ", \"certified\": " << (r.certified ? "true" : "false")
            << ", \"node_distance\": " << (std::isfinite(r.nodeDistance) ? r.nodeDistance : r.distance)
            << ", \"open_body\": " << (r.openBody ? "true" : "false") << "}";
        return out.str();
    }

    /** \brief "N poses, LABEL: median X us, mean Y us per query" on stderr (printed whatever the log level). */
    void printTimes(const std::vector<double> &micros, const std::string &label)
    {
        if (micros.empty())
            return;
        std::vector<double> sorted = micros;
        std::sort(sorted.begin(), sorted.end());
        double sum = 0.0;
        for (double us : micros)
            sum += us;
        std::fprintf(stderr, "meshgap_distance: %zu poses, %s: median %.1f us, mean %.1f us per query\n", micros.size(),
                     label.c_str(), sorted[sorted.size() / 2], sum / double(micros.size()));
    }

    /** \brief The command line. */
    struct Options
    {
        std::string cfg, poseText, posesFile, algorithm = "enumeration", grid = "auto", gridA, gridB, cacheDir,
                                              sizing = "uniform";
        std::vector<std::string> meshes, settings;
        std::uint64_t seed = 1;
        double budgetMiB = 512;
        bool algorithmGiven = false, cold = false, json = false, exact = false, noDepth = false;

        /** \brief With --cfg and no --algorithm: the checker's answer (the scene), not a node-level solver. */
        bool scene() const { return !cfg.empty() && !algorithmGiven; }
        bool many() const { return !posesFile.empty(); }
        /** \brief --urdf, --srdf, --scene, --request: a robot problem in MoveIt's files. */
        MoveItFiles moveit;
    };

    /** \brief Parse the command line; false after --help. */
    bool parseOptions(int argc, char **argv, Options &o)
    {
        po::options_description visible("meshgap_distance [options] [A B]\n\nOptions");
        visible.add_options()("help,h", "print this help")
            ("cfg", po::value(&o.cfg), "OMPL.app problem file: A = its world, B = its robot (pose = robot state)")
            ("pose", po::value(&o.poseText), "pose of B in A's frame: \"x y z qx qy qz qw\" (default: identity); with --cfg the "
                                           "problem's state (default: its start): a single body's x y theta or x y z qx qy qz qw, a robot's numbers")
            ("poses", po::value(&o.posesFile), "file of poses (with --cfg: the problem's states), one per line (OMPL.app .path format); prints CSV "
                                           "with a header")
            ("algorithm,a", po::value(&o.algorithm), "solver name (unknown names list the valid ones)")
            ("seed", po::value(&o.seed), "random seed (same seed, same answer)")
            ("param", po::value(&o.settings), "ALGORITHM.NAME=VALUE: a parameter of the --algorithm, e.g. comb-GA-wl.population=200 (repeatable)")
            ("grid", po::value(&o.grid), "grid size h for both bodies: a length, 0 (no refinement) or auto (1/25 of body size)")
            ("grid-a", po::value(&o.gridA), "grid size for body A only")
            ("grid-b", po::value(&o.gridB), "grid size for body B only")
            ("sizing", po::value(&o.sizing), "node sizing of both bodies: uniform (the --grid sizes) or adaptive (finer at thin parts, holes and creases, coarser on thick parts; --grid is then ignored)")
            ("cache", po::value(&o.cacheDir), "folder for cached mesh-distance tables")
            ("memory-budget", po::value(&o.budgetMiB), "largest all-pairs mesh-distance table, MiB (default 512)")
            ("exact", "refine the answer to the exact, certified surface distance (triangles + BVH)")
            ("cold", "with --cfg and no --algorithm: a cold query at every state, no warm start (default: one carried along)")
            ("no-depth", "with --cfg and no --algorithm: in collision the verdict alone (distance -2.2e-308, a zero below zero, as FCL answers 0), no penetration depth")
            ("json", "print JSON instead of text or CSV")
            ("quiet,q", "print errors only (no log, no warnings such as a mesh's open surface)");
        cli::addMoveItOptions(visible, o.moveit);
        po::options_description hidden;
        hidden.add_options()("mesh", po::value(&o.meshes));
        po::options_description all;
        all.add(visible).add(hidden);
        cli::addRenamedOptions(all, {{"set", "--param ALGORITHM.NAME=VALUE"}});
        po::positional_options_description positional;
        positional.add("mesh", 2);
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, all, vm, &positional, &visible))
            return false;
        o.algorithmGiven = vm.count("algorithm") > 0;
        o.cold = vm.count("cold") > 0;
        o.noDepth = vm.count("no-depth") > 0;
        o.json = vm.count("json") > 0;
        o.exact = vm.count("exact") > 0;
        if (!(o.budgetMiB >= 0.0 && o.budgetMiB <= 1e9))  // NaN included; the bytes are a size_t
        {
            char found[32];
            std::snprintf(found, sizeof found, "%g", o.budgetMiB);
            throw Exception("--memory-budget", std::string(found) + " is not a size in MiB from 0 to 1e9");
        }
        return true;
    }

    /** \brief The checker's answer at each state of \e problem, whatever its kind (a single body as a robot of one
        link, rigidBodyProblem()): the whole robot's exact, certified signed clearance (cli::robotDistance()). */
    int answerWithScene(const Options &o, Problem problem)
    {
        if (!o.meshes.empty())
            throw Exception("command line", "give either --cfg or two mesh files, not both");
        if (problem.robot && o.algorithmGiven)
            throw Exception("--algorithm", "a robot problem (" + o.cfg + o.moveit.urdf +
                                               ") is answered by the exact whole-robot scene; the node-level solvers "
                                               "take single bodies");
        if (!o.settings.empty())
            throw Exception("--param", "solver parameters need --algorithm (with --cfg alone the answer is the scene's)");
        const RobotProblem p = problem.robot ? std::move(*problem.robot) : rigidBodyProblem(*problem.rigidBody);
        cli::RobotDistanceOptions options;
        options.json = o.json;
        options.cold = o.cold;
        options.depth = !o.noDepth;
        cli::robotDistance(p, o.poseText, o.posesFile, options, std::cout);
        return 0;
    }

    /** \brief The named solver with its --param values; fails on a bad name or parameter before any loading. */
    DistanceSolverPtr solverOf(const Options &o)
    {
        if (o.cold && !o.scene())
            throw Exception("--cold", "applies to the scene's answer only (--cfg without --algorithm)");
        if (o.noDepth && !o.scene())
            throw Exception("--no-depth", "applies to the scene's answer only (--cfg without --algorithm)");
        if (o.scene() && !o.settings.empty())
            throw Exception("--param", "solver parameters need --algorithm (with --cfg alone the answer is the scene's)");
        DistanceSolverPtr solver = allocSolver(o.algorithm);
        for (const std::string &s : o.settings)
        {
            const cli::OwnedParam param = cli::parseOwnedParam(s, "ALGORITHM", o.algorithm + ".NAME=VALUE");
            if (param.owner != o.algorithm)
                throw Exception("--param", quote(s) + ": the algorithm is " + o.algorithm + ", not " + param.owner);
            if (!solver->params().hasParam(param.name) || !solver->params().setParam(param.name, param.value))
                throw Exception("--param", quote(s) + " is not a valid parameter of " + o.algorithm);
        }
        if (o.sizing != "uniform" && o.sizing != "adaptive")
            throw Exception("--sizing", quote(o.sizing) + " is not a node sizing (uniform or adaptive)");
        return solver;
    }

    /** \brief The two meshes (A: the world or the first file, B: the robot or the second) and the poses of B. */
    struct Input
    {
        Mesh a, b;
        LoadReport reportA, reportB;
        std::vector<Eigen::Isometry3d> poses;
    };

    /** \brief \e single: the single-body problem of --cfg, if given. */
    Input loadInput(const Options &o, const std::optional<ProblemConfig> &single)
    {
        Input in;
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        if (single)
        {
            if (!o.meshes.empty())
                throw Exception("command line", "give either --cfg or two mesh files, not both");
            const ProblemConfig &problem = *single;
            in.a = loadMesh(problem.world, &in.reportA);
            in.b = loadRobotMesh(problem.robot, problem.planar, &in.reportB);  // OMPL.app's centring, 2D or 3D
            pose = problem.start;
        }
        else
        {
            if (o.meshes.size() != 2)
                throw Exception("command line", "need two mesh files (A B) or --cfg FILE; see --help");
            in.a = loadMesh(o.meshes[0], &in.reportA);
            in.b = loadMesh(o.meshes[1], &in.reportB);
        }
        if (!o.poseText.empty())
            pose = parsePose(o.poseText, "--pose");
        in.poses = {pose};
        if (!o.posesFile.empty())
            in.poses = readPoses(o.posesFile);
        return in;
    }

    /** \brief One solver answer as text (one pose, no --json). */
    void printResult(const DistanceResult &result, const Options &o)
    {
        std::printf("algorithm      %s%s\ndistance       %.10g (%s)\n", o.algorithm.c_str(),
                    o.exact && o.algorithm != "exact" ? " + exact" : "", result.distance,
                    result.inCollision ? penetrationText(result.penetration)
                    : result.certified ? "exact, certified"
                                       : "node to node: an upper bound");
        if (result.certified && std::isfinite(result.nodeDistance))
            std::printf("node distance  %.10g\n", result.nodeDistance);
        const std::string nodes = hasNodePair(o.algorithm) ? "A " + std::to_string(result.nodes.a) + ", B " +
                                                                 std::to_string(result.nodes.b)
                                                           : "none (the exact solver searches the surfaces)";
        std::printf("in collision   %s\nnode pair      %s\nwitness on A   %s\nwitness on B   %s\n"
                    "evaluations    %zu\ntime           %.3f ms\n",
                    result.inCollision ? "yes" : "no", nodes.c_str(), vec(result.onA, " ").c_str(),
                    vec(result.onB, " ").c_str(), result.evaluations, result.seconds * 1e3);
        if (result.openBody)
            std::printf("%s", OPEN_BODY_LINE);
    }

    /** \brief One solver answer as a CSV row or a JSON array entry (--poses). */
    void printRow(const DistanceResult &result, const Options &o, std::size_t i, std::size_t count)
    {
        // The exact solver's rows leave node_a and node_b empty: it has no node pair.
        const std::string nodes = hasNodePair(o.algorithm)
                                      ? std::to_string(result.nodes.a) + "," + std::to_string(result.nodes.b)
                                      : ",";
        if (o.json)
            std::cout << "  " << json(result, o.algorithm) << (i + 1 < count ? ",\n" : "\n");
        else
            std::printf("%zu,%.17g,%zu,%.3f,%s,%s,%s,%d,%d,%.17g\n", i, result.distance, result.evaluations,
                        result.seconds * 1e6, nodes.c_str(), vec(result.onA, ",").c_str(), vec(result.onB, ",").c_str(),
                        result.inCollision ? 1 : 0, result.certified ? 1 : 0,
                        std::isfinite(result.nodeDistance) ? result.nodeDistance : result.distance);
    }

    /** \brief The named solver's answer on the two whole bodies at each pose; with --exact refined to the exact,
        certified distance; collision always decided exactly. */
    int answerWithSolver(const Body &a, const Body &b, const DistanceSolver &solver,
                         const std::vector<Eigen::Isometry3d> &poses, const Options &o)
    {
        DistanceRequest request;
        request.seed = o.seed;
        if (o.many())
            std::cout << (o.json ? "[\n" : "index,distance,evaluations,time_us,node_a,node_b,"
                                           "witness_a_x,witness_a_y,witness_a_z,witness_b_x,witness_b_y,witness_b_z,"
                                           "in_collision,certified,node_distance\n");
        std::vector<double> micros;
        auto lastReport = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            DistanceResult result;
            const auto queryStart = std::chrono::steady_clock::now();
            solver.solve(a, b, poses[i], request, result);
            result.openBody = !a.isClosed() || !b.isClosed();  // refineExact() sets it too
            if (o.exact && !result.certified)
                refineExact(a, b, poses[i], result);
            else if (!result.certified && inCollision(a, b, poses[i]))  // collision is always decided exactly
            {
                // ... and then the distance is signed, as in exact mode: minus the penetration depth estimate.
                result.nodeDistance = result.distance;
                setPenetration(a, b, poses[i], result);
            }
            result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - queryStart).count();
            micros.push_back(result.seconds * 1e6);
            if (!o.many())
            {
                if (o.json)
                    std::cout << json(result, o.algorithm) << "\n";
                else
                    printResult(result, o);
                continue;
            }
            printRow(result, o, i, poses.size());
            const auto now = std::chrono::steady_clock::now();
            if (now - lastReport > std::chrono::seconds(2))
            {
                OMPL_INFORM("pose %zu of %zu", i + 1, poses.size());
                lastReport = now;
            }
        }
        if (o.many() && o.json)
            std::cout << "]\n";
        if (o.many())
            printTimes(micros, o.algorithm + (o.exact && o.algorithm != "exact" ? " + exact" : ""));
        return 0;
    }

    int run(int argc, char **argv)
    {
        Options o;
        if (!parseOptions(argc, argv, o))
            return 0;
        std::optional<ProblemConfig> single;
        if (!o.cfg.empty() || cli::moveItGiven(o.moveit))
        {
            Problem problem = cli::readToolProblem(o.cfg, o.moveit);
            if (problem.robot || !o.algorithmGiven)
                return answerWithScene(o, std::move(problem));
            single = std::move(problem.rigidBody);
        }
        const DistanceSolverPtr solver = solverOf(o);
        const double hA = gridValue(o.gridA.empty() ? o.grid : o.gridA, o.gridA.empty() ? "grid" : "grid-a");
        const double hB = gridValue(o.gridB.empty() ? o.grid : o.gridB, o.gridB.empty() ? "grid" : "grid-b");
        MeshDistancesOptions distances;
        distances.memoryBudgetBytes = static_cast<std::size_t>(o.budgetMiB * 1024 * 1024);
        distances.cacheDir = o.cacheDir;
        const Input in = loadInput(o, single);
        const BodyPtr a = makeBody(in.a, in.reportA, hA, o.sizing == "adaptive", distances, "A");
        const BodyPtr b = makeBody(in.b, in.reportB, hB, o.sizing == "adaptive", distances, "B");
        return answerWithSolver(*a, *b, *solver, in.poses, o);
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
