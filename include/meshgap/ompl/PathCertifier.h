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
       iterations of the planner (and until the termination condition); every other sample of that RRTConnect is
       drawn within the motion's length of a point on it (the space's sampleUniformNear()), the others uniformly,
       so a detour around an obstacle's edge stays near the motion but one that must go far still can. The path's
       own states are never moved,
       only states inserted between them. Given a SpaceInformation with a sampled motion check
       (setSampledSpaceInformation(): the search's), a refused motion is first replanned there, at the price of
       sampled checks, and each motion of that detour is then put to the certified validator in turn, a refused one
       replanned the same way (up to three levels deep); only when that fails is the detour searched with the
       certified validator itself. Unlike CertifiedPathRepair (one rigid body, bisection up the exact clearance gradient first), it needs
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
            unsigned sampled{0};   ///< detours found by the sampled search and proven (nested ones included)
            unsigned detourRefused{0};  ///< motions of sampled detours the certified validator refused
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
        /** \brief The SpaceInformation whose (sampled) motion check searches a detour first, on the same state
            space (null, the default: every detour searched with the certified validator). Throws
            meshgap::Exception for another state space. */
        void setSampledSpaceInformation(ompl::base::SpaceInformationPtr sampled);

    private:
        /** \brief The interior states of a path from \e a to \e b found by RRTConnect in \e si (its motions
            accepted by \e si's motion validator), appended to \e out (each allocated here); false, \e out as it
            was, when none is found within repairIterations(). */
        bool search(const ompl::base::SpaceInformationPtr &si, const ompl::base::State *a,
                    const ompl::base::State *b, std::vector<ompl::base::State *> &out,
                    const ompl::base::PlannerTerminationCondition &ptc) const;
        /** \brief The interior states of a certified path from \e a to \e b appended to \e out: a sampled
            search's, proven (proveDetour()), when \e depth allows, else the certified search's. */
        bool detour(const ompl::base::State *a, const ompl::base::State *b, unsigned depth,
                    std::vector<ompl::base::State *> &out, const ompl::base::PlannerTerminationCondition &ptc);
        /** \brief Put each motion of a -> rough -> b to the certified validator, a refused one replaced by a
            detour one level deeper; on success the states (rough's and the nested detours') appended to \e out,
            else every one of them freed. */
        bool proveDetour(const ompl::base::State *a, const ompl::base::State *b,
                         const std::vector<ompl::base::State *> &rough, unsigned depth,
                         std::vector<ompl::base::State *> &out, const ompl::base::PlannerTerminationCondition &ptc);

        ompl::base::SpaceInformationPtr si_;
        Stats stats_;
        unsigned repairIterations_{2000};
        double repairRange_{0.1};
        ompl::base::SpaceInformationPtr sampled_;
        /** \brief Levels of sampled detours at most (a refused motion of the third is searched certified). */
        static constexpr unsigned SAMPLED_DEPTH = 3;
    };
}  // namespace meshgap

#endif
