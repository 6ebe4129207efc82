// Replays every fuzz input kept in the repository through the fuzz targets' own entry functions (fuzz/FuzzTargets.h):
// the seed corpora in fuzz/corpus/<target>/ and the inputs that once crashed a target, in
// tests/resources/fuzz/<target>/. Each must end in an answer that keeps the invariants or in a meshgap::Exception;
// a broken invariant throws fuzz::Violation, any other exception (or a crash) is a failure too.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "../fuzz/FuzzTargets.h"

namespace fs = std::filesystem;
using namespace meshgap;

namespace
{
    std::vector<fs::path> inputsOf(const std::string &target)
    {
        std::vector<fs::path> files;
        for (const fs::path &dir : {fs::path(MESHGAP_SOURCE_DIR) / "fuzz" / "corpus" / target,
                                   fs::path(MESHGAP_TEST_RESOURCES_DIR) / "fuzz" / target})
            if (fs::is_directory(dir))
                for (const auto &entry : fs::directory_iterator(dir))
                    if (entry.is_regular_file())
                        files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        return files;
    }

    std::vector<std::uint8_t> readBytes(const fs::path &file)
    {
        std::ifstream in(file, std::ios::binary);
        return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }

    class FuzzReplay : public ::testing::TestWithParam<fuzz::Target>
    {
    };
}  // namespace

TEST_P(FuzzReplay, KeptInputsEndInAnAnswerOrAMeshgapException)
{
    const fuzz::Target &target = GetParam();
    const std::vector<fs::path> files = inputsOf(target.name);
    ASSERT_FALSE(files.empty()) << "no seed corpus for fuzz target '" << target.name << "'";
    std::size_t accepted = 0;
    for (const fs::path &file : files)
    {
        SCOPED_TRACE(file.string());
        const std::vector<std::uint8_t> bytes = readBytes(file);
        fuzz::Outcome outcome = fuzz::Outcome::Rejected;
        EXPECT_NO_THROW(outcome = target.run(bytes.data(), bytes.size()));
        accepted += outcome == fuzz::Outcome::Accepted;
    }
    // Some inputs must get past the readers, so the invariant checks run in every test run.
    EXPECT_GT(accepted, 0u) << "no kept input of '" << target.name << "' is accepted";
}

INSTANTIATE_TEST_SUITE_P(Fuzz, FuzzReplay, ::testing::ValuesIn(fuzz::targets()),
                         [](const ::testing::TestParamInfo<fuzz::Target> &param) { return std::string(param.param.name); });

// The oracles the distance target relies on, against known geometry.
TEST(FuzzOracles, WindingNumberAndViolation)
{
    Mesh tetra;
    tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    EXPECT_NEAR(fuzz::windingNumber(tetra, Eigen::Vector3d(0.1, 0.1, 0.1)), 1.0, 1e-12);
    EXPECT_NEAR(fuzz::windingNumber(tetra, Eigen::Vector3d(1.0, 1.0, 1.0)), 0.0, 1e-12);
    EXPECT_THROW(fuzz::check(false, "test"), fuzz::Violation);
    EXPECT_FALSE(fuzz::isRotation(2.0 * Eigen::Matrix3d::Identity()));
    EXPECT_FALSE(fuzz::isRotation(-Eigen::Matrix3d::Identity()));
}
