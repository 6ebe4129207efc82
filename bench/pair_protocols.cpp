// meshgap_bench_pair_protocols: the exact pair query against FCL under two published protocols of mesh–mesh
// benchmarks, on meshes of the user's choice.
//
//   --protocol coal  --robot A --world B: coal's test/benchmark.cpp, two meshes and --poses random poses of A
//       (10,000 by default): a uniform random rotation, the translation uniform in B's bounding box grown by A's
//       bounding radius (coal draws it in a fixed box of its own meshes' size), so that poses collide and miss both.
//   --protocol trueform --mesh A: trueform's, one mesh against itself, --poses random poses (1,000 by default), a
//       uniform random rotation, the translation uniform in the ball of twice the mesh's bounding-box diagonal.
//
// Each side answers the same question on the same poses: FCL's distance on BVHModel<OBBRSS> (nearest points
// requested, as coal's protocol asks) and its collide, meshgap's exact distance (refineExact(), certified, with no
// penetration depth: FCL's distance gives none either) and its collision test (inCollision()). Times are the thread's
// CPU time per query (robust to other load on the machine), summed over the poses as the protocols report them; the
// sides alternate pose by pose. Where FCL finds the meshes apart, meshgap's distance must agree with FCL's within
// --tolerance relative to the larger of the distance and the meshes' scale (1e-9 by default): the row counts those
// that do not, and the exit status is 1 if any does or if a collision verdict differs.
//
// Example: meshgap_bench_pair_protocols --protocol coal --robot link_1.stl --world link_2.stl

#include <boost/program_options.hpp>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "CliMain.h"
#include "FclOracle.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshLoader.h"

namespace po = boost::program_options;

#ifdef MESHGAP_HAVE_FCL
namespace meshgap::bench
{
    namespace
    {
        double threadSeconds()
        {
            timespec t{};
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
            return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
        }

        template <typename F>
        double timed(F &&f)
        {
            const double start = threadSeconds();
            f();
            return threadSeconds() - start;
        }

        Eigen::Quaterniond randomRotation(std::mt19937_64 &rng)
        {
            std::normal_distribution<double> n(0.0, 1.0);
            Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
            return q.normalized();
        }

        /** \brief The poses of A relative to B the protocol draws. */
        std::vector<Eigen::Isometry3d> protocolPoses(const std::string &protocol, const Mesh &a, const Mesh &b,
                                                     std::size_t count, std::uint64_t seed)
        {
            std::mt19937_64 rng(seed);
            std::uniform_real_distribution<double> u(-1.0, 1.0);
            Eigen::AlignedBox3d boxA, boxB;
            for (const Eigen::Vector3d &p : a.vertices)
                boxA.extend(p);
            for (const Eigen::Vector3d &p : b.vertices)
                boxB.extend(p);
            double radiusA = 0.0;
            for (const Eigen::Vector3d &p : a.vertices)
                radiusA = std::max(radiusA, p.norm());
            std::vector<Eigen::Isometry3d> poses;
            while (poses.size() < count)
            {
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                X.linear() = randomRotation(rng).toRotationMatrix();
                if (protocol == "coal")
                {
                    const Eigen::Vector3d lo = boxB.min().array() - radiusA, hi = boxB.max().array() + radiusA;
                    for (int k = 0; k < 3; ++k)
                        X.translation()[k] = lo[k] + 0.5 * (u(rng) + 1.0) * (hi[k] - lo[k]);
                }
                else
                {
                    const double reach = 2.0 * boxA.diagonal().norm();
                    Eigen::Vector3d t(u(rng), u(rng), u(rng));
                    if (t.squaredNorm() > 1.0)
                        continue;  // uniform in the ball: rejection from the cube
                    X.translation() = reach * t;
                }
                poses.push_back(X);
            }
            return poses;
        }

        struct Tally
        {
            double meshgapDistance{0}, fclDistance{0}, meshgapCollide{0}, fclCollide{0};
            std::size_t separated{0}, colliding{0}, disagree{0}, verdicts{0};
            double largestError{0};
            std::size_t boxTests{0}, triangleTests{0};  ///< meshgap's distance queries, summed
        };

        Tally run(const Mesh &a, const Mesh &b, const std::vector<Eigen::Isometry3d> &poses, double tolerance)
        {
            const BodyPtr bodyA = Body::build(a), bodyB = Body::build(b);
            const auto fclA = test::fclModel(a), fclB = test::fclModel(b);
            Eigen::AlignedBox3d box;
            for (const Eigen::Vector3d &p : b.vertices)
                box.extend(p);
            const double scale = box.diagonal().norm();
            DistanceRequest request;
            request.computeDepth = false;
            Tally t;
            for (const Eigen::Isometry3d &X : poses)
            {
                // B is the fixed mesh (FCL's first object at the identity), A moves: refineExact(B, A, X_BA).
                double dF = 0.0;
                bool cF = false, cM = false;
                DistanceResult result;  // a cold query: no node pair to seed from (as Scene asks)
                t.fclDistance += timed([&] { dF = test::fclDistance(fclB, fclA, X); });
                t.meshgapDistance += timed([&] { refineExact(*bodyB, *bodyA, X, result, request); });
                t.boxTests += result.boxTests;
                t.triangleTests += result.triangleTests;
                t.meshgapCollide += timed([&] { cM = inCollision(*bodyB, *bodyA, X); });
                t.fclCollide += timed([&] { cF = test::fclCollide(fclB, fclA, X); });
                t.verdicts += cM != cF || cM != result.inCollision;
                if (cF)
                {
                    ++t.colliding;
                    continue;
                }
                ++t.separated;
                const double error = std::abs(result.distance - dF) / std::max({1.0, dF, scale});
                t.largestError = std::max(t.largestError, error);
                t.disagree += !(error <= tolerance);
            }
            return t;
        }

        int main(int argc, char **argv)
        {
            std::string protocol, robot, world, mesh;
            std::size_t poses = 0;
            std::uint64_t seed = 1;
            double tolerance = 1e-9;
            po::options_description options("meshgap_bench_pair_protocols");
            options.add_options()("help,h", "print this help")(
                "protocol", po::value(&protocol)->required(), "coal (--robot, --world) or trueform (--mesh)")(
                "robot", po::value(&robot), "coal: the moving mesh file")("world", po::value(&world),
                                                                         "coal: the fixed mesh file")(
                "mesh", po::value(&mesh), "trueform: the mesh file, against itself")(
                "poses", po::value(&poses), "random poses (coal 10000, trueform 1000)")(
                "seed", po::value(&seed)->default_value(1), "seed of the poses")(
                "tolerance", po::value(&tolerance)->default_value(1e-9),
                "largest relative difference from FCL's distance where apart");
            po::variables_map vm;
            if (!cli::parseCommandLine(argc, argv, options, vm))
                return 0;
            if (protocol == "coal" && (robot.empty() || world.empty() || !mesh.empty()))
                throw Exception("--protocol coal", "takes --robot FILE and --world FILE");
            if (protocol == "trueform" && (mesh.empty() || !robot.empty() || !world.empty()))
                throw Exception("--protocol trueform", "takes --mesh FILE");
            if (protocol != "coal" && protocol != "trueform")
                throw Exception("--protocol " + protocol, "unknown protocol (coal, trueform)");
            if (poses == 0)
                poses = protocol == "coal" ? 10000 : 1000;
            const Mesh a = loadMesh(protocol == "coal" ? robot : mesh);
            const Mesh b = protocol == "coal" ? loadMesh(world) : a;
            const std::vector<Eigen::Isometry3d> drawn = protocolPoses(protocol, a, b, poses, seed);
            const Tally t = run(a, b, drawn, tolerance);
            const auto name = [](const std::string &path) { return path.substr(path.find_last_of('/') + 1); };
            std::printf("| protocol | meshes | triangles | poses (apart / colliding) | meshgap distance s "
                        "| FCL distance s | ratio | meshgap collide s | FCL collide s | ratio "
                        "| largest relative error where apart | beyond %.0e | verdicts differing |\n",
                        tolerance);
            std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
            std::printf("| %s | %s / %s | %zu / %zu | %zu (%zu / %zu) | %.4f | %.4f | **%.2f** | %.4f | %.4f "
                        "| **%.2f** | %.1e | %zu | %zu |\n",
                        protocol.c_str(), name(protocol == "coal" ? robot : mesh).c_str(),
                        name(protocol == "coal" ? world : mesh).c_str(), a.triangles.size(), b.triangles.size(),
                        drawn.size(), t.separated, t.colliding, t.meshgapDistance, t.fclDistance,
                        t.meshgapDistance / t.fclDistance, t.meshgapCollide, t.fclCollide,
                        t.meshgapCollide / t.fclCollide, t.largestError, t.disagree, t.verdicts);
            std::printf("\nmeshgap's distance per query: %.1f node pairs bounded, %.1f triangle pairs tested\n",
                        static_cast<double>(t.boxTests) / drawn.size(),
                        static_cast<double>(t.triangleTests) / drawn.size());
            return t.disagree == 0 && t.verdicts == 0 ? 0 : 1;
        }
    }  // namespace
}  // namespace meshgap::bench
#endif

int main(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    (void)argc;
    (void)argv;
    std::cerr << "meshgap_bench_pair_protocols: built without FCL, the peer it measures against\n";
    return 2;
#else
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    try
    {
        return meshgap::bench::main(argc, argv);
    }
    catch (const std::exception &e)
    {
        std::cerr << "meshgap_bench_pair_protocols: " << e.what() << "\n";
        return 2;
    }
#endif
}
