#ifndef MESHGAP_PLANNERS_BENCHMARK_CONTROL_BENCHMARK_H
#define MESHGAP_PLANNERS_BENCHMARK_CONTROL_BENCHMARK_H

// meshgap_benchmark on a control problem (an OMPL.app .cfg with a "control" key): OMPL's Benchmark over the control
// planners of support/ControlRun.h, once per clearance checker mode, written in OMPL's .log format.

#include <string>
#include <vector>

#include "benchmark/BenchmarkConfig.h"
#include "meshgap/scene/ProblemConfig.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief The checkers of a control problem: the ClearanceChecker's modes, certified and fast. */
        const std::vector<std::string> &controlCheckerNames();

        /** \brief The planners (names of controlPlannerNames(); empty: the cfg's [planner] section, whose planners
            meshgap does not offer, such as OMPL.app's Syclop planners, are left out with a note) and the checkers
            (empty: every one of controlCheckerNames()) of a control benchmark. Throws meshgap::Exception naming an
            unknown planner or checker. */
        struct ControlGrid
        {
            std::vector<std::string> planners, checkers;
        };
        ControlGrid controlGrid(const ProblemConfig &config, const std::string &plannerList,
                                const std::string &checkerList);

        /** \brief For each checker, OMPL's Benchmark of every planner, settings.runs runs of settings.time seconds
            each, written to OUT/<problem>.control.<checker>.log (OMPL's .log format, whole runs only: written
            once the checker's runs are done); a line per run (exact, approximate or none, and the distance to the
            goal) and per planner (runs exact, approximate, median time and goal distance) on stderr. Each run adds
            the checker's counters ("checker validity calls INTEGER", "checker query time REAL") to OMPL's
            properties. */
        void runControlBenchmark(const ProblemConfig &config, const Settings &settings, const ControlGrid &grid);
    }  // namespace cli
}  // namespace meshgap

#endif
