#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_OPTIONS_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_OPTIONS_H

// The options of one planning run as one table, read by both meshgap_plan (planners/plan.cpp builds its command line
// from it) and the Python module's plan() (python/meshgap_module.cpp takes its keywords from it), so the two accept
// the same settings under the same names (a flag's dashes are a keyword's underscores).

#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "meshgap/robot/MoveItScene.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief Every setting of one planning run, with meshgap_plan's defaults. */
        struct PlanOptions
        {
            std::string cfg, planner = "rrtconnect", objective, checker = "certified", motion = "discrete", out, csv,
                             summaryFile, glb, report, optimize, sampler;
            double time = 10.0, weight = 0.0, optimizeTime = 5.0;
            /** \brief --param PLANNER.NAME=VALUE texts. */
            std::vector<std::string> params;
            /** \brief NAME, VALUE parameters of the chosen planner (Python's params= dict). */
            std::vector<std::pair<std::string, std::string>> plannerParams;
            unsigned dense = 4, exportStates = 8, seed = 1, optimizeRounds = 1000;
            bool quiet = false;
            /** \brief --urdf, --srdf, --scene, --request: a robot problem in MoveIt's files instead of --cfg
                (support/MoveItOptions.h; meshgap_plan's, not in the table). */
            MoveItFiles moveit;
            /** \brief The names (as in the table) of the options set explicitly. */
            std::set<std::string> given;
            /** \brief Whether errors name options as Python keywords (checker) rather than flags (--checker). */
            bool keywords = false;

            bool isGiven(const std::string &name) const { return given.count(name) > 0; }
            /** \brief How an error names option \e name: "--name", or "name" with '_' for '-' as a keyword. */
            std::string label(const std::string &name) const;
        };

        /** \brief What an option's value is. */
        enum class PlanOptionKind
        {
            TEXT,    ///< a word (planner name, checker mode, ...)
            FILE,    ///< a file path (str or os.PathLike in Python)
            REAL,    ///< a real number
            COUNT,   ///< a non-negative integer
            SWITCH,  ///< on when given (a flag without a value; a bool in Python)
            TEXTS    ///< repeatable text (a list of str in Python)
        };

        /** \brief One row of the table: the long flag (without "--"), an optional one-letter flag, what the value
            is, where it is stored, and the help line. */
        struct PlanOption
        {
            std::string name;
            char letter;
            PlanOptionKind kind;
            std::variant<std::string PlanOptions::*, double PlanOptions::*, unsigned PlanOptions::*,
                         bool PlanOptions::*, std::vector<std::string> PlanOptions::*>
                field;
            std::string help;
        };

        /** \brief meshgap_plan's options, in --help's order. */
        const std::vector<PlanOption> &planOptionTable();

        /** \brief Python's keyword of a flag: \e name with '_' for '-'. */
        std::string planKeyword(const std::string &name);

        /** \brief Every check of \e o that needs no file, so bad options fail before any loading; throws
            meshgap::Exception naming the option (o.label()). */
        void checkPlanOptions(const PlanOptions &o);
    }  // namespace cli
}  // namespace meshgap

#endif
