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
// 2 approximate or none (or --optimize could not certify the path), 1 bad input (including a start or goal in
// collision: the message says which, the obstacle and the distance). --optimize clearance runs the
// ClearancePathOptimizer on the planner's path before any of this
//
// The parts: plan/Progress.h (the progress line), plan/PlanOutputs.h (the files it writes), OptimizeOption.h.

#include <boost/algorithm/string/case_conv.hpp>
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <ompl/base/PlannerData.h>
#include <ompl/util/RandomNumbers.h>
#include <sstream>

#include "CliMain.h"
#include "OptimizeOption.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "plan/PlanOutputs.h"
#include "plan/Progress.h"
#include "support/DenseClearance.h"
#include "support/MeshWriter.h"
#include "support/PlanReport.h"
#include "support/SceneExport.h"

namespace po = boost::program_options;
namespace ob = ompl::base;
using namespace meshgap;
using namespace meshgap::cli;

namespace
{
    /** \brief The command line. */
    struct Options
    {
        std::string cfg, planner = "rrtconnect", objective, checker = "certified", motion = "discrete", out, csv,
                         summaryFile, glb, report, optimize, sampler;
        double time = 10.0, weight = 0.0, optimizeTime = 5.0;
        std::vector<std::string> params;
        unsigned dense = 4, exportStates = 8;
        std::uint32_t seed = 1;
        bool quiet = false, weightGiven = false, optimizeTimeGiven = false;
    };

    /** \brief Declare every option of meshgap_plan, bound to \e o. */
    void declareOptions(po::options_description &options, Options &o)
    {
        options.add_options()("help,h", "print this help")("cfg", po::value(&o.cfg), "OMPL.app problem file (.cfg)")(
            "planner", po::value(&o.planner), ("planner: " + joinNames(plannerNames())).c_str())(
            "param", po::value(&o.params),
            "PLANNER.NAME=VALUE: one of the planner's OMPL parameters, e.g. rrtconnect.range=5 or "
            "rrtstar.use_k_nearest=0; repeatable")(
            "time", po::value(&o.time), "time limit in seconds (default 10)")(
            "objective", po::value(&o.objective),
            "length, clearance (integral of 1/clearance), max_min_clearance, or weighted (length + W * clearance); "
            "default: the cfg's objective, else length")(
            "weight", po::value(&o.weight),
            "W of --objective weighted, a length (default: a tenth of the robot's radius)")(
            "checker", po::value(&o.checker),
            "clearance checker: certified (exact) or fast (an upper bound from the paper's solver, warm-started: "
            "APPROXIMATE)")(
            "motion", po::value(&o.motion),
            "motion validator: discrete (OMPL's, sampled) or clearance (conservative advancement, certified)")(
            "seed", po::value(&o.seed), "OMPL's random seed (default 1)")(
            "out", po::value(&o.out), "write the path here (.path)")(
            "clearance-csv", po::value(&o.csv),
            "write the exact clearance along the densely interpolated path here (CSV)")(
            "dense", po::value(&o.dense), "states per OMPL validity-check segment of the dense path (default 4)")(
            "summary", po::value(&o.summaryFile), "also write the summary here")(
            "export-glb", po::value(&o.glb),
            "write the scene as glTF 2.0 binary (.glb): the world, the robot at --export-states states evenly spaced "
            "along the dense path (start and goal without a path) and the exact closest-point segment at each")(
            "export-states", po::value(&o.exportStates), "robot states in the --export-glb file (default 8)")(
            "report", po::value(&o.report),
            "write a self-contained HTML report (3D scene with the robot along the dense path, clearance plot, "
            "summary) here")(
            "optimize", po::value(&o.optimize),
            "after planning, optimise the path: clearance (raise its minimum clearance up the exact gradient, every "
            "motion certified; needs --checker certified)")(
            "optimize-time", po::value(&o.optimizeTime), "time limit of --optimize in seconds (default 5)")(
            "sampler", po::value(&o.sampler),
            ("valid-state sampler of planners that use one (PRM, EST, ...; default: the cfg's sampler, else "
             "uniform): " + joinNames(validStateSamplerNames())).c_str())(
            "quiet,q", "print warnings and errors only (no OMPL messages, no progress)");
    }

    /** \brief Every check that needs no file, so bad options fail before any loading. */
    void checkOptions(const Options &o)
    {
        if (o.cfg.empty())
            throw Exception("command line", "--cfg FILE is required; see --help");
        if (o.checker != "certified" && o.checker != "fast")
            throw Exception("--checker", "'" + o.checker + "' is not certified or fast");
        if (o.motion != "discrete" && o.motion != "clearance")
            throw Exception("--motion", "'" + o.motion + "' is not discrete or clearance");
        if (o.motion == "clearance" && o.checker != "certified")
            throw Exception("--motion", "clearance needs --checker certified (it steps by exact clearance)");
        if (!(o.time > 0.0))
            throw Exception("--time", "must be positive");
        if (o.dense < 1)
            throw Exception("--dense", "must be at least 1");
        if (o.exportStates < 1)
            throw Exception("--export-states", "must be at least 1");
        checkOptimizeOptions(o.optimize, o.optimizeTimeGiven, o.optimizeTime, o.checker);
        if (o.weightGiven && !(o.weight > 0.0 && std::isfinite(o.weight)))
            throw Exception("--weight", "must be positive and finite");
    }

    /** \brief Parse and check the command line; false after --help. */
    bool parseOptions(int argc, char **argv, Options &o)
    {
        po::options_description options("meshgap_plan --cfg FILE [options]\n\nOptions");
        declareOptions(options, o);
        po::options_description all;
        all.add(options);
        addRenamedOptions(all, {{"mode", "--checker certified|fast"}});
        po::variables_map vm;
        if (!parseCommandLine(argc, argv, all, vm, nullptr, &options))
            return false;
        o.quiet = vm.count("quiet") > 0;
        o.weightGiven = vm.count("weight") > 0;
        o.optimizeTimeGiven = vm.count("optimize-time") > 0;
        checkOptions(o);
        return true;
    }

    /** \brief The problem set up to plan: checker, sampler, motion validator and the planner with its parameters. */
    struct Planning
    {
        ProblemConfig config;
        OmplProblem problem;
        std::shared_ptr<ClearanceMotionValidator> cmv;
    };

    Planning setUp(const Options &o)
    {
        Planning p;
        p.config = readProblemConfig(o.cfg);
        const std::string chosen = !o.objective.empty() ? o.objective : p.config.objective;
        if (o.weightGiven && chosen != "weighted")
            throw Exception("--weight", "applies to --objective weighted only (the objective is " +
                                            (chosen.empty() ? std::string("length") : chosen) + ")");
        ObjectiveOptions objectiveOptions;
        objectiveOptions.weight = o.weight;
        p.problem = setupProblem(p.config,
                                 o.checker == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                            ClearanceChecker::Mode::FAST,
                                 o.objective, BodyOptions(), objectiveOptions);
        const ob::SpaceInformationPtr si = p.problem.setup->getSpaceInformation();
        if (!o.sampler.empty())
            setValidStateSampler(*si, o.sampler, "--sampler");
        if (o.motion == "clearance")
            si->setMotionValidator(p.cmv = std::make_shared<ClearanceMotionValidator>(si, p.problem.checker));
        const ob::PlannerPtr planner = allocPlanner(o.planner, si);
        for (const std::string &text : o.params)
        {
            const OwnedParam param = parseOwnedParam(text, "PLANNER", o.planner + ".range=5");
            if (boost::algorithm::to_lower_copy(param.owner) != boost::algorithm::to_lower_copy(o.planner))
                throw Exception("--param", "'" + text + "': the planner is " + o.planner + ", not " + param.owner);
            setPlannerParam(*planner, param.name, param.value, "--param");
        }
        p.problem.setup->setPlanner(planner);
        p.problem.setup->setup();
        return p;
    }

    /** \brief The summary, one "key  value" line at a time, keys padded as OptimizeOption.h pads its own. */
    class Summary
    {
    public:
        Summary() { text_.precision(6); }

        template <typename T>
        void line(const char *key, const T &value)
        {
            char padded[24];
            std::snprintf(padded, sizeof padded, "%-16s", key);
            text_ << padded << value << "\n";
        }
        std::ostringstream &stream() { return text_; }
        std::string str() const { return text_.str(); }

    private:
        std::ostringstream text_;
    };

    /** \brief The summary lines of the path and its dense clearance. */
    void summarizePath(const Planning &p, const DenseClearance &d, Summary &summary)
    {
        ompl::geometric::PathGeometric &path = p.problem.setup->getSolutionPath();
        summary.line("states", std::to_string(path.getStateCount()) + " (dense: " +
                                   std::to_string(d.path.getStateCount()) + ")");
        summary.line("length", path.length());
        summary.line("cost", std::to_string(path.cost(p.problem.setup->getOptimizationObjective()).value()) + " (" +
                                 p.problem.objective + ")");
        std::ostringstream mc;
        mc.precision(6);
        mc << d.minClearance << " (exact, over the dense path; at arc length " << d.arcLength[d.argmin] << " of "
           << d.arcLength.back() << ")";
        summary.line("min clearance", mc.str());
        summary.line("dense path free", d.collisions == 0 ? std::string("yes") :
                                                            "NO: " + std::to_string(d.collisions) + " states collide");
    }

    /** \brief The summary lines of the search: its graph, the checker's counters, the objective's and the motion
        validator's. */
    void summarizeSearch(const Planning &p, Summary &summary)
    {
        const CheckerStats stats = p.problem.checker->stats();
        {
            ob::PlannerData data(p.problem.setup->getSpaceInformation());
            p.problem.setup->getPlannerData(data);
            summary.line("graph states", data.numVertices());
        }
        summary.line("validity calls", stats.validityCalls);
        summary.line("clearance calls", stats.clearanceCalls);
        if (const auto *maxMin =
                dynamic_cast<const MaxMinClearanceObjective *>(p.problem.setup->getOptimizationObjective().get()))
            summary.line("cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                             std::to_string(maxMin->gridStates()) + " motion grid states");
        if (p.cmv)
            summary.line("motion checks",
                         std::to_string(p.cmv->getValidMotionCount() + p.cmv->getInvalidMotionCount()) + " (" +
                             std::to_string(p.cmv->getValidMotionCount()) + " free), " +
                             std::to_string(p.cmv->queries()) + " clearance queries");
        summary.line("query time", std::to_string(stats.seconds * 1e3) + " ms");
    }

    /** \brief The scene (.glb) and the HTML report: the robot along the dense path, or at the start and the goal
        without one. */
    void writeScenes(const Options &o, const Planning &p, const DenseClearance *d, const std::string &summary)
    {
        if (!o.glb.empty())
        {
            std::vector<Eigen::Isometry3d> poses;
            if (d != nullptr)
                poses = posesAlong(*d, o.exportStates);
            else
            {
                poses.push_back(p.config.start);
                if (p.config.goal)
                    poses.push_back(*p.config.goal);
            }
            writeGlb(sceneExportParts(*p.problem.scene, poses), o.glb);
            std::printf("scene written   %s (%zu robot states)\n", o.glb.c_str(), poses.size());
        }
        if (!o.report.empty())
        {
            const auto rows = summaryRows(summary);
            writePlanReport(*p.problem.scene, d != nullptr ? reportFromDense(*d, rows) : reportWithoutPath(p.config, rows),
                            o.report);
            std::printf("report written  %s\n", o.report.c_str());
        }
    }

    int run(int argc, char **argv)
    {
        Options o;
        if (!parseOptions(argc, argv, o))
            return 0;
        ompl::RNG::setSeed(o.seed);
        Planning p = setUp(o);
        OMPL_INFORM("%s: %s, %zu obstacles, planner %s, objective %s, clearance %s, motion %s", p.config.name.c_str(),
                    p.config.planar ? "SE(2)" : "SE(3)", p.problem.scene->obstacles().size(), o.planner.c_str(),
                    p.problem.objective.c_str(), o.checker.c_str(), o.motion.c_str());
        ob::PlannerStatus status;
        {
            Progress progress(p.problem.setup->getPlanner(), *p.problem.checker, !o.quiet);
            status = p.problem.setup->solve(o.time);
        }
        const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
        const bool havePath = p.problem.setup->haveSolutionPath() &&
                              (exact || status == ob::PlannerStatus::APPROXIMATE_SOLUTION);

        Summary summary;
        summary.line("problem", p.config.name + (p.config.planar ? " (SE(2))" : " (SE(3))"));
        summary.line("planner", o.planner);
        summary.line("objective", p.problem.objective);
        summary.line("clearance mode", o.checker + ", motion " + o.motion);
        summary.line("status", status.asString());
        summary.line("solved", !havePath ? "no" : exact ? "yes (exact)" : "approximate");
        summary.line("exact solution", exact ? "yes" : "no");
        summary.line("planning time", std::to_string(p.problem.setup->getLastPlanComputationTime()) + " s");
        bool optimizeFailed = false;
        if (havePath && !o.optimize.empty())
            summary.stream() << optimizeSolution(*p.problem.setup, p.problem.checker, o.optimizeTime, o.seed,
                                                 optimizeFailed);
        std::unique_ptr<DenseClearance> d;
        if (havePath)
        {
            d = std::make_unique<DenseClearance>(denseClearance(p.problem.setup->getSolutionPath(), *p.problem.scene,
                                                                o.dense));
            summarizePath(p, *d, summary);
        }
        summarizeSearch(p, summary);
        std::cout << summary.str();
        if (!o.summaryFile.empty())
            writeTextFile(summary.str(), o.summaryFile);
        writeScenes(o, p, d.get(), summary.str());
        if (!havePath)
        {
            std::fprintf(stderr, "no path found within %g s\n", o.time);
            return 2;
        }
        if (!o.out.empty())
        {
            writePathFile(p.problem.setup->getSolutionPath(), o.out);
            std::printf("path written    %s\n", o.out.c_str());
        }
        if (!o.csv.empty())
        {
            writeClearanceCsv(*d, o.csv);
            std::printf("clearance CSV   %s\n", o.csv.c_str());
        }
        return exact && !optimizeFailed ? 0 : 2;
    }
}  // namespace

int main(int argc, char **argv)
{
    return runMain(argc, argv, run);
}
