#include "meshgap/ompl/ClearanceMotionValidator.h"

#include <algorithm>
#include <cmath>

#include "meshgap/Exception.h"

namespace meshgap
{
    ClearanceMotionValidator::ClearanceMotionValidator(const ompl::base::SpaceInformationPtr &si,
                                                       ClearanceCheckerPtr checker)
      : ompl::base::MotionValidator(si), checker_(std::move(checker)), states_(si->getStateSpace())
    {
        if (!checker_)
            throw Exception("ClearanceMotionValidator", "no checker");
        if (checker_->mode() != ClearanceChecker::Mode::CERTIFIED)
            throw Exception("ClearanceMotionValidator", "needs a checker in CERTIFIED mode (exact clearance)");
    }

    bool ClearanceMotionValidator::advance(const ompl::base::State *s1, const ompl::base::State *s2,
                                           double &lastFree) const
    {
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        const double sweep = sweepBound(space, s1, s2, checker_->scene().robot().radiusAboutOrigin());
        lastFree = 0.0;
        if (sweep == 0.0)
            return true;  // s2 == s1 in pose
        const StatePool::Lease lease(states_);
        ompl::base::State *state = lease.get();
        double f = 0.0;
        bool reached = false;
        SceneRequest request;
        request.computeDepth = false;  // a state in collision ends the advance: its verdict is enough
        for (;;)
        {
            space.interpolate(s1, s2, f, state);
            counts_.add(QUERIES, 1);
            const SceneResult r = checker_->query(state, request);
            if (r.inCollision || !(r.distance > 0.0))  // signed: never step on a zero or negative clearance
                break;
            // The certified distance may exceed the true minimum by the BVH's tie slack (1e-12 relative): step on
            // a slightly smaller clearance so no point ever reaches an obstacle.
            const double step = r.distance * (1.0 - 1e-9) / sweep;
            lastFree = f;
            if (f + step >= 1.0)
            {
                reached = true;
                break;
            }
            if (step < minStepFraction_)
                break;  // grazing: refuse rather than creep (the motion is reported invalid from here)
            f += step;
        }
        return reached;
    }

    bool ClearanceMotionValidator::probesCollide(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        if (!checker_->isValid(s2))
            return true;
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        const unsigned n = std::min(space.validSegmentCount(s1, s2), PROBE_SEGMENTS);
        if (n < 2)
            return false;
        const StatePool::Lease lease(states_);
        ompl::base::State *state = lease.get();
        bool collides = false;
        // The middle first, then the others of the n - 1 states at k / n.
        const unsigned middle = n / 2;
        for (unsigned i = 0; i < n && !collides; ++i)
        {
            const unsigned k = i == 0 ? middle : i;
            if (i > 0 && k == middle)
                continue;
            space.interpolate(s1, s2, static_cast<double>(k) / n, state);
            counts_.add(PROBES, 1);
            collides = !checker_->isValid(state);
        }
        return collides;
    }

    bool ClearanceMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        // s1 is assumed valid (OMPL's contract); s2 is checked by the advancement's last step reaching it, and
        // explicitly, since a motion ending in collision is never valid. First a few exact collision checks (s2,
        // the middle, the quarters, ...; probesCollide()): a motion into or through an obstacle is refused by
        // one of them, a few microseconds, rather than by advancing up to the obstacle, a distance query per step
        // and ever more steps as the clearance shrinks. They can only refuse, and only what the advancement would
        // refuse too (it never passes a state in collision): the answers are the advancement's.
        double lastFree;
        const bool ok = si_->satisfiesBounds(s2) && !probesCollide(s1, s2) && advance(s1, s2, lastFree);
        ok ? ++valid_ : ++invalid_;
        return ok;
    }

    bool ClearanceMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                               std::pair<ompl::base::State *, double> &lastValid) const
    {
        double lastFree = 0.0;
        const bool ok = si_->satisfiesBounds(s2) && advance(s1, s2, lastFree) && checker_->isValid(s2);
        if (!ok)
        {
            if (lastValid.first != nullptr)
                si_->getStateSpace()->interpolate(s1, s2, lastFree, lastValid.first);
            lastValid.second = lastFree;
        }
        ok ? ++valid_ : ++invalid_;
        return ok;
    }
}  // namespace meshgap
