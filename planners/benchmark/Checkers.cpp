#include "benchmark/Checkers.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>
#include <sstream>

#include "benchmark/BenchmarkLog.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/CertifiedAnswerPlanner.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "meshgap/robot/RigidBodyRobot.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief How a checker of the menu checks states and motions. */
            enum class Validity
            {
                CERTIFIED,  ///< meshgap's exact checker (certified clearance)
                FAST,       ///< ClearanceChecker's fast clearance (a rigid body's only)
                FCL         ///< FclChecker
            };

            enum class Motion
            {
                DISCRETE,   ///< OMPL's DiscreteMotionValidator
                CERTIFIED,  ///< meshgap's certified motion validator on every motion
                ANSWER      ///< a sampled search, every motion of its answer certified (CertifiedAnswerPlanner)
            };

            struct Recipe
            {
                const char *name;
                Validity validity;
                Motion motion;
            };

            /** \brief The menu of one rigid body, checked by its link's Scene (the names OMPL.app's problems have
                always had), and the menu of any other robot. */
            const std::vector<Recipe> RIGID_BODY = {{"certified", Validity::CERTIFIED, Motion::DISCRETE},
                                                    {"fast", Validity::FAST, Motion::DISCRETE},
                                                    {"certified-cmv", Validity::CERTIFIED, Motion::CERTIFIED},
                                                    {"fcl", Validity::FCL, Motion::DISCRETE}};
            const std::vector<Recipe> ROBOT = {{"certified", Validity::CERTIFIED, Motion::ANSWER},
                                               {"certified-search", Validity::CERTIFIED, Motion::CERTIFIED},
                                               {"discrete", Validity::CERTIFIED, Motion::DISCRETE},
                                               {"fcl", Validity::FCL, Motion::DISCRETE}};

            /** \brief True when \e robot is one rigid body: one link placed by its one SE(2) or SE(3) state block
                exactly where poseFromState() places a body (no offset), so its link's Scene answers it. */
            bool isOneRigidBody(const RobotModel &robot)
            {
                const std::vector<StateBlock> blocks = robot.stateBlocks();
                if (robot.links().size() != 1 || blocks.size() != 1 ||
                    (blocks[0].space != JointSpace::SE2 && blocks[0].space != JointSpace::SE3))
                    return false;
                const RigidSpace space = blocks[0].space == JointSpace::SE2 ? RigidSpace::SE2 : RigidSpace::SE3;
                const Eigen::Isometry3d pose = Eigen::Translation3d(0.3, -0.7, space == RigidSpace::SE2 ? 0.0 : 1.1) *
                                               Eigen::AngleAxisd(0.4, space == RigidSpace::SE2 ?
                                                                          Eigen::Vector3d::UnitZ() :
                                                                          Eigen::Vector3d(0.2, -0.5, 0.8).normalized());
                return robot.linkPoses(rigidState(space, pose))[0].isApprox(pose, 1e-12);
            }

            const std::vector<Recipe> &menuOf(const RobotModel &robot)
            {
                return isOneRigidBody(robot) ? RIGID_BODY : ROBOT;
            }

            std::vector<std::string> namesOf(const std::vector<Recipe> &menu)
            {
                std::vector<std::string> names;
                for (const Recipe &r : menu)
    #ifndef MESHGAP_HAVE_FCL
                    if (r.validity != Validity::FCL)
    #endif
                        names.push_back(r.name);
                return names;
            }

            std::uint64_t nanosecondsSince(std::chrono::steady_clock::time_point start)
            {
                return static_cast<std::uint64_t>(
                    std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
                        .count());
            }

            /** \brief A motion validator that times another's checkMotion() into the checker's counters. */
            class TimedMotionValidator : public ob::MotionValidator
            {
            public:
                TimedMotionValidator(const ob::SpaceInformationPtr &si, ob::MotionValidatorPtr inner,
                                     std::shared_ptr<const CountingRobotChecker> checker)
                  : ob::MotionValidator(si), inner_(std::move(inner)), checker_(std::move(checker))
                {
                }

                bool checkMotion(const ob::State *s1, const ob::State *s2) const override
                {
                    const auto start = std::chrono::steady_clock::now();
                    const bool valid = inner_->checkMotion(s1, s2);
                    checker_->addTime(nanosecondsSince(start));
                    valid ? ++valid_ : ++invalid_;
                    return valid;
                }

                bool checkMotion(const ob::State *s1, const ob::State *s2,
                                 std::pair<ob::State *, double> &lastValid) const override
                {
                    const auto start = std::chrono::steady_clock::now();
                    const bool valid = inner_->checkMotion(s1, s2, lastValid);
                    checker_->addTime(nanosecondsSince(start));
                    valid ? ++valid_ : ++invalid_;
                    return valid;
                }

            private:
                ob::MotionValidatorPtr inner_;
                std::shared_ptr<const CountingRobotChecker> checker_;
            };

            /** \brief The 3-D box a floating base or rigid bodies move in: the problem's volume; a robot that does
                not move free needs none (a unit box stands in). */
            ob::RealVectorBounds boundsOf(const RobotProblem &problem)
            {
                ob::RealVectorBounds bounds(3);
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

            /** \brief robotStateSpace(), or for one rigid body the SE(2) or SE(3) space of its one block: it plans
                in that space, as OMPL.app's problems do. */
            ob::StateSpacePtr planningSpace(const RobotProblem &problem)
            {
                if (problem.robot->dimension() == 0)
                    throw Exception(problem.file, "the robot has no movable joint (a fixed robot): there is nothing "
                                                  "to plan; meshgap_distance --cfg gives its clearance");
                const ob::StateSpacePtr space = robotStateSpace(*problem.robot, boundsOf(problem));
                const auto *compound = space->as<ob::CompoundStateSpace>();
                return isOneRigidBody(*problem.robot) ? compound->getSubspace(0) : space;
            }

            /** \brief The pair that attains \e r and its signed distance, for an error message. */
            std::string pairText(const RobotScene &scene, const RobotResult &r)
            {
                std::ostringstream text;
                text.precision(6);
                text << "link " << quote(scene.links()[r.link].name) << " against "
                     << (r.selfPair ? "link " + quote(scene.links()[r.other].name) :
                                      "obstacle " + std::to_string(r.other) + " of " +
                                          std::to_string(scene.obstacles().size()))
                     << " near (" << r.onB.x() << ", " << r.onB.y() << ", " << r.onB.z() << ")";
                if (r.distance < -1e-12)
                    text << ": signed distance " << r.distance << " (penetration depth " << -r.distance << ")";
                else
                    text << ": the surfaces touch or cross (no penetration depth found)";
                return text.str();
            }
        }  // namespace

        std::vector<std::string> checkerNames(const RobotModel &robot)
        {
            return namesOf(menuOf(robot));
        }

        std::string checkerMenuText()
        {
            return "one rigid body: " + joinNames(namesOf(RIGID_BODY)) + "; any other robot: " +
                   joinNames(namesOf(ROBOT));
        }

        bool CountingRobotChecker::isValid(const ob::State *state) const
        {
            const auto start = std::chrono::steady_clock::now();
            ++validityCalls_;
            const bool valid = RobotChecker::isValid(state);
            nanoseconds_ += nanosecondsSince(start);
            return valid;
        }

        double CountingRobotChecker::clearance(const ob::State *state) const
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

        Checkers::Checkers(const RobotProblem &problem, const std::string &objective)
          : names_(checkerNames(*problem.robot)), file_(problem.file)
        {
            if (!problem.goal)
                throw Exception(problem.file, "no goal (goal.x ..., goal.joints, or goal.N.* for every body)");
            setup_ = std::make_shared<ompl::geometric::SimpleSetup>(planningSpace(problem));
            scene_ = planningScene(problem);
            const ob::SpaceInformationPtr si = setup_->getSpaceInformation();
            if (&menuOf(*problem.robot) == &RIGID_BODY)
            {
                // The link's own Scene, shared with the robot scene that owns it.
                linkScene_ = SceneConstPtr(scene_, &scene_->linkScene(0));
                certified_ = std::make_shared<ClearanceChecker>(si, linkScene_, ClearanceChecker::Mode::CERTIFIED);
            }
            else
            {
                robotChecker_ = std::make_shared<CountingRobotChecker>(si, scene_);
                certifiedMotion_ = std::make_shared<TimedMotionValidator>(
                    si, allocMotionValidator("clearance", si, scene_, "--checker"), robotChecker_);
            }
    #ifdef MESHGAP_HAVE_FCL
            fcl_ = std::make_shared<FclChecker>(si, scene_);
    #endif
            install(names_.front());
            setStartAndGoal(problem);
            setObjective(problem, objective);
            if (!problem.sampler.empty())
                setValidStateSampler(*si, problem.sampler, problem.file + ": [problem] sampler");
        }

        void Checkers::setStartAndGoal(const RobotProblem &problem)
        {
            const ob::SpaceInformationPtr si = setup_->getSpaceInformation();
            ob::ScopedState<> start(si), goal(si);
            robotStateFromVector(*si->getStateSpace(), problem.start, start.get());
            robotStateFromVector(*si->getStateSpace(), *problem.goal, goal.get());
            for (const auto &[label, state] : {std::make_pair("start", &start), std::make_pair("goal", &goal)})
            {
                if (!si->satisfiesBounds(state->get()))
                    throw Exception(problem.file, std::string(label) + " lies outside the volume (or the joint "
                                                                       "limits)");
                if (!si->isValid(state->get()))
                {
                    RobotResult r;
                    scene_->distance(label == std::string("start") ? problem.start : *problem.goal, RobotRequest(), r);
                    throw Exception(problem.file, std::string(label) + " is in collision: " + pairText(*scene_, r));
                }
            }
            setup_->setStartAndGoalStates(start, goal);
        }

        void Checkers::setObjective(const RobotProblem &problem, const std::string &objective)
        {
            const std::string name = !objective.empty() ? objective : !problem.objective.empty() ? problem.objective :
                                                                                                    "length";
            const ob::SpaceInformationPtr si = setup_->getSpaceInformation();
            try
            {
                setup_->setOptimizationObjective(allocObjective(name, si));
            }
            catch (const Exception &e)
            {
                throw Exception(problem.file, e.what());
            }
            if (problem.objectiveThreshold)
                setup_->getOptimizationObjective()->setCostThreshold(ob::Cost(*problem.objectiveThreshold));
        }

        void Checkers::install(const std::string &name)
        {
            const std::vector<Recipe> &menu = certified_ ? RIGID_BODY : ROBOT;
            const auto recipe = std::find_if(menu.begin(), menu.end(), [&](const Recipe &r) { return r.name == name; });
            if (std::find(names_.begin(), names_.end(), name) == names_.end() || recipe == menu.end())
                throw Exception("--checker", "unknown checker " + quote(name) + "; valid names: " + joinNames(names_));
            const ob::SpaceInformationPtr si = setup_->getSpaceInformation();
            ob::StateValidityCheckerPtr checker = certified_ ? ob::StateValidityCheckerPtr(certified_) : robotChecker_;
            ob::MotionValidatorPtr validator;
            if (recipe->validity == Validity::FAST)
                checker = fast_ ? fast_ :
                                  (fast_ = std::make_shared<ClearanceChecker>(si, linkScene_,
                                                                              ClearanceChecker::Mode::FAST));
    #ifdef MESHGAP_HAVE_FCL
            else if (recipe->validity == Validity::FCL)
                checker = fcl_;
    #endif
            if (recipe->motion != Motion::DISCRETE && certified_)
            {
                // A certified checker of its own: its warm starts and counters apart from the other slices'.
                if (!cmvChecker_)
                {
                    cmvChecker_ = std::make_shared<ClearanceChecker>(si, linkScene_,
                                                                     ClearanceChecker::Mode::CERTIFIED);
                    certifiedMotion_ = allocMotionValidator("clearance", si, cmvChecker_, "--checker");
                }
                checker = cmvChecker_;
            }
            if (recipe->motion == Motion::CERTIFIED || recipe->motion == Motion::ANSWER)
                validator = certifiedMotion_;
            active_ = name;
            certifyAnswer_ = recipe->motion == Motion::ANSWER;
            si->setStateValidityChecker(checker);
            si->setMotionValidator(validator ? validator : allocMotionValidator("discrete", si, scene_, "--checker"));
        }

        ob::PlannerPtr Checkers::allocPlanner(const PlannerAllocator &allocate)
        {
            const ob::SpaceInformationPtr &si = setup_->getSpaceInformation();
            if (certifyAnswer_)
            {
                // The space set up before the twins a CertifiedAnswerPlanner sets up on it (else the projection the
                // Benchmark prints with the settings is one a twin replaced). Nothing else is set up ahead of the
                // runs: the runs' random streams are the seed's own.
                if (!si->isSetup())
                    si->setup();
                return std::make_shared<CertifiedAnswerPlanner>(si, allocate);
            }
            return allocate(si);
        }

        CheckerStats Checkers::stats() const
        {
    #ifdef MESHGAP_HAVE_FCL
            if (active_ == "fcl")
                return fcl_->stats();
    #endif
            if (robotChecker_)
                return robotChecker_->stats();
            return std::static_pointer_cast<const ClearanceChecker>(
                       setup_->getSpaceInformation()->getStateValidityChecker())
                ->stats();
        }

        void Checkers::pathProperties(const ompl::geometric::PathGeometric &solution,
                                      ompl::tools::Benchmark::RunProperties &run)
        {
            ompl::geometric::PathGeometric path(solution);
            const ob::StateSpacePtr &space = setup_->getStateSpace();
            const unsigned factor = space->getValidSegmentCountFactor();
            space->setValidSegmentCountFactor(4 * factor);
            path.interpolate();
            space->setValidSegmentCountFactor(factor);
            // meshgap's exact whole-robot clearance at every state of the same dense path: its least.
            const std::vector<ob::State *> &states = path.getStates();
            RobotWarmStart warm;
            RobotResult r;
            std::vector<double> q, clearance(states.size());
            for (std::size_t i = 0; i < states.size(); ++i)
            {
                robotStateToVector(*space, states[i], q);
                scene_->distance(q.data(), q.size(), RobotRequest(), warm, r);
                clearance[i] = r.distance;
            }
            run["path min clearance REAL"] =
                real(states.empty() ? std::numeric_limits<double>::infinity()
                                    : *std::min_element(clearance.begin(), clearance.end()));
    #ifdef MESHGAP_HAVE_FCL
            // FCL's verdict at every state; its least distance over them all, each state asked only whether it is
            // nearer than the least so far (the states in the order of meshgap's clearance, which only makes the
            // bound tight early: FCL answers every state).
            bool free = true;
            for (const ob::State *s : states)
                free = free && !fcl_->inCollision(fcl_->pose(s));
            double fclLeast = free ? std::numeric_limits<double>::infinity() : 0.0;
            std::vector<std::size_t> order(states.size());
            std::iota(order.begin(), order.end(), std::size_t(0));
            std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return clearance[a] < clearance[b]; });
            for (std::size_t k = 0; free && k < order.size(); ++k)
                fclLeast = fcl_->distance(fcl_->pose(states[order[k]]), fclLeast);
            run["fcl path states INTEGER"] = std::to_string(path.getStateCount());
            run["fcl path collision free BOOLEAN"] = free ? "1" : "0";
            run["fcl path min clearance REAL"] = real(fclLeast);
    #endif
        }
    }  // namespace cli
}  // namespace meshgap
