// The one atomic file writer (meshgap/AtomicFile.h): a reader sees the old file or the whole new one, never a part,
// and no temporary file is left behind, whether the writer succeeds or throws.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    std::string slurp(const fs::path &p)
    {
        std::ifstream in(p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    /** \brief A fresh empty folder for one test. */
    fs::path freshFolder(const std::string &name)
    {
        const fs::path dir = fs::temp_directory_path() / ("meshgap_atomic_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        return dir;
    }

    std::size_t entries(const fs::path &dir)
    {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
    }
}  // namespace

TEST(AtomicFile, WritesTheWholeFileAndLeavesNoTemporary)
{
    const fs::path dir = freshFolder("whole"), file = dir / "out.txt";
    writeStreamAtomically(file.string(), [](std::ostream &out) { out << "old\n"; });
    EXPECT_EQ(slurp(file), "old\n");
    writeStreamAtomically(file.string(), [](std::ostream &out) { out << "new, longer\n"; });
    EXPECT_EQ(slurp(file), "new, longer\n");
    EXPECT_EQ(entries(dir), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, AWriterThatThrowsKeepsTheOldFileAndRemovesItsTemporary)
{
    const fs::path dir = freshFolder("throws"), file = dir / "out.txt";
    writeStreamAtomically(file.string(), [](std::ostream &out) { out << "old\n"; });
    std::string seen;
    EXPECT_THROW(writeAtomically(file.string(),
                                 [&](const std::string &temporary)
                                 {
                                     seen = temporary;
                                     std::ofstream(temporary) << "half";
                                     throw std::runtime_error("disk full");
                                 }),
                 std::runtime_error);
    EXPECT_EQ(fs::path(seen).parent_path(), dir);  // beside the file, so the rename stays on one file system
    EXPECT_FALSE(fs::exists(seen));
    EXPECT_EQ(slurp(file), "old\n");
    EXPECT_EQ(entries(dir), 1u);
    fs::remove_all(dir);
}

TEST(AtomicFile, AnUnwritableFolderGivesOneErrorNamingTheFile)
{
    const std::string file = "/nonexistent/folder/out.txt";
    try
    {
        writeStreamAtomically(file, [](std::ostream &out) { out << "x"; });
        ADD_FAILURE() << "no error";
    }
    catch (const Exception &e)
    {
        EXPECT_EQ(std::string(e.what()).rfind(file + ": cannot open ", 0), 0u) << e.what();
    }
}

TEST(AtomicFile, TemporaryNamesAreDistinct)
{
    EXPECT_NE(temporaryPath("a.log"), temporaryPath("a.log"));
    EXPECT_EQ(temporaryPath("dir/a.log").rfind("dir/a.log.tmp.", 0), 0u);
}
