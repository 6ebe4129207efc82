#include "benchmark/ControlBenchmark.h"

#include <algorithm>
#include <boost/algorithm/string/case_conv.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <ompl/tools/benchmark/Benchmark.h>
#include <vector>

#include "benchmark/BenchmarkLog.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/ControlRun.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief What a planner's runs came to, for its line on stderr. */
            struct Tally
            {
                std::size_t exact{0}, approximate{0};
                std::vector<double> times, goalDistances;
            };

            double median(std::vector<double> values)
            {
                if (values.empty())
                    return 0.0;
                std::sort(values.begin(), values.end());
                const std::size_t n = values.size();
                return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
            }

            /** \brief \e runs runs of each of \e planners, each run a call of \e benchmark of its own (as for
                geometric problems), gathered into one experiment, every planner's runs in order. OMPL's memory limit
                counts the process's growth from the start of a call, so a single call over every planner and run
                would stop the later runs at once (in a millisecond, "approximate", the goal where it started) once
                the earlier runs' states, freed but still held by the allocator, add up to the limit. */
            ompl::tools::Benchmark::CompleteExperiment eachRunAlone(ompl::tools::Benchmark &benchmark,
                                                                    const std::vector<ob::PlannerPtr> &planners,
                                                                    const ompl::tools::Benchmark::Request &request,
                                                                    unsigned runs)
            {
                ompl::tools::Benchmark::CompleteExperiment all;
                for (const ob::PlannerPtr &planner : planners)
                {
                    benchmark.clearPlanners();
                    benchmark.addPlanner(planner);
                    for (unsigned r = 0; r < runs; ++r)
                    {
                        benchmark.benchmark(request);
                        const ompl::tools::Benchmark::CompleteExperiment &e = benchmark.getRecordedExperimentData();
                        if (e.planners.size() != 1 || e.planners[0].runs.size() != 1)
                            throw Exception(planner->getName(), "OMPL's benchmark recorded no run");
                        if (all.planners.empty() && r == 0)
                        {
                            all = e;  // the experiment's fields (name, seed, host, set-up) and the first run
                            all.totalDuration = 0.0;
                        }
                        else if (r == 0)
                            all.planners.push_back(e.planners[0]);
                        else
                        {
                            ompl::tools::Benchmark::PlannerExperiment &mine = all.planners.back();
                            mine.runs.push_back(e.planners[0].runs[0]);
                            mine.runsProgressData.insert(mine.runsProgressData.end(),
                                                         e.planners[0].runsProgressData.begin(),
                                                         e.planners[0].runsProgressData.end());
                        }
                        all.totalDuration += e.totalDuration;
                    }
                }
                all.runCount = runs;
                return all;
            }

            /** \brief OMPL's Benchmark of every planner of \e grid with the checker in \e mode, its .log written;
                each run alone (eachRunAlone()), so that the memory limit applies to each run. */
            void runChecker(const ProblemConfig &config, const Settings &settings, const ControlGrid &grid,
                            const std::string &checker)
            {
                const OmplControlProblem problem = setupControlProblem(
                    config, checker == "certified" ? ClearanceChecker::Mode::CERTIFIED : ClearanceChecker::Mode::FAST);
                ompl::tools::Benchmark benchmark(*problem.setup, config.name);
                std::vector<ob::PlannerPtr> planners;
                for (const std::string &name : grid.planners)
                {
                    planners.push_back(allocControlPlanner(name, problem.setup->getSpaceInformation()));
                    planners.back()->setName(planners.back()->getName() + "[meshgap-" + checker + "]");
                }
                const auto start = std::chrono::steady_clock::now();
                std::map<std::string, Tally> tallies;
                CheckerStats before;
                std::size_t done = 0;
                const std::size_t total = grid.planners.size() * settings.runs;
                benchmark.setPreRunEvent([&](const ob::PlannerPtr &) { before = problem.checker->stats(); });
                benchmark.setPostRunEvent(
                    [&](const ob::PlannerPtr &planner, ompl::tools::Benchmark::RunProperties &run)
                    {
                        const CheckerStats after = problem.checker->stats();
                        run["checker validity calls INTEGER"] =
                            std::to_string(after.validityCalls - before.validityCalls);
                        run["checker query time REAL"] = real(after.seconds - before.seconds);
                        const ob::ProblemDefinitionPtr &pdef = planner->getProblemDefinition();
                        const bool exact = pdef->hasExactSolution(), found = pdef->hasSolution();
                        Tally &tally = tallies[planner->getName()];
                        double seconds = 0.0;
                        if (run.count("time REAL"))
                            parseNumber(run.at("time REAL"), seconds);
                        tally.times.push_back(seconds);
                        tally.exact += exact ? 1 : 0;
                        tally.approximate += found && !exact ? 1 : 0;
                        const double gap = exact ? 0.0 : pdef->getSolutionDifference();
                        if (found)
                            tally.goalDistances.push_back(gap);
                        const double elapsed =
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                        std::fprintf(stderr, "[%7.1f s] run %zu of %zu: %s: %s in %.3g s, goal distance %.4g\n",
                                     elapsed, ++done, total, planner->getName().c_str(),
                                     exact ? "exact" : found ? "approximate" : "no path", seconds,
                                     found ? gap : -1.0);
                    });
                ompl::tools::Benchmark::Request request(settings.time, settings.memory, 1);  // one run a call
                request.displayProgress = false;
                request.saveConsoleOutput = false;
                const ompl::tools::Benchmark::CompleteExperiment all = eachRunAlone(benchmark, planners, request,
                                                                                     settings.runs);
                const std::filesystem::path log =
                    settings.outDir / (fileSafe(config.name) + ".control." + fileSafe(checker) + ".log");
                LogWriter(*problem.setup).write(all, log);
                std::fprintf(stderr, "wrote %s\n", log.c_str());
                for (const auto &[name, t] : tallies)
                    std::fprintf(stderr, "%s: %zu runs, %zu exact, %zu approximate, median time %.3g s, median goal "
                                         "distance %.4g (of runs with a path)\n",
                                 name.c_str(), t.times.size(), t.exact, t.approximate, median(t.times),
                                 median(t.goalDistances));
            }
        }  // namespace

        const std::vector<std::string> &controlCheckerNames()
        {
            static const std::vector<std::string> names{"certified", "fast"};
            return names;
        }

        ControlGrid controlGrid(const ProblemConfig &config, const std::string &plannerList,
                                const std::string &checkerList)
        {
            ControlGrid grid;
            const std::vector<std::string> &offered = controlPlannerNames();
            if (!plannerList.empty())
                for (const std::string &p : splitList(plannerList))
                {
                    grid.planners.push_back(boost::algorithm::to_lower_copy(p));
                    if (std::find(offered.begin(), offered.end(), grid.planners.back()) == offered.end())
                        throw Exception("--planner", quote(p) + " is not a control planner (a control problem is "
                                                                "planned by one of: " + joinNames(offered) + ")");
                }
            else
            {
                std::vector<std::string> left;
                for (const PlannerSpec &spec : plannersFromConfig(config.file, config.planners))
                    if (std::find(offered.begin(), offered.end(), spec.type) != offered.end())
                        grid.planners.push_back(spec.type);
                    else
                        left.push_back(spec.type);
                if (!left.empty())
                    std::fprintf(stderr, "%s: [planner] %s left out: meshgap plans a control problem with %s\n",
                                 config.file.c_str(), joinNames(left).c_str(), joinNames(offered).c_str());
                if (grid.planners.empty())
                    throw Exception(config.file, "no control planner in [planner]; give --planner (one of " +
                                                     joinNames(offered) + ")");
            }
            const std::vector<std::string> &checkers = controlCheckerNames();
            grid.checkers = checkerList.empty() ? checkers : splitList(checkerList);
            for (const std::string &c : grid.checkers)
                if (std::find(checkers.begin(), checkers.end(), c) == checkers.end())
                    throw Exception("--checker", quote(c) + " does not check a control problem (its checkers: " +
                                                     joinNames(checkers) + ")");
            return grid;
        }

        void runControlBenchmark(const ProblemConfig &config, const Settings &settings, const ControlGrid &grid)
        {
            std::fprintf(stderr, "%s (control: %s): %zu planners x %zu checkers x %u runs, %g s and %g MB each\n",
                         config.name.c_str(), config.control.c_str(), grid.planners.size(), grid.checkers.size(),
                         settings.runs, settings.time, settings.memory);
            for (const std::string &checker : grid.checkers)
                runChecker(config, settings, grid, checker);
        }
    }  // namespace cli
}  // namespace meshgap
