#include "benchmark/RobotCheckers.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <ompl/base/DiscreteMotionValidator.h>

#include "benchmark/BenchmarkLog.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/UrdfRobot.h"

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            std::uint64_t nanosecondsSince(std::chrono::steady_clock::time_point start)
            {
                return static_cast<std::uint64_t>(
                    std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
                        .count());
            }

            /** \brief A motion validator that times another's checkMotion() into the checker's counters. */
            class TimedMotionValidator : public ompl::base::MotionValidator
            {
            public:
                TimedMotionValidator(const ompl::base::SpaceInformationPtr &si, ompl::base::MotionValidatorPtr inner,
                                     std::shared_ptr<const CountingRobotChecker> checker)
                  : ompl::base::MotionValidator(si), inner_(std::move(inner)), checker_(std::move(checker))
                {
                }

                bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override
                {
                    const auto start = std::chrono::steady_clock::now();
                    const bool valid = inner_->checkMotion(s1, s2);
                    checker_->addTime(nanosecondsSince(start));
                    valid ? ++valid_ : ++invalid_;
                    return valid;
                }

                bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                 std::pair<ompl::base::State *, double> &lastValid) const override
                {
                    const auto start = std::chrono::steady_clock::now();
                    const bool valid = inner_->checkMotion(s1, s2, lastValid);
                    checker_->addTime(nanosecondsSince(start));
                    valid ? ++valid_ : ++invalid_;
                    return valid;
                }

            private:
                ompl::base::MotionValidatorPtr inner_;
                std::shared_ptr<const CountingRobotChecker> checker_;
            };

            /** \brief The 3-D box a floating base or rigid bodies move in: the problem's volume; a fixed-base URDF
                needs none (a unit box stands in). */
            ompl::base::RealVectorBounds boundsOf(const RobotProblem &problem)
            {
                ompl::base::RealVectorBounds bounds(3);
                bounds.setLow(-1.0);
                bounds.setHigh(1.0);
                if (problem.volume)
                    for (int k = 0; k < 3; ++k)
                    {
                        bounds.setLow(k, problem.volume->min()[k]);
                        bounds.setHigh(k, problem.volume->max()[k]);
                    }
                else if (problem.robot->movesFree())
                    throw Exception(problem.file, "no volume (volume.min.* and volume.max.*): a robot moving free "
                                                  "needs bounds");
                return bounds;
            }
        }  // namespace

        std::vector<std::string> robotCheckerNames(const RobotModel * /*robot*/)
        {
            std::vector<std::string> names = {"certified", "certified-search", "discrete"};
    #ifdef MESHGAP_HAVE_FCL
            names.push_back("fcl");
    #endif
            return names;
        }

        ProblemConfig benchmarkConfigOf(const RobotProblem &problem)
        {
            ProblemConfig config;
            config.file = problem.file;
            config.name = problem.name;
            config.objective = problem.objective;
            config.objectiveThreshold = problem.objectiveThreshold;
            config.benchmark = problem.benchmark;
            config.planners = problem.planners;
            return config;
        }

        bool CountingRobotChecker::isValid(const ompl::base::State *state) const
        {
            const auto start = std::chrono::steady_clock::now();
            ++validityCalls_;
            const bool valid = RobotChecker::isValid(state);
            nanoseconds_ += nanosecondsSince(start);
            return valid;
        }

        double CountingRobotChecker::clearance(const ompl::base::State *state) const
        {
            const auto start = std::chrono::steady_clock::now();
            ++clearanceCalls_;
            const double d = RobotChecker::clearance(state);
            nanoseconds_ += nanosecondsSince(start);
            return d;
        }

        CheckerStats CountingRobotChecker::stats() const
        {
            CheckerStats s;
            s.validityCalls = validityCalls_;
            s.clearanceCalls = clearanceCalls_;
            s.seconds = 1e-9 * static_cast<double>(nanoseconds_.load());
            return s;
        }

        RobotCheckers::RobotCheckers(const RobotProblem &problem, const std::string &objective)
          : scene_(std::make_shared<RobotScene>(problem.robot, problem.obstacles, problem.allowedObstacles)),
            file_(problem.file)
        {
            if (!problem.goal)
                throw Exception(problem.file, "no goal (goal.joints, or goal.N.* for every body)");
            setup_ = std::make_shared<ompl::geometric::SimpleSetup>(robotStateSpace(*problem.robot, boundsOf(problem)));
            const ompl::base::SpaceInformationPtr si = setup_->getSpaceInformation();
            checker_ = std::make_shared<CountingRobotChecker>(si, scene_);
            certified_ = std::make_shared<TimedMotionValidator>(
                si, allocMotionValidator("clearance", si, scene_, "--checker"), checker_);
    #ifdef MESHGAP_HAVE_FCL
            fcl_ = std::make_shared<FclRobotChecker>(si, scene_);
    #endif
            ompl::base::ScopedState<> start(si), goal(si);
            robotStateFromVector(*si->getStateSpace(), problem.start, start.get());
            robotStateFromVector(*si->getStateSpace(), *problem.goal, goal.get());
            setup_->setStartAndGoalStates(start, goal);
            install("discrete");
            const std::string name = !objective.empty() ? objective : !problem.objective.empty() ? problem.objective :
                                                                                                    "length";
            setup_->setOptimizationObjective(allocObjective(name, si));
            setup_->setup();
        }

        void RobotCheckers::install(const std::string &name)
        {
            const ompl::base::SpaceInformationPtr si = setup_->getSpaceInformation();
            ompl::base::StateValidityCheckerPtr checker = checker_;
            ompl::base::MotionValidatorPtr validator;
            if (name == "certified" || name == "certified-search")
                validator = certified_;
    #ifdef MESHGAP_HAVE_FCL
            else if (name == "fcl")
                checker = fcl_;
    #endif
            else if (name != "discrete")
                throw Exception("--checker", "unknown checker " + quote(name));
            active_ = name;
            si->setStateValidityChecker(checker);
            si->setMotionValidator(validator ? validator : allocMotionValidator("discrete", si, scene_, "--checker"));
        }

        ompl::base::PlannerPtr RobotCheckers::allocPlanner(
            const std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)> &allocate)
        {
            if (active_ == "certified")
                return std::make_shared<CertifiedAnswerPlanner>(setup_->getSpaceInformation(), allocate);
            return allocate(setup_->getSpaceInformation());
        }

        CheckerStats RobotCheckers::stats() const
        {
    #ifdef MESHGAP_HAVE_FCL
            if (active_ == "fcl")
                return fcl_->stats();
    #endif
            return checker_->stats();
        }

        void RobotCheckers::fclPathProperties(const ompl::geometric::PathGeometric &solution,
                                              ompl::tools::Benchmark::RunProperties &run)
        {
            ompl::geometric::PathGeometric path(solution);
            const ompl::base::StateSpacePtr &space = setup_->getStateSpace();
            const unsigned factor = space->getValidSegmentCountFactor();
            space->setValidSegmentCountFactor(4 * factor);
            path.interpolate();
            space->setValidSegmentCountFactor(factor);
            // meshgap's exact whole-robot clearance at every state of the same dense path: its least.
            RobotWarmStart warm;
            RobotResult r;
            std::vector<double> q;
            double least = std::numeric_limits<double>::infinity();
            for (const ompl::base::State *s : path.getStates())
            {
                robotStateToVector(*space, s, q);
                scene_->distance(q.data(), q.size(), RobotRequest(), warm, r);
                least = std::min(least, r.distance);
            }
            run["path min clearance REAL"] = real(least);
    #ifdef MESHGAP_HAVE_FCL
            // The verdict only: FCL's distance on every pair of an arm costs milliseconds a state.
            bool free = true;
            for (const ompl::base::State *s : path.getStates())
                free = free && !fcl_->inCollision(fcl_->pose(s));
            run["fcl path states INTEGER"] = std::to_string(path.getStateCount());
            run["fcl path collision free BOOLEAN"] = free ? "1" : "0";
    #endif
        }
    }  // namespace cli
}  // namespace meshgap
