// meshgap_distance: minimum distance between two bodies at one or many poses.
//
//   meshgap_distance A.obj B.obj --pose "x y z qx qy qz qw" [--algorithm NAME]
//   meshgap_distance --cfg problem.cfg [--pose ...] [--poses path.path] [--json]
//
// A is fixed (the world frame); B is placed by the pose. With --cfg, A is the problem's world and B its robot in
// OMPL.app's conventions (robot shifted by its centre; the pose is the robot's state), and the default pose is the
// problem's start. Results go to stdout (text, CSV with --poses, or JSON with --json); the log goes to stderr.
// In collision (always decided exactly) the distance is signed: negative, minus a penetration depth estimate.

#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <ompl/util/Console.h>
#include <sstream>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/mesh/Body.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

namespace po = boost::program_options;
using namespace meshgap;

namespace
{
    double gridValue(const std::string &text, const std::string &option)
    {
        if (text == "auto")
            return -1.0;
        try
        {
            std::size_t used = 0;
            const double h = std::stod(text, &used);
            if (used == text.size() && h >= 0.0 && std::isfinite(h))
                return h;
        }
        catch (const std::exception &)
        {
        }
        throw Exception("--" + option, "'" + text + "' is not a grid size (a number >= 0, 0 = no refinement, or auto)");
    }

    BodyPtr makeBody(const Mesh &mesh, const LoadReport &report, double grid, bool adaptive,
                     const MeshDistancesOptions &distances, const char *label)
    {
        BodyOptions options;
        options.gridSize = grid;
        if (adaptive)
            options.sizing = GridSizing::Adaptive;
        options.distances = distances;
        BodyPtr body = Body::build(mesh, options);
        const Eigen::AlignedBox3d box = mesh.bounds();
        OMPL_INFORM("%s: %s: %zu vertices, %zu triangles, components: %zu, box [%g %g %g]..[%g %g %g]", label,
                    mesh.source.c_str(), mesh.vertices.size(), mesh.triangles.size(), report.components,
                    box.min().x(), box.min().y(), box.min().z(), box.max().x(), box.max().y(), box.max().z());
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

    const char *penetrationText(Penetration kind)
    {
        switch (kind)
        {
            case Penetration::DeepestNode:
                return "in collision: minus the depth of the deepest node inside the other body";
            case Penetration::NoNodeInside:
                return "in collision: no node inside the other body, depth 0";
            case Penetration::OpenBodies:
                return "in collision: open bodies have no depth";
            default:
                return "in collision: depth not computed";
        }
    }

    std::string json(const DistanceResult &r, const std::string &algorithm)
    {
        std::ostringstream out;
        out.precision(17);
        out << "{\"algorithm\": \"" << algorithm << "\", \"distance\": " << r.distance << ", \"nodes\": [" << r.nodes.a
            << ", " << r.nodes.b << "], \"witness_a\": [" << vec(r.onA, ", ") << "], \"witness_b\": ["
            << vec(r.onB, ", ") << "], \"evaluations\": " << r.evaluations << ", \"time_us\": " << r.seconds * 1e6
            << ", \"node_optimal\": " << (r.nodeOptimal ? "true" : "false") << ", \"in_collision\": "
            << (r.inCollision ? "true" : "false") << ", \"certified\": " << (r.certified ? "true" : "false")
            << ", \"node_distance\": " << (std::isfinite(r.nodeDistance) ? r.nodeDistance : r.distance) << "}";
        return out.str();
    }

    int run(int argc, char **argv)
    {
        std::string cfg, poseText, posesFile, algorithm = "enumeration", grid = "auto", gridA, gridB, cacheDir;
        std::string sizing = "uniform";
        std::vector<std::string> meshes, settings;
        std::uint64_t seed = 1;
        double budgetMiB = 512;
        po::options_description visible("meshgap_distance [options] [A B]\n\nOptions");
        visible.add_options()("help,h", "print this help")
            ("cfg", po::value(&cfg), "OMPL.app problem file: A = its world, B = its robot (pose = robot state)")
            ("pose", po::value(&poseText), "pose of B in A's frame: \"x y z qx qy qz qw\" (default: identity, or the cfg's start)")
            ("poses", po::value(&posesFile), "file of poses, one per line (OMPL.app .path format); prints CSV")
            ("algorithm,a", po::value(&algorithm), "solver name (unknown names list the valid ones)")
            ("seed", po::value(&seed), "random seed (same seed, same answer)")
            ("set", po::value(&settings), "solver parameter NAME=VALUE (repeatable)")
            ("grid", po::value(&grid), "grid size h for both bodies: a length, 0 (no refinement) or auto (1/25 of body size)")
            ("grid-a", po::value(&gridA), "grid size for body A only")
            ("grid-b", po::value(&gridB), "grid size for body B only")
            ("sizing", po::value(&sizing), "node sizing of both bodies: uniform (the --grid sizes) or adaptive (finer at thin parts, holes and creases, coarser on thick parts; --grid is then ignored)")
            ("cache", po::value(&cacheDir), "folder for cached mesh-distance tables")
            ("memory-budget", po::value(&budgetMiB), "largest all-pairs mesh-distance table, MiB (default 512)")
            ("exact", "refine the answer to the exact, certified surface distance (triangles + BVH)")
            ("json", "print JSON instead of text or CSV")
            ("quiet,q", "print warnings and errors only");
        po::options_description hidden;
        hidden.add_options()("mesh", po::value(&meshes));
        po::options_description all;
        all.add(visible).add(hidden);
        po::positional_options_description positional;
        positional.add("mesh", 2);
        po::variables_map vm;
        po::store(po::command_line_parser(argc, argv).options(all).positional(positional).run(), vm);
        po::notify(vm);
        if (vm.count("help"))
        {
            std::cout << visible << "\n";
            return 0;
        }
        if (vm.count("quiet"))
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

        // Fail on a bad algorithm or parameter before any expensive loading.
        DistanceSolverPtr solver = allocSolver(algorithm);
        for (const std::string &s : settings)
        {
            const auto eq = s.find('=');
            if (eq == std::string::npos)
                throw Exception("--set", "'" + s + "' is not NAME=VALUE");
            if (!solver->params().hasParam(s.substr(0, eq)) || !solver->params().setParam(s.substr(0, eq), s.substr(eq + 1)))
                throw Exception("--set", "'" + s + "' is not a valid parameter of " + algorithm);
        }
        if (sizing != "uniform" && sizing != "adaptive")
            throw Exception("--sizing", "'" + sizing + "' is not a node sizing (uniform or adaptive)");
        const double hA = gridValue(gridA.empty() ? grid : gridA, gridA.empty() ? "grid" : "grid-a");
        const double hB = gridValue(gridB.empty() ? grid : gridB, gridB.empty() ? "grid" : "grid-b");
        MeshDistancesOptions distances;
        distances.memoryBudgetBytes = static_cast<std::size_t>(budgetMiB * 1024 * 1024);
        distances.cacheDir = cacheDir;

        Mesh meshA, meshB;
        LoadReport reportA, reportB;
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        if (!cfg.empty())
        {
            if (!meshes.empty())
                throw Exception("command line", "give either --cfg or two mesh files, not both");
            const ProblemConfig problem = readProblemConfig(cfg);
            meshA = loadMesh(problem.world, &reportA);
            meshB = loadRobotMesh(problem.robot, problem.planar, &reportB);  // OMPL.app's centring, 2D or 3D
            pose = problem.start;
        }
        else
        {
            if (meshes.size() != 2)
                throw Exception("command line", "need two mesh files (A B) or --cfg FILE; see --help");
            meshA = loadMesh(meshes[0], &reportA);
            meshB = loadMesh(meshes[1], &reportB);
        }
        if (!poseText.empty())
            pose = parsePose(poseText, "--pose");
        std::vector<Eigen::Isometry3d> poses{pose};
        if (!posesFile.empty())
            poses = readPoses(posesFile);

        const BodyPtr a = makeBody(meshA, reportA, hA, sizing == "adaptive", distances, "A");
        const BodyPtr b = makeBody(meshB, reportB, hB, sizing == "adaptive", distances, "B");

        DistanceRequest request;
        request.seed = seed;
        const bool many = !posesFile.empty(), asJson = vm.count("json") > 0, exact = vm.count("exact") > 0;
        if (many)
            std::cout << (asJson ? "[\n" : "index,distance,evaluations,time_us,node_a,node_b,"
                                           "witness_a_x,witness_a_y,witness_a_z,witness_b_x,witness_b_y,witness_b_z,"
                                           "in_collision,certified,node_distance\n");
        auto lastReport = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            DistanceResult result;
            const auto queryStart = std::chrono::steady_clock::now();
            solver->solve(*a, *b, poses[i], request, result);
            if (exact && !result.certified)
                refineExact(*a, *b, poses[i], result);
            else if (!result.certified && inCollision(*a, *b, poses[i]))  // collision is always decided exactly
            {
                // ... and then the distance is signed, as in exact mode: minus the penetration depth estimate.
                result.nodeDistance = result.distance;
                setPenetration(*a, *b, poses[i], result);
            }
            result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - queryStart).count();
            if (!many)
            {
                if (asJson)
                    std::cout << json(result, algorithm) << "\n";
                else
                {
                    std::printf("algorithm      %s%s\ndistance       %.10g (%s)\n", algorithm.c_str(),
                                exact && algorithm != "exact" ? " + exact" : "", result.distance,
                                result.inCollision ? penetrationText(result.penetration)
                                : result.certified ? "exact, certified"
                                                   : "node to node: an upper bound");
                    if (result.certified && std::isfinite(result.nodeDistance))
                        std::printf("node distance  %.10g\n", result.nodeDistance);
                    std::printf("in collision   %s\nnode pair      A %u, B %u\nwitness on A   %s\nwitness on B   %s\n"
                                "evaluations    %zu\ntime           %.3f ms\n",
                                result.inCollision ? "yes" : "no", result.nodes.a, result.nodes.b,
                                vec(result.onA, " ").c_str(), vec(result.onB, " ").c_str(), result.evaluations,
                                result.seconds * 1e3);
                }
                continue;
            }
            if (asJson)
                std::cout << "  " << json(result, algorithm) << (i + 1 < poses.size() ? ",\n" : "\n");
            else
                std::printf("%zu,%.17g,%zu,%.3f,%u,%u,%s,%s,%d,%d,%.17g\n", i, result.distance, result.evaluations,
                            result.seconds * 1e6, result.nodes.a, result.nodes.b, vec(result.onA, ",").c_str(),
                            vec(result.onB, ",").c_str(), result.inCollision ? 1 : 0, result.certified ? 1 : 0,
                            std::isfinite(result.nodeDistance) ? result.nodeDistance : result.distance);
            const auto now = std::chrono::steady_clock::now();
            if (now - lastReport > std::chrono::seconds(2))
            {
                OMPL_INFORM("pose %zu of %zu", i + 1, poses.size());
                lastReport = now;
            }
        }
        if (many && asJson)
            std::cout << "]\n";
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
