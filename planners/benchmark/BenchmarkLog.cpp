#include "benchmark/BenchmarkLog.h"

#include <cctype>
#include <cstdio>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"

namespace meshgap
{
    namespace cli
    {
        std::string real(double value)
        {
            char buffer[32];
            std::snprintf(buffer, sizeof buffer, "%.9g", value);
            return buffer;
        }

        std::string fileSafe(const std::string &name)
        {
            std::string out = name;
            for (char &c : out)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '+')
                    c = '_';
            return out;
        }

        std::filesystem::path logPath(const std::filesystem::path &outDir, const std::string &problem,
                                      const std::string &planner, const std::string &checkerLabel,
                                      const std::string &sampler, unsigned shard, unsigned shards)
        {
            return outDir / (fileSafe(problem) + "." + fileSafe(planner) + "." + checkerLabel +
                             (sampler.empty() ? "" : "." + sampler) +
                             (shards > 1 ? ".shard" + std::to_string(shard) + "of" + std::to_string(shards) : "") +
                             ".log");
        }

        void LogWriter::write(const CompleteExperiment &experiment, const std::filesystem::path &path)
        {
            exp_ = experiment;
            writeStreamAtomically(path.string(),
                                  [&](std::ostream &out)
                                  {
                                      if (!saveResultsToStream(out))
                                          throw Exception(path.string(), "cannot write the benchmark log");
                                  });
        }
    }  // namespace cli
}  // namespace meshgap
