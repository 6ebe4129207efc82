#ifndef MESHGAP_PLANNERS_BENCHMARK_CHECKERS_H
#define MESHGAP_PLANNERS_BENCHMARK_CHECKERS_H

// The checkers meshgap_benchmark compares, by name: meshgap's (certified, fast, certified with the clearance motion
// validator) and, when built with FCL, a checker built the way OMPL.app builds its own.

#include <functional>
#include <limits>
#include <memory>
#include <ompl/tools/benchmark/Benchmark.h>
#include <string>
#include <vector>

#include "FclChecker.h"
#include "benchmark/BenchmarkLog.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief The checkers this build can run, in grid order, as --checker spells them (as meshgap_plan does). */
        inline std::vector<std::string> checkerNames()
        {
            std::vector<std::string> names = {"certified", "fast", "certified-cmv"};
    #ifdef MESHGAP_HAVE_FCL
            names.push_back("fcl");
    #endif
            return names;
        }

        /** \brief A checker's label in the .log (planner names, file names, the "checker" property): the library's name
            too, meshgap-certified beside fcl, as before the flags were unified. */
        inline std::string checkerLabel(const std::string &name)
        {
            return name == "fcl" ? name : "meshgap-" + name;
        }

        /** \brief What the benchmark's grid needs of a problem: its SimpleSetup, and checkers (with their motion
            validators) installed into it by name in turn. Checkers serves a single rigid body (OMPL.app's problems),
            RobotCheckers (RobotCheckers.h) a robot of many bodies. */
        class CheckerSet
        {
        public:
            virtual ~CheckerSet() = default;
            virtual ompl::geometric::SimpleSetup &setup() = 0;
            /** \brief Make \e name the problem's validity checker and motion validator. */
            virtual void install(const std::string &name) = 0;
            /** \brief The planner a run of the installed checker uses, made by \e allocate on the SpaceInformation it
                is given: by default \e allocate on the problem's own. */
            virtual ompl::base::PlannerPtr
            allocPlanner(const std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)> &allocate)
            {
                return allocate(setup().getSpaceInformation());
            }
            /** \brief Counters of the installed checker (cumulative). */
            virtual CheckerStats stats() const = 0;
            virtual bool isMeshgap() const = 0;
            /** \brief FCL's verdict on \e path, densely interpolated (4x OMPL's motion-check resolution, as the
                Benchmark's strict check): states checked, whether all are collision-free, the least distance. */
            virtual void fclPathProperties(const ompl::geometric::PathGeometric &solution,
                                           ompl::tools::Benchmark::RunProperties &run) = 0;
        };

        /** \brief One problem, its scene built once, and the checkers installed into its SpaceInformation in turn. */
        class Checkers : public CheckerSet
        {
        public:
            Checkers(const ProblemConfig &config, const std::string &objective)
              : problem_(setupProblem(config, ClearanceChecker::Mode::CERTIFIED, objective))
            {
                si_ = problem_.setup->getSpaceInformation();
    #ifdef MESHGAP_HAVE_FCL
                // FCL gets the meshes as OMPL.app loads them: the robot centred as OMPL.app centres it (x and y only
                // in a 2D problem), the whole world, so the same state is the same pose for both checkers.
                fcl_ = std::make_shared<FclChecker>(si_, loadRobotMesh(config.robot, config.planar),
                                                    loadMesh(config.world));
    #endif
            }

            ompl::geometric::SimpleSetup &setup() override { return *problem_.setup; }
            const OmplProblem &problem() const { return problem_; }

            void install(const std::string &name) override
            {
                ompl::base::StateValidityCheckerPtr checker;
                ompl::base::MotionValidatorPtr validator;
                if (name == "certified")
                    checker = problem_.checker;
                else if (name == "fast")
                    checker = fast_ ? fast_ : (fast_ = std::make_shared<ClearanceChecker>(si_, problem_.scene,
                                                                                          ClearanceChecker::Mode::FAST));
                else if (name == "certified-cmv")
                {
                    if (!cmvChecker_)
                    {
                        cmvChecker_ = std::make_shared<ClearanceChecker>(si_, problem_.scene, ClearanceChecker::Mode::CERTIFIED);
                        cmv_ = allocMotionValidator("clearance", si_, cmvChecker_, "--checker");
                    }
                    checker = cmvChecker_;
                    validator = cmv_;
                }
    #ifdef MESHGAP_HAVE_FCL
                else if (name == "fcl")
                    checker = fcl_;
    #endif
                else
                    throw Exception("--checker", "unknown checker " + quote(name));
                active_ = name;
                si_->setStateValidityChecker(checker);
                si_->setMotionValidator(validator ? validator :
                                                    allocMotionValidator("discrete", si_, problem_.checker, "--checker"));
            }

            CheckerStats stats() const override
            {
    #ifdef MESHGAP_HAVE_FCL
                if (active_ == "fcl")
                    return fcl_->stats();
    #endif
                return std::static_pointer_cast<const ClearanceChecker>(si_->getStateValidityChecker())->stats();
            }

            bool isMeshgap() const override { return active_ != "fcl"; }

            void fclPathProperties(const ompl::geometric::PathGeometric &solution,
                                   ompl::tools::Benchmark::RunProperties &run) override
            {
    #ifdef MESHGAP_HAVE_FCL
                ompl::geometric::PathGeometric path(solution);
                const ompl::base::StateSpacePtr &space = si_->getStateSpace();
                const unsigned factor = space->getValidSegmentCountFactor();
                space->setValidSegmentCountFactor(4 * factor);
                path.interpolate();
                space->setValidSegmentCountFactor(factor);
                bool free = true;
                double least = std::numeric_limits<double>::infinity();
                for (const ompl::base::State *s : path.getStates())
                {
                    const Eigen::Isometry3d X = fcl_->pose(s);
                    const bool collides = fcl_->inCollision(X);
                    free = free && !collides;
                    least = std::min(least, collides ? 0.0 : fcl_->distance(X));
                }
                run["fcl path states INTEGER"] = std::to_string(path.getStateCount());
                run["fcl path collision free BOOLEAN"] = free ? "1" : "0";
                run["fcl path min clearance REAL"] = real(least);
    #else
                (void)solution;
                (void)run;
    #endif
            }

        private:
            OmplProblem problem_;
            ompl::base::SpaceInformationPtr si_;
            ClearanceCheckerPtr fast_, cmvChecker_;
            ompl::base::MotionValidatorPtr cmv_;
    #ifdef MESHGAP_HAVE_FCL
            std::shared_ptr<FclChecker> fcl_;
    #endif
            std::string active_;
        };
    }  // namespace cli
}  // namespace meshgap

#endif
