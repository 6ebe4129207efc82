#include "support/ControlRun.h"

#include <algorithm>
#include <boost/algorithm/string/case_conv.hpp>
#include <cstdio>
#include <limits>
#include <ompl/control/planners/est/EST.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/pdst/PDST.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/planners/sst/SST.h>
#include <ostream>
#include <sstream>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "support/PlanOutputs.h"
#include "support/Progress.h"
#include "support/SurfaceText.h"

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief Options of geometric problems only: refused by name when given. */
            void refuseGeometricOptions(const PlanOptions &o)
            {
                for (const char *name : {"objective", "weight", "optimize", "optimize-time", "optimize-rounds",
                                         "sampler", "export-glb", "export-states", "report", "clearance-csv", "dense"})
                    if (o.isGiven(name))
                        throw Exception(o.label(name), "applies to geometric problems only (" + o.cfg +
                                                           " is a control problem)");
                if (o.motion != "discrete")
                    throw Exception(o.label("motion"), "applies to geometric problems only (" + o.cfg +
                                                           " is a control problem: its motions are propagated)");
            }

            /** \brief The path written: its states one propagation step apart. */
            ompl::geometric::PathGeometric writtenPath(const ControlPlanRun &p)
            {
                oc::PathControl path(p.problem.setup->getSolutionPath());
                path.interpolate();
                return path.asGeometric();
            }

            /** \brief One summary line: "key" padded to 16 columns, then the value. */
            void line(std::ostringstream &text, const char *key, const std::string &value)
            {
                char padded[24];
                std::snprintf(padded, sizeof padded, "%-16s", key);
                text << padded << value << "\n";
            }

            /** \brief The path's numbers into \e p, and its summary lines. */
            void summarizePath(ControlPlanRun &p, std::ostringstream &text)
            {
                const oc::PathControl &path = p.problem.setup->getSolutionPath();
                const ompl::geometric::PathGeometric states = writtenPath(p);
                const ob::StateSpace &space = *p.problem.setup->getStateSpace();
                p.minClearance = std::numeric_limits<double>::infinity();
                p.states.clear();
                for (std::size_t i = 0; i < states.getStateCount(); ++i)
                {
                    p.minClearance = std::min(p.minClearance, p.problem.checker->clearance(states.getState(i)));
                    space.copyToReals(p.states.emplace_back(), states.getState(i));
                }
                p.duration = path.length();
                p.goalDistance = p.exact ? 0.0 : p.problem.setup->getProblemDefinition()->getSolutionDifference();
                std::ostringstream value;
                value.precision(6);
                value << path.getControlCount() << " controls, " << states.getStateCount()
                      << " states one propagation step apart, duration " << p.duration;
                line(text, "path", value.str());
                value.str("");
                value << p.goalDistance;
                line(text, "goal distance", p.exact ? std::string("0 (exact)") : value.str());
                value.str("");
                value << p.minClearance << " (certified, least over the path's states)";
                line(text, "min clearance", value.str());
            }

        }  // namespace

        const std::vector<std::string> &controlPlannerNames()
        {
            static const std::vector<std::string> names{"kpiece", "rrt", "est", "pdst", "sst"};
            return names;
        }

        ob::PlannerPtr allocControlPlanner(const std::string &name, const oc::SpaceInformationPtr &si,
                                           const std::string &where)
        {
            const std::string lower = boost::algorithm::to_lower_copy(name);
            if (lower == "kpiece")
                return std::make_shared<oc::KPIECE1>(si);
            if (lower == "rrt")
                return std::make_shared<oc::RRT>(si);
            if (lower == "est")
                return std::make_shared<oc::EST>(si);
            if (lower == "pdst")
                return std::make_shared<oc::PDST>(si);
            if (lower == "sst")
                return std::make_shared<oc::SST>(si);
            std::string names;
            for (const std::string &n : controlPlannerNames())
                names += (names.empty() ? "" : ", ") + n;
            throw Exception(where + " " + name,
                            "not a control planner (a control problem is planned by one of: " + names + ")");
        }

        std::unique_ptr<ControlPlanRun> setUpControlPlan(const PlanOptions &o, ProblemConfig config)
        {
            refuseGeometricOptions(o);
            auto p = std::make_unique<ControlPlanRun>();
            p->config = std::move(config);
            p->problem = setupControlProblem(p->config, o.checker == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                                                  ClearanceChecker::Mode::FAST);
            p->planner = o.isGiven("planner") ? o.planner : "kpiece";
            const ob::PlannerPtr planner =
                allocControlPlanner(p->planner, p->problem.setup->getSpaceInformation(), o.label("planner"));
            for (const std::string &text : o.params)
            {
                const OwnedParam param = parseOwnedParam(text, "PLANNER", p->planner + ".goal_bias=0.1");
                if (boost::algorithm::to_lower_copy(param.owner) != boost::algorithm::to_lower_copy(p->planner))
                    throw Exception(o.label("param"),
                                    quote(text) + ": the planner is " + p->planner + ", not " + param.owner);
                setPlannerParam(*planner, param.name, param.value, o.label("param"));
            }
            for (const auto &[name, value] : o.plannerParams)
                setPlannerParam(*planner, name, value, "params");
            p->problem.setup->setPlanner(planner);
            p->problem.setup->setup();
            return p;
        }

        void solveControlPlan(ControlPlanRun &p, const PlanOptions &o)
        {
            {
                const ClearanceCheckerPtr checker = p.problem.checker;
                Progress progress(p.problem.setup->getPlanner(),
                                  [checker] { return checker->stats().validityCalls; }, !o.quiet);
                p.status = p.problem.setup->solve(o.time);
            }
            p.exact = p.status == ob::PlannerStatus::EXACT_SOLUTION;
            p.havePath = p.problem.setup->haveSolutionPath() &&
                         (p.exact || p.status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
            std::ostringstream text;
            text.precision(6);
            const oc::SpaceInformationPtr &si = p.problem.setup->getSpaceInformation();
            line(text, "problem", p.config.name + " (control: " + p.config.control + ")");
            line(text, "surfaces", sceneSurfacesText(*p.problem.scene));
            line(text, "planner", p.planner);
            line(text, "clearance mode", o.checker + ", motion propagated");
            line(text, "propagation", std::to_string(si->getPropagationStepSize()) + " a step, " +
                                          std::to_string(si->getMinControlDuration()) + " to " +
                                          std::to_string(si->getMaxControlDuration()) + " steps a control");
            line(text, "status", p.status.asString());
            line(text, "solved", !p.havePath ? "no" : p.exact ? "yes (exact)" : "approximate");
            line(text, "exact solution", p.exact ? "yes" : "no");
            line(text, "planning time", std::to_string(p.problem.setup->getLastPlanComputationTime()) + " s");
            if (p.havePath)
                summarizePath(p, text);
            const CheckerStats stats = p.problem.checker->stats();
            line(text, "validity calls", std::to_string(stats.validityCalls));
            line(text, "query time", std::to_string(stats.seconds * 1e3) + " ms");
            p.summary = text.str();
        }

        void writeControlPlanFiles(const ControlPlanRun &p, const PlanOptions &o, std::ostream &log)
        {
            if (!o.summaryFile.empty())
                writeTextFile(p.summary, o.summaryFile);
            if (!p.havePath || o.out.empty())
                return;
            writePathFile(writtenPath(p), o.out);
            log << "path written    " << o.out << "\n";
        }
    }  // namespace cli
}  // namespace meshgap
