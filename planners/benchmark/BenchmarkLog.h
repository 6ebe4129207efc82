#ifndef MESHGAP_PLANNERS_BENCHMARK_BENCHMARK_LOG_H
#define MESHGAP_PLANNERS_BENCHMARK_BENCHMARK_LOG_H

// meshgap_benchmark's .log files: OMPL's own writer, one file per (planner, checker[, sampler]) slice.

#include <filesystem>
#include <ompl/control/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <string>

namespace meshgap
{
    namespace cli
    {
        /** \brief A real for a .log: 9 significant digits (std::to_string's fixed 6 decimals lose small times). */
        std::string real(double value);

        /** \brief \e name with every character but letters, digits, '-', '_' and '+' replaced by '_'. */
        std::string fileSafe(const std::string &name);

        /** \brief The .log of one slice: OUT/<problem>.<planner>.<checker label>[.<sampler>][.shard<i>of<n>].log */
        std::filesystem::path logPath(const std::filesystem::path &outDir, const std::string &problem,
                                      const std::string &planner, const std::string &checkerLabel,
                                      const std::string &sampler, unsigned shard, unsigned shards);

        /** \brief OMPL's own .log writer for an experiment assembled run by run; written under a temporary name, then
            renamed (writeStreamAtomically()), so a .log on disk is always whole. */
        class LogWriter : public ompl::tools::Benchmark
        {
        public:
            explicit LogWriter(ompl::geometric::SimpleSetup &setup) : Benchmark(setup) {}
            explicit LogWriter(ompl::control::SimpleSetup &setup) : Benchmark(setup) {}

            /** \brief Write \e experiment to \e path (whole, or not at all). */
            void write(const CompleteExperiment &experiment, const std::filesystem::path &path);
        };
    }  // namespace cli
}  // namespace meshgap

#endif
