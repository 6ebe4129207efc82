#include "benchmark/BenchmarkConfig.h"

#include <limits>
#include <ompl/util/Console.h>
#include <regex>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    namespace cli
    {
        std::vector<PlannerSpec> plannersFromConfig(const std::string &file, const ConfigSection &planners)
        {
            std::vector<PlannerSpec> specs;
            for (const auto &[key, value] : planners)
            {
                const std::size_t dot = key.find('.');
                if (dot == std::string::npos)
                {
                    specs.push_back({key, "", {}});
                    continue;
                }
                const std::string prefix = key.substr(0, dot), rest = key.substr(dot + 1);
                if (prefix == "problem")
                    throw Exception(file,
                                    "[planner] " + quote(key) + ": per-planner problem settings are not supported");
                if (specs.empty() || specs.back().type != prefix)
                    throw Exception(file,
                                    "[planner] " + quote(key) + " does not follow a " + quote(prefix + "=") + " line");
                if (rest == "name")
                    specs.back().name = value;
                else
                    specs.back().params.push_back({rest, value, file + ": [planner] " + key});
            }
            return specs;
        }

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
            throw Exception("--shard", quote(text) + " is not i/n with 1 <= i <= n");
        }

        void applyConfig(const std::string &file, const ConfigSection &benchmark, Settings &settings)
        {
            for (const auto &[key, value] : benchmark)
            {
                const std::string where = file + ": [benchmark] " + key;
                unsigned long runs = 0;
                if (key == "time_limit")
                    settings.time = parseFiniteNumber(value, where);
                else if (key == "mem_limit")
                    settings.memory = parseFiniteNumber(value, where);
                else if (key == "run_count")
                {
                    if (!parseUnsigned(value, runs) || runs > std::numeric_limits<unsigned>::max())
                        throw Exception(where, quote(value) + " is not a whole number of runs");
                    settings.runs = static_cast<unsigned>(runs);
                }
                else if (key == "output")
                    settings.outDir = value;
                else
                    OMPL_WARN("%s: [benchmark] %s is not supported; ignored", file.c_str(), key.c_str());
            }
        }
    }  // namespace cli
}  // namespace meshgap
