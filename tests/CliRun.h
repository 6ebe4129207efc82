#ifndef MESHGAP_TESTS_CLI_RUN_H
#define MESHGAP_TESTS_CLI_RUN_H

// Running one of meshgap's executables as a user does, for the CLI tests: exit status, stdout, stderr.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace meshgap
{
    namespace test
    {
        struct CliRun
        {
            int status{-1};  ///< exit status; -1 if killed by a signal (a crash); 124 if it ran out of time
            std::string out, err;
        };

        /** \brief Run a shell \e command under `timeout seconds`, capturing its stdout and stderr. */
        inline CliRun runCommand(const std::string &command, int seconds = 300)
        {
            namespace fs = std::filesystem;
            // Unique per process and call: ctest runs several tests at once.
            static int calls = 0;
            const std::string stem = (fs::temp_directory_path() / ("meshgap_cli_" + std::to_string(::getpid()) +
                                                                   "_" + std::to_string(++calls)))
                                         .string();
            const std::string line = "timeout " + std::to_string(seconds) + " " + command + " >" + stem + ".out 2>" +
                                     stem + ".err";
            const int raw = std::system(line.c_str());
            auto slurp = [](const std::string &path) {
                std::ifstream in(path);
                std::stringstream s;
                s << in.rdbuf();
                fs::remove(path);
                return s.str();
            };
            CliRun r;
            r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
            // `timeout` reports a child killed by a signal as 128 + signal.
            if (r.status > 128 && r.status != 124)
                r.status = -1;
            r.out = slurp(stem + ".out");
            r.err = slurp(stem + ".err");
            return r;
        }

        /** \brief Run build/planners/<executable> with \e args (shell syntax) under `timeout seconds`. */
        inline CliRun runExecutable(const std::string &executable, const std::string &args, int seconds = 300)
        {
            return runCommand(std::string(MESHGAP_BINARY_DIR) + "/planners/" + executable + " " + args, seconds);
        }

        /** \brief Run meshgap_plan with \e args. */
        inline CliRun runPlan(const std::string &args)
        {
            return runExecutable("meshgap_plan", args);
        }

        /** \brief Run meshgap_benchmark with \e args. */
        inline CliRun runBenchmark(const std::string &args)
        {
            return runExecutable("meshgap_benchmark", args);
        }

        /** \brief Lines of \e text that start with \e prefix. */
        inline int countLines(const std::string &text, const std::string &prefix)
        {
            std::istringstream in(text);
            std::string line;
            int n = 0;
            while (std::getline(in, line))
                n += line.rfind(prefix, 0) == 0;
            return n;
        }

        /** \brief A test with a folder of its own per test process (named \e prefix and the process id, removed at
            the end), and file() to write into it. */
        class FolderTest : public ::testing::Test
        {
        protected:
            explicit FolderTest(const std::string &prefix)
              : dir_(std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid())))
            {
            }
            void SetUp() override { std::filesystem::create_directories(dir_); }
            void TearDown() override { std::filesystem::remove_all(dir_); }

            /** \brief Write \e text to \e name in the folder; returns its path. */
            std::string file(const std::string &name, const std::string &text) const
            {
                const std::string path = (dir_ / name).string();
                std::ofstream(path) << text;
                return path;
            }

            std::filesystem::path dir_;
        };
    }  // namespace test
}  // namespace meshgap

#endif
