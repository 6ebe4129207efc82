#include "support/PlanRun.h"

#include <boost/algorithm/string/case_conv.hpp>
#include <sstream>

#include "CliMain.h"
#include "OptimizeOption.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "support/PlanOutputs.h"
#include "support/Progress.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief The summary lines of the path and its dense clearance. */
            void summarizeRunPath(const PlanRun &p, const DenseClearance &d, PlanSummary &summary)
            {
                const ompl::geometric::PathGeometric &path = p.setup->getSolutionPath();
                summary.line("states", std::to_string(path.getStateCount()) + " (dense: " +
                                           std::to_string(d.path.getStateCount()) + ")");
                summary.line("length", path.length());
                summary.line("cost", std::to_string(path.cost(p.setup->getOptimizationObjective()).value()) + " (" +
                                         p.objective + ")");
                std::ostringstream mc;
                mc.precision(6);
                mc << d.minClearance << " (exact, over the dense path; " << p.checks->clearanceWhere(p, d) << ")";
                summary.line("min clearance", mc.str());
                summary.line("dense path free", d.collisions == 0 ? std::string("yes") :
                                                                    "NO: " + std::to_string(d.collisions) +
                                                                        " states collide");
            }

            /** \brief --optimize clearance on the solution path: the planner's path's dense clearance kept, the
                optimiser's lines, then the checks'. */
            void optimizeRunPath(PlanRun &p, const PlanOptions &o, PlanSummary &summary)
            {
                p.before = std::make_unique<DenseClearance>(
                    denseClearance(p.setup->getSolutionPath(), *p.scene, o.dense, false));
                summary.stream() << optimizeSolution(*p.setup, p.checks->field(), o.optimizeTime, o.optimizeRounds,
                                                     o.seed, p.optimizeFailed);
                p.checks->optimized(p, o, summary);
            }
        }  // namespace

        ompl::base::PlannerPtr allocPlanPlanner(const PlanOptions &o, const ompl::base::SpaceInformationPtr &si)
        {
            const ob::PlannerPtr planner = allocPlanner(o.planner, si);
            for (const std::string &text : o.params)
            {
                const OwnedParam param = parseOwnedParam(text, "PLANNER", o.planner + ".range=5");
                if (boost::algorithm::to_lower_copy(param.owner) != boost::algorithm::to_lower_copy(o.planner))
                    throw Exception(o.label("param"),
                                    quote(text) + ": the planner is " + o.planner + ", not " + param.owner);
                setPlannerParam(*planner, param.name, param.value, o.label("param"));
            }
            for (const auto &[name, value] : o.plannerParams)
                setPlannerParam(*planner, name, value, "params");
            return planner;
        }

        std::unique_ptr<PlanRun> setUpPlan(const PlanOptions &o, Problem problem)
        {
            checkPlanOptions(o);
            auto p = std::make_unique<PlanRun>();
            p->checks = planChecks(std::move(problem));
            const ProblemSettings &settings = p->checks->settings();
            p->objective = !o.objective.empty() ? o.objective : !settings.objective.empty() ? settings.objective :
                                                                                               "length";
            if (o.isGiven("weight") && p->objective != "weighted")
                throw Exception(o.label("weight"), "applies to " + o.label("objective") +
                                                       " weighted only (the objective is " + p->objective + ")");
            p->checks->setUp(*p, o);
            return p;
        }

        void solvePlan(PlanRun &p, const PlanOptions &o)
        {
            {
                const std::function<std::uint64_t()> count = p.checks->validityCount();
                Progress progress(p.setup->getPlanner(), count, !o.quiet && count);
                p.status = p.setup->solve(o.time);
            }
            p.exact = p.status == ob::PlannerStatus::EXACT_SOLUTION;
            p.havePath = p.setup->haveSolutionPath() &&
                         (p.exact || p.status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
            PlanSummary summary;
            p.checks->describe(p, summary);
            summary.line("planner", o.planner);
            summary.line("objective", p.objective);
            summary.line("clearance mode", p.checks->clearanceMode(p, o));
            summary.line("status", p.status.asString());
            summary.line("solved", !p.havePath ? "no" : p.exact ? "yes (exact)" : "approximate");
            summary.line("exact solution", p.exact ? "yes" : "no");
            summary.line("planning time", std::to_string(p.setup->getLastPlanComputationTime()) + " s");
            if (p.havePath && !o.optimize.empty())
                optimizeRunPath(p, o, summary);
            if (p.havePath)
            {
                p.dense = std::make_unique<DenseClearance>(
                    denseClearance(p.setup->getSolutionPath(), *p.scene, o.dense, !o.report.empty()));
                summarizeRunPath(p, *p.dense, summary);
            }
            p.checks->summarizeSearch(p, summary);
            p.summary = summary.str();
        }

        void writePlanFiles(const PlanRun &p, const PlanOptions &o, std::ostream &log)
        {
            if (!o.summaryFile.empty())
                writeTextFile(p.summary, o.summaryFile);
            writeSceneFiles(*p.scene, p.dense.get(), p.ends, p.summary, o, log);
            if (!p.havePath)
                return;
            if (!o.out.empty())
            {
                p.checks->writePath(p, o.out);
                log << "path written    " << o.out << "\n";
            }
            if (!o.csv.empty())
            {
                writeClearanceCsv(*p.dense, stateColumns(p.scene->robot()), o.csv);
                log << "clearance CSV   " << o.csv << "\n";
            }
        }
    }  // namespace cli
}  // namespace meshgap
