#include "meshgap/ompl/RobotChecker.h"

#include <algorithm>
#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/ThreadInstances.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/JointGradient.h"

namespace meshgap
{
    namespace
    {
        /** \brief This thread's working memory for one checker (keyed by the checker's unique id). */
        struct ThreadState
        {
            RobotWarmStart warm;
            std::vector<double> values, other, moves, step;
            std::vector<Eigen::Isometry3d> frames;
            RobotResult result;
        };

        /** \brief A thread keeps its working memory for its last few checkers (threadInstanceFor()). */
        constexpr std::size_t STATES_PER_THREAD = 8;

        ThreadState &threadStateFor(std::uint64_t id)
        {
            return threadInstanceFor<ThreadState, STATES_PER_THREAD>(id);
        }
    }  // namespace

    RobotChecker::RobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene)
        : ompl::base::StateValidityChecker(si),
          scene_(scene ? std::move(scene) : throw Exception("RobotChecker", "no robot scene")),
          id_(newInstanceId()),
          bound_(scene_->robot())
    {
        specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
        levers_ = robotTangentLevers(scene_->robot());
        const double longest = levers_.empty() ? 0.0 : *std::max_element(levers_.begin(), levers_.end());
        lengthScale_ = longest > 0.0 ? longest : 1.0;
        for (double &lever : levers_)
            lever = std::max(lever, 1e-9 * lengthScale_);
    }

    bool RobotChecker::isValid(const ompl::base::State *state) const
    {
        counts_.add(0, 1);
        if (!si_->satisfiesBounds(state))
            return false;  // outside the joint limits or the volume: invalid, as OMPL expects, never an exception
        ThreadState &t = threadStateFor(id_);
        robotStateToVector(*si_->getStateSpace(), state, t.values);
        return !scene_->inCollision(t.values.data(), t.values.size(), t.warm);
    }

    double RobotChecker::clearance(const ompl::base::State *state) const
    {
        ThreadState &t = threadStateFor(id_);
        distance(state, RobotRequest(), t.result);
        return t.result.distance;
    }

    void RobotChecker::distance(const ompl::base::State *state, const RobotRequest &request, RobotResult &result) const
    {
        ThreadState &t = threadStateFor(id_);
        robotStateToVector(*si_->getStateSpace(), state, t.values);
        scene_->distance(t.values.data(), t.values.size(), request, t.warm, result);
    }

    double RobotChecker::clearanceOrContact(const ompl::base::State *state) const
    {
        ThreadState &t = threadStateFor(id_);
        RobotRequest request;
        request.stopBelow = 0.0;
        distance(state, request, t.result);
        return t.result.inCollision ? std::min(t.result.distance, 0.0) : t.result.distance;
    }

    double RobotChecker::clearanceBelow(const ompl::base::State *state, double bound) const
    {
        if (!(bound > 0.0))
            throw Exception("RobotChecker::clearanceBelow", "the bound must be positive");
        ThreadState &t = threadStateFor(id_);
        RobotRequest request;
        request.stopBelow = 0.0;
        request.upperBound = bound;
        distance(state, request, t.result);
        if (t.result.inCollision)
            return std::min(t.result.distance, 0.0);
        return t.result.atLeast ? bound : std::min(t.result.distance, bound);
    }

    double RobotChecker::sweep(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        ThreadState &t = threadStateFor(id_);
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        robotStateToVector(space, s1, t.values);
        robotStateToVector(space, s2, t.other);
        bound_.linkDisplacements(t.values, t.other, t.moves);
        double most = 0.0;
        for (std::size_t i = 0; i < scene_->links().size(); ++i)
            most = std::max(most, t.moves[i]);
        for (const auto &[a, b] : scene_->selfPairs())
            most = std::max(most, bound_.pairDisplacement(a, b, t.values, t.other));
        return most;
    }

    double RobotChecker::gradient(const ompl::base::State *state, std::vector<double> &gradient,
                                  const ClearanceGradientOptions & /*options*/, ClearanceGradientInfo *info) const
    {
        ThreadState &t = threadStateFor(id_);
        distance(state, RobotRequest(), t.result);
        const RobotModel &robot = scene_->robot();
        robot.framePoses(t.values.data(), t.values.size(), t.frames);
        Eigen::VectorXd g;
        const bool direction = robotClearanceGradient(robot, *scene_, t.frames, t.result, g);
        gradient.assign(g.data(), g.data() + g.size());
        if (info != nullptr)
        {
            *info = ClearanceGradientInfo();
            info->inCollision = t.result.inCollision;
            info->hasDirection = direction;
            info->activePairs = direction ? 1 : 0;
        }
        return t.result.distance;
    }

    double RobotChecker::gradientNorm2(const std::vector<double> &gradient) const
    {
        double g2 = 0.0;
        for (std::size_t k = 0; k < gradient.size(); ++k)
            g2 += gradient[k] * gradient[k] / (levers_[k] * levers_[k]);
        return g2;
    }

    void RobotChecker::ascentStep(const std::vector<double> &gradient, double alpha, std::vector<double> &step) const
    {
        step.resize(gradient.size());
        for (std::size_t k = 0; k < gradient.size(); ++k)
            step[k] = alpha * gradient[k] / (levers_[k] * levers_[k]);
    }

    void RobotChecker::applyStep(const ompl::base::State *state, const double *step, ompl::base::State *out) const
    {
        ThreadState &t = threadStateFor(id_);
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        robotStateToVector(space, state, t.values);
        t.step.resize(t.values.size());
        applyRobotStep(scene_->robot(), t.values.data(), step, t.step.data());
        robotStateFromVector(space, t.step, out);
    }
}  // namespace meshgap
