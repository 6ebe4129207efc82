// A writer of the on-disk mesh-distance cache killed at any moment (SIGKILL: no handler, no flush) must never make a
// later reader see a corrupt table: the file at the cache path is either absent (the table is rebuilt) or complete
// and valid, because writeDistanceCache() writes a temporary file and renames it. Corrupt, truncated and stale files
// at the cache path itself are covered by MeshDistancesCache.* in MeshDistancesTest.cpp.

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <random>
#include <signal.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "TestMeshes.h"
#include "meshgap/mesh/DistanceCache.h"
#include "meshgap/mesh/MeshDistances.h"

namespace fs = std::filesystem;
using namespace meshgap;

namespace
{
    using Clock = std::chrono::steady_clock;

    class CacheInterrupt : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            // On the real file system (not /dev/shm), so that the write and its fsync take measurable time.
            dir_ = fs::temp_directory_path() / ("meshgap-cache-interrupt-" + std::to_string(::getpid()));
            fs::remove_all(dir_);
            fs::create_directories(dir_);
        }
        void TearDown() override
        {
            std::error_code ignored;
            fs::remove_all(dir_, ignored);
        }

        /** \brief Temporary files in the folder (what killed writers leave), of process \e pid or (0) of any. */
        std::size_t temporaries(pid_t pid = 0) const
        {
            const std::string mark = pid ? "." + std::to_string(pid) + "." : ".tmp.";
            std::size_t count = 0;
            for (const auto &entry : fs::directory_iterator(dir_))
            {
                const std::string name = entry.path().filename().string();
                count += name.find(".tmp.") != std::string::npos && name.find(mark) != std::string::npos;
            }
            return count;
        }

        /** \brief Run \e work in a child process; kill it with SIGKILL after \e delay (never, if negative). Returns
            the time from fork to the child's end. */
        template <typename Work>
        static double runChild(Work work, double delay, pid_t *child = nullptr)
        {
            const auto start = Clock::now();
            const pid_t pid = ::fork();
            if (child)
                *child = pid;
            if (pid == 0)
            {
                const bool ok = work();
                ::_exit(ok ? 0 : 3);
            }
            EXPECT_GT(pid, 0) << "fork failed";
            if (pid <= 0)
                return 0.0;
            if (delay >= 0.0)
            {
                std::this_thread::sleep_for(std::chrono::duration<double>(delay));
                ::kill(pid, SIGKILL);
            }
            int status = 0;
            ::waitpid(pid, &status, 0);
            if (delay < 0.0)
            {
                EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the uninterrupted writer failed";
            }
            return std::chrono::duration<double>(Clock::now() - start).count();
        }

        /** \brief Run \e work in a child process and kill it with SIGKILL as soon as its temporary file is seen
            (polled every 50 us), so the kill lands during the write whatever the machine's load. Returns the
            child's id, or 0 if it ended before its temporary file was seen. */
        template <typename Work>
        pid_t killChildMidWrite(Work work) const
        {
            const pid_t pid = ::fork();
            if (pid == 0)
                ::_exit(work() ? 0 : 3);
            EXPECT_GT(pid, 0) << "fork failed";
            if (pid <= 0)
                return 0;
            int status = 0;
            while (temporaries(pid) == 0)
            {
                if (::waitpid(pid, &status, WNOHANG) == pid)
                    return 0;
                std::this_thread::sleep_for(std::chrono::microseconds(50));
            }
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return pid;
        }

        fs::path dir_;
    };
}  // namespace

// The file-level guarantee, on a 16.5 MiB table (1176 nodes; about 30-60 ms to write and sync here): kill the writer
// at delays spread over its whole run, then read. Every read either finds no file or the exact table.
TEST_F(CacheInterrupt, KilledWriterLeavesNoFileOrTheCompleteTable)
{
    constexpr std::uint32_t n = 1176;
    const std::size_t entries = std::size_t(n) * n;
    std::vector<double> D(entries);
    std::vector<std::uint32_t> P(entries);
    std::mt19937_64 random(7);
    for (std::size_t i = 0; i < entries; ++i)
    {
        D[i] = std::uniform_real_distribution<double>(0.0, 100.0)(random);
        P[i] = static_cast<std::uint32_t>(random());
    }
    const std::uint64_t hash = 0x0123456789abcdefull;
    const std::string path = distanceCachePath(dir_.string(), hash);
    auto write = [&] { return writeDistanceCache(path, hash, n, D.data(), P.data()); };

    // Uninterrupted: how long a writer lives (fork to exit), then the delays are spread over 0 .. 1.2 x that (and
    // one well after).
    const double full = runChild(write, -1.0);
    ASSERT_TRUE(fs::exists(path));
    std::vector<double> readD(entries);
    std::vector<std::uint32_t> readP(entries);
    ASSERT_TRUE(readDistanceCache(path, hash, n, readD.data(), readP.data()));
    std::printf("[ info ] writing the %.1f MiB table takes %.1f ms (fork to exit)\n", 12.0 * entries / 1048576.0,
                1e3 * full);

    constexpr int kills = 24;
    int absent = 0, complete = 0, midWrite = 0;
    for (int k = 0; k < kills; ++k)
    {
        fs::remove(path);
        pid_t child = 0;
        // Spread over 0 .. 1.2 x the measured life, and the last one long after it: a writer's life varies from
        // run to run (page cache, disk), and at least one kill must land after the rename.
        const double delay = k + 1 < kills ? 1.2 * full * k / (kills - 2) : 5.0 * full + 0.5;
        runChild(write, delay, &child);
        midWrite += temporaries(child) > 0;  // (the next writer removes it: its process is gone)
        if (!fs::exists(path))
        {
            ++absent;
            continue;
        }
        // Present: it must be the complete table, bit for bit (never a partial one that fails a check).
        std::fill(readD.begin(), readD.end(), -1.0);
        ASSERT_TRUE(readDistanceCache(path, hash, n, readD.data(), readP.data())) << "kill " << k;
        ASSERT_EQ(0, std::memcmp(readD.data(), D.data(), entries * sizeof(double))) << "kill " << k;
        ASSERT_EQ(0, std::memcmp(readP.data(), P.data(), entries * sizeof(std::uint32_t))) << "kill " << k;
        ++complete;
    }
    std::printf("[ info ] %d kills: %d left no file (%d of them mid-write, leaving a .tmp file), %d a complete table\n",
                kills, absent, midWrite, complete);
    EXPECT_EQ(absent + complete, kills);
    EXPECT_GT(complete, 0) << "no writer finished: the delays are too short";
    // Timed kills may all miss the write on a busy machine: kill writers as their temporary file appears, until
    // one is caught mid-write (its temporary file left), and read again. The test means something only then.
    int caught = 0;
    for (int attempt = 0; attempt < 20 && caught == 0; ++attempt)
    {
        fs::remove(path);
        const pid_t killed = killChildMidWrite(write);
        caught += killed != 0 && temporaries(killed) > 0;
        if (fs::exists(path))
        {
            std::fill(readD.begin(), readD.end(), -1.0);
            ASSERT_TRUE(readDistanceCache(path, hash, n, readD.data(), readP.data())) << "attempt " << attempt;
            ASSERT_EQ(0, std::memcmp(readD.data(), D.data(), entries * sizeof(double))) << "attempt " << attempt;
        }
    }
    EXPECT_GT(caught, 0) << "no writer was caught during its write";

    // Temporary files of killed writers are never read, and the next write removes them.
    ASSERT_TRUE(write());
    EXPECT_EQ(temporaries(), 0u);
    EXPECT_TRUE(readDistanceCache(path, hash, n, readD.data(), readP.data()));
}

// The same through MeshDistances: a child builds the all-pairs table of a 1178-node box with a cache folder (build,
// then write) and is killed at delays spread over its run; the parent's build then either reads the complete table
// or rebuilds it, and answers exactly as a build without a cache does.
TEST_F(CacheInterrupt, KilledBuildIsReadBackCompleteOrRebuilt)
{
    const auto graph = std::make_shared<const SurfaceGraph>(test::box(1.0, 1.5, 2.0, 14));
    const std::uint32_t n = graph->numNodes();
    MeshDistancesOptions plain;
    plain.threads = 1;
    const MeshDistancesPtr reference = MeshDistances::build(graph, plain);
    ASSERT_TRUE(reference->isDense());
    MeshDistancesOptions cached = plain;
    cached.cacheDir = dir_.string();
    const std::string path = distanceCachePath(dir_.string(), graphHash(*graph));
    auto build = [&] { return MeshDistances::build(graph, cached)->isDense(); };

    const double full = runChild(build, -1.0);
    ASSERT_TRUE(fs::exists(path));
    constexpr int kills = 10;
    int fromCache = 0, rebuilt = 0;
    for (int k = 0; k < kills; ++k)
    {
        fs::remove(path);
        runChild(build, 1.2 * full * k / (kills - 1));
        const MeshDistancesPtr md = MeshDistances::build(graph, cached);
        (md->fromCache() ? fromCache : rebuilt)++;
        for (std::uint32_t u = 0; u < n; u += 97)
            for (std::uint32_t v = 0; v < n; ++v)
                ASSERT_EQ(md->distance(u, v), reference->distance(u, v)) << "kill " << k << ", " << u << " -> " << v;
        // After the parent's build the cache holds the complete table whichever way it went.
        EXPECT_TRUE(MeshDistances::build(graph, cached)->fromCache()) << "kill " << k;
    }
    std::printf("[ info ] build of %u nodes takes %.1f ms; %d kills: %d read back from the cache, %d rebuilt\n", n,
                1e3 * full, kills, fromCache, rebuilt);
    EXPECT_GT(rebuilt, 0);
    EXPECT_EQ(temporaries(), 0u) << "the parent's writes should have removed the killed writers' temporary files";
}
