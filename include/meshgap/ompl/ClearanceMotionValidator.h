#ifndef MESHGAP_OMPL_CLEARANCE_MOTION_VALIDATOR_H
#define MESHGAP_OMPL_CLEARANCE_MOTION_VALIDATOR_H

#include <ompl/base/MotionValidator.h>

#include "meshgap/ThreadCounters.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/StatePool.h"

namespace meshgap
{
    /**
       @anchor mgClearanceMotionValidator
       @par Short description
       Conservative advancement on certified clearance. Along OMPL's SE(3) interpolation (translation linear,
       rotation by slerp) and its SE(2) interpolation (x, y linear, yaw along the shorter arc, so theta = |dyaw|
       wrapped to [0, pi]), a motion fraction df moves no robot point further than df * (|p2 - p1| + r * theta),
       r the robot's radius about its origin and theta the rotation angle between the two states. So from a state
       at exact clearance c the motion is free for a fraction c / (|p2 - p1| + r * theta); the validator steps by
       that much, and certifies the motion free only if the steps reach s2. A step below minStepFraction (the robot
       grazing an obstacle) is refused rather than taken: the motion is then reported invalid, never guessed free.
       Needs a ClearanceChecker in CERTIFIED mode (its clearance is exact); counts its clearance queries.
       As OMPL's validators do, it assumes s1 is valid.
    */
    class ClearanceMotionValidator : public ompl::base::MotionValidator
    {
    public:
        ClearanceMotionValidator(const ompl::base::SpaceInformationPtr &si, ClearanceCheckerPtr checker);

        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                         std::pair<ompl::base::State *, double> &lastValid) const override;

        /** \brief Smallest step, as a fraction of the motion, the validator takes before refusing (default 1e-4). */
        void setMinStepFraction(double f) { minStepFraction_ = f; }
        double getMinStepFraction() const { return minStepFraction_; }

        /** \brief Clearance queries made, over all threads. */
        std::uint64_t queries() const { return counts_.sum(QUERIES); }
        /** \brief Collision checks of states between s1 and s2 made before advancing (not counting s2), over all
            threads. */
        std::uint64_t probes() const { return counts_.sum(PROBES); }

    private:
        /** \brief Advance from s1 towards s2; returns true if s2 is reached, else the last fraction proven free. */
        bool advance(const ompl::base::State *s1, const ompl::base::State *s2, double &lastFree) const;
        /** \brief Whether s2 or a state at k / n of the motion collides, n = min(validSegmentCount(), 4)
            (exact isValid() checks, middle first). */
        bool probesCollide(const ompl::base::State *s1, const ompl::base::State *s2) const;
        static constexpr unsigned PROBE_SEGMENTS = 4;

        ClearanceCheckerPtr checker_;
        double minStepFraction_{1e-4};
        enum Count : std::size_t
        {
            QUERIES,
            PROBES,
            COUNTS
        };
        mutable StatePool states_;  ///< the working state of each thread checking a motion
        mutable ThreadCounters<COUNTS> counts_;  ///< per thread: threads sharing the validator share no cache line
    };
}  // namespace meshgap

#endif
