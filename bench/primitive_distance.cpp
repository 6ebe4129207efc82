// Primitive solids answered as the shapes they are: µs per query of meshgap's exact distance and collision of each
// solid (box, sphere, cylinder, capsule, cone) against a triangle mesh (bvhSolidDistance(), bvhSolidCollide()) and
// against each other (primitiveGap()), next to FCL 0.7 with its own shapes on the same random poses (fcl::distance,
// fcl::collide, as MoveIt calls them: default requests, libccd's GJK), and the largest difference of the distances.
// The mesh is a 320-triangle ellipsoid; poses put the solid's centre uniformly in a cube of half-side 1.3 about it.
//
//   build/bench/meshgap_bench_primitive_distance [--poses 10000] [--seed 1]

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "CliMain.h"
#include "TestMeshes.h"
#include "TestSolids.h"
#include "meshgap/geometry/BvhSolid.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/geometry/TriangleBvh.h"
#ifdef MESHGAP_HAVE_FCL
#include <fcl/fcl.h>

#include "FclOracle.h"
#include "FclRobotScene.h"
#endif

using namespace meshgap;
using Eigen::Isometry3d;
using Eigen::Vector3d;

namespace
{
    const char *name(Primitive::Kind kind)
    {
        static const char *names[] = {"box", "sphere", "cylinder", "cone", "capsule"};
        return names[static_cast<int>(kind)];
    }

    /** \brief Mean µs per call of \e f over the poses. */
    template <typename F>
    double microseconds(const std::vector<Isometry3d> &poses, F &&f)
    {
        const auto start = std::chrono::steady_clock::now();
        for (const Isometry3d &X : poses)
            f(X);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return 1e6 * seconds / static_cast<double>(poses.size());
    }

#ifdef MESHGAP_HAVE_FCL
    double fclDistance(const fcl::CollisionObjectd &a, const fcl::CollisionObjectd &b)
    {
        fcl::DistanceRequestd request;
        fcl::DistanceResultd result;
        fcl::distance(&a, &b, request, result);
        return std::max(result.min_distance, 0.0);
    }

    bool fclCollide(const fcl::CollisionObjectd &a, const fcl::CollisionObjectd &b)
    {
        fcl::CollisionRequestd request;
        fcl::CollisionResultd result;
        fcl::collide(&a, &b, request, result);
        return result.isCollision();
    }
#endif

    /** \brief One row: the solid against the mesh. */
    void meshRow(const Primitive &p, const TriangleBvh &bvh, const std::vector<Isometry3d> &poses, double &sink)
    {
        std::vector<double> ours;
        const double tDistance = microseconds(poses,
                                              [&](const Isometry3d &X)
                                              {
                                                  BvhSolidResult r;
                                                  bvhSolidDistance(bvh, p, X, std::numeric_limits<double>::infinity(),
                                                                   -1.0, r);
                                                  ours.push_back(r.distance);
                                              });
        std::size_t hits = 0;
        const double tCollide =
            microseconds(poses, [&](const Isometry3d &X) { hits += bvhSolidCollide(bvh, p, X) ? 1 : 0; });
        sink += static_cast<double>(hits);
        std::string fcl = "n/a | n/a | n/a";
#ifdef MESHGAP_HAVE_FCL
        const fcl::CollisionObjectd mesh(test::fclModel(bvh.mesh()), fcl::Transform3d::Identity());
        const auto shape = fclSolidOf(p);
        std::size_t k = 0;
        double worst = 0.0;
        const double tFcl = microseconds(poses,
                                         [&](const Isometry3d &X)
                                         {
                                             const fcl::CollisionObjectd o(shape, fcl::Transform3d(X.matrix()));
                                             worst = std::max(worst, std::abs(fclDistance(mesh, o) - ours[k++]));
                                         });
        const double tFclCollide = microseconds(poses,
                                                [&](const Isometry3d &X)
                                                {
                                                    const fcl::CollisionObjectd o(shape, fcl::Transform3d(X.matrix()));
                                                    sink += fclCollide(mesh, o) ? 1.0 : 0.0;
                                                });
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.2f µs | %.2f µs | %.1e", tFcl, tFclCollide, worst);
        fcl = buf;
#endif
        std::printf("| %s / mesh | %.1f%% | %.2f µs | %.2f µs | %s |\n", name(p.kind),
                    100.0 * static_cast<double>(hits) / static_cast<double>(poses.size()), tDistance, tCollide,
                    fcl.c_str());
    }

    /** \brief One row: the solid against another. */
    void pairRow(const Primitive &a, const Primitive &b, const std::vector<Isometry3d> &poses, double &sink)
    {
        std::vector<double> ours;
        std::size_t hits = 0;
        const double tDistance = microseconds(poses,
                                              [&](const Isometry3d &X)
                                              {
                                                  const SolidGap g = primitiveGap(a, Isometry3d::Identity(), b, X);
                                                  ours.push_back(g.distance);
                                                  hits += g.distance == 0.0;
                                              });
        sink += static_cast<double>(hits);
        std::string fcl = "n/a | n/a | n/a";
#ifdef MESHGAP_HAVE_FCL
        const fcl::CollisionObjectd oa(fclSolidOf(a), fcl::Transform3d::Identity());
        const auto shape = fclSolidOf(b);
        std::size_t k = 0;
        double worst = 0.0;
        const double tFcl = microseconds(poses,
                                         [&](const Isometry3d &X)
                                         {
                                             const fcl::CollisionObjectd ob(shape, fcl::Transform3d(X.matrix()));
                                             worst = std::max(worst, std::abs(fclDistance(oa, ob) - ours[k++]));
                                         });
        const double tFclCollide = microseconds(poses,
                                                [&](const Isometry3d &X)
                                                {
                                                    const fcl::CollisionObjectd ob(shape, fcl::Transform3d(X.matrix()));
                                                    sink += fclCollide(oa, ob) ? 1.0 : 0.0;
                                                });
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.2f µs | %.2f µs | %.1e", tFcl, tFclCollide, worst);
        fcl = buf;
#endif
        std::printf("| %s / %s | %.1f%% | %.2f µs | (same) | %s |\n", name(a.kind), name(b.kind),
                    100.0 * static_cast<double>(hits) / static_cast<double>(poses.size()), tDistance, fcl.c_str());
    }
}  // namespace

static int run(int argc, char **argv)
{
    std::size_t n = 10000;
    std::uint32_t seed = 1;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_primitive_distance");
    cli.add_options()("help,h", "print this help")("poses", po::value(&n), "random poses per row")(
        "seed", po::value(&seed), "random seed");
    po::variables_map vm;
    if (!meshgap::cli::parseCommandLine(argc, argv, cli, vm))
        return 0;
    Mesh mesh = test::icosphere(0.6, 2);
    for (Vector3d &v : mesh.vertices)
        v = Vector3d(1.4 * v.x(), v.y(), 0.6 * v.z());
    const TriangleBvh bvh(mesh);
    std::vector<Isometry3d> poses(std::max<std::size_t>(n, 1)), near(poses.size());
    std::mt19937 rng(seed);
    for (std::size_t k = 0; k < poses.size(); ++k)
    {
        poses[k] = test::randomPose(static_cast<std::uint32_t>(rng()), 1.3);
        near[k] = test::randomPose(static_cast<std::uint32_t>(rng()), 0.8);
    }
    double sink = 0.0;
    std::printf("| solid / other | touching | meshgap distance | meshgap collision | FCL distance | FCL collision | "
                "largest distance difference |\n|---|---|---|---|---|---|---|\n");
    const std::vector<Primitive> all = test::oneSolidOfEachKind();
    for (const Primitive &p : all)
        meshRow(p, bvh, poses, sink);
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i; j < all.size(); ++j)
            pairRow(all[i], all[j], near, sink);
    std::fprintf(stderr, "(checksum %g)\n", sink);
    return 0;
}

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
