#include "support/PlanChecks.h"

#include <iomanip>
#include <ompl/base/PlannerData.h>

#include "meshgap/Exception.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "meshgap/robot/RigidBodyRobot.h"
#include "support/PlanOutputs.h"
#include "support/PlanRun.h"
#include "support/SurfaceText.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief A single rigid body: its ClearanceChecker (--checker certified or fast) over OMPL's SE(2) or
                SE(3) space (setupProblem()), the motion validator --motion names (discrete by default), the planner
                searching with them; the body as a robot of one link (its body and obstacles the scene's) for the
                dense path. */
            class BodyChecks : public PlanChecks
            {
            public:
                explicit BodyChecks(ProblemConfig config) : config_(std::move(config)) {}

                const ProblemSettings &settings() const override { return config_; }

                void setUp(PlanRun &run, const PlanOptions &o) override
                {
                    ObjectiveOptions objectiveOptions;
                    objectiveOptions.weight = o.weight;
                    problem_ = setupProblem(config_,
                                            o.checker == "certified" ? ClearanceChecker::Mode::CERTIFIED :
                                                                       ClearanceChecker::Mode::FAST,
                                            o.objective, BodyOptions(), objectiveOptions);
                    run.setup = problem_.setup;
                    run.objective = problem_.objective;
                    run.motion = o.motion;
                    const RigidSpace space = config_.planar ? RigidSpace::SE2 : RigidSpace::SE3;
                    run.scene = std::make_shared<RobotScene>(
                        std::make_shared<RigidBodyRobot>(BodyConstPtr(problem_.scene, &problem_.scene->robot()),
                                                         space),
                        problem_.scene->obstacles());
                    run.ends = {rigidState(space, config_.start)};
                    if (config_.goal)
                        run.ends.push_back(rigidState(space, *config_.goal));
                    const ob::SpaceInformationPtr si = run.setup->getSpaceInformation();
                    if (!o.sampler.empty())
                        setValidStateSampler(*si, o.sampler, o.label("sampler"));
                    const ob::MotionValidatorPtr motion =
                        allocMotionValidator(o.motion, si, problem_.checker, o.label("motion"));
                    si->setMotionValidator(motion);
                    cmv_ = std::dynamic_pointer_cast<ClearanceMotionValidator>(motion);
                    run.setup->setPlanner(allocPlanPlanner(o, si));
                    run.setup->setup();
                }

                std::function<std::uint64_t()> validityCount() const override
                {
                    const ClearanceCheckerPtr checker = problem_.checker;
                    return [checker] { return checker->stats().validityCalls; };
                }

                std::optional<CheckerStats> stats() const override { return problem_.checker->stats(); }

                ClearanceFieldPtr field() const override { return problem_.checker; }

                void describe(const PlanRun &, PlanSummary &summary) const override
                {
                    summary.line("problem", config_.name + (config_.planar ? " (SE(2))" : " (SE(3))"));
                    summary.line("surfaces", sceneSurfacesText(*problem_.scene));
                }

                std::string clearanceMode(const PlanRun &, const PlanOptions &o) const override
                {
                    return o.checker + ", motion " + o.motion;
                }

                void optimized(const PlanRun &, const PlanOptions &, PlanSummary &) const override {}

                std::string clearanceWhere(const PlanRun &, const DenseClearance &d) const override
                {
                    std::ostringstream text;
                    text.precision(6);
                    text << "at arc length " << d.arcLength[d.argmin] << " of " << d.arcLength.back();
                    return text.str();
                }

                void summarizeSearch(const PlanRun &run, PlanSummary &summary) const override;

                void writePath(const PlanRun &run, const std::string &file) const override
                {
                    writePathFile(run.setup->getSolutionPath(), file);
                }

            private:
                ProblemConfig config_;
                OmplProblem problem_;
                /** \brief The certified motion validator (--motion clearance); null otherwise. */
                std::shared_ptr<ClearanceMotionValidator> cmv_;
            };

            void BodyChecks::summarizeSearch(const PlanRun &run, PlanSummary &summary) const
            {
                const CheckerStats stats = problem_.checker->stats();
                {
                    ob::PlannerData data(run.setup->getSpaceInformation());
                    run.setup->getPlannerData(data);
                    summary.line("graph states", data.numVertices());
                }
                summary.line("validity calls", stats.validityCalls);
                summary.line("clearance calls", stats.clearanceCalls);
                if (stats.carried + stats.written + stats.cold > 0)
                    summary.line("warm starts", std::to_string(stats.carried) + " carried, " +
                                                    std::to_string(stats.written) + " written, " +
                                                    std::to_string(stats.cold) + " cold (certified queries)");
                if (const auto *maxMin =
                        dynamic_cast<const MaxMinClearanceObjective *>(run.setup->getOptimizationObjective().get()))
                    summary.line("cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                                     std::to_string(maxMin->gridStates()) + " motion grid states");
                if (cmv_)
                    summary.line("motion checks",
                                 std::to_string(cmv_->getValidMotionCount() + cmv_->getInvalidMotionCount()) + " (" +
                                     std::to_string(cmv_->getValidMotionCount()) + " free), " +
                                     std::to_string(cmv_->queries()) + " clearance queries");
                summary.line("query time", std::to_string(stats.seconds * 1e3) + " ms");
            }

            /** \brief OMPL's discrete motion check (--motion discrete; the certified validator is a robot's default)
                steps this fraction of the state space's extent on a robot problem (its default, 0.01, lets two
                bodies moving at once pass through each other between steps). */
            constexpr double ROBOT_DISCRETE_RESOLUTION = 0.002;

            /** \brief A robot of many links (a URDF robot, its payload, several bodies): a RobotChecker over
                robotStateSpace(), exact whole-robot checks; by default (--motion clearance) a sampled search whose
                every answer motion RobotMotionValidator proves (CertifiedAnswerPlanner), else OMPL's discrete motion
                check. --checker fast is a single body's. */
            class RobotChecks : public PlanChecks
            {
            public:
                explicit RobotChecks(RobotProblem problem) : problem_(std::move(problem)) {}

                const ProblemSettings &settings() const override { return problem_; }

                void setUp(PlanRun &run, const PlanOptions &o) override;

                std::function<std::uint64_t()> validityCount() const override
                {
                    return [checker = checker_] { return checker->validityCalls(); };
                }

                std::optional<CheckerStats> stats() const override { return std::nullopt; }

                ClearanceFieldPtr field() const override { return checker_; }

                void describe(const PlanRun &run, PlanSummary &summary) const override
                {
                    const RobotModel &robot = *problem_.robot;
                    summary.line("problem", problem_.name + " (robot problem)");
                    summary.line("robot", robot.description() + ", " + std::to_string(robot.links().size()) +
                                              " links, " + std::to_string(run.scene->selfPairs().size()) +
                                              " self pairs, " + std::to_string(problem_.obstacles.size()) +
                                              " obstacles");
                }

                std::string clearanceMode(const PlanRun &, const PlanOptions &) const override
                {
                    return std::string("certified, motion ") +
                           (answer_ ? "certified (displacement bound per pair; the search sampled, every motion of "
                                      "the answer proven)" :
                                      "discrete (OMPL's)");
                }

                /** \brief The dense path's least clearance and its pair before and after the optimiser. */
                void optimized(const PlanRun &run, const PlanOptions &o, PlanSummary &summary) const override
                {
                    const DenseClearance after = denseClearance(run.setup->getSolutionPath(), *run.scene, o.dense,
                                                                false);
                    summary.line("opt before", clearanceText(run, *run.before));
                    summary.line("opt after", clearanceText(run, after));
                }

                std::string clearanceWhere(const PlanRun &run, const DenseClearance &d) const override
                {
                    return pairText(*run.scene, d.worst);
                }

                void summarizeSearch(const PlanRun &run, PlanSummary &summary) const override;

                void writePath(const PlanRun &run, const std::string &file) const override
                {
                    const og::PathGeometric &path = run.setup->getSolutionPath();
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
                    writeTextFile(text.str(), file);
                }

            private:
                /** \brief "0.0123 (exact, over the dense path; link 'a' and obstacle 3)". */
                std::string clearanceText(const PlanRun &run, const DenseClearance &d) const
                {
                    std::ostringstream text;
                    text.precision(6);
                    text << d.worst.distance << " (exact, over the dense path; " << pairText(*run.scene, d.worst)
                         << ")";
                    return text.str();
                }

                /** \brief The state space's bounds: the volume, or (a fixed-base arm needs none) a unit cube. */
                ob::RealVectorBounds bounds() const;

                /** \brief The start or goal as an OMPL state; throws when it is out of bounds or in collision. */
                void checkEnd(const PlanRun &run, const std::vector<double> &q, const char *which,
                              ob::ScopedState<> &state) const;

                /** \brief The objective run.objective names, with the problem's threshold. */
                void setObjective(const PlanRun &run, const PlanOptions &o) const;

                RobotProblem problem_;
                std::shared_ptr<RobotChecker> checker_;
                /** \brief With the certified validator, the planner: a sampled search, its answer certified. */
                std::shared_ptr<CertifiedAnswerPlanner> answer_;
            };

            ob::RealVectorBounds RobotChecks::bounds() const
            {
                ob::RealVectorBounds b(3);
                b.setLow(-1.0);
                b.setHigh(1.0);
                if (!problem_.volume && problem_.robot->movesFree())
                    throw Exception(problem_.file,
                                    "needs volume.min.x .. volume.max.z (the bounds of its bodies' positions)");
                if (problem_.volume)
                    for (int k = 0; k < 3; ++k)
                    {
                        b.setLow(k, problem_.volume->min()[k]);
                        b.setHigh(k, problem_.volume->max()[k]);
                    }
                return b;
            }

            void RobotChecks::checkEnd(const PlanRun &run, const std::vector<double> &q, const char *which,
                                       ob::ScopedState<> &state) const
            {
                robotStateFromVector(*run.setup->getStateSpace(), q, state.get());
                if (!run.setup->getStateSpace()->satisfiesBounds(state.get()))
                    throw Exception(problem_.file, std::string(which) + " is outside the state space's bounds");
                RobotResult r;
                run.scene->distance(q, RobotRequest(), r);
                if (r.inCollision)
                {
                    std::ostringstream text;
                    text << which << " is in collision: " << pairText(*run.scene, r) << " (signed distance "
                         << r.distance << ")";
                    throw Exception(problem_.file, text.str());
                }
            }

            void RobotChecks::setObjective(const PlanRun &run, const PlanOptions &o) const
            {
                ObjectiveOptions objectiveOptions;
                objectiveOptions.weight = o.weight;
                const ob::OptimizationObjectivePtr objective =
                    allocObjective(run.objective, run.setup->getSpaceInformation(), objectiveOptions);
                if (problem_.objectiveThreshold)
                    objective->setCostThreshold(ob::Cost(*problem_.objectiveThreshold));
                run.setup->setOptimizationObjective(objective);
            }

            void RobotChecks::setUp(PlanRun &run, const PlanOptions &o)
            {
                if (o.checker != "certified")
                    throw Exception(o.label("checker"), "a robot problem is checked exactly (certified) only");
                const RobotProblem &p = problem_;
                if (p.robot->dimension() == 0)
                    throw Exception(p.file, "the robot has no movable joint (a fixed robot): there is nothing to "
                                            "plan; meshgap_distance --cfg gives its clearance");
                if (!p.goal)
                    throw Exception(p.file, "no goal (goal.joints, or goal.N.x ... for each body)");
                run.scene = planningScene(p);
                run.ends = {p.start, *p.goal};
                run.setup = std::make_shared<og::SimpleSetup>(robotStateSpace(*p.robot, bounds()));
                const ob::SpaceInformationPtr si = run.setup->getSpaceInformation();
                checker_ = std::make_shared<RobotChecker>(si, run.scene);
                run.setup->setStateValidityChecker(checker_);
                // Certified motions by default, for every kind of robot.
                run.motion = o.isGiven("motion") ? o.motion : "clearance";
                const ob::MotionValidatorPtr validator =
                    allocMotionValidator(run.motion, si, run.scene, o.label("motion"));
                si->setMotionValidator(validator);
                const bool certified = std::dynamic_pointer_cast<RobotMotionValidator>(validator) != nullptr;
                if (!certified)
                    si->setStateValidityCheckingResolution(ROBOT_DISCRETE_RESOLUTION);
                ob::ScopedState<> start(si), goal(si);
                checkEnd(run, p.start, "start", start);
                checkEnd(run, *p.goal, "goal", goal);
                run.setup->setStartAndGoalStates(start, goal);
                setObjective(run, o);
                // Certified: the planner searches with a sampled motion check; every motion of its answer is
                // certified. The valid-state sampler (--sampler, else the problem's) of the space it searches.
                const std::string sampler = !o.sampler.empty() ? o.sampler : p.sampler;
                const std::string where = !o.sampler.empty() ? o.label("sampler") : p.file + ": [problem] sampler";
                auto search = [&o, sampler, where](const ob::SpaceInformationPtr &s)
                {
                    if (!sampler.empty())
                        setValidStateSampler(*s, sampler, where);
                    return allocPlanPlanner(o, s);
                };
                if (certified)
                    run.setup->setPlanner(answer_ = std::make_shared<CertifiedAnswerPlanner>(si, search));
                else
                    run.setup->setPlanner(search(si));
                run.setup->setup();
            }

            void RobotChecks::summarizeSearch(const PlanRun &run, PlanSummary &summary) const
            {
                // The search's checks (sampled when the answer is certified afterwards).
                const ob::MotionValidatorPtr &mv = (answer_ ? answer_->searchSpaceInformation() :
                                                              run.setup->getSpaceInformation())
                                                       ->getMotionValidator();
                summary.line("motion checks", std::to_string(mv->getValidMotionCount() +
                                                             mv->getInvalidMotionCount()) +
                                                  " (" + std::to_string(mv->getValidMotionCount()) + " free" +
                                                  (answer_ ? ", sampled)" : ")"));
                if (const auto *maxMin =
                        dynamic_cast<const MaxMinClearanceObjective *>(run.setup->getOptimizationObjective().get()))
                    summary.line("cost queries", std::to_string(maxMin->queriedStates()) + " states queried for " +
                                                     std::to_string(maxMin->gridStates()) +
                                                     " motion grid states (bounded queries)");
                if (answer_)
                {
                    const CertifiedAnswerPlanner::Stats &a = answer_->lastStats();
                    summary.line("certified path", std::to_string(a.motions) + " motions proven, " +
                                                       std::to_string(a.refused) + " refused, " +
                                                       std::to_string(a.repaired) + " of them replanned, " +
                                                       std::to_string(a.searches) + " searches");
                }
            }
        }  // namespace

        std::unique_ptr<PlanChecks> planChecks(Problem problem)
        {
            if (problem.robot)
                return std::make_unique<RobotChecks>(std::move(*problem.robot));
            return std::make_unique<BodyChecks>(std::move(*problem.rigidBody));
        }
    }  // namespace cli
}  // namespace meshgap
