#ifndef MESHGAP_PLANNERS_BENCHMARK_BENCHMARK_CONFIG_H
#define MESHGAP_PLANNERS_BENCHMARK_BENCHMARK_CONFIG_H

// What meshgap_benchmark reads from the cfg (its [planner] and [benchmark] sections, as OMPL.app reads them) and the
// --shard option.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace meshgap
{
    namespace cli
    {
        /** \brief A section of a problem file ([planner], [benchmark]): its entries in order. */
        using ConfigSection = std::vector<std::pair<std::string, std::string>>;

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
            "rrt.range=50" sets a parameter of the entry just started; errors name \e file. */
        std::vector<PlannerSpec> plannersFromConfig(const std::string &file, const ConfigSection &planners);

        /** \brief "i/n" with 1 <= i <= n. */
        std::pair<unsigned, unsigned> parseShard(const std::string &text);

        struct Settings
        {
            double time{10.0}, memory{4096.0};
            unsigned runs{10};
            bool simplify{true};
            std::filesystem::path outDir{"."};
        };

        /** \brief The [benchmark] section of \e file; unknown keys are reported and ignored, as OMPL.app does. */
        void applyConfig(const std::string &file, const ConfigSection &benchmark, Settings &settings);
    }  // namespace cli
}  // namespace meshgap

#endif
