#include "meshgap/ompl/RobotChecker.h"

#include <atomic>
#include <unordered_map>

#include "meshgap/Exception.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    namespace
    {
        std::atomic<std::uint64_t> nextCheckerId{1};

        /** \brief This thread's working memory for one checker (keyed by the checker's unique id). */
        struct ThreadState
        {
            RobotWarmStart warm;
            std::vector<double> values;
            RobotResult result;
        };

        ThreadState &threadStateFor(std::uint64_t id)
        {
            thread_local std::unordered_map<std::uint64_t, ThreadState> states;
            return states[id];
        }
    }  // namespace

    RobotChecker::RobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene)
        : ompl::base::StateValidityChecker(si), scene_(std::move(scene)), id_(nextCheckerId++)
    {
        if (!scene_)
            throw Exception("RobotChecker", "no robot scene");
        specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
    }

    bool RobotChecker::isValid(const ompl::base::State *state) const
    {
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

    void RobotChecker::distance(const ompl::base::State *state, const RobotRequest &request,
                                RobotResult &result) const
    {
        ThreadState &t = threadStateFor(id_);
        robotStateToVector(*si_->getStateSpace(), state, t.values);
        scene_->distance(t.values.data(), t.values.size(), request, t.warm, result);
    }
}  // namespace meshgap
