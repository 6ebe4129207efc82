#ifndef MESHGAP_PLANNERS_BENCHMARK_CHECKERS_H
#define MESHGAP_PLANNERS_BENCHMARK_CHECKERS_H

// The checkers meshgap_benchmark compares, by name, on a problem of any kind (RobotProblem: a single body is a robot of
// one link, rigidBodyProblem()): meshgap's exact checker with OMPL's discrete or meshgap's certified motion
// validator, and FCL as MoveIt uses it (FclChecker: broad-phase managers, FCL's narrow phase on the same pairs).

#include <atomic>
#include <functional>
#include <memory>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <string>
#include <vector>

#include "FclChecker.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/robot/RobotProblem.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief The checkers a problem of \e robot offers, in grid order, as --checker spells them (as meshgap_plan
            does). A robot that is one rigid body (one link placed by its one SE(2) or SE(3) state: a single-body
            problem, OMPL.app's) is checked by its link's Scene (ClearanceChecker): "certified" (certified
            clearance queries, OMPL's DiscreteMotionValidator), "fast" (the fast clearance queries, the same
            validator), "certified-cmv" (certified queries, ClearanceMotionValidator on every motion). Any other robot
            by RobotChecker: "certified" (the planner searches with a sampled motion check and every motion of its
            answer is certified by RobotMotionValidator, refused ones replanned: CertifiedAnswerPlanner),
            "certified-search" (RobotMotionValidator on every motion the search tries), "discrete" (OMPL's
            DiscreteMotionValidator at its default resolution). When built with FCL, every robot has "fcl" too
            (FclChecker, OMPL's DiscreteMotionValidator). */
        std::vector<std::string> checkerNames(const RobotModel &robot);

        /** \brief Both menus of checkerNames(), for --help. */
        std::string checkerMenuText();

        /** \brief A checker's label in the .log (planner names, file names, the "checker" property): the library's name
            too, meshgap-certified beside fcl. */
        inline std::string checkerLabel(const std::string &name)
        {
            return name == "fcl" ? name : "meshgap-" + name;
        }

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

        /** \brief One problem of any kind: its RobotScene and SimpleSetup built once, the checkers of checkerNames()
            installed into it by name in turn. The state space is robotStateSpace()'s, or for one rigid body the SE(2) or
            SE(3) space of its one state block (a single body plans in it, as OMPL.app's problems do); the
            problem's start and goal (checked in bounds and free), objective (\e objective when given), its threshold
            and sampler are set. */
        class Checkers
        {
        public:
            /** \brief \e objective: allocObjective()'s name, empty for the problem's own (default: length). Throws
                meshgap::Exception naming the file for a robot without movable joints, a problem without a goal, a
                robot moving free without a volume, a start or goal out of bounds or in collision (the pair and its
                signed distance), an unknown objective or sampler. */
            Checkers(const RobotProblem &problem, const std::string &objective);

            ompl::geometric::SimpleSetup &setup() { return *setup_; }
            const std::vector<std::string> &names() const { return names_; }

            /** \brief Make \e name the problem's validity checker and motion validator. */
            void install(const std::string &name);
            /** \brief The planner a run of the installed checker uses, made by \e allocate on the SpaceInformation it
                is given: a CertifiedAnswerPlanner around it for a robot's "certified", else \e allocate on the
                problem's own. */
            using PlannerAllocator = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)>;
            ompl::base::PlannerPtr allocPlanner(const PlannerAllocator &allocate);
            /** \brief Counters of the installed checker (cumulative). */
            CheckerStats stats() const;
            bool isMeshgap() const { return active_ != "fcl"; }
            /** \brief The path's checks, densely interpolated (4x OMPL's motion-check resolution, as the Benchmark's
                strict check): FCL's verdict and least distance over its states ("fcl path states INTEGER", "fcl path
                collision free BOOLEAN", "fcl path min clearance REAL") and meshgap's exact least clearance over the
                same states ("path min clearance REAL", negative in collision). */
            void pathProperties(const ompl::geometric::PathGeometric &solution,
                                ompl::tools::Benchmark::RunProperties &run);

        private:
            void setStartAndGoal(const RobotProblem &problem);
            void setObjective(const RobotProblem &problem, const std::string &objective);

            RobotSceneConstPtr scene_;
            std::shared_ptr<ompl::geometric::SimpleSetup> setup_;
            std::vector<std::string> names_;
            /** \brief A rigid body's link Scene and its checkers: certified, fast, and certified with the clearance
                motion validator; null for other robots. */
            SceneConstPtr linkScene_;
            ClearanceCheckerPtr certified_, fast_, cmvChecker_;
            /** \brief Another robot's checker, and its certified motion validator (timed into its counters). */
            std::shared_ptr<CountingRobotChecker> robotChecker_;
            ompl::base::MotionValidatorPtr certifiedMotion_;
    #ifdef MESHGAP_HAVE_FCL
            std::shared_ptr<FclChecker> fcl_;
    #endif
            std::string file_, active_;
            bool certifyAnswer_{false};  ///< the installed checker plans through CertifiedAnswerPlanner
        };
    }  // namespace cli
}  // namespace meshgap

#endif
