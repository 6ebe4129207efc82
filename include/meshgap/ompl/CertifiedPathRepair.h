#ifndef MESHGAP_OMPL_CERTIFIED_PATH_REPAIR_H
#define MESHGAP_OMPL_CERTIFIED_PATH_REPAIR_H

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>

#include <memory>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include "meshgap/ompl/ClearanceField.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"

namespace meshgap
{
    /**
       @anchor mgCertifiedPathRepair
       @par Short description
       Makes every motion of a path accepted by the certified motion validator (allocCertifiedMotionValidator():
       ClearanceMotionValidator for one body, RobotMotionValidator for a robot of many; the path is then proven
       collision-free everywhere, not only at samples). A planner run with OMPL's sampled motion validator may return
       a motion that cuts a corner or a thin obstacle between two checked states, or that passes an obstacle closer
       than conservative advancement can prove free; each motion the certified validator refuses is repaired, by
       the second way only if the first fails:
       - bisection: the motion's middle state is pushed up the exact clearance gradient (ClearanceField::gradient(); out
         of the obstacle along the penetration direction where it collides, for one rigid body) until it is at least as
         clear as the motion's less clear end or the ascent stalls, and each half is repaired the same way, at most
         max_depth levels deep;
       - replanning: RRTConnect from the motion's first state to its last, in a SpaceInformation whose motion
         validator is the certified one (every motion of its path is certified), until the termination condition;
         its path's redundant states are then removed (PathSimplifier::reduceVertices() with the same validator).
       The path's own states are never moved, only states inserted between them. They must be valid (within bounds,
       collision-free): repair() throws meshgap::Exception naming a state that is not, and names the motion
       ("motion i→j", the input's numbering) it could not repair before the termination condition; the path is
       then left as it was. Needs a certified ClearanceField (a ClearanceChecker in CERTIFIED mode, a RobotChecker).
       Not thread-safe (one path at a time); the checker it shares is.
    */
    class CertifiedPathRepair
    {
    public:
        /** \brief What the last repair() did. */
        struct Stats
        {
            unsigned refused{0};    ///< motions of the input the certified validator refused
            unsigned bisected{0};   ///< of those, repaired by bisection
            unsigned replanned{0};  ///< of those, repaired by replanning
            unsigned inserted{0};   ///< states inserted into the path
            double seconds{0.0};
        };

        /** \brief \e checker: the space's validity checker as a clearance field (ClearanceField), certified. */
        CertifiedPathRepair(const ompl::base::SpaceInformationPtr &si, ClearanceFieldPtr checker);

        /** \brief Repair every motion of \e path the certified validator refuses, in place, until \e ptc; returns
            true if states were inserted. Throws meshgap::Exception as the class description says. */
        bool repair(ompl::geometric::PathGeometric &path, const ompl::base::PlannerTerminationCondition &ptc);

        const Stats &lastStats() const { return stats_; }

        /** \brief Levels of bisection at most (default 10; 0: replan every refused motion). */
        void setMaxDepth(unsigned depth) { maxDepth_ = depth; }
        unsigned getMaxDepth() const { return maxDepth_; }
        /** \brief Replan what bisection cannot repair (default true). */
        void setReplan(bool on) { replan_ = on; }
        bool getReplan() const { return replan_; }

    private:
        void validateStates(const ompl::geometric::PathGeometric &path) const;
        /** \brief States that make a -> b certified, appended to \e out (every one allocated here); false, with
            \e out as it was, if none are found within \e depth levels. */
        bool bisect(const ompl::base::State *a, double ca, const ompl::base::State *b, double cb, unsigned depth,
                    std::vector<ompl::base::State *> &out, const ompl::base::PlannerTerminationCondition &ptc);
        /** \brief Move \e s up the clearance gradient until its clearance reaches \e target or no step raises it;
            returns its clearance. */
        double pushOut(ompl::base::State *s, double target, const ompl::base::PlannerTerminationCondition &ptc);
        /** \brief The interior states of a certified path a -> b found by RRTConnect, appended to \e out. */
        bool replan(const ompl::base::State *a, const ompl::base::State *b, std::vector<ompl::base::State *> &out,
                    const ompl::base::PlannerTerminationCondition &ptc);
        void freeFrom(std::vector<ompl::base::State *> &states, std::size_t first) const;

        ompl::base::SpaceInformationPtr si_;
        ClearanceFieldPtr checker_;
        ompl::base::MotionValidatorPtr validator_;
        /** \brief The replanning's space information (the same state space and checker, the certified validator),
            made when first needed. */
        ompl::base::SpaceInformationPtr replanSi_;
        Stats stats_;
        unsigned maxDepth_{10};
        bool replan_{true};
        static constexpr unsigned MAX_PUSH_STEPS = 40;
    };
}  // namespace meshgap

#endif
