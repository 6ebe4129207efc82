#include "support/PlanRun.h"

#include <boost/algorithm/string/case_conv.hpp>
#include <cstdio>
#include <ompl/base/PlannerData.h>
#include <sstream>

#include "CliMain.h"
#include "OptimizeOption.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "meshgap/robot/RigidBodyRobot.h"
#include "support/PlanOutputs.h"
#include "support/Progress.h"
#include "support/SurfaceText.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief The summary, one "key  value" line at a time, keys padded as OptimizeOption.h pads its own. */
            class Summary
            {
            public:
                Summary() { text_.precision(6); }

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

            /** \brief The planner of \e o with its parameters (--param texts, then Python's NAME, VALUE pairs). */
            ob::PlannerPtr planner(const PlanOptions &o, const ob::SpaceInformationPtr &si)
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

            /** \brief The summary lines of the path and its dense clearance. */
            void summarizePath(const PlanRun &p, const DenseClearance &d, Summary &summary)
            {
                ompl::geometric::PathGeometric &path = p.problem.setup->getSolutionPath();
                summary.line("states", std::to_string(path.getStateCount()) + " (dense: " +
                                           std::to_string(d.path.getStateCount()) + ")");
                summary.line("length", path.length());
                summary.line("cost", std::to_string(path.cost(p.problem.setup->getOptimizationObjective()).value()) +
                                         " (" + p.problem.objective + ")");
                std::ostringstream mc;
                mc.precision(6);
                mc << d.minClearance << " (exact, over the dense path; at arc length " << d.arcLength[d.argmin]
                   << " of " << d.arcLength.back() << ")";
                summary.line("min clearance", mc.str());
                summary.line("dense path free", d.collisions == 0 ? std::string("yes") :
                                                                    "NO: " + std::to_string(d.collisions) +
                                                                        " states collide");
            }

            /** \brief The summary lines of the search: its graph, the checker's counters, the objective's and the
                motion validator's. */
            void summarizeSearch(const PlanRun &p, Summary &summary)
            {
                const CheckerStats stats = p.problem.checker->stats();
                {
                    ob::PlannerData data(p.problem.setup->getSpaceInformation());
                    p.problem.setup->getPlannerData(data);
                    summary.line("graph states", data.numVertices());
                }
                summary.line("validity calls", stats.validityCalls);
                summary.line("clearance calls", stats.clearanceCalls);
                if (stats.carried + stats.written + stats.cold > 0)
                    summary.line("warm starts", std::to_string(stats.carried) + " carried, " +
                                                    std::to_string(stats.written) + " written, " +
                                                    std::to_string(stats.cold) + " cold (certified queries)");
                if (const auto *maxMin = dynamic_cast<const MaxMinClearanceObjective *>(
                        p.problem.setup->getOptimizationObjective().get()))
                    summary.line("cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                                     std::to_string(maxMin->gridStates()) + " motion grid states");
                if (p.cmv)
                    summary.line("motion checks",
                                 std::to_string(p.cmv->getValidMotionCount() + p.cmv->getInvalidMotionCount()) +
                                     " (" + std::to_string(p.cmv->getValidMotionCount()) + " free), " +
                                     std::to_string(p.cmv->queries()) + " clearance queries");
                summary.line("query time", std::to_string(stats.seconds * 1e3) + " ms");
            }
        }  // namespace

        ompl::base::PlannerPtr allocPlanPlanner(const PlanOptions &o, const ompl::base::SpaceInformationPtr &si)
        {
            return planner(o, si);
        }

        std::unique_ptr<PlanRun> setUpPlan(const PlanOptions &o, ProblemConfig config)
        {
            checkPlanOptions(o);
            auto p = std::make_unique<PlanRun>();
            p->config = std::move(config);
            const std::string chosen = !o.objective.empty() ? o.objective : p->config.objective;
            if (o.isGiven("weight") && chosen != "weighted")
                throw Exception(o.label("weight"), "applies to " + o.label("objective") +
                                                       " weighted only (the objective is " +
                                                       (chosen.empty() ? std::string("length") : chosen) + ")");
            ObjectiveOptions objectiveOptions;
            objectiveOptions.weight = o.weight;
            p->problem = setupProblem(p->config,
                                      o.checker == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                                 ClearanceChecker::Mode::FAST,
                                      o.objective, BodyOptions(), objectiveOptions);
            // The body as a robot of one link (its body the scene's, shared with the scene that owns it).
            p->robotScene = std::make_shared<RobotScene>(
                std::make_shared<RigidBodyRobot>(BodyConstPtr(p->problem.scene, &p->problem.scene->robot()),
                                                 p->config.planar ? RigidSpace::SE2 : RigidSpace::SE3),
                p->problem.scene->obstacles());
            const ob::SpaceInformationPtr si = p->problem.setup->getSpaceInformation();
            if (!o.sampler.empty())
                setValidStateSampler(*si, o.sampler, o.label("sampler"));
            const ob::MotionValidatorPtr motion = allocMotionValidator(o.motion, si, p->problem.checker,
                                                                       o.label("motion"));
            si->setMotionValidator(motion);
            p->cmv = std::dynamic_pointer_cast<ClearanceMotionValidator>(motion);
            p->problem.setup->setPlanner(planner(o, si));
            p->problem.setup->setup();
            return p;
        }

        void solvePlan(PlanRun &p, const PlanOptions &o)
        {
            {
                Progress progress(p.problem.setup->getPlanner(), *p.problem.checker, !o.quiet);
                p.status = p.problem.setup->solve(o.time);
            }
            p.exact = p.status == ob::PlannerStatus::EXACT_SOLUTION;
            p.havePath = p.problem.setup->haveSolutionPath() &&
                         (p.exact || p.status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
            Summary summary;
            summary.line("problem", p.config.name + (p.config.planar ? " (SE(2))" : " (SE(3))"));
            summary.line("surfaces", sceneSurfacesText(*p.problem.scene));
            summary.line("planner", o.planner);
            summary.line("objective", p.problem.objective);
            summary.line("clearance mode", o.checker + ", motion " + o.motion);
            summary.line("status", p.status.asString());
            summary.line("solved", !p.havePath ? "no" : p.exact ? "yes (exact)" : "approximate");
            summary.line("exact solution", p.exact ? "yes" : "no");
            summary.line("planning time", std::to_string(p.problem.setup->getLastPlanComputationTime()) + " s");
            if (p.havePath && !o.optimize.empty())
                summary.stream() << optimizeSolution(*p.problem.setup, p.problem.checker, o.optimizeTime, o.seed,
                                                     p.optimizeFailed);
            if (p.havePath)
            {
                p.dense = std::make_unique<DenseClearance>(
                    denseClearance(p.problem.setup->getSolutionPath(), *p.robotScene, o.dense, !o.report.empty()));
                summarizePath(p, *p.dense, summary);
            }
            summarizeSearch(p, summary);
            p.summary = summary.str();
        }

        void writePlanFiles(const PlanRun &p, const PlanOptions &o, std::ostream &log)
        {
            if (!o.summaryFile.empty())
                writeTextFile(p.summary, o.summaryFile);
            const RigidSpace space = p.config.planar ? RigidSpace::SE2 : RigidSpace::SE3;
            std::vector<std::vector<double>> ends = {rigidState(space, p.config.start)};
            if (p.config.goal)
                ends.push_back(rigidState(space, *p.config.goal));
            writeSceneFiles(*p.robotScene, p.dense.get(), ends, p.summary, o, log);
            if (!p.havePath)
                return;
            if (!o.out.empty())
            {
                writePathFile(p.problem.setup->getSolutionPath(), o.out);
                log << "path written    " << o.out << "\n";
            }
            if (!o.csv.empty())
            {
                writeClearanceCsv(*p.dense, stateColumns(p.robotScene->robot()), o.csv);
                log << "clearance CSV   " << o.csv << "\n";
            }
        }
    }  // namespace cli
}  // namespace meshgap
