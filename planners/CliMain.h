#ifndef MESHGAP_PLANNERS_CLI_MAIN_H
#define MESHGAP_PLANNERS_CLI_MAIN_H

// What every meshgap executable shares: OMPL's log goes to stderr (stdout carries results: text, CSV or JSON), and
// any error ends in one line "error: <file>: <problem>" and exit status 1, never a crash.

#include <cstdio>
#include <exception>
#include <ompl/util/Console.h>
#include <string>

namespace meshgap
{
    namespace cli
    {
        class StderrOutputHandler : public ompl::msg::OutputHandler
        {
        public:
            void log(const std::string &text, ompl::msg::LogLevel level, const char *, int) override
            {
                static const char *prefix[] = {"debug: ", "", "warning: ", "error: ", "", ""};
                std::fprintf(stderr, "%s%s\n", prefix[level < 6 ? level : 1], text.c_str());
            }
        };

        template <typename Run>
        int runMain(int argc, char **argv, Run run)
        {
            static StderrOutputHandler handler;
            ompl::msg::useOutputHandler(&handler);
            ompl::msg::setLogLevel(ompl::msg::LOG_INFO);  // OMPL's debug chatter only on request
            try
            {
                return run(argc, argv);
            }
            catch (const std::exception &e)
            {
                std::fprintf(stderr, "error: %s\n", e.what());
                return 1;
            }
        }
    }  // namespace cli
}  // namespace meshgap

#endif
