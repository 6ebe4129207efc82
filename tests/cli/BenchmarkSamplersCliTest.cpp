// meshgap_benchmark --sampler: the valid-state sampler as a dimension of the experiment (one .log per checker and
// sampler, the sampler in its common properties), and unknown or repeated names refused with one error.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CliRun.h"

namespace fs = std::filesystem;

namespace
{
    using meshgap::test::runBenchmark;

    const std::string SLOTTED_WALL_CFG = std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg";
}  // namespace

TEST(BenchmarkSamplersCli, BadSamplersGiveOneErrorAndExitOne)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_bench_samplers_bad_" + std::to_string(::getpid()));
    for (const char *list : {"bogus", "uniform,uniform", "uniform,,bridge"})
    {
        const auto r = runBenchmark("--cfg " + SLOTTED_WALL_CFG +
                                    " --planner prm --checker certified --runs 1 --time 0.1 "
                                    "--sampler " +
                                    list + " --out " + dir.string());
        EXPECT_EQ(r.status, 1) << list << "\n" << r.err;
        EXPECT_NE(r.err.find("--sampler"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir) && !fs::is_empty(dir)) << "nothing written for " << list;
    }
    const auto r = runBenchmark("--cfg " + SLOTTED_WALL_CFG + " --sampler bogus");
    EXPECT_NE(r.err.find("narrow_passage"), std::string::npos) << "the valid names are listed: " << r.err;
    fs::remove_all(dir);
}

TEST(BenchmarkSamplersCli, EachSamplerIsItsOwnSlice)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_bench_samplers_" + std::to_string(::getpid()));
    const auto r = runBenchmark("--cfg " + SLOTTED_WALL_CFG +
                                " --planner prm --checker certified --runs 1 --time 0.3 "
                                "--seed 4 --sampler uniform,narrow_passage --out " +
                                dir.string());
    ASSERT_EQ(r.status, 0) << r.err;
    for (const std::string sampler : {"uniform", "narrow_passage"})
    {
        const fs::path log = dir / ("slotted_wall.PRM.meshgap-certified." + sampler + ".log");
        ASSERT_TRUE(fs::exists(log)) << log << "\n" << r.err;
        std::ifstream in(log);
        std::stringstream text;
        text << in.rdbuf();
        EXPECT_NE(text.str().find("PRM[meshgap-certified," + sampler + "]"), std::string::npos) << text.str();
        EXPECT_NE(text.str().find("sampler = " + sampler), std::string::npos) << text.str();
    }
    fs::remove_all(dir);
}
