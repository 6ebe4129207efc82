// meshgap_benchmark as a user runs it: errors, and a small sharded benchmark whose .log files are read back here
// (and by OMPL's ompl_benchmark_statistics when it is installed).

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "CliRun.h"

using namespace std::string_literals;
namespace fs = std::filesystem;

namespace
{
    using meshgap::test::CliRun;
    using meshgap::test::runBenchmark;

    CliRun shell(const std::string &command) { return meshgap::test::runCommand(command); }

    const std::string MAPS = std::string(MESHGAP_SOURCE_DIR) + "/maps";
    const std::string CFG = MAPS + "/slotted_wall/slotted_wall.cfg";

    /** \brief One planner block of an OMPL .log: its name, common properties, run properties and runs. */
    struct PlannerLog
    {
        std::string name;
        std::vector<std::string> common, properties;
        std::vector<std::map<std::string, std::string>> runs;
    };

    struct ExperimentLog
    {
        std::string name, seed;
        std::vector<PlannerLog> planners;
    };

    /** \brief A reader of OMPL's .log format (Benchmark::saveResultsToStream), strict about the counts. */
    ExperimentLog readLog(const fs::path &path)
    {
        std::ifstream in(path);
        std::string line;
        ExperimentLog log;
        auto next = [&]() {
            if (!std::getline(in, line))
                throw std::runtime_error(path.string() + ": ends early");
            return line;
        };
        auto count = [&](const std::string &suffix) {
            const std::string l = next();
            if (l.size() < suffix.size() || l.compare(l.size() - suffix.size(), suffix.size(), suffix) != 0)
                throw std::runtime_error(path.string() + ": expected '... " + suffix + "', got '" + l + "'");
            return std::stoul(l);
        };
        std::string first = next();
        if (first.rfind("Experiment ", 0) != 0 && first.find(" version") != std::string::npos)
            first = next();  // "OMPL version 1.5.2" (Debian's OMPL leaves the number empty)
        if (first.rfind("Experiment ", 0) != 0)
            throw std::runtime_error(path.string() + ": no Experiment line");
        log.name = first.substr(11);
        while (next() != "|>>>")  // experiment properties, host, date, then the setup
        {
        }
        if (next() == "<<<|")  // the CPU's description, optional
        {
            while (next() != "|>>>")
            {
            }
            next();
        }
        log.seed = line.substr(0, line.find(' '));
        for (const char *suffix : {"seconds per run", "MB per run", "runs per planner", "seconds spent to collect the data"})
            if (next().find(suffix) == std::string::npos)
                throw std::runtime_error(path.string() + ": expected '" + suffix + "'");
        for (std::size_t e = count("enum type"); e > 0; --e)
            next();
        for (std::size_t p = count("planners"); p > 0; --p)
        {
            PlannerLog planner;
            planner.name = next();
            for (std::size_t k = count("common properties"); k > 0; --k)
                planner.common.push_back(next());
            for (std::size_t k = count("properties for each run"); k > 0; --k)
                planner.properties.push_back(next());
            for (std::size_t r = count("runs"); r > 0; --r)
            {
                std::string values = next();
                std::map<std::string, std::string> run;
                for (const std::string &property : planner.properties)
                {
                    const std::size_t end = values.find("; ");
                    if (end == std::string::npos)
                        throw std::runtime_error(path.string() + ": too few values in '" + line + "'");
                    run[property] = values.substr(0, end);
                    values.erase(0, end + 2);
                }
                if (!values.empty())
                    throw std::runtime_error(path.string() + ": too many values in '" + line + "'");
                planner.runs.push_back(run);
            }
            if (next() != ".")  // progress data: property names, then one line per run
            {
                std::size_t names = std::stoul(line);
                while (names-- > 0)
                    next();
                for (std::size_t r = count("runs"); r > 0; --r)
                    next();
                if (next() != ".")
                    throw std::runtime_error(path.string() + ": no '.' after " + planner.name);
            }
            log.planners.push_back(planner);
        }
        return log;
    }

    /** \brief Two shards of one small grid (rrtconnect x two checkers x 2 runs), run once for all tests here.
        RRTConnect ends each run at its first solution (well under a second here): the time limit only ends a run
        that fails anyway, so a busy machine cannot change what is solved. */
    class BenchmarkCli : public ::testing::Test
    {
    protected:
        static void SetUpTestSuite()
        {
            dir_ = fs::temp_directory_path() / ("meshgap_benchmark_logs_" + std::to_string(::getpid()));
            fs::remove_all(dir_);
            for (const char *shard : {"1/2", "2/2"})
                shards_.push_back(runBenchmark("--cfg " + CFG +
                                               " --planner rrtconnect --checker certified,fcl"
                                               " --runs 2 --time 120 --seed 7 --out " +
                                               dir_.string() + " --shard " + shard));
            for (const auto &entry : fs::directory_iterator(dir_))
                if (entry.path().extension() == ".log")
                    logs_.push_back(entry.path());
            std::sort(logs_.begin(), logs_.end());
        }
        static void TearDownTestSuite() { fs::remove_all(dir_); }

        static fs::path dir_;
        static std::vector<CliRun> shards_;
        static std::vector<fs::path> logs_;
    };
    fs::path BenchmarkCli::dir_;
    std::vector<CliRun> BenchmarkCli::shards_;
    std::vector<fs::path> BenchmarkCli::logs_;
}  // namespace

TEST(BenchmarkCliErrors, BadInputGivesOneErrorAndExitOne)
{
    const std::string ok = "--cfg " + CFG + " --planner rrtconnect ";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--cfg /nonexistent/p.cfg --planner rrtconnect", "/nonexistent/p.cfg"},
        {"--cfg " + CFG + " --planner rrtconnect,nope", "'nope'"},
        {"--cfg " + CFG, "--planner"},  // the map's cfg has no [planner] section
        {ok + "--checker certified,nope", "'nope'"},
        {ok + "--shard 3/2", "--shard"},
        {ok + "--shard 0/2", "--shard"},
        {ok + "--shard half", "--shard"},
        {ok + "--runs 0", "positive"},
        {ok + "--param rrtstar.range=3", "no planner rrtstar"},
        {ok + "--param rrtconnect.reach=3", "'reach' is no parameter of RRTConnect"},
        {ok + "--param rrtconnect.range=far", "'far'"},
        {ok + "--param range=3", "PLANNER.NAME=VALUE"},
        // The old spellings, refused with the new one named.
        {"--cfg " + CFG + " --planners rrtconnect", "--planners: renamed: use --planner"},
        {ok + "--checkers fcl", "--checkers: renamed: use --checker"},
        {ok + "--samplers uniform", "--samplers: renamed: use --sampler"},
        {ok + "--out-dir /tmp", "--out-dir: renamed: use --out"},
        {ok + "--checker meshgap-certified", "'meshgap-certified' is now spelled 'certified'"},
        {ok + "--checker meshgap-fast,fcl", "'meshgap-fast' is now spelled 'fast'"},
        {"--planner rrtconnect", "--cfg"},
    };
    for (const auto &[args, mention] : cases)
    {
        const CliRun r = runBenchmark(args);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(mention), std::string::npos) << args << "\n" << r.err;
    }
}

TEST_F(BenchmarkCli, ShardsCoverTheGridExactlyOnce)
{
    for (const CliRun &r : shards_)
    {
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.err.find("run 2 of 2"), std::string::npos) << r.err;  // progress, per shard
    }
    // Cells (rrtconnect, checker, run) in order: shard 1 takes cells 0 and 2, shard 2 cells 1 and 3, so each shard
    // has one run of each checker: four .log files, one run each, and each shard with its own seed.
    ASSERT_EQ(logs_.size(), 4u);
    std::map<std::string, std::size_t> runs;
    std::map<std::string, std::set<std::string>> seeds;
    for (const fs::path &path : logs_)
    {
        const ExperimentLog log = readLog(path);
        EXPECT_EQ(log.name, "slotted_wall");
        ASSERT_EQ(log.planners.size(), 1u) << path;
        runs[log.planners[0].name] += log.planners[0].runs.size();
        seeds[log.planners[0].name].insert(log.seed);
    }
    const std::map<std::string, std::size_t> expected = {{"geometric_RRTConnect[fcl]", 2},
                                                         {"geometric_RRTConnect[meshgap-certified]", 2}};
    EXPECT_EQ(runs, expected);
    for (const auto &[planner, s] : seeds)
        EXPECT_EQ(s, (std::set<std::string>{"7", "8"})) << planner;
}

TEST_F(BenchmarkCli, RunsCarryCheckerCountersAndFclVerdicts)
{
    ASSERT_FALSE(logs_.empty());
    std::size_t solved = 0;
    for (const fs::path &path : logs_)
    {
        const PlannerLog planner = readLog(path).planners.at(0);
        const bool fcl = planner.name.find("[fcl]") != std::string::npos;
        EXPECT_NE(std::find(planner.common.begin(), planner.common.end(), fcl ? "checker = fcl" : "checker = meshgap-certified"),
                  planner.common.end());
        for (const auto &run : planner.runs)
        {
            EXPECT_GT(std::stoul(run.at("checker validity calls INTEGER")), 0u) << path;
            EXPECT_EQ(run.at("checker clearance calls INTEGER"), "0") << path;  // rrtconnect, length
            EXPECT_GT(std::stod(run.at("checker mean query time REAL")), 0.0) << path;
            EXPECT_EQ(run.count("checker evaluations INTEGER"), fcl ? 0u : 1u) << path;
            if (run.at("solved BOOLEAN") != "1")
                continue;
            ++solved;
            // Every densely interpolated state of the path is free by FCL, with a positive distance.
            EXPECT_EQ(run.at("fcl path collision free BOOLEAN"), "1") << path;
            EXPECT_GT(std::stoul(run.at("fcl path states INTEGER")), std::stoul(run.at("solution segments INTEGER")));
            EXPECT_GT(std::stod(run.at("fcl path min clearance REAL")), 0.0) << path;
            // meshgap's exact least clearance over the same dense states: FCL's least distance, the oracle.
            EXPECT_NEAR(std::stod(run.at("path min clearance REAL")), std::stod(run.at("fcl path min clearance REAL")),
                        1e-6)
                << path;
            EXPECT_EQ(run.at("correct solution BOOLEAN"), "1") << path;
        }
    }
    EXPECT_GE(solved, 2u) << "slotted_wall is solved by rrtconnect in well under a second (limit: 120 s a run)";
}

TEST_F(BenchmarkCli, StatisticsScriptLoadsEveryRunIntoOneDatabase)
{
    // ompl_benchmark_statistics ships in Debian's ompl-demos; OMPL_BENCHMARK_STATISTICS names another copy.
    std::string script = std::getenv("OMPL_BENCHMARK_STATISTICS") ? std::getenv("OMPL_BENCHMARK_STATISTICS") : "";
    if (script.empty() && std::system("command -v ompl_benchmark_statistics >/dev/null 2>&1") == 0)
        script = "ompl_benchmark_statistics";
    if (script.empty())
        GTEST_SKIP() << "ompl_benchmark_statistics not found (Debian package ompl-demos); not checking the database";
    ASSERT_EQ(logs_.size(), 4u);
    const fs::path db = dir_ / "results.db";
    // The script's own interpreter (its #! line: Debian's python3), not whichever python3 comes first on PATH.
    std::string command = script.find('/') == std::string::npos ? "$(command -v " + script + ")" : script;
    for (const fs::path &log : logs_)
        command += " " + log.string();
    const CliRun load = shell(command + " -d " + db.string());
    ASSERT_EQ(load.status, 0) << load.out << load.err;
    const CliRun query = shell(
        "python3 -c \"import sqlite3; c = sqlite3.connect('" + db.string() +
        "'); print(*c.execute('SELECT p.name, COUNT(*), SUM(COALESCE(r.fcl_path_collision_free, 1) = 0), "
        "COUNT(DISTINCT r.experimentid) FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id "
        "GROUP BY p.name ORDER BY p.name').fetchall(), sep='\\n')\"");
    ASSERT_EQ(query.status, 0) << query.err;
    // Two planner configurations (one per checker), two runs each from two experiments (shards), no path that
    // FCL finds in collision.
    EXPECT_EQ(query.out, "('geometric_RRTConnect[fcl]', 2, 0, 2)\n('geometric_RRTConnect[meshgap-certified]', 2, 0, 2)\n")
        << query.out;
}

TEST(BenchmarkCliErrors, ARobotsStartAndGoalAreCheckedAsASingleBodys)
{
    // Every problem takes one path: a start in collision or a goal outside the volume is one error naming the file,
    // for several bodies (maps/swap_se2 with both bodies at one place, or one outside the box) as for one body.
    const fs::path dir = fs::temp_directory_path() / ("meshgap_benchmark_ends_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string swap = MAPS + "/swap_se2/";
    // Body 2 starts at \e start2 and ends at \e goal2 ("x y"); body 1 goes from (-3.3, -1.2) to (3.3, 1.2).
    auto write = [&](const std::string &name, const std::string &start2, const std::string &goal2) {
        std::istringstream s(start2), g(goal2);
        std::string sx, sy, gx, gy;
        s >> sx >> sy;
        g >> gx >> gy;
        std::ofstream cfg(dir / name);
        cfg << "[problem]\nrobot.1 = " << swap << "swap_se2_robot.obj\nrobot.2 = " << swap
            << "swap_se2_robot.obj\nworld = " << swap << "swap_se2_world.obj\n"
            << "start.1.x = -3.3\nstart.1.y = -1.2\nstart.2.x = " << sx << "\nstart.2.y = " << sy << "\n"
            << "goal.1.x = 3.3\ngoal.1.y = 1.2\ngoal.2.x = " << gx << "\ngoal.2.y = " << gy << "\n"
            << "volume.min.x = -4\nvolume.min.y = -2\nvolume.max.x = 4\nvolume.max.y = 2\n";
        return (dir / name).string();
    };
    const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
        {write("together.cfg", "-3.3 -1.2", "-3.3 -1.2"),
         {"together.cfg", "start is in collision", "'robot.1' against link 'robot.2'"}},
        {write("outside.cfg", "3.3 1.2", "-9 -1.2"), {"outside.cfg", "goal lies outside the volume"}},
    };
    for (const auto &[cfg, mentions] : cases)
    {
        const CliRun r =
            runBenchmark("--cfg " + cfg + " --planner rrtconnect --runs 1 --time 1 --out " + (dir / "logs").string());
        EXPECT_EQ(r.status, 1) << cfg << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << cfg << "\n" << r.err;
        for (const std::string &m : mentions)
            EXPECT_NE(r.err.find(m), std::string::npos) << cfg << ": no '" << m << "'\n" << r.err;
    }
    fs::remove_all(dir);
}

TEST(BenchmarkCliInterrupted, AKilledBenchmarkKeepsEveryFinishedRun)
{
    // A long benchmark (many short runs), killed with SIGKILL once its first log is on disk: every .log left is
    // complete and readable, with at least the runs that had finished; the half-written temporaries are not logs.
    const fs::path dir = fs::temp_directory_path() / ("meshgap_benchmark_killed_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path pidFile = dir / "pid";
    const std::string command = std::string(MESHGAP_BINARY_DIR) + "/planners/meshgap_benchmark --cfg " + CFG +
                                " --planner rrtconnect --checker certified --runs 200 --time 1 --seed 3"
                                " --out " + dir.string() + " >/dev/null 2>&1 & echo $! > " + pidFile.string();
    ASSERT_EQ(std::system(command.c_str()), 0);
    auto logs = [&] {
        std::vector<fs::path> found;
        for (const auto &entry : fs::directory_iterator(dir))
            if (entry.path().extension() == ".log")
                found.push_back(entry.path());
        return found;
    };
    for (int waited = 0; logs().empty() && waited < 1200; ++waited)  // up to 120 s on a loaded machine
        ::usleep(100000);
    ::usleep(300000);  // let it get into later runs, so the kill may land mid-write
    pid_t pid = 0;
    std::ifstream(pidFile) >> pid;
    ASSERT_GT(pid, 0);
    ::kill(pid, SIGKILL);
    ::usleep(200000);
    const std::vector<fs::path> kept = logs();
    ASSERT_FALSE(kept.empty()) << "no log was written before the kill";
    for (const fs::path &log : kept)
    {
        ExperimentLog parsed;
        ASSERT_NO_THROW(parsed = readLog(log)) << log;
        ASSERT_EQ(parsed.planners.size(), 1u);
        EXPECT_GE(parsed.planners[0].runs.size(), 1u) << log;
        EXPECT_LT(parsed.planners[0].runs.size(), 200u) << "the benchmark finished before the kill: nothing was tested";
    }
    fs::remove_all(dir);
}

TEST(BenchmarkCliControl, ControlProblemsRunWithTheControlPlannersAndWriteOMPLsLog)
{
    // The blimp of maps/blimp_window: two control planners, 1 s a run; every run ends with a path (exact or
    // approximate), and the .log reads back in OMPL's format with the checker's counters per run.
    const fs::path dir = fs::temp_directory_path() / ("meshgap_benchmark_control_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const std::string cfg = MAPS + "/blimp_window/blimp_window.cfg";
    const CliRun r = runBenchmark("--cfg " + cfg +
                                  " --planner kpiece,RRT --checker certified --runs 2 --time 1 --seed 3"
                                  " --out " +
                                  dir.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("blimp_window (control: blimp): 2 planners x 1 checkers x 2 runs"), std::string::npos)
        << r.err;
    const ExperimentLog log = readLog(dir / "blimp_window.control.certified.log");
    EXPECT_EQ(log.name, "blimp_window");
    EXPECT_EQ(log.seed, "3");
    ASSERT_EQ(log.planners.size(), 2u);
    EXPECT_EQ(log.planners[0].name, "control_KPIECE1[meshgap-certified]");
    EXPECT_EQ(log.planners[1].name, "control_RRT[meshgap-certified]");
    for (const PlannerLog &planner : log.planners)
    {
        ASSERT_EQ(planner.runs.size(), 2u) << planner.name;
        for (const auto &run : planner.runs)
        {
            const bool exact = run.at("solved BOOLEAN") == "1";
            EXPECT_TRUE(exact || run.at("approximate solution BOOLEAN") == "1") << planner.name;
            EXPECT_GT(std::stol(run.at("checker validity calls INTEGER")), 0) << planner.name;
            EXPECT_GT(std::stod(run.at("checker query time REAL")), 0.0) << planner.name;
        }
    }
    fs::remove_all(dir);
    // Bad input: one error naming the option, exit 1.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"--planner rrtconnect", "'rrtconnect' is not a control planner"},
        {"--planner kpiece --checker fcl", "'fcl' does not check a control problem (its checkers: certified, fast)"},
        {"--planner kpiece --sampler uniform", "--sampler: applies to geometric problems only"},
        {"--planner kpiece --shard 1/2", "--shard: a control benchmark runs whole"},
        {"--planner kpiece --objective length", "--objective: applies to geometric problems only"},
    };
    for (const auto &[args, mention] : cases)
    {
        const CliRun bad = runBenchmark("--cfg " + cfg + " --runs 1 --time 1 " + args);
        EXPECT_EQ(bad.status, 1) << args << "\n" << bad.err;
        EXPECT_NE(bad.err.find(mention), std::string::npos) << args << "\n" << bad.err;
    }
}
