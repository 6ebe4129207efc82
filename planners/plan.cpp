// meshgap_plan: plan a path for an OMPL.app-format problem (SE(3), or SE(2) for a 2D cfg) with meshgap's clearance
// checker.
//
//   meshgap_plan --cfg problem.cfg [--planner rrtconnect] [--time 10] [--objective NAME [--weight W]]
//                [--checker certified|fast] [--motion discrete|clearance] [--seed N] [--out solution.path]
//                [--clearance-csv clearance.csv] [--summary summary.txt] [--export-glb scene.glb [--export-states N]]
//                [--report plan.html] [--optimize clearance [--optimize-time S]] [--sampler NAME]
//
// While it plans, one progress line a second goes to stderr (elapsed time, validity checks, the planner's best cost
// when it reports one). Then it prints a summary (solved, exact or approximate, planning time, path length, cost,
// the exact minimum clearance along the densely interpolated path, checker counters), writes the path in OMPL's
// .path format (one state per line: x y z qx qy qz qw, or x y theta), which meshgap_distance --poses and OMPL.app
// read, the exact clearance along the dense path as CSV, and the scene (world, the robot at N states along the path,
// the closest-point segment at each) as a glTF 2.0 binary file for any 3D viewer. Exit status: 0 exact solution,
// 2 approximate or none, 1 bad input (including a start or goal in collision: the message says which, the obstacle
// and the distance). --optimize clearance runs the ClearancePathOptimizer on the planner's path before any of this
// (the summary gives its minimum clearance and length before and after; everything else is of the optimised path).

#include <boost/algorithm/string/case_conv.hpp>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <ompl/base/PlannerData.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>
#include <sstream>
#include <thread>

#include "CliMain.h"
#include "OptimizeOption.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "support/SceneExport.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/DenseClearance.h"
#include "support/PlanReport.h"
#include "meshgap/ompl/SamplerFactory.h"

namespace po = boost::program_options;
namespace ob = ompl::base;
using namespace meshgap;

namespace
{
    /** \brief One stderr line a second while the planner runs: elapsed time, validity checks, and the planner's
        iterations and best cost when it reports them (OMPL's planner progress properties, read from this thread
        as ompl::tools::Benchmark does). */
    class Progress
    {
    public:
        Progress(const ob::PlannerPtr &planner, const ClearanceChecker &checker, bool enabled)
        {
            if (!enabled)
                return;
            thread_ = std::thread([this, planner, &checker] {
                const auto start = std::chrono::steady_clock::now();
                const auto properties = planner->getPlannerProgressProperties();
                std::unique_lock<std::mutex> lock(mutex_);
                while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; }))
                {
                    const double elapsed =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                    std::string line = "planning: " + std::to_string(static_cast<int>(elapsed + 0.5)) + " s, " +
                                       std::to_string(checker.stats().validityCalls) + " validity checks";
                    for (const char *name : {"iterations INTEGER", "best cost REAL"})
                    {
                        const auto it = properties.find(name);
                        if (it == properties.end())
                            continue;
                        const std::string value = it->second();
                        const std::string label = std::string(name).substr(0, std::string(name).rfind(' '));
                        if (!value.empty() && value != "nan" && value != "inf" && value != "-inf")
                            line += ", " + label + " " + value;
                    }
                    std::fprintf(stderr, "%s\n", line.c_str());
                }
            });
        }
        ~Progress()
        {
            if (!thread_.joinable())
                return;
            {
                std::lock_guard<std::mutex> lock(mutex_);
                done_ = true;
            }
            cv_.notify_all();
            thread_.join();
        }

    private:
        std::mutex mutex_;
        std::condition_variable cv_;
        bool done_{false};
        std::thread thread_;
    };

    void writeClearanceCsv(const DenseClearance &d, const std::string &file)
    {
        std::ofstream out(file);
        if (!out)
            throw Exception(file, "cannot open for writing");
        const ob::StateSpace &space = *d.path.getSpaceInformation()->getStateSpace();
        const bool planar = space.getType() == ob::STATE_SPACE_SE2;
        out << "index,arc_length,fraction," << (planar ? "x,y,theta" : "x,y,z,qx,qy,qz,qw") << ",clearance,in_collision\n";
        out.precision(17);
        const double total = d.arcLength.empty() ? 0.0 : d.arcLength.back();
        for (std::size_t i = 0; i < d.path.getStateCount(); ++i)
        {
            out << i << "," << d.arcLength[i] << "," << (total > 0.0 ? d.arcLength[i] / total : 0.0);
            const ob::State *s = d.path.getState(i);
            if (planar)
            {
                const auto *se2 = s->as<ob::SE2StateSpace::StateType>();
                out << "," << se2->getX() << "," << se2->getY() << "," << se2->getYaw();
            }
            else
            {
                const auto *se3 = s->as<ob::SE3StateSpace::StateType>();
                const auto &q = se3->rotation();
                out << "," << se3->getX() << "," << se3->getY() << "," << se3->getZ() << "," << q.x << "," << q.y
                    << "," << q.z << "," << q.w;
            }
            out << "," << d.clearance[i] << "," << int(d.inCollision[i]) << "\n";
        }
        if (!out)
            throw Exception(file, "write failed");
    }

    int run(int argc, char **argv)
    {
        std::string cfg, planner = "rrtconnect", objective, checker = "certified", motion = "discrete", out, csv, summaryFile,
                    glb, report, optimize, sampler;
        double time = 10.0, weight = 0.0, optimizeTime = 5.0;
        std::vector<std::string> params;
        unsigned dense = 4, exportStates = 8;
        std::uint32_t seed = 1;
        po::options_description options("meshgap_plan --cfg FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help")("cfg", po::value(&cfg), "OMPL.app problem file (.cfg)")(
            "planner", po::value(&planner), ("planner: " + joinNames(plannerNames())).c_str())(
            "param", po::value(&params),
            "PLANNER.NAME=VALUE: one of the planner's OMPL parameters, e.g. rrtconnect.range=5 or "
            "rrtstar.use_k_nearest=0; repeatable")(
            "time", po::value(&time), "time limit in seconds (default 10)")(
            "objective", po::value(&objective),
            "length, clearance (integral of 1/clearance), max_min_clearance, or weighted (length + W * clearance); "
            "default: the cfg's objective, else length")(
            "weight", po::value(&weight),
            "W of --objective weighted, a length (default: a tenth of the robot's radius)")(
            "checker", po::value(&checker), "clearance checker: certified (exact) or fast (the paper's node distance)")(
            "motion", po::value(&motion),
            "motion validator: discrete (OMPL's, sampled) or clearance (conservative advancement, certified)")(
            "seed", po::value(&seed), "OMPL's random seed (default 1)")(
            "out", po::value(&out), "write the path here (.path)")(
            "clearance-csv", po::value(&csv),
            "write the exact clearance along the densely interpolated path here (CSV)")(
            "dense", po::value(&dense), "states per OMPL validity-check segment of the dense path (default 4)")(
            "summary", po::value(&summaryFile), "also write the summary here")(
            "export-glb", po::value(&glb),
            "write the scene as glTF 2.0 binary (.glb): the world, the robot at --export-states states evenly spaced "
            "along the dense path (start and goal without a path) and the exact closest-point segment at each")(
            "export-states", po::value(&exportStates), "robot states in the --export-glb file (default 8)")(
            "report", po::value(&report),
            "write a self-contained HTML report (3D scene with the robot along the dense path, clearance plot, "
            "summary) here")(
            "optimize", po::value(&optimize),
            "after planning, optimise the path: clearance (raise its minimum clearance up the exact gradient, every "
            "motion certified; needs --checker certified)")(
            "optimize-time", po::value(&optimizeTime), "time limit of --optimize in seconds (default 5)")(
            "sampler", po::value(&sampler),
            ("valid-state sampler of planners that use one (PRM, EST, ...; default: the cfg's sampler, else "
             "uniform): " + joinNames(validStateSamplerNames())).c_str())(
            "quiet,q", "print warnings and errors only (no OMPL messages, no progress)");
        po::options_description all;
        all.add(options);
        cli::addRenamedOptions(all, {{"mode", "--checker certified|fast"}});
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, all, vm, nullptr, &options))
            return 0;
        const bool quiet = vm.count("quiet") > 0;
        if (cfg.empty())
            throw Exception("command line", "--cfg FILE is required; see --help");
        if (checker != "certified" && checker != "fast")
            throw Exception("--checker", "'" + checker + "' is not certified or fast");
        if (motion != "discrete" && motion != "clearance")
            throw Exception("--motion", "'" + motion + "' is not discrete or clearance");
        if (motion == "clearance" && checker != "certified")
            throw Exception("--motion", "clearance needs --checker certified (it steps by exact clearance)");
        if (!(time > 0.0))
            throw Exception("--time", "must be positive");
        if (dense < 1)
            throw Exception("--dense", "must be at least 1");
        if (exportStates < 1)
            throw Exception("--export-states", "must be at least 1");
        cli::checkOptimizeOptions(optimize, vm.count("optimize-time") > 0, optimizeTime, checker);
        if (vm.count("weight") && !(weight > 0.0 && std::isfinite(weight)))
            throw Exception("--weight", "must be positive and finite");
        ompl::RNG::setSeed(seed);

        const ProblemConfig config = readProblemConfig(cfg);
        const std::string chosen = !objective.empty() ? objective : config.objective;
        if (vm.count("weight") && chosen != "weighted")
            throw Exception("--weight", "applies to --objective weighted only (the objective is " +
                                            (chosen.empty() ? std::string("length") : chosen) + ")");
        ObjectiveOptions objectiveOptions;
        objectiveOptions.weight = weight;
        OmplProblem problem = setupProblem(config, checker == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                                         ClearanceChecker::Mode::FAST,
                                           objective, BodyOptions(), objectiveOptions);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        if (!sampler.empty())
            setValidStateSampler(*si, sampler, "--sampler");
        std::shared_ptr<ClearanceMotionValidator> cmv;
        if (motion == "clearance")
            si->setMotionValidator(cmv = std::make_shared<ClearanceMotionValidator>(si, problem.checker));
        const ob::PlannerPtr plannerPtr = allocPlanner(planner, si);
        for (const std::string &text : params)
        {
            const cli::OwnedParam param = cli::parseOwnedParam(text, "PLANNER", planner + ".range=5");
            if (boost::algorithm::to_lower_copy(param.owner) != boost::algorithm::to_lower_copy(planner))
                throw Exception("--param", "'" + text + "': the planner is " + planner + ", not " + param.owner);
            setPlannerParam(*plannerPtr, param.name, param.value, "--param");
        }
        problem.setup->setPlanner(plannerPtr);
        problem.setup->setup();
        OMPL_INFORM("%s: %s, %zu obstacles, planner %s, objective %s, clearance %s, motion %s", config.name.c_str(),
                    config.planar ? "SE(2)" : "SE(3)", problem.scene->obstacles().size(), planner.c_str(),
                    problem.objective.c_str(), checker.c_str(), motion.c_str());
        ob::PlannerStatus status;
        {
            Progress progress(problem.setup->getPlanner(), *problem.checker, !quiet);
            status = problem.setup->solve(time);
        }
        const CheckerStats stats = problem.checker->stats();
        const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
        const bool havePath = problem.setup->haveSolutionPath() &&
                              (exact || status == ob::PlannerStatus::APPROXIMATE_SOLUTION);

        std::ostringstream summary;
        summary.precision(6);
        auto line = [&summary](const char *key, const auto &value) {
            char padded[24];
            std::snprintf(padded, sizeof padded, "%-16s", key);
            summary << padded << value << "\n";
        };
        line("problem", config.name + (config.planar ? " (SE(2))" : " (SE(3))"));
        line("planner", planner);
        line("objective", problem.objective);
        line("clearance mode", checker + ", motion " + motion);
        line("status", status.asString());
        line("solved", !havePath ? "no" : exact ? "yes (exact)" : "approximate");
        line("exact solution", exact ? "yes" : "no");
        line("planning time", std::to_string(problem.setup->getLastPlanComputationTime()) + " s");
        if (havePath && !optimize.empty())
            summary << cli::optimizeSolution(*problem.setup, problem.checker, optimizeTime, seed);
        std::unique_ptr<DenseClearance> d;
        if (havePath)
        {
            ompl::geometric::PathGeometric &path = problem.setup->getSolutionPath();
            d = std::make_unique<DenseClearance>(denseClearance(path, *problem.scene, dense));
            line("states", std::to_string(path.getStateCount()) + " (dense: " +
                               std::to_string(d->path.getStateCount()) + ")");
            line("length", path.length());
            line("cost", std::to_string(path.cost(problem.setup->getOptimizationObjective()).value()) + " (" +
                             problem.objective + ")");
            std::ostringstream mc;
            mc.precision(6);
            mc << d->minClearance << " (exact, over the dense path; at arc length " << d->arcLength[d->argmin]
               << " of " << d->arcLength.back() << ")";
            line("min clearance", mc.str());
            line("dense path free", d->collisions == 0 ? std::string("yes") :
                                                         "NO: " + std::to_string(d->collisions) + " states collide");
        }
        {
            ob::PlannerData data(problem.setup->getSpaceInformation());
            problem.setup->getPlannerData(data);
            line("graph states", data.numVertices());
        }
        line("validity calls", stats.validityCalls);
        line("clearance calls", stats.clearanceCalls);
        if (const auto *maxMin =
                dynamic_cast<const MaxMinClearanceObjective *>(problem.setup->getOptimizationObjective().get()))
            line("cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                  std::to_string(maxMin->gridStates()) + " motion grid states");
        if (cmv)
            line("motion checks", std::to_string(cmv->getValidMotionCount() + cmv->getInvalidMotionCount()) + " (" +
                                      std::to_string(cmv->getValidMotionCount()) + " free), " +
                                      std::to_string(cmv->queries()) + " clearance queries");
        line("query time", std::to_string(stats.seconds * 1e3) + " ms");
        std::cout << summary.str();
        if (!summaryFile.empty())
        {
            std::ofstream file(summaryFile);
            if (!(file << summary.str()))
                throw Exception(summaryFile, "cannot write");
        }
        if (!glb.empty())
        {
            // States evenly spaced (by index) along the dense path, first and last included; without a path the
            // start and the goal, so the scene can still be looked at.
            std::vector<Eigen::Isometry3d> poses;
            if (havePath)
            {
                const std::size_t n = d->path.getStateCount(), k = std::min<std::size_t>(exportStates, n);
                for (std::size_t i = 0; i < k; ++i)
                {
                    const std::size_t at = k == 1 ? 0 : (i * (n - 1) + (k - 1) / 2) / (k - 1);
                    poses.push_back(poseFromState(*si->getStateSpace(), d->path.getState(at)));
                }
            }
            else
            {
                poses.push_back(config.start);
                if (config.goal)
                    poses.push_back(*config.goal);
            }
            writeGlb(sceneExportParts(*problem.scene, poses), glb);
            std::printf("scene written   %s (%zu robot states)\n", glb.c_str(), poses.size());
        }
        if (!report.empty())
        {
            const auto rows = summaryRows(summary.str());
            writePlanReport(*problem.scene, havePath ? reportFromDense(*d, rows) : reportWithoutPath(config, rows),
                            report);
            std::printf("report written  %s\n", report.c_str());
        }
        if (!havePath)
        {
            std::fprintf(stderr, "no path found within %g s\n", time);
            return 2;
        }
        if (!out.empty())
        {
            std::ofstream file(out);
            if (!file)
                throw Exception(out, "cannot open for writing");
            file.precision(17);  // full precision: the states must round-trip exactly
            problem.setup->getSolutionPath().printAsMatrix(file);
            if (!file)
                throw Exception(out, "write failed");
            std::printf("path written    %s\n", out.c_str());
        }
        if (!csv.empty())
        {
            writeClearanceCsv(*d, csv);
            std::printf("clearance CSV   %s\n", csv.c_str());
        }
        return exact ? 0 : 2;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
