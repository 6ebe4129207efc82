// meshgap_benchmark: OMPL's Benchmark on an OMPL.app problem, with the clearance checker as a dimension of the
// experiment grid (planners x checkers x runs), written in OMPL's .log format for ompl_benchmark_statistics and
// Planner Arena.
//
//   meshgap_benchmark --cfg problem.cfg [--planner rrtconnect,rrtstar] [--checker certified,fcl]
//                     [--param PLANNER.NAME=VALUE] [--runs N] [--time S] [--memory MB] [--seed N] [--objective NAME]
//                     [--out DIR] [--shard i/n] [--no-simplify] [--sampler uniform,narrow_passage]
//
// Every planner runs once per checker, named "<planner>[<checker label>]" (e.g. RRTConnect[fcl],
// RRTConnect[meshgap-certified]), all in one experiment
// named after the problem: the statistics script and Planner Arena show the checkers side by side. Each
// (planner, checker) slice is its own .log file, rewritten (write, then rename) after every run, so an interrupted
// benchmark keeps every finished run; --shard i/n runs every n-th cell of the grid, and all the .log files of all
// the shards load into one database (ompl_benchmark_statistics *.log -d results.db). --sampler makes the
// valid-state sampler a dimension too: each checker runs once per sampler, as "<planner>[<checker>,<sampler>]".

#include <boost/algorithm/string.hpp>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>
#include <regex>
#include <set>

#include "CliMain.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "FclChecker.h"
#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/RobotMesh.h"

namespace po = boost::program_options;
namespace ob = ompl::base;
namespace fs = std::filesystem;
using namespace meshgap;

namespace
{
    /** \brief The checkers this build can run, in grid order, as --checker spells them (as meshgap_plan does). */
    std::vector<std::string> checkerNames()
    {
        std::vector<std::string> names = {"certified", "fast", "certified-cmv"};
#ifdef MESHGAP_HAVE_FCL
        names.push_back("fcl");
#endif
        return names;
    }

    /** \brief A checker's label in the .log (planner names, file names, the "checker" property): the library's name
        too, meshgap-certified beside fcl, as before the flags were unified. */
    std::string checkerLabel(const std::string &name)
    {
        return name == "fcl" ? name : "meshgap-" + name;
    }

    /** \brief A real for a .log: 9 significant digits (std::to_string's fixed 6 decimals lose small times). */
    std::string real(double value)
    {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.9g", value);
        return buffer;
    }

    /** \brief One [planner] entry: a factory name, an optional display name, and parameters (ParamSet keys). */
    struct PlannerSpec
    {
        std::string type, name;
        struct Param
        {
            std::string key, value, where;  ///< where: the cfg line or the command-line option that set it
        };
        std::vector<Param> params;
    };

    /** \brief The cfg's [planner] section as OMPL.app reads it: "rrt=" starts an entry, "rrt.name=X" names it,
        "rrt.range=50" sets a parameter of the entry just started. */
    std::vector<PlannerSpec> plannersFromConfig(const ProblemConfig &config)
    {
        std::vector<PlannerSpec> specs;
        for (const auto &[key, value] : config.planners)
        {
            const std::size_t dot = key.find('.');
            if (dot == std::string::npos)
            {
                specs.push_back({key, "", {}});
                continue;
            }
            const std::string prefix = key.substr(0, dot), rest = key.substr(dot + 1);
            if (prefix == "problem")
                throw Exception(config.file, "[planner] " + key + ": per-planner problem settings are not supported");
            if (specs.empty() || specs.back().type != prefix)
                throw Exception(config.file, "[planner] " + key + " does not follow a '" + prefix + "=' line");
            if (rest == "name")
                specs.back().name = value;
            else
                specs.back().params.push_back({rest, value, config.file + ": [planner] " + key});
        }
        return specs;
    }

    /** \brief "i/n" with 1 <= i <= n. */
    std::pair<unsigned, unsigned> parseShard(const std::string &text)
    {
        std::smatch m;
        if (std::regex_match(text, m, std::regex("([0-9]{1,6})/([0-9]{1,6})")))
        {
            const auto i = static_cast<unsigned>(std::strtoul(m.str(1).c_str(), nullptr, 10)),
                       n = static_cast<unsigned>(std::strtoul(m.str(2).c_str(), nullptr, 10));
            if (i >= 1 && i <= n)
                return {i, n};
        }
        throw Exception("--shard", "'" + text + "' is not i/n with 1 <= i <= n");
    }

    std::string fileSafe(const std::string &name)
    {
        std::string out = name;
        for (char &c : out)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '+')
                c = '_';
        return out;
    }

    /** \brief One problem, its scene built once, and the checkers installed into its SpaceInformation in turn. */
    class Checkers
    {
    public:
        Checkers(const ProblemConfig &config, const std::string &objective)
          : problem_(setupProblem(config, ClearanceChecker::Mode::CERTIFIED, objective))
        {
            si_ = problem_.setup->getSpaceInformation();
#ifdef MESHGAP_HAVE_FCL
            // FCL gets the meshes as OMPL.app loads them: the robot centred as OMPL.app centres it (x and y only
            // in a 2D problem), the whole world, so the same state is the same pose for both checkers.
            fcl_ = std::make_shared<FclChecker>(si_, loadRobotMesh(config.robot, config.planar),
                                                loadMesh(config.world));
#endif
        }

        ompl::geometric::SimpleSetup &setup() { return *problem_.setup; }
        const OmplProblem &problem() const { return problem_; }

        /** \brief Make \e name the problem's validity checker and motion validator. */
        void install(const std::string &name)
        {
            ob::StateValidityCheckerPtr checker;
            ob::MotionValidatorPtr validator;
            if (name == "certified")
                checker = problem_.checker;
            else if (name == "fast")
                checker = fast_ ? fast_ : (fast_ = std::make_shared<ClearanceChecker>(si_, problem_.scene,
                                                                                      ClearanceChecker::Mode::FAST));
            else if (name == "certified-cmv")
            {
                if (!cmvChecker_)
                {
                    cmvChecker_ = std::make_shared<ClearanceChecker>(si_, problem_.scene, ClearanceChecker::Mode::CERTIFIED);
                    cmv_ = std::make_shared<ClearanceMotionValidator>(si_, cmvChecker_);
                }
                checker = cmvChecker_;
                validator = cmv_;
            }
#ifdef MESHGAP_HAVE_FCL
            else if (name == "fcl")
                checker = fcl_;
#endif
            else
                throw Exception("--checker", "unknown checker '" + name + "'");
            active_ = name;
            si_->setStateValidityChecker(checker);
            si_->setMotionValidator(validator ? validator : std::make_shared<ob::DiscreteMotionValidator>(si_));
        }

        /** \brief Counters of the installed checker (cumulative). */
        CheckerStats stats() const
        {
#ifdef MESHGAP_HAVE_FCL
            if (active_ == "fcl")
                return fcl_->stats();
#endif
            return std::static_pointer_cast<const ClearanceChecker>(si_->getStateValidityChecker())->stats();
        }

        bool isMeshgap() const { return active_ != "fcl"; }

        /** \brief FCL's verdict on \e path, densely interpolated (4x OMPL's motion-check resolution, as the
            Benchmark's strict check): states checked, whether all are collision-free, the least distance. */
        void fclPathProperties(const ompl::geometric::PathGeometric &solution, ompl::tools::Benchmark::RunProperties &run)
        {
#ifdef MESHGAP_HAVE_FCL
            ompl::geometric::PathGeometric path(solution);
            const ob::StateSpacePtr &space = si_->getStateSpace();
            const unsigned factor = space->getValidSegmentCountFactor();
            space->setValidSegmentCountFactor(4 * factor);
            path.interpolate();
            space->setValidSegmentCountFactor(factor);
            bool free = true;
            double least = std::numeric_limits<double>::infinity();
            for (const ob::State *s : path.getStates())
            {
                const Eigen::Isometry3d X = fcl_->pose(s);
                const bool collides = fcl_->inCollision(X);
                free = free && !collides;
                least = std::min(least, collides ? 0.0 : fcl_->distance(X));
            }
            run["fcl path states INTEGER"] = std::to_string(path.getStateCount());
            run["fcl path collision free BOOLEAN"] = free ? "1" : "0";
            run["fcl path min clearance REAL"] = real(least);
#else
            (void)solution;
            (void)run;
#endif
        }

    private:
        OmplProblem problem_;
        ob::SpaceInformationPtr si_;
        ClearanceCheckerPtr fast_, cmvChecker_;
        std::shared_ptr<ClearanceMotionValidator> cmv_;
#ifdef MESHGAP_HAVE_FCL
        std::shared_ptr<FclChecker> fcl_;
#endif
        std::string active_;
    };

    /** \brief A planner run through another, so the checker's counters are read the moment solve() returns,
        before the Benchmark simplifies and checks the path with the same checker. Forwards what the Benchmark
        calls; carries the inner planner's parameters, specs and progress properties. */
    class MeasuredPlanner : public ob::Planner
    {
    public:
        MeasuredPlanner(ob::PlannerPtr inner, const std::string &name, std::function<void()> solved)
          : ob::Planner(inner->getSpaceInformation(), name), inner_(std::move(inner)), solved_(std::move(solved))
        {
            specs_ = inner_->getSpecs();
            params_.include(inner_->params());
            for (const auto &[key, property] : inner_->getPlannerProgressProperties())
                addPlannerProgressProperty(key, property);
        }

        ob::PlannerStatus solve(const ob::PlannerTerminationCondition &ptc) override
        {
            const ob::PlannerStatus status = inner_->solve(ptc);
            solved_();
            return status;
        }
        void setProblemDefinition(const ob::ProblemDefinitionPtr &pdef) override
        {
            ob::Planner::setProblemDefinition(pdef);
            inner_->setProblemDefinition(pdef);
        }
        void clear() override
        {
            ob::Planner::clear();
            inner_->clear();
        }
        void setup() override
        {
            ob::Planner::setup();
            if (!inner_->isSetup())
                inner_->setup();
        }
        void getPlannerData(ob::PlannerData &data) const override { inner_->getPlannerData(data); }
        void printProperties(std::ostream &out) const override { inner_->printProperties(out); }

    private:
        ob::PlannerPtr inner_;
        std::function<void()> solved_;
    };

    /** \brief OMPL's own .log writer for an experiment assembled run by run; written under a temporary name, then
        renamed (writeStreamAtomically()), so a .log on disk is always whole. */
    class LogWriter : public ompl::tools::Benchmark
    {
    public:
        explicit LogWriter(ompl::geometric::SimpleSetup &setup) : Benchmark(setup) {}

        void write(const CompleteExperiment &experiment, const fs::path &path)
        {
            exp_ = experiment;
            writeStreamAtomically(path.string(),
                                  [&](std::ostream &out)
                                  {
                                      if (!saveResultsToStream(out))
                                          throw Exception(path.string(), "cannot write the benchmark log");
                                  });
        }
    };

    struct Settings
    {
        double time{10.0}, memory{4096.0};
        unsigned runs{10};
        bool simplify{true};
        fs::path outDir{"."};
    };

    /** \brief The [benchmark] section; unknown keys are reported and ignored, as OMPL.app does. */
    void applyConfig(const ProblemConfig &config, Settings &settings)
    {
        for (const auto &[key, value] : config.benchmark)
        {
            const std::string where = config.file + ": [benchmark] " + key;
            unsigned long runs = 0;
            if (key == "time_limit")
                settings.time = parseFiniteNumber(value, where);
            else if (key == "mem_limit")
                settings.memory = parseFiniteNumber(value, where);
            else if (key == "run_count")
            {
                if (!parseUnsigned(value, runs) || runs > std::numeric_limits<unsigned>::max())
                    throw Exception(where, "'" + value + "' is not a whole number of runs");
                settings.runs = static_cast<unsigned>(runs);
            }
            else if (key == "output")
                settings.outDir = value;
            else
                OMPL_WARN("%s: [benchmark] %s is not supported; ignored", config.file.c_str(), key.c_str());
        }
    }

    int run(int argc, char **argv)
    {
        std::string cfg, plannerList, checkerList, samplerList, objective, shardText = "1/1";
        std::vector<std::string> params;
        std::uint32_t seed = 0;
        Settings settings;
        po::options_description options("meshgap_benchmark --cfg FILE [options]\n\nOptions");
        options.add_options()("help,h", "print this help")("cfg", po::value(&cfg), "OMPL.app problem file (.cfg)")(
            "planner", po::value(&plannerList), "planners, comma-separated (default: the cfg's [planner] section)")(
            "param", po::value(&params),
            "PLANNER.NAME=VALUE: a parameter of every planner of that kind, after the cfg's, e.g. "
            "rrtstar.use_k_nearest=0; repeatable")(
            "checker", po::value(&checkerList),
            ("checkers, comma-separated (default: all of " + joinNames(checkerNames()) + ")").c_str())(
            "sampler", po::value(&samplerList),
            ("valid-state samplers, comma-separated, a dimension of the experiment like the checkers (default: the "
             "cfg's sampler, else OMPL's; only planners that use one, e.g. PRM, EST, notice): " +
             joinNames(validStateSamplerNames())).c_str())(
            "runs", po::value<unsigned>(), "runs per planner and checker (default: the cfg's run_count, else 10)")(
            "time", po::value<double>(), "seconds per run (default: the cfg's time_limit, else 10)")(
            "memory", po::value<double>(), "MB per run (default: the cfg's mem_limit, else 4096)")(
            "seed", po::value(&seed), "OMPL's random seed; shard i uses seed + i - 1 (default: random)")(
            "objective", po::value(&objective), "optimization objective (default: the cfg's, else length)")(
            "out", po::value<std::string>(), "folder of the .log files (default: the cfg's output, else .)")(
            "shard", po::value(&shardText), "run the i-th of n slices of the grid (default 1/1)")(
            "no-simplify", "record the planner's path as it is (default: simplified, as OMPL's Benchmark does)")(
            "verbose,v", "OMPL's informational messages too");
        po::options_description all;
        all.add(options);
        cli::addRenamedOptions(all, {{"planners", "--planner"},
                                     {"checkers", "--checker (certified, fast, certified-cmv, fcl)"},
                                     {"samplers", "--sampler"},
                                     {"out-dir", "--out"}});
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, all, vm, nullptr, &options))
            return 0;
        if (cfg.empty())
            throw Exception("command line", "--cfg FILE is required; see --help");
        const auto [shard, shards] = parseShard(shardText);
        const std::vector<std::string> available = checkerNames();
        const std::vector<std::string> checkers = checkerList.empty() ? available : splitList(checkerList);
        for (const std::string &c : checkers)
        {
            if (c.rfind("meshgap-", 0) == 0)
                throw Exception("--checker", "'" + c + "' is now spelled '" + c.substr(8) + "' (as meshgap_plan does)");
            if (std::find(available.begin(), available.end(), c) == available.end())
                throw Exception("--checker", "unknown checker '" + c + "'; valid names: " + joinNames(available));
        }
        if (checkers.empty() || std::set<std::string>(checkers.begin(), checkers.end()).size() != checkers.size())
            throw Exception("--checker", "'" + checkerList + "' names no checker, or one twice");
        // The grid's second axis: every checker with every sampler ("": the problem's own).
        const std::vector<std::string> samplers =
            samplerList.empty() ? std::vector<std::string>{""} : splitList(samplerList);
        for (const std::string &s : samplers)
            if (!samplerList.empty())
                validStateSamplerAllocator(s, "--sampler");  // throws for an unknown name, listing the valid ones
        if (samplers.empty() || std::set<std::string>(samplers.begin(), samplers.end()).size() != samplers.size())
            throw Exception("--sampler", "'" + samplerList + "' names no sampler, or one twice");
        std::vector<std::pair<std::string, std::string>> setups;  // (checker, sampler)
        for (const std::string &c : checkers)
            for (const std::string &s : samplers)
                setups.emplace_back(c, s);

        const ProblemConfig config = readProblemConfig(cfg);
        applyConfig(config, settings);
        if (vm.count("runs"))
            settings.runs = vm["runs"].as<unsigned>();
        if (vm.count("time"))
            settings.time = vm["time"].as<double>();
        if (vm.count("memory"))
            settings.memory = vm["memory"].as<double>();
        if (vm.count("out"))
            settings.outDir = vm["out"].as<std::string>();
        settings.simplify = !vm.count("no-simplify");
        if (settings.runs == 0 || !(settings.time > 0.0) || !(settings.memory > 0.0))
            throw Exception("command line", "runs, time and memory must be positive");

        std::vector<PlannerSpec> planners;
        if (!plannerList.empty())
            for (const std::string &p : splitList(plannerList))
                planners.push_back({boost::algorithm::to_lower_copy(p), "", {}});
        else
            planners = plannersFromConfig(config);
        if (planners.empty())
            throw Exception(cfg, "no planners: the cfg has no [planner] section; give --planner");
        const std::vector<std::string> known = plannerNames();
        for (const PlannerSpec &p : planners)
            if (std::find(known.begin(), known.end(), p.type) == known.end())
                throw Exception("planner", "unknown planner '" + p.type + "'; valid names: " + joinNames(known) +
                                               (plannerList.empty() ? " (choose with --planner)" : ""));
        for (const std::string &text : params)
        {
            const cli::OwnedParam param = cli::parseOwnedParam(text, "PLANNER", "rrtconnect.range=5");
            const std::string type = boost::algorithm::to_lower_copy(param.owner);
            bool used = false;
            for (PlannerSpec &p : planners)
                if (p.type == type)
                {
                    p.params.push_back({param.name, param.value, "--param " + text});
                    used = true;
                }
            if (!used)
                throw Exception("--param", "'" + text + "': no planner " + type + " in this benchmark");
        }
        if (seed != 0)
            ompl::RNG::setSeed(seed + shard - 1);

        Checkers problem(config, objective);
        const ob::SpaceInformationPtr si = problem.setup().getSpaceInformation();
        // Allocate each planner once now, so a bad parameter or a duplicate name fails before any run.
        auto allocate = [&](const PlannerSpec &spec) {
            ob::PlannerPtr planner = allocPlanner(spec.type, si);
            for (const PlannerSpec::Param &param : spec.params)
                setPlannerParam(*planner, param.key, param.value, param.where);
            if (!spec.name.empty())
                planner->setName(spec.name);
            return planner;
        };
        std::set<std::string> names;
        for (const PlannerSpec &spec : planners)
        {
            const std::string name = allocate(spec)->getName();
            if (!names.insert(name).second)
                throw Exception(config.file, "two planners named '" + name + "': name each ([planner] " + spec.type +
                                                 ".name = ...)");
        }
        fs::create_directories(settings.outDir);

        // The grid: cell k = (planner p, checker c, run r), k = (p * C + c) * R + r; this shard runs k % n == i - 1.
        const std::size_t C = setups.size(), R = settings.runs, cells = planners.size() * C * R;
        std::size_t mine = 0;
        for (std::size_t k = shard - 1; k < cells; k += shards)
            ++mine;
        if (mine == 0)
        {
            std::fprintf(stderr, "shard %u/%u: no runs (the grid has %zu)\n", shard, shards, cells);
            return 0;
        }
        std::fprintf(stderr, "%s: %zu planners x %zu checkers x %zu runs, %g s and %g MB each; shard %u/%u runs %zu\n",
                     config.name.c_str(), planners.size(), C, R, settings.time, settings.memory, shard, shards, mine);

        const auto start = std::chrono::steady_clock::now();
        LogWriter writer(problem.setup());
        std::size_t done = 0;
        for (std::size_t p = 0; p < planners.size(); ++p)
            for (std::size_t c = 0; c < C; ++c)
            {
                std::vector<std::size_t> runs;
                for (std::size_t r = 0; r < R; ++r)
                    if (((p * C + c) * R + r) % shards == shard - 1)
                        runs.push_back(r);
                if (runs.empty())
                    continue;
                const auto &[checker, sampler] = setups[c];
                problem.install(checker);
                if (!sampler.empty())
                    setValidStateSampler(*si, sampler, "--sampler");
                const ob::PlannerPtr inner = allocate(planners[p]);
                const std::string label = checkerLabel(checker);
                const std::string name = inner->getName() + "[" + label + (sampler.empty() ? "" : "," + sampler) + "]";
                CheckerStats before, after;
                bool solvedSeen = false;
                auto measured = std::make_shared<MeasuredPlanner>(inner, name, [&]() {
                    after = problem.stats();
                    solvedSeen = true;
                });
                problem.setup().setPlanner(measured);
                ompl::tools::Benchmark benchmark(problem.setup(), config.name);
                benchmark.addPlanner(measured);
                benchmark.setPreRunEvent([&](const ob::PlannerPtr &) {
                    before = problem.stats();
                    solvedSeen = false;
                });
                benchmark.setPostRunEvent([&](const ob::PlannerPtr &, ompl::tools::Benchmark::RunProperties &run) {
                    if (!solvedSeen)
                        after = problem.stats();
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
                        problem.fclPathProperties(problem.setup().getSolutionPath(), run);
                });

                ompl::tools::Benchmark::Request request(settings.time, settings.memory, 1);
                request.displayProgress = false;
                request.saveConsoleOutput = false;
                request.simplify = settings.simplify;
                ompl::tools::Benchmark::CompleteExperiment slice;
                const fs::path log = settings.outDir / (fileSafe(config.name) + "." + fileSafe(inner->getName()) +
                                                        "." + label + (sampler.empty() ? "" : "." + sampler) +
                                                        (shards > 1 ? ".shard" + std::to_string(shard) + "of" +
                                                                          std::to_string(shards) : "") + ".log");
                for (std::size_t r : runs)
                {
                    benchmark.benchmark(request);
                    const auto &e = benchmark.getRecordedExperimentData();
                    ++done;
                    const double elapsed =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                    if (e.planners.size() != 1 || e.planners[0].runs.size() != 1)
                    {
                        std::fprintf(stderr, "[%7.1f s] run %zu of %zu: %s run %zu: no result recorded\n", elapsed,
                                     done, mine, name.c_str(), r + 1);
                        continue;
                    }
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
                    writer.write(slice, log);
                    const auto &props = e.planners[0].runs[0];
                    const bool exact = props.count("solved BOOLEAN") && props.at("solved BOOLEAN") == "1";
                    std::fprintf(stderr, "[%7.1f s] run %zu of %zu: %s run %zu: %s in %.3g s\n", elapsed, done, mine,
                                 name.c_str(), r + 1,
                                 exact ? "solved" :
                                         (problem.setup().haveSolutionPath() ? "approximate" : "not solved"),
                                 std::stod(props.at("time REAL")));
                }
                if (!slice.planners.empty())
                    std::fprintf(stderr, "wrote %s (%zu runs)\n", log.c_str(), slice.planners[0].runs.size());
            }
        return 0;
    }
}  // namespace

int main(int argc, char **argv)
{
    return cli::runMain(argc, argv, run);
}
