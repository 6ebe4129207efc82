// meshgap_benchmark: OMPL's Benchmark on a planning problem, with the checker as a dimension of the experiment grid
// (planners x checkers x runs), written in OMPL's .log format for ompl_benchmark_statistics and Planner Arena.
//
//   meshgap_benchmark --cfg problem.cfg [--planner rrtconnect,rrtstar] [--checker certified,fcl]
//                     [--param PLANNER.NAME=VALUE] [--runs N] [--time S] [--memory MB] [--seed N] [--objective NAME]
//                     [--out DIR] [--shard i/n] [--no-simplify] [--sampler uniform,narrow_passage]
//
// Every planner runs once per checker, named "<planner>[<checker label>]" (e.g. RRTConnect[fcl],
// RRTConnect[meshgap-certified]), all in one experiment named after the problem: the statistics script and Planner
// Arena show the checkers side by side. Each (planner, checker) slice is its own .log file, rewritten (write, then
// rename) after every run, so an interrupted benchmark keeps every finished run; --shard i/n runs every n-th cell of
// the grid, and all the .log files of all the shards load into one database (ompl_benchmark_statistics *.log -d
// results.db). --sampler makes the valid-state sampler a dimension too: each checker runs once per sampler, as
// "<planner>[<checker>,<sampler>]".
//
// Any problem runs the same way (RobotProblem: an OMPL.app single-body .cfg is a robot of one link,
// rigidBodyProblem(); a URDF robot, several bodies: robot.urdf = ..., robot.1 = ...; or --urdf R.urdf --srdf R.srdf
// --scene S.yaml --request Q.yaml, a problem in MoveIt's files: MoveItScene.h), with the checkers the robot offers
// (benchmark/Checkers.h): for one rigid body its link's clearance checker certified, fast, or certified with the
// clearance motion validator on every motion; for any other robot meshgap's whole-robot checker searching with a
// sampled motion check, every motion of the answer certified and refused ones replanned ("certified"), with its
// certified motion validator on every motion the search tries ("certified-search"), or with OMPL's discrete one
// ("discrete"); and for every robot FCL as MoveIt uses it, on the same pairs at the same link poses, with OMPL's
// discrete validator ("fcl"). After each slice a line gives its valid paths per minute: runs solved whose path FCL
// finds free, densely interpolated, per minute of planning.
//
// On a control problem (a "control" key: OMPL.app's kinematic_car, dynamic_car, blimp, quadrotor) the grid is the
// control planners (kpiece, rrt, est, pdst, sst; the cfg's [planner] section less those meshgap does not offer) with
// the clearance checker certified and fast, in OMPL's Benchmark, one .log per checker: benchmark/ControlBenchmark.h.
//
// The parts: benchmark/Checkers.h (the checkers by name), benchmark/MeasuredPlanner.h (reads the checker's counters
// when solve() returns), benchmark/BenchmarkLog.h (the .log files), benchmark/BenchmarkConfig.h (the cfg's sections).

#include <boost/algorithm/string/case_conv.hpp>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <ompl/util/RandomNumbers.h>
#include <set>

#include "CliMain.h"
#include "benchmark/BenchmarkConfig.h"
#include "benchmark/BenchmarkLog.h"
#include "benchmark/ControlBenchmark.h"
#include "benchmark/Checkers.h"
#include "benchmark/MeasuredPlanner.h"
#include "support/MoveItOptions.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/SamplerFactory.h"

namespace po = boost::program_options;
namespace ob = ompl::base;
namespace fs = std::filesystem;
using namespace meshgap;
using namespace meshgap::cli;

namespace
{
    /** \brief The command line, as given (the cfg's values are merged in later). */
    struct Options
    {
        std::string cfg, plannerList, checkerList, samplerList, objective, shardText = "1/1";
        std::vector<std::string> params;
        std::uint32_t seed = 0;
        MoveItFiles moveit;  ///< --urdf, --srdf, --scene, --request instead of --cfg
        po::variables_map vm;
    };

    /** \brief Parse the command line; false after --help. */
    bool parseOptions(int argc, char **argv, Options &o)
    {
        po::options_description options("meshgap_benchmark --cfg FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help")(
            "cfg", po::value(&o.cfg), "OMPL.app problem file, or a robot problem file (.cfg)")(
            "planner", po::value(&o.plannerList), "planners, comma-separated (default: the cfg's [planner] section)")(
            "param", po::value(&o.params),
            "PLANNER.NAME=VALUE: a parameter of every planner of that kind, after the cfg's, e.g. "
            "rrtstar.use_k_nearest=0; repeatable")(
            "checker", po::value(&o.checkerList),
            ("checkers, comma-separated (default: all the problem's: " + checkerMenuText() + ")").c_str())(
            "sampler", po::value(&o.samplerList),
            ("valid-state samplers, comma-separated, a dimension of the experiment like the checkers (default: the "
             "cfg's sampler, else OMPL's; only planners that use one, e.g. PRM, EST, notice): " +
             joinNames(validStateSamplerNames())).c_str())(
            "runs", po::value<unsigned>(), "runs per planner and checker (default: the cfg's run_count, else 10)")(
            "time", po::value<double>(), "seconds per run (default: the cfg's time_limit, else 10)")(
            "memory", po::value<double>(), "MB per run (default: the cfg's mem_limit, else 4096)")(
            "seed", po::value(&o.seed), "OMPL's random seed; shard i uses seed + i - 1 (default: random)")(
            "objective", po::value(&o.objective), "optimization objective (default: the cfg's, else length)")(
            "out", po::value<std::string>(), "folder of the .log files (default: the cfg's output, else .)")(
            "shard", po::value(&o.shardText), "run the i-th of n slices of the grid (default 1/1)")(
            "no-simplify", "record the planner's path as it is (default: simplified, as OMPL's Benchmark does)")(
            "verbose,v", "OMPL's informational messages too");
        addMoveItOptions(options, o.moveit);
        po::options_description all;
        all.add(options);
        addRenamedOptions(all, {{"planners", "--planner"},
                                {"checkers", "--checker (certified, fast, certified-cmv, fcl)"},
                                {"samplers", "--sampler"},
                                {"out-dir", "--out"}});
        if (!parseCommandLine(argc, argv, all, o.vm, nullptr, &options))
            return false;
        if (o.cfg.empty() && o.moveit.urdf.empty())
            throw Exception("command line",
                            "--cfg FILE (or --urdf with --scene and --request) is required; see --help");
        return true;
    }

    /** \brief The grid's second axis: every checker with every sampler ("": the problem's own), as (checker,
        sampler) pairs. */
    std::vector<std::pair<std::string, std::string>> checkerSetups(const Options &o,
                                                                   const std::vector<std::string> &available)
    {
        const std::vector<std::string> checkers = o.checkerList.empty() ? available : splitList(o.checkerList);
        for (const std::string &c : checkers)
        {
            if (c.rfind("meshgap-", 0) == 0)
                throw Exception("--checker",
                                quote(c) + " is now spelled " + quote(c.substr(8)) + " (as meshgap_plan does)");
            if (std::find(available.begin(), available.end(), c) == available.end())
                throw Exception("--checker", "unknown checker " + quote(c) + "; valid names: " + joinNames(available));
        }
        if (checkers.empty() || std::set<std::string>(checkers.begin(), checkers.end()).size() != checkers.size())
            throw Exception("--checker", quote(o.checkerList) + " names no checker, or one twice");
        const std::vector<std::string> samplers =
            o.samplerList.empty() ? std::vector<std::string>{""} : splitList(o.samplerList);
        for (const std::string &s : samplers)
            if (!o.samplerList.empty())
                validStateSamplerAllocator(s, "--sampler");  // throws for an unknown name, listing the valid ones
        if (samplers.empty() || std::set<std::string>(samplers.begin(), samplers.end()).size() != samplers.size())
            throw Exception("--sampler", quote(o.samplerList) + " names no sampler, or one twice");
        std::vector<std::pair<std::string, std::string>> setups;
        for (const std::string &c : checkers)
            for (const std::string &s : samplers)
                setups.emplace_back(c, s);
        return setups;
    }

    /** \brief The cfg's [benchmark] section (\e file's), then the options over it. */
    Settings settingsOf(const std::string &file, const ConfigSection &benchmark, const po::variables_map &vm)
    {
        Settings settings;
        applyConfig(file, benchmark, settings);
        if (vm.count("runs"))
            settings.runs = vm["runs"].as<unsigned>();
        if (vm.count("time"))
            settings.time = vm["time"].as<double>();
        if (vm.count("memory"))
            settings.memory = vm["memory"].as<double>();
        if (vm.count("out"))
            settings.outDir = vm["out"].as<std::string>();
        settings.simplify = !vm.count("no-simplify");
        if (settings.runs == 0 || !(settings.memory > 0.0))
            throw Exception("command line", "runs, time and memory must be positive");
        cli::checkSeconds(settings.time, vm.count("time") ? "--time" : file + ": [benchmark] time_limit");
        return settings;
    }

    /** \brief The planners: --planner, else the cfg's [planner] section; then each --param given to its kind. */
    std::vector<PlannerSpec> plannerSpecs(const Options &o, const RobotProblem &problem)
    {
        std::vector<PlannerSpec> planners;
        if (!o.plannerList.empty())
            for (const std::string &p : splitList(o.plannerList))
                planners.push_back({boost::algorithm::to_lower_copy(p), "", {}});
        else
            planners = plannersFromConfig(problem.file, problem.planners);
        if (planners.empty())
            throw Exception(problem.file, "no planners: the cfg has no [planner] section; give --planner");
        const std::vector<std::string> known = plannerNames();
        for (const PlannerSpec &p : planners)
            if (std::find(known.begin(), known.end(), p.type) == known.end())
                throw Exception("planner", "unknown planner " + quote(p.type) + "; valid names: " + joinNames(known) +
                                               (o.plannerList.empty() ? " (choose with --planner)" : ""));
        for (const std::string &text : o.params)
        {
            const OwnedParam param = parseOwnedParam(text, "PLANNER", "rrtconnect.range=5");
            const std::string type = boost::algorithm::to_lower_copy(param.owner);
            bool used = false;
            for (PlannerSpec &p : planners)
                if (p.type == type)
                {
                    p.params.push_back({param.name, param.value, "--param " + text});
                    used = true;
                }
            if (!used)
                throw Exception("--param", quote(text) + ": no planner " + type + " in this benchmark");
        }
        return planners;
    }

    /** \brief A planner of \e spec on \e si, its parameters set and its name given. */
    ob::PlannerPtr allocate(const PlannerSpec &spec, const ob::SpaceInformationPtr &si)
    {
        ob::PlannerPtr planner = allocPlanner(spec.type, si);
        for (const PlannerSpec::Param &param : spec.params)
            setPlannerParam(*planner, param.key, param.value, param.where);
        if (!spec.name.empty())
            planner->setName(spec.name);
        return planner;
    }

    /** \brief Allocate each planner once, so a bad parameter or a duplicate name fails before any run. */
    void checkPlanners(const std::vector<PlannerSpec> &planners, const ob::SpaceInformationPtr &si,
                       const std::string &file)
    {
        std::set<std::string> names;
        for (const PlannerSpec &spec : planners)
        {
            const std::string name = allocate(spec, si)->getName();
            if (!names.insert(name).second)
                throw Exception(file, "two planners named " + quote(name) + ": name each ([planner] " +
                                                 spec.type + ".name = ...)");
        }
    }

    /** \brief The run properties meshgap adds to OMPL's: the checker's counters over the run (\e before and
        \e after it), and FCL's verdict on the path. */
    void addCheckerProperties(Checkers &problem, const CheckerStats &before, const CheckerStats &after,
                              ompl::tools::Benchmark::RunProperties &run)
    {
        const double validity = static_cast<double>(after.validityCalls - before.validityCalls);
        const double clearance = static_cast<double>(after.clearanceCalls - before.clearanceCalls);
        const double seconds = after.seconds - before.seconds;
        run["checker validity calls INTEGER"] = std::to_string(after.validityCalls - before.validityCalls);
        run["checker clearance calls INTEGER"] = std::to_string(after.clearanceCalls - before.clearanceCalls);
        run["checker query time REAL"] = real(seconds);
        if (validity + clearance > 0)
            run["checker mean query time REAL"] = real(seconds / (validity + clearance));
        if (problem.isMeshgap())
        {
            run["checker evaluations INTEGER"] = std::to_string(after.evaluations - before.evaluations);
            if (clearance > 0)
                run["checker warm start hit rate REAL"] =
                    real(static_cast<double>(after.warmStartHits - before.warmStartHits) / clearance);
        }
        if (problem.setup().haveSolutionPath())
            problem.pathProperties(problem.setup().getSolutionPath(), run);
    }

    /** \brief Add the one run \e e recorded to \e slice (the first run starts it, with the slice's labels). */
    void appendRun(const ompl::tools::Benchmark::CompleteExperiment &e, const std::string &label,
                   const std::string &sampler, ompl::tools::Benchmark::CompleteExperiment &slice)
    {
        if (slice.planners.empty())
        {
            slice = e;
            slice.planners[0].common["checker"] = label;
            if (!sampler.empty())
                slice.planners[0].common["sampler"] = sampler;
        }
        else
        {
            slice.planners[0].runs.push_back(e.planners[0].runs[0]);
            for (const auto &progress : e.planners[0].runsProgressData)
                slice.planners[0].runsProgressData.push_back(progress);
            slice.totalDuration += e.totalDuration;
        }
        slice.runCount = static_cast<unsigned>(slice.planners[0].runs.size());
    }

    /** \brief A slice's solved runs, those FCL finds free along the densely interpolated path, and the time they
        took: valid paths per minute. */
    struct SliceTally
    {
        std::size_t runs{0}, solved{0}, free{0};
        double seconds{0.0};

        void add(bool exact, const std::map<std::string, std::string> &props, double time)
        {
            ++runs;
            seconds += time;
            solved += exact ? 1 : 0;
            const auto fcl = props.find("fcl path collision free BOOLEAN");
            free += exact && fcl != props.end() && fcl->second == "1" ? 1 : 0;
        }

        void print(const std::string &name) const
        {
            if (runs == 0)
                return;
            std::fprintf(stderr, "%s: %zu runs, %zu solved, %zu free by FCL's dense check, %.3f s planning: %.1f "
                                 "valid paths per minute\n",
                         name.c_str(), runs, solved, free, seconds,
                         seconds > 0.0 ? 60.0 * double(free) / seconds : 0.0);
        }
    };

    /** \brief Where the grid is and how far it has got, for the progress lines. */
    struct Progress
    {
        std::chrono::steady_clock::time_point start{std::chrono::steady_clock::now()};
        std::size_t done{0}, mine{0};
        unsigned shard{1}, shards{1};
    };

    /** \brief One slice of the grid: \e runs of \e spec with one (checker, sampler) setup, each appended to the
        slice's .log as soon as it is done. */
    void runSlice(Checkers &problem, const std::string &experiment, const Settings &settings, const PlannerSpec &spec,
                  const std::pair<std::string, std::string> &setup, const std::vector<std::size_t> &runs,
                  LogWriter &writer, Progress &progress)
    {
        const auto &[checker, sampler] = setup;
        const ob::SpaceInformationPtr si = problem.setup().getSpaceInformation();
        problem.install(checker);
        if (!sampler.empty())
            setValidStateSampler(*si, sampler, "--sampler");
        const ob::PlannerPtr inner =
            problem.allocPlanner([&spec](const ob::SpaceInformationPtr &space) { return allocate(spec, space); });
        const std::string label = checkerLabel(checker);
        const std::string name = inner->getName() + "[" + label + (sampler.empty() ? "" : "," + sampler) + "]";
        CheckerStats before, after;
        bool solvedSeen = false;
        auto measured = std::make_shared<MeasuredPlanner>(inner, name, [&]() {
            after = problem.stats();
            solvedSeen = true;
        });
        problem.setup().setPlanner(measured);
        ompl::tools::Benchmark benchmark(problem.setup(), experiment);
        benchmark.addPlanner(measured);
        benchmark.setPreRunEvent([&](const ob::PlannerPtr &) {
            before = problem.stats();
            solvedSeen = false;
        });
        benchmark.setPostRunEvent([&](const ob::PlannerPtr &, ompl::tools::Benchmark::RunProperties &run) {
            if (!solvedSeen)
                after = problem.stats();
            addCheckerProperties(problem, before, after, run);
        });

        ompl::tools::Benchmark::Request request(settings.time, settings.memory, 1);
        request.displayProgress = false;
        request.saveConsoleOutput = false;
        request.simplify = settings.simplify;
        ompl::tools::Benchmark::CompleteExperiment slice;
        SliceTally tally;
        const fs::path log =
            logPath(settings.outDir, experiment, inner->getName(), label, sampler, progress.shard, progress.shards);
        for (std::size_t r : runs)
        {
            benchmark.benchmark(request);
            const auto &e = benchmark.getRecordedExperimentData();
            ++progress.done;
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - progress.start).count();
            if (e.planners.size() != 1 || e.planners[0].runs.size() != 1)
            {
                std::fprintf(stderr, "[%7.1f s] run %zu of %zu: %s run %zu: no result recorded\n", elapsed,
                             progress.done, progress.mine, name.c_str(), r + 1);
                continue;
            }
            appendRun(e, label, sampler, slice);
            writer.write(slice, log);
            const auto &props = e.planners[0].runs[0];
            const bool exact = props.count("solved BOOLEAN") && props.at("solved BOOLEAN") == "1";
            double seconds = 0.0;
            parseNumber(props.at("time REAL"), seconds);
            tally.add(exact, props, seconds);
            std::fprintf(stderr, "[%7.1f s] run %zu of %zu: %s run %zu: %s in %.3g s\n", elapsed, progress.done,
                         progress.mine, name.c_str(), r + 1,
                         exact ? "solved" : (problem.setup().haveSolutionPath() ? "approximate" : "not solved"),
                         seconds);
        }
        if (!slice.planners.empty())
            std::fprintf(stderr, "wrote %s (%zu runs)\n", log.c_str(), slice.planners[0].runs.size());
        tally.print(name);
    }

    /** \brief A control problem: benchmark/ControlBenchmark.h; the options of geometric problems refused. */
    int runControl(const Options &o, const ProblemConfig &config)
    {
        for (const char *name : {"sampler", "objective", "param", "no-simplify"})
            if (o.vm.count(name))
                throw Exception(std::string("--") + name,
                                "applies to geometric problems only (" + o.cfg + " is a control problem)");
        if (o.shardText != "1/1")
            throw Exception("--shard", "a control benchmark runs whole (" + o.cfg + " is a control problem)");
        const ControlGrid grid = controlGrid(config, o.plannerList, o.checkerList);
        const Settings settings = settingsOf(config.file, config.benchmark, o.vm);
        if (o.seed != 0)
            ompl::RNG::setSeed(o.seed);
        fs::create_directories(settings.outDir);
        runControlBenchmark(config, settings, grid);
        return 0;
    }

    int run(int argc, char **argv)
    {
        Options o;
        if (!parseOptions(argc, argv, o))
            return 0;
        const auto [shard, shards] = parseShard(o.shardText);
        Problem read = readToolProblem(o.cfg, o.moveit);
        if (read.rigidBody && !read.rigidBody->control.empty())
            return runControl(o, *read.rigidBody);
        // One language from here on: a single body is a robot of one link.
        const RobotProblem problem = read.robot ? std::move(*read.robot) : rigidBodyProblem(*read.rigidBody);
        const std::vector<std::pair<std::string, std::string>> setups = checkerSetups(o, checkerNames(*problem.robot));
        const Settings settings = settingsOf(problem.file, problem.benchmark, o.vm);
        const std::vector<PlannerSpec> planners = plannerSpecs(o, problem);
        if (o.seed != 0)
            ompl::RNG::setSeed(o.seed + shard - 1);

        Checkers checkers(problem, o.objective);
        checkPlanners(planners, checkers.setup().getSpaceInformation(), problem.file);
        fs::create_directories(settings.outDir);

        // The grid: cell k = (planner p, checker c, run r), k = (p * C + c) * R + r; this shard runs k % n == i - 1.
        const std::size_t C = setups.size(), R = settings.runs, cells = planners.size() * C * R;
        Progress progress;
        progress.shard = shard;
        progress.shards = shards;
        for (std::size_t k = shard - 1; k < cells; k += shards)
            ++progress.mine;
        if (progress.mine == 0)
        {
            std::fprintf(stderr, "shard %u/%u: no runs (the grid has %zu)\n", shard, shards, cells);
            return 0;
        }
        std::fprintf(stderr, "%s: %zu planners x %zu checkers x %zu runs, %g s and %g MB each; shard %u/%u runs %zu\n",
                     problem.name.c_str(), planners.size(), C, R, settings.time, settings.memory, shard, shards,
                     progress.mine);
        LogWriter writer(checkers.setup());
        for (std::size_t p = 0; p < planners.size(); ++p)
            for (std::size_t c = 0; c < C; ++c)
            {
                std::vector<std::size_t> runs;
                for (std::size_t r = 0; r < R; ++r)
                    if (((p * C + c) * R + r) % shards == shard - 1)
                        runs.push_back(r);
                if (!runs.empty())
                    runSlice(checkers, problem.name, settings, planners[p], setups[c], runs, writer, progress);
            }
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    return runMain(argc, argv, run);
}
