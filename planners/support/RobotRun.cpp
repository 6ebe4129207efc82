#include "support/MoveItOptions.h"
#include "support/RobotRun.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <ompl/util/Console.h>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "OptimizeOption.h"
#include "support/PathFile.h"
#include "support/PlanOutputs.h"
#include "support/PlanRun.h"
#include "support/PlanReport.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief OMPL's discrete motion check (--motion discrete; the certified validator is the default)
                steps this fraction of the state space's extent on a robot problem (its default, 0.01, lets two
                bodies moving at once pass through each other between steps). */
            constexpr double DISCRETE_RESOLUTION = 0.002;

            /** \brief One summary line: "key" padded to 16 columns, then the value. */
            template <typename T>
            void line(std::ostringstream &out, const char *key, const T &value)
            {
                char padded[24];
                std::snprintf(padded, sizeof padded, "%-16s", key);
                out << padded << value << "\n";
            }

            /** \brief "link 'a' and obstacle 3" or "links 'a' and 'b'": the pair \e r names. */
            std::string pairText(const RobotScene &scene, const RobotResult &r)
            {
                if (r.link >= scene.links().size() || (scene.obstacles().empty() && scene.selfPairs().empty()))
                    return "no pair (the robot has neither obstacles nor self pairs to check)";
                const std::string link = quote(scene.links()[r.link].name);
                return r.selfPair ? "links " + link + " and " + quote(scene.links()[r.other].name)
                                  : "link " + link + " and obstacle " + std::to_string(r.other);
            }

            /** \brief The option meshgap_plan has that a robot problem does not take (yet): --checker fast. */
            void checkRobotOptions(const PlanOptions &o)
            {
                if (o.checker != "certified")
                    throw Exception(o.label("checker"), "a robot problem is checked exactly (certified) only");
            }

            /** \brief The state space's bounds: the volume, or (a fixed-base arm needs none) a unit cube. */
            ob::RealVectorBounds bounds(const RobotProblem &p)
            {
                ob::RealVectorBounds b(3);
                b.setLow(-1.0);
                b.setHigh(1.0);
                if (!p.volume && p.robot->movesFree())
                    throw Exception(p.file, "needs volume.min.x .. volume.max.z (the bounds of its bodies' positions)");
                if (p.volume)
                    for (int k = 0; k < 3; ++k)
                    {
                        b.setLow(k, p.volume->min()[k]);
                        b.setHigh(k, p.volume->max()[k]);
                    }
                return b;
            }

            /** \brief The start or goal as an OMPL state; throws when it is out of bounds or in collision. */
            void checkEnd(const RobotPlanRun &run, const std::vector<double> &q, const char *which,
                          ob::ScopedState<> &state)
            {
                robotStateFromVector(*run.setup->getStateSpace(), q, state.get());
                if (!run.setup->getStateSpace()->satisfiesBounds(state.get()))
                    throw Exception(run.problem.file, std::string(which) + " is outside the state space's bounds");
                RobotResult r;
                run.scene->distance(q, RobotRequest(), r);
                if (r.inCollision)
                {
                    std::ostringstream text;
                    text << which << " is in collision: " << pairText(*run.scene, r) << " (signed distance "
                         << r.distance << ")";
                    throw Exception(run.problem.file, text.str());
                }
            }

            /** \brief What the robot is, in a few words. */
            std::string robotText(const RobotPlanRun &run)
            {
                std::ostringstream text;
                const RobotModel &robot = *run.problem.robot;
                text << robot.description() << ", " << robot.links().size() << " links, " << run.scene->selfPairs().size() << " self pairs, "
                     << run.problem.obstacles.size() << " obstacles";
                return text.str();
            }

            /** \brief The solution path densely interpolated (o.dense states per validity-check segment), each state
                checked exactly (the whole robot; every link's clearance too when \e everyLink, for the report). */
            DenseClearance denseCheck(const RobotPlanRun &run, const PlanOptions &o, bool everyLink = false)
            {
                return denseClearance(run.setup->getSolutionPath(), *run.scene, o.dense, everyLink);
            }

            /** \brief "0.0123 (exact, over the dense path; link 'a' and obstacle 3)". */
            std::string clearanceText(const RobotScene &scene, const DenseClearance &d)
            {
                std::ostringstream mc;
                mc.precision(6);
                mc << d.worst.distance << " (exact, over the dense path; " << pairText(scene, d.worst) << ")";
                return mc.str();
            }

            /** \brief The summary's path lines: states, length, cost, the dense path's exact clearance and pair. */
            void summarizePath(RobotPlanRun &run, const DenseClearance &d, std::ostringstream &summary)
            {
                run.minClearance = d.worst.distance;
                run.limitingPair = pairText(*run.scene, d.worst);
                run.denseFree = d.collisions == 0;
                const og::PathGeometric &path = run.setup->getSolutionPath();
                line(summary, "states", std::to_string(path.getStateCount()) + " (dense: " +
                                            std::to_string(d.path.getStateCount()) + ")");
                line(summary, "length", path.length());
                line(summary, "cost", std::to_string(path.cost(run.setup->getOptimizationObjective()).value()) + " (" +
                                          run.objective + ")");
                line(summary, "min clearance", clearanceText(*run.scene, d));
                line(summary, "dense path free", d.collisions == 0 ? std::string("yes") :
                                                                     "NO: " + std::to_string(d.collisions) +
                                                                         " states collide");
            }

            /** \brief --optimize clearance on the solution path: the optimiser's lines, and the pair that limits
                the dense path's clearance before and after. */
            void optimizeRobotPath(RobotPlanRun &run, const PlanOptions &o, std::ostringstream &summary)
            {
                const DenseClearance before = denseCheck(run, o);
                run.minClearanceBefore = before.worst.distance;
                run.limitingPairBefore = pairText(*run.scene, before.worst);
                summary << optimizeSolution(*run.setup, run.checker, o.optimizeTime, o.seed, run.optimizeFailed);
                const DenseClearance after = denseCheck(run, o);
                line(summary, "opt before", clearanceText(*run.scene, before));
                line(summary, "opt after", clearanceText(*run.scene, after));
            }
        }  // namespace

        std::unique_ptr<RobotPlanRun> setUpRobotPlan(const PlanOptions &o, RobotProblem problem)
        {
            checkPlanOptions(o);
            checkRobotOptions(o);
            auto run = std::make_unique<RobotPlanRun>();
            run->problem = std::move(problem);
            const RobotProblem &p = run->problem;
            if (p.robot->dimension() == 0)
                throw Exception(p.file, "the robot has no movable joint (a fixed robot): there is nothing to plan; "
                                        "meshgap_distance --cfg gives its clearance");
            if (!p.goal)
                throw Exception(p.file, "no goal (goal.joints, or goal.N.x ... for each body)");
            run->scene = std::make_shared<RobotScene>(p.robot, p.obstacles, p.allowedObstacles);
            run->setup = std::make_shared<og::SimpleSetup>(robotStateSpace(*p.robot, bounds(p)));
            const ob::SpaceInformationPtr si = run->setup->getSpaceInformation();
            run->checker = std::make_shared<RobotChecker>(si, run->scene);
            run->setup->setStateValidityChecker(run->checker);
            // Certified motions by default, for every kind of robot.
            const std::string motion = o.isGiven("motion") ? o.motion : "clearance";
            const ob::MotionValidatorPtr validator = allocMotionValidator(motion, si, run->scene, o.label("motion"));
            si->setMotionValidator(validator);
            run->motion = std::dynamic_pointer_cast<RobotMotionValidator>(validator);
            if (!run->motion)
                si->setStateValidityCheckingResolution(DISCRETE_RESOLUTION);
            ob::ScopedState<> start(si), goal(si);
            checkEnd(*run, p.start, "start", start);
            checkEnd(*run, *p.goal, "goal", goal);
            run->setup->setStartAndGoalStates(start, goal);
            run->objective = !o.objective.empty() ? o.objective : !p.objective.empty() ? p.objective : "length";
            if (o.isGiven("weight") && run->objective != "weighted")
                throw Exception(o.label("weight"), "applies to " + o.label("objective") +
                                                       " weighted only (the objective is " + run->objective + ")");
            ObjectiveOptions objectiveOptions;
            objectiveOptions.weight = o.weight;
            const ob::OptimizationObjectivePtr objective = allocObjective(run->objective, si, objectiveOptions);
            if (p.objectiveThreshold)
                objective->setCostThreshold(ob::Cost(*p.objectiveThreshold));
            run->setup->setOptimizationObjective(objective);
            // Certified: the planner searches with a sampled motion check; every motion of its answer is certified.
            // The valid-state sampler (--sampler, else the problem's) of the space the planner searches.
            const std::string sampler = !o.sampler.empty() ? o.sampler : p.sampler;
            const std::string where = !o.sampler.empty() ? o.label("sampler") : p.file + ": [problem] sampler";
            auto search = [&o, sampler, where](const ob::SpaceInformationPtr &s)
            {
                if (!sampler.empty())
                    setValidStateSampler(*s, sampler, where);
                return allocPlanPlanner(o, s);
            };
            if (run->motion)
                run->setup->setPlanner(run->answer = std::make_shared<CertifiedAnswerPlanner>(si, search));
            else
                run->setup->setPlanner(search(si));
            run->setup->setup();
            return run;
        }

        void solveRobotPlan(RobotPlanRun &run, const PlanOptions &o)
        {
            run.status = run.setup->solve(o.time);
            run.exact = run.status == ob::PlannerStatus::EXACT_SOLUTION;
            run.havePath = run.setup->haveSolutionPath() &&
                           (run.exact || run.status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
            std::ostringstream summary;
            summary.precision(6);
            line(summary, "problem", run.problem.name + " (robot problem)");
            line(summary, "robot", robotText(run));
            line(summary, "planner", o.planner);
            line(summary, "objective", run.objective);
            line(summary, "clearance mode", std::string("certified, motion ") +
                                                (run.motion ? "certified (displacement bound per pair; the search "
                                                              "sampled, every motion of the answer proven)" :
                                                              "discrete (OMPL's)"));
            line(summary, "status", run.status.asString());
            line(summary, "solved", !run.havePath ? "no" : run.exact ? "yes (exact)" : "approximate");
            line(summary, "exact solution", run.exact ? "yes" : "no");
            line(summary, "planning time", std::to_string(run.setup->getLastPlanComputationTime()) + " s");
            if (run.havePath && !o.optimize.empty())
                optimizeRobotPath(run, o, summary);
            if (run.havePath)
            {
                run.dense = std::make_unique<DenseClearance>(denseCheck(run, o, !o.report.empty()));
                summarizePath(run, *run.dense, summary);
            }
            // The search's checks (sampled when the answer is certified afterwards).
            const ob::MotionValidatorPtr &mv = (run.answer ? run.answer->searchSpaceInformation() :
                                                             run.setup->getSpaceInformation())->getMotionValidator();
            line(summary, "motion checks", std::to_string(mv->getValidMotionCount() + mv->getInvalidMotionCount()) +
                                               " (" + std::to_string(mv->getValidMotionCount()) + " free" +
                                               (run.answer ? ", sampled)" : ")"));
            if (const auto *maxMin =
                    dynamic_cast<const MaxMinClearanceObjective *>(run.setup->getOptimizationObjective().get()))
                line(summary, "cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                                  std::to_string(maxMin->gridStates()) +
                                                  " motion grid states (bounded queries)");
            if (run.answer)
            {
                const CertifiedAnswerPlanner::Stats &a = run.answer->lastStats();
                line(summary, "certified path", std::to_string(a.motions) + " motions proven, " +
                                                    std::to_string(a.refused) + " refused, " +
                                                    std::to_string(a.repaired) + " of them replanned, " +
                                                    std::to_string(a.searches) + " searches");
            }
            run.summary = summary.str();
        }

        void writeRobotPlanFiles(const RobotPlanRun &run, const PlanOptions &o, std::ostream &log)
        {
            if (!o.summaryFile.empty())
                writeTextFile(run.summary, o.summaryFile);
            const og::PathGeometric &path = run.setup->getSolutionPath();
            writeSceneFiles(*run.scene, run.dense.get(), {run.problem.start, *run.problem.goal}, run.summary, o, log);
            if (!run.havePath)
                return;
            if (!o.out.empty())
            {
                std::ostringstream text;
                text << std::setprecision(17);
                std::vector<double> q;
                for (std::size_t i = 0; i < path.getStateCount(); ++i)
                {
                    robotStateToVector(*run.setup->getStateSpace(), path.getState(i), q);
                    for (std::size_t k = 0; k < q.size(); ++k)
                        text << (k ? " " : "") << q[k];
                    text << "\n";
                }
                writeTextFile(text.str(), o.out);
                log << "path written    " << o.out << "\n";
            }
            if (!o.csv.empty())
            {
                writeClearanceCsv(*run.dense, stateColumns(*run.problem.robot), o.csv);
                log << "clearance CSV   " << o.csv << "\n";
            }
        }

        namespace
        {
            /** \brief One state's answer: the clearance, its pair and witnesses, every link's clearance. */
            void printAnswer(const RobotScene &scene, const RobotResult &r, std::size_t index, std::ostream &out)
            {
                out << "state " << index << ": clearance " << r.distance << " ("
                    << (r.certified ? "exact, certified" : "not certified") << ")"
                    << (r.inCollision ? ", IN COLLISION" : "") << "\n";
                out << "  closest pair   " << pairText(scene, r) << "\n";
                out << "  witnesses      (" << r.onLink.transpose() << ") on the link, (" << r.onOther.transpose()
                    << ") on the other\n";
                for (std::size_t i = 0; i < scene.links().size(); ++i)
                {
                    char name[40];
                    std::snprintf(name, sizeof name, "  link %-24s", scene.links()[i].name.c_str());
                    out << name << " " << r.linkClearance[i] << "\n";
                }
            }

            /** \brief "N states, whole robot: median X us, mean Y us per query" on stderr (whatever the log level),
                as meshgap_distance prints for a single body. */
            void printQueryTimes(std::vector<double> micros, bool cold)
            {
                if (micros.empty())
                    return;
                double sum = 0.0;
                for (double us : micros)
                    sum += us;
                std::sort(micros.begin(), micros.end());
                std::fprintf(stderr, "meshgap_distance: %zu states, whole robot, every pair exact, %s: median %.1f us, "
                                     "mean %.1f us per query\n",
                             micros.size(), cold ? "cold" : "warm start carried", micros[micros.size() / 2],
                             sum / double(micros.size()));
            }

            /** \brief \e text as a JSON string (quotes, backslashes and control characters escaped). */
            std::string jsonString(const std::string &text)
            {
                std::string s = "\"";
                for (unsigned char c : text)
                {
                    if (c == '"' || c == '\\')
                        s += std::string("\\") + char(c);
                    else if (c < 0x20)
                    {
                        char escaped[8];
                        std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
                        s += escaped;
                    }
                    else
                        s += char(c);
                }
                return s + "\"";
            }

            /** \brief \e v as a JSON number, null when not finite (a link with nothing to be checked against). */
            std::string jsonNumber(double v)
            {
                std::ostringstream text;
                text.precision(17);
                if (std::isfinite(v))
                    text << v;
                else
                    text << "null";
                return text.str();
            }

            /** \brief One state's answer as a JSON object: the fields of the CSV (ROBOT_CSV_COLUMNS; witnesses as
                arrays, link clearances as an object by link name), pairs_checked and the query's time. */
            std::string jsonAnswer(const RobotScene &scene, const RobotResult &r, double micros)
            {
                std::ostringstream o;
                o << "{\"distance\": " << jsonNumber(r.distance) << ", \"in_collision\": "
                  << (r.inCollision ? "true" : "false") << ", \"certified\": " << (r.certified ? "true" : "false")
                  << ", \"link\": " << jsonString(scene.links()[r.link].name) << ", \"other_link\": "
                  << (r.selfPair ? jsonString(scene.links()[r.other].name) : "null")
                  << ", \"obstacle\": " << (r.selfPair ? std::string("null") : std::to_string(r.other));
                for (const auto &[key, v] : {std::pair{"witness_link", &r.onLink}, {"witness_other", &r.onOther}})
                    o << ", \"" << key << "\": [" << jsonNumber(v->x()) << ", " << jsonNumber(v->y()) << ", "
                      << jsonNumber(v->z()) << "]";
                o << ", \"pairs_checked\": " << r.pairsChecked << ", \"time_us\": " << jsonNumber(micros)
                  << ", \"link_clearance\": {";
                for (std::size_t i = 0; i < scene.links().size(); ++i)
                    o << (i ? ", " : "") << jsonString(scene.links()[i].name) << ": " << jsonNumber(r.linkClearance[i]);
                o << "}}";
                return o.str();
            }

            /** \brief \e text as one CSV field: quoted (quotes doubled) when it holds a comma, quote or line end. */
            std::string csvField(const std::string &text)
            {
                if (text.find_first_of(",\"\n\r") == std::string::npos)
                    return text;
                std::string quoted = "\"";
                for (char c : text)
                    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
                return quoted + "\"";
            }

            /** \brief The header of --poses' CSV (ROBOT_CSV_COLUMNS, then a clearance column per link). */
            void printCsvHeader(const RobotScene &scene, std::ostream &out)
            {
                out << ROBOT_CSV_COLUMNS;
                for (const RobotLink &link : scene.links())
                    out << "," << csvField("clearance_" + link.name);
                out << "\n";
            }

            /** \brief One state's answer as a CSV row: index, clearance, collision, certified, the pair (a link and an
                obstacle index, or two links), its witnesses, every link's clearance. */
            void printCsvRow(const RobotScene &scene, const RobotResult &r, std::size_t index, std::ostream &out)
            {
                // The numbers through snprintf ("%.17g", what the stream's precision 17 prints): formatting them
                // through the stream costs more than a warm query's own work on a single body.
                char number[32];
                auto put = [&](double v)
                {
                    std::snprintf(number, sizeof number, ",%.17g", v);
                    out << number;
                };
                out << index;
                put(r.distance);
                out << "," << (r.inCollision ? 1 : 0) << "," << (r.certified ? 1 : 0) << ","
                    << csvField(scene.links()[r.link].name) << ","
                    << (r.selfPair ? csvField(scene.links()[r.other].name) : std::string()) << ","
                    << (r.selfPair ? std::string() : std::to_string(r.other));
                for (const Eigen::Vector3d *v : {&r.onLink, &r.onOther})
                    for (int k = 0; k < 3; ++k)
                        put((*v)[k]);
                for (double c : r.linkClearance)
                    put(c);
                out << "\n";
            }
        }  // namespace

        void robotDistance(const RobotProblem &p, const std::string &stateText, const std::string &statesFile,
                           const RobotDistanceOptions &options, std::ostream &out)
        {
            const RobotScene scene(p.robot, p.obstacles, p.allowedObstacles);
            const std::size_t n = p.robot->dimension();
            std::vector<std::vector<double>> states = {p.start};
            if (!stateText.empty())
                states = {parseRobotState(stateText, *p.robot, "--pose")};
            const bool many = !statesFile.empty();
            if (many)
                states = readRobotPathFile(statesFile, *p.robot);
            OMPL_INFORM("%s: %s, links %zu, self pairs %zu, obstacles %zu; exact, every pair, %s", p.name.c_str(),
                        p.robot->description().c_str(), scene.links().size(), scene.selfPairs().size(),
                        scene.obstacles().size(), options.cold ? "a cold query per state (--cold)" :
                                                                 "one warm start carried from state to state");
            RobotRequest request;
            request.everyPair = true;
            request.computeDepth = options.depth;
            RobotWarmStart warm;
            RobotResult r;
            out << std::setprecision(many || options.json ? 17 : 10);
            if (many)
                out << (options.json ? "[\n" : "");
            if (many && !options.json)
                printCsvHeader(scene, out);
            std::vector<double> micros;
            for (std::size_t i = 0; i < states.size(); ++i)
            {
                if (options.cold)
                    warm.reset();
                const auto start = std::chrono::steady_clock::now();
                scene.distance(states[i].data(), n, request, warm, r);
                micros.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e6);
                if (options.json)
                    out << (many ? "  " : "") << jsonAnswer(scene, r, micros.back())
                        << (many && i + 1 < states.size() ? ",\n" : "\n");
                else if (many)
                    printCsvRow(scene, r, i, out);
                else
                    printAnswer(scene, r, i + 1, out);
            }
            if (many && options.json)
                out << "]\n";
            if (many)
                printQueryTimes(micros, options.cold);
        }
    }  // namespace cli
}  // namespace meshgap
