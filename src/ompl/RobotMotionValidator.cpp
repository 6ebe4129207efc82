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

    bool RobotMotionValidator::pairClearances(const std::vector<double> &q, double bound,
                                              std::vector<double> &pairs) const
    {
        thread_local RobotWarmStart warm;
        thread_local RobotResult result;
        RobotRequest request;
        request.everyPair = true;
        // A pair at or beyond the bound is answered AT_LEAST with the bound as its distance: enough for any
        // segment whose displacement bound is at most it (the other end's clearance being positive).
        request.upperBound = bound > 0.0 ? bound : std::numeric_limits<double>::min();
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

    double RobotMotionValidator::largestReach(const std::vector<double> &moves) const
    {
        const std::size_t links = scene_->links().size();
        double largest = 0.0;
        for (std::size_t i = 0; i < links; ++i)
            largest = std::max(largest, moves[i]);
        for (const LinkPair &p : scene_->selfPairs())
            largest = std::max(largest, moves[p.first] + moves[p.second]);
        return largest;
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
        std::vector<double> moves;
        bound_.linkDisplacements(first.q0, first.q1, moves);
        const double whole = largestReach(moves);
        if (!pairClearances(first.q0, whole, first.d0) || !pairClearances(first.q1, whole, first.d1))
        {
            invalid_++;
            return false;
        }
        const std::size_t links = scene_->links().size();
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
            if (!pairClearances(left.q1, largestReach(moves), left.d1))
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
