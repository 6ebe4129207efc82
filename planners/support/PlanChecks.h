#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_CHECKS_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_CHECKS_H

// The one part of a planning run (support/PlanRun.h) that depends on the problem's kind, made from the problem in one
// place, planChecks(): the validity checker, the motion validator and the planner, and the summary lines that speak
// of them. A single rigid body (a one-link robot) is checked by its ClearanceChecker (--checker certified or fast,
// its warm-started queries and counters; ClearanceMotionValidator with --motion clearance); every other robot by a
// RobotChecker, with RobotMotionValidator proving each motion of the answer of a sampled search
// (CertifiedAnswerPlanner) unless --motion discrete. Everything else (the dense path, the summary's shape, the files)
// is the run's, the same for every kind.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/ClearanceField.h"
#include "meshgap/robot/RobotProblem.h"
#include "support/DenseClearance.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        struct PlanRun;

        /** \brief meshgap_plan's summary, one "key  value" line at a time: the key padded to 16 columns (as
            OptimizeOption.h pads its own), numbers at 6 significant digits. */
        class PlanSummary
        {
        public:
            PlanSummary() { text_.precision(6); }

            template <typename T>
            void line(const char *key, const T &value)
            {
                char padded[24];
                std::snprintf(padded, sizeof padded, "%-16s", key);
                text_ << padded << value << "\n";
            }
            std::ostringstream &stream() { return text_; }
            std::string str() const { return text_.str(); }

        private:
            std::ostringstream text_;
        };

        /** \brief What a planning run does by the problem's kind (planChecks() makes it). */
        class PlanChecks
        {
        public:
            virtual ~PlanChecks() = default;

            /** \brief The problem's settings: name, file, planar, volume, objective, sampler. */
            virtual const ProblemSettings &settings() const = 0;

            /** \brief Set up \e run: its setup (state space, validity checker, motion validator, objective, start
                and goal, the planner of \e o with its parameters: allocPlanPlanner()), scene (the robot among the
                obstacles), ends (start and goal state numbers), objective and motion; run.objective holds the
                objective chosen (--objective, else the problem's, else length) when called. Throws
                meshgap::Exception naming the option or file at fault (a start or goal in collision: the pair and
                its distance). */
            virtual void setUp(PlanRun &run, const PlanOptions &o) = 0;

            /** \brief The validity checks made so far, for the progress line; empty when the checker counts none
                (then no progress line). */
            virtual std::function<std::uint64_t()> validityCount() const = 0;

            /** \brief The checker's counters, when it keeps them. */
            virtual std::optional<CheckerStats> stats() const = 0;

            /** \brief The clearance --optimize clearance raises (the validity checker's). */
            virtual ClearanceFieldPtr field() const = 0;

            /** \brief The summary's first lines: the problem, and what plans in it. */
            virtual void describe(const PlanRun &run, PlanSummary &summary) const = 0;

            /** \brief The "clearance mode" line's value: the checker and the motion check. */
            virtual std::string clearanceMode(const PlanRun &run, const PlanOptions &o) const = 0;

            /** \brief The summary's lines after --optimize's own (run.before: the planner's path's dense
                clearance). */
            virtual void optimized(const PlanRun &run, const PlanOptions &o, PlanSummary &summary) const = 0;

            /** \brief Where the dense path \e d is least clear, as the "min clearance" line names it. */
            virtual std::string clearanceWhere(const PlanRun &run, const DenseClearance &d) const = 0;

            /** \brief The summary's last lines: the search's checks and counters. */
            virtual void summarizeSearch(const PlanRun &run, PlanSummary &summary) const = 0;

            /** \brief Write the solution path to \e file: OMPL's .path format for a single body (as OMPL.app writes
                and reads it), one state a line of the robot's state numbers otherwise. */
            virtual void writePath(const PlanRun &run, const std::string &file) const = 0;
        };

        /** \brief The checks of \e problem (readToolProblem()'s; not a control problem: support/ControlRun.h), the one
            place that tells the kinds apart. */
        std::unique_ptr<PlanChecks> planChecks(Problem problem);
    }  // namespace cli
}  // namespace meshgap

#endif
