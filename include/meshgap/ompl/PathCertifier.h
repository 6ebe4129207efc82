#ifndef MESHGAP_OMPL_PATH_CERTIFIER_H
#define MESHGAP_OMPL_PATH_CERTIFIER_H

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>

#include <vector>

namespace meshgap
{
    /**
       @anchor mgPathCertifier
       @par Short description
       Makes every motion of a path accepted by a certified motion validator: the one of the SpaceInformation it is
       given (RobotMotionValidator, ClearanceMotionValidator: a motion it accepts is proven free). Each motion of the
       path is put to that validator once; a motion it refuses (one that a sampled check let through, which cuts an
       obstacle between two checked states or passes too close to be proven free) is replanned between its two
       states with RRTConnect in that same SpaceInformation, so that every motion of the detour is one the
       validator accepted, in steps of repairRange() of the motion's length, for at most repairIterations()
       iterations of the planner (and until the termination condition). The path's own states are never moved,
       only states inserted between them. Unlike CertifiedPathRepair (one rigid body, bisection up the exact clearance gradient first), it needs
       nothing but the validator: any state space, any robot. Not thread-safe (one path at a time).
    */
    class PathCertifier
    {
    public:
        /** \brief What the last certify() did. */
        struct Stats
        {
            unsigned motions{0};   ///< motions of the input put to the certified validator
            unsigned refused{0};   ///< of those, refused
            unsigned repaired{0};  ///< of those, replaced by a certified detour
            unsigned inserted{0};  ///< states inserted into the path
            double seconds{0.0};        ///< the whole certify()
            double repairSeconds{0.0};  ///< of which replanning
        };

        /** \brief \e si: its motion validator is the certified one; its validity checker the problem's. */
        explicit PathCertifier(ompl::base::SpaceInformationPtr si);

        /** \brief Certify \e path in place: true when every motion of it is accepted by the certified validator
            (after the repairs, states inserted); false, the path left as it was, when a refused motion could not be
            repaired within repairIterations() (or before \e ptc). The checks themselves run whatever \e ptc says
            (each is bounded); only the repairs stop at it. A path of fewer than two states is certified as it is. */
        bool certify(ompl::geometric::PathGeometric &path, const ompl::base::PlannerTerminationCondition &ptc);

        const Stats &lastStats() const { return stats_; }

        /** \brief Iterations of RRTConnect (termination-condition checks) allowed to repair one refused motion
            (default 2000; 0: no repair, a refused motion fails the path). */
        void setRepairIterations(unsigned n) { repairIterations_ = n; }
        unsigned repairIterations() const { return repairIterations_; }
        /** \brief The repairing RRTConnect's range, a fraction of the refused motion's length (default 0.1; OMPL's
            own, a fifth of the space's extent, makes each step a long motion, costly to prove). */
        void setRepairRange(double fraction);
        double repairRange() const { return repairRange_; }

    private:
        /** \brief The interior states of a certified path from \e a to \e b, appended to \e out (every one
            allocated here); false, \e out as it was, when none is found. */
        bool replan(const ompl::base::State *a, const ompl::base::State *b, std::vector<ompl::base::State *> &out,
                    const ompl::base::PlannerTerminationCondition &ptc);

        ompl::base::SpaceInformationPtr si_;
        Stats stats_;
        unsigned repairIterations_{2000};
        double repairRange_{0.1};
    };
}  // namespace meshgap

#endif
