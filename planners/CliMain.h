#ifndef MESHGAP_PLANNERS_CLI_MAIN_H
#define MESHGAP_PLANNERS_CLI_MAIN_H

// What every meshgap executable shares: OMPL's log goes to stderr (stdout carries results: text, CSV or JSON), one
// command-line preamble (parse, --help, log level), and any error ends in one line "error: <file>: <problem>" and exit
// status 1, never a crash.

#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <ompl/util/Console.h>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief How the description of a renamed (refused) flag begins; what follows says what to write. */
        constexpr const char *RENAMED = "renamed: use ";

        class StderrOutputHandler : public ompl::msg::OutputHandler
        {
        public:
            void log(const std::string &text, ompl::msg::LogLevel level, const char *, int) override
            {
                static const char *prefix[] = {"debug: ", "", "warning: ", "error: ", "", ""};
                std::fprintf(stderr, "%s%s\n", prefix[level < 6 ? level : 1], text.c_str());
            }
        };

        /** \brief Declare \e renamed's old flags (each with the text to write instead) in \e options, hidden from
            --help: parseCommandLine() refuses each with one error naming the new spelling. */
        /** \brief The longest time limit a tool takes, in seconds (about 11.6 days): beyond it OMPL's clock, which
            counts microseconds in 64 bits from now, overflows at 1e13 s and a run that solves is recorded as not
            solved; nobody means a limit that long. */
        constexpr double MAX_SECONDS = 1e6;

        /** \brief Throws meshgap::Exception naming \e what ("--time") unless \e seconds is a positive finite number
            of at most MAX_SECONDS. */
        inline void checkSeconds(double seconds, const std::string &what)
        {
            if (!(seconds > 0.0) || !std::isfinite(seconds))
                throw Exception(what, "must be positive and finite");
            if (seconds > MAX_SECONDS)
            {
                char found[32];
                std::snprintf(found, sizeof found, "%g", seconds);
                throw Exception(what, std::string("must be at most 1e6 seconds (11.6 days), found ") + found);
            }
        }

        inline void addRenamedOptions(boost::program_options::options_description &options,
                                      const std::vector<std::pair<std::string, std::string>> &renamed)
        {
            namespace po = boost::program_options;
            for (const auto &[old, now] : renamed)
                options.add_options()(old.c_str(), po::value<std::vector<std::string>>()->composing(),
                                      (RENAMED + now).c_str());
        }

        /** \brief One --param of the flag language, OWNER.NAME=VALUE: OWNER is the planner (or algorithm) the
            parameter belongs to, NAME one of its parameters. */
        struct OwnedParam
        {
            std::string owner, name, value;
        };

        /** \brief Split \e text as OWNER.NAME=VALUE; throws meshgap::Exception("--param", ...) naming the form and
            \e example otherwise. */
        inline OwnedParam parseOwnedParam(const std::string &text, const std::string &owner,
                                          const std::string &example)
        {
            const std::size_t dot = text.find('.'), eq = text.find('=');
            if (dot == std::string::npos || eq == std::string::npos || dot == 0 || eq < dot + 2)
                throw Exception("--param",
                                quote(text) + " is not " + owner + ".NAME=VALUE (e.g. --param " + example + ")");
            return {text.substr(0, dot), text.substr(dot + 1, eq - dot - 1), text.substr(eq + 1)};
        }

        /** \brief The one command-line preamble: parse \e argv against \e options (and \e positional, if given);
            on --help print \e visible (default: \e options) to stdout and return false, before any required option
            is checked; otherwise run the notifiers and set OMPL's log level: LOG_ERROR with --quiet, and where the
            options declare --verbose, LOG_INFO with it and LOG_WARN without. A flag declared by addRenamedOptions()
            throws meshgap::Exception naming the new spelling. */
        /** \brief Whether \e value holds an unsigned integer, which boost::program_options reads from "-3" by
            wrapping it round (to 4294967293) rather than refusing it. */
        inline bool holdsUnsigned(const boost::any &value)
        {
            const std::type_info &t = value.type();
            return t == typeid(unsigned short) || t == typeid(unsigned) || t == typeid(unsigned long) ||
                   t == typeid(unsigned long long);
        }

        /** \brief Throws meshgap::Exception naming the flag when a count (an option of unsigned type) was given a
            negative number in \e parsed. */
        inline void refuseNegativeCounts(const boost::program_options::parsed_options &parsed,
                                         const boost::program_options::variables_map &vm)
        {
            for (const auto &option : parsed.options)
            {
                if (option.string_key.empty() || !vm.count(option.string_key) ||
                    !holdsUnsigned(vm[option.string_key].value()))
                    continue;
                for (const std::string &text : option.value)
                {
                    const auto first = text.find_first_not_of(" \t");
                    if (first != std::string::npos && text[first] == '-')
                        throw Exception("--" + option.string_key, quote(text) + " is not a non-negative integer");
                }
            }
        }

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
            const po::parsed_options parsed = parser.run();
            po::store(parsed, vm);
            if (vm.count("help"))
            {
                std::cout << (visible != nullptr ? *visible : options) << "\n";
                return false;
            }
            for (const auto &entry : vm)
            {
                const po::option_description *option = options.find_nothrow(entry.first, false);
                if (option != nullptr && option->description().rfind(RENAMED, 0) == 0)
                    throw Exception("--" + entry.first, option->description());
            }
            refuseNegativeCounts(parsed, vm);
            po::notify(vm);
            if (options.find_nothrow("verbose", false) != nullptr)
                ompl::msg::setLogLevel(vm.count("verbose") ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
            if (vm.count("quiet"))
                ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
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
