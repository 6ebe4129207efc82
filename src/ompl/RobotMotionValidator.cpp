#include "meshgap/ompl/RobotMotionValidator.h"

#include <ompl/base/SpaceInformation.h>

#include "meshgap/Exception.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    RobotMotionValidator::RobotMotionValidator(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene,
                                               const UrdfRobot &robot)
        : ompl::base::MotionValidator(si), scene_(std::move(scene)), bound_(robot)
    {
        if (!scene_)
            throw Exception("RobotMotionValidator", "no robot scene");
        if (scene_->links().size() != robot.links().size())
            throw Exception("RobotMotionValidator", "the robot scene was built with another set of links");
    }

    bool RobotMotionValidator::pairClearances(const std::vector<double> &q, double needed,
                                              std::vector<double> &pairs) const
    {
        thread_local RobotWarmStart warm;
        thread_local RobotResult result;
        RobotRequest request;
        request.everyPair = true;
        // A pair at least `needed` away is proven on every segment it takes part in: its lower bound will do.
        request.upperBound = std::max(needed, 1e-12);
        scene_->distance(q.data(), q.size(), request, warm, result);
        if (result.inCollision)
            return false;
        pairs.resize(result.pairs.size());
        for (std::size_t k = 0; k < pairs.size(); ++k)
            pairs[k] = result.pairs[k].status == RobotPairAnswer::Status::NOT_CHECKED
                           ? std::numeric_limits<double>::infinity()
                           : result.pairs[k].distance;
        return true;
    }

    bool RobotMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        struct Segment
        {
            double t0, t1;
            std::vector<double> q0, q1, d0, d1;
            int depth;
        };
        Segment first{0.0, 1.0, {}, {}, {}, {}, 0};
        robotStateToVector(space, s1, first.q0);
        robotStateToVector(space, s2, first.q1);
        const std::size_t links = scene_->links().size();
        std::vector<double> moves;
        // The largest displacement bound of any pair over \e s: no pair needs its clearance known beyond it.
        auto largestReach = [&](const Segment &s)
        {
            bound_.linkDisplacements(s.q0, s.q1, moves);
            double most = 0.0;
            for (std::size_t i = 0; i < links; ++i)
                most = std::max(most, moves[i]);
            for (const auto &[a, b] : scene_->selfPairs())
                most = std::max(most, bound_.pairDisplacement(a, b, s.q0, s.q1));
            return most;
        };
        const double reach = largestReach(first);
        if (!pairClearances(first.q0, reach, first.d0) || !pairClearances(first.q1, reach, first.d1))
        {
            invalid_++;
            return false;
        }
        std::vector<Segment> stack{first};
        ompl::base::State *middle = si_->allocState();
        bool free = true;
        while (free && !stack.empty())
        {
            Segment s = std::move(stack.back());
            stack.pop_back();
            bound_.linkDisplacements(s.q0, s.q1, moves);
            bool proven = true;
            for (std::size_t k = 0; k < s.d0.size() && proven; ++k)
            {
                const double reach = k < links ? moves[k]
                                               : bound_.pairDisplacement(scene_->selfPairs()[k - links].first,
                                                                         scene_->selfPairs()[k - links].second,
                                                                         s.q0, s.q1);
                proven = s.d0[k] + s.d1[k] > reach;
            }
            if (proven)
                continue;
            if (s.depth >= 30)
            {
                free = false;
                break;
            }
            // Split at the middle, along OMPL's own interpolation (SO(2) by the shorter arc).
            const double t = 0.5 * (s.t0 + s.t1);
            space.interpolate(s1, s2, t, middle);
            Segment left{s.t0, t, s.q0, {}, s.d0, {}, s.depth + 1}, right{t, s.t1, {}, s.q1, {}, s.d1, s.depth + 1};
            robotStateToVector(space, middle, left.q1);
            if (!pairClearances(left.q1, largestReach(s), left.d1))
            {
                free = false;
                break;
            }
            right.q0 = left.q1;
            right.d0 = left.d1;
            stack.push_back(std::move(right));
            stack.push_back(std::move(left));
        }
        si_->freeState(middle);
        if (free)
            valid_++;
        else
            invalid_++;
        return free;
    }

    bool RobotMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                           std::pair<ompl::base::State *, double> &lastValid) const
    {
        const bool free = checkMotion(s1, s2);
        if (!free)
        {
            if (lastValid.first)
                si_->copyState(lastValid.first, s1);
            lastValid.second = 0.0;
        }
        return free;
    }
}  // namespace meshgap
