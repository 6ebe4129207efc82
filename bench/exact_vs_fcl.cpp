// meshgap's exact distance and collision against FCL 0.7 (BVHModel<OBBRSS>, as OMPL.app uses it) along the
// OMPL.app problems' solution paths, interpolated to at least --states states and queried in path order (as a
// planner's motion checks ask them). Both libraries get the same triangles (meshgap's loader output: welded, with
// degenerate and duplicated faces dropped). Per query: median and 90th percentile in microseconds, the ratio to
// FCL's distance query, and every disagreement counted.
//
//   build/bench/meshgap_bench_exact_vs_fcl [--states 1000] [--data ../shared/data/omplapp]

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <ompl/util/Console.h>

#include "FclOracle.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    std::vector<Eigen::Isometry3d> interpolate(const std::vector<Eigen::Isometry3d> &path, std::size_t atLeast)
    {
        const std::size_t segments = path.size() - 1;
        const std::size_t per = std::max<std::size_t>(1, (atLeast + segments - 1) / segments);
        std::vector<Eigen::Isometry3d> out;
        for (std::size_t s = 0; s < segments; ++s)
        {
            const Eigen::Quaterniond q0(path[s].linear()), q1(path[s + 1].linear());
            for (std::size_t k = 0; k < per; ++k)
            {
                const double t = double(k) / per;
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                X.linear() = q0.slerp(t, q1).toRotationMatrix();
                X.translation() = (1 - t) * path[s].translation() + t * path[s + 1].translation();
                out.push_back(X);
            }
        }
        out.push_back(path.back());
        return out;
    }

    struct Stats
    {
        double median, p90;
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
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
}  // namespace

int main(int argc, char **argv)
{
#ifndef MESHGAP_HAVE_FCL
    std::fprintf(stderr, "built without FCL\n");
    return 1;
#else
    std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp";
    std::size_t states = 1000;
    namespace po = boost::program_options;
    po::options_description cli("meshgap_bench_exact_vs_fcl");
    cli.add_options()("data", po::value(&data), "folder with OMPL.app problems")("states", po::value(&states),
                                                                                 "interpolated states per path");
    po::variables_map vm;
    po::store(po::parse_command_line(argc, argv, cli), vm);
    po::notify(vm);
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    std::printf("| problem | states | world / robot triangles | FCL distance | FCL collision | meshgap exact cold | "
                "meshgap exact warm | meshgap collision | warm / FCL distance | collision / FCL collision | "
                "disagreements |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const char *name : {"Easy", "cubicles", "Twistycool"})
    {
        const fs::path cfg = fs::path(data) / (std::string(name) + ".cfg"), pathFile = fs::path(data) / (std::string(name) + ".path");
        if (!fs::exists(cfg) || !fs::exists(pathFile))
            continue;
        const ProblemConfig problem = readProblemConfig(cfg.string());
        const Mesh world = loadMesh(problem.world), robot = loadRobotMesh(problem.robot);
        const BodyPtr a = Body::build(world), b = Body::build(robot);
        const auto fw = test::fclModel(world), fr = test::fclModel(robot);
        const std::vector<Eigen::Isometry3d> poses = interpolate(readPoses(pathFile.string()), states);

        std::vector<double> tFclD, tFclC, tCold, tWarm, tColl;
        std::size_t disagreements = 0;
        const ExactSolver exact;
        DistanceRequest warm;
        for (const Eigen::Isometry3d &X : poses)
        {
            double dF = 0, dCold = 0, dWarm = 0;
            bool cF = false, cM = false, cWarm = false;
            tFclD.push_back(timed([&] { dF = test::fclDistance(fw, fr, X); }));
            tFclC.push_back(timed([&] { cF = test::fclCollide(fw, fr, X); }));
            DistanceResult cold, hot;
            tCold.push_back(timed([&] { exact.solve(*a, *b, X, DistanceRequest(), cold); }));
            tWarm.push_back(timed([&] { exact.solve(*a, *b, X, warm, hot); }));
            warm.start = hot.nodes;
            tColl.push_back(timed([&] { cM = inCollision(*a, *b, X); }));
            dCold = cold.distance;
            dWarm = hot.distance;
            cWarm = hot.inCollision;
            const bool same = cF == cM && cF == cWarm && cF == cold.inCollision &&
                              (cF || (std::abs(dCold - dF) <= 1e-6 * dF + 1e-9 && std::abs(dWarm - dF) <= 1e-6 * dF + 1e-9));
            disagreements += !same;
        }
        const Stats fd = stats(tFclD), fc = stats(tFclC), mc = stats(tCold), mw = stats(tWarm), mk = stats(tColl);
        std::printf("| %s | %zu | %zu / %zu | %.1f (p90 %.1f) | %.1f (p90 %.1f) | %.1f (p90 %.1f) | %.1f (p90 %.1f) | "
                    "%.1f (p90 %.1f) | %.2f | %.2f | %zu |\n",
                    name, poses.size(), world.triangles.size(), robot.triangles.size(), fd.median, fd.p90, fc.median,
                    fc.p90, mc.median, mc.p90, mw.median, mw.p90, mk.median, mk.p90, mw.median / fd.median,
                    mk.median / fc.median, disagreements);
    }
    return 0;
#endif
}
