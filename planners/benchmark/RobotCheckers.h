#ifndef MESHGAP_PLANNERS_BENCHMARK_ROBOT_CHECKERS_H
#define MESHGAP_PLANNERS_BENCHMARK_ROBOT_CHECKERS_H

// meshgap_benchmark on a robot of many bodies (a robot problem file, RobotProblem.h): the joint-space problem and the
// checkers it compares, by name: meshgap's exact whole-robot checker with its certified motion validator or with
// OMPL's discrete one, and FCL as MoveIt uses it (broad-phase managers, primitives as FCL's shapes) checking the same
// pairs with OMPL's discrete motion validator.

#include <atomic>
#include <memory>
#include <ompl/geometric/SimpleSetup.h>
#include <string>
#include <vector>

#include "FclRobotChecker.h"
#include "benchmark/Checkers.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/robot/RobotProblem.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief The checkers of a robot problem, in grid order, as --checker spells them: "certified" (RobotChecker;
            the planner searches with a sampled motion check and every motion of its answer is certified by
            RobotMotionValidator, refused ones replanned: CertifiedAnswerPlanner), "certified-search" (RobotChecker,
            RobotMotionValidator on every motion the search tries), "discrete" (RobotChecker, OMPL's
            DiscreteMotionValidator at its default resolution) and, when built with FCL, "fcl" (FclRobotChecker,
            OMPL's DiscreteMotionValidator). Every kind of robot has all of them (\e robot is not looked at). */
        std::vector<std::string> robotCheckerNames(const RobotModel *robot = nullptr);

        /** \brief What the grid reads of a problem file (name, file, objective, [benchmark], [planner]) for a robot
            problem. */
        ProblemConfig benchmarkConfigOf(const RobotProblem &problem);

        /** \brief RobotChecker counting its queries and their time, as ClearanceChecker does (CheckerStats). */
        class CountingRobotChecker : public RobotChecker
        {
        public:
            using RobotChecker::RobotChecker;
            bool isValid(const ompl::base::State *state) const override;
            double clearance(const ompl::base::State *state) const override;
            CheckerStats stats() const;
            /** \brief Add \e nanoseconds of work done for it elsewhere (the certified motion validator's queries). */
            void addTime(std::uint64_t nanoseconds) const { nanoseconds_ += nanoseconds; }

        private:
            mutable std::atomic<std::uint64_t> validityCalls_{0}, clearanceCalls_{0}, nanoseconds_{0};
        };

        /** \brief One robot problem: its RobotScene and joint-space SimpleSetup built once, the checkers of
            robotCheckerNames() installed into it in turn. */
        class RobotCheckers : public CheckerSet
        {
        public:
            /** \brief \e objective: allocObjective()'s name, empty for the problem's own (default: length). Throws
                meshgap::Exception naming the file for a problem without a goal, or a floating base or several
                bodies without a volume. */
            RobotCheckers(const RobotProblem &problem, const std::string &objective);

            ompl::geometric::SimpleSetup &setup() override { return *setup_; }
            void install(const std::string &name) override;
            /** \brief Under "certified", a CertifiedAnswerPlanner around the planner \e allocate makes. */
            ompl::base::PlannerPtr
            allocPlanner(const std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)> &allocate)
                override;
            CheckerStats stats() const override;
            bool isMeshgap() const override { return active_ != "fcl"; }
            /** \brief FCL's verdict on \e path densely interpolated, as Checkers gives it (FclRobotChecker: the true
                shapes of primitive solids), without the least distance (FCL's distance of an arm costs a millisecond
                or more a state); and meshgap's exact least clearance over the same states ("path min clearance REAL",
                negative in collision). */
            void fclPathProperties(const ompl::geometric::PathGeometric &solution,
                                   ompl::tools::Benchmark::RunProperties &run) override;

        private:
            RobotSceneConstPtr scene_;
            std::shared_ptr<ompl::geometric::SimpleSetup> setup_;
            std::shared_ptr<CountingRobotChecker> checker_;
            ompl::base::MotionValidatorPtr certified_;
    #ifdef MESHGAP_HAVE_FCL
            std::shared_ptr<FclRobotChecker> fcl_;
    #endif
            std::string file_, active_;
        };
    }  // namespace cli
}  // namespace meshgap

#endif
