#ifndef MESHGAP_PLANNERS_CLI_MAIN_H
#define MESHGAP_PLANNERS_CLI_MAIN_H

// What every meshgap executable shares: OMPL's log goes to stderr (stdout carries results: text, CSV or JSON), one
// command-line preamble (parse, --help, log level), and any error ends in one line "error: <file>: <problem>" and exit
// status 1, never a crash.

#include <boost/program_options.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
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

        /** \brief The one command-line preamble: parse \e argv against \e options (and \e positional, if given);
            on --help print \e visible (default: \e options) to stdout and return false, before any required option
            is checked; otherwise run the notifiers and set OMPL's log level: LOG_WARN with --quiet, and where the
            options declare --verbose, LOG_INFO with it and LOG_WARN without. */
        inline bool parseCommandLine(int argc, char **argv, const boost::program_options::options_description &options,
                                     boost::program_options::variables_map &vm,
                                     const boost::program_options::positional_options_description *positional = nullptr,
                                     const boost::program_options::options_description *visible = nullptr)
        {
            namespace po = boost::program_options;
            po::command_line_parser parser(argc, argv);
            parser.options(options);
            if (positional != nullptr)
                parser.positional(*positional);
            po::store(parser.run(), vm);
            if (vm.count("help"))
            {
                std::cout << (visible != nullptr ? *visible : options) << "\n";
                return false;
            }
            po::notify(vm);
            if (options.find_nothrow("verbose", false) != nullptr)
                ompl::msg::setLogLevel(vm.count("verbose") ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
            if (vm.count("quiet"))
                ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
            return true;
        }

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
