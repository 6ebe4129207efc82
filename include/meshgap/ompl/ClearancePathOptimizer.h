#ifndef MESHGAP_OMPL_CLEARANCE_PATH_OPTIMIZER_H
#define MESHGAP_OMPL_CLEARANCE_PATH_OPTIMIZER_H

#include <ompl/base/GenericParam.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>

#include <chrono>
#include <functional>
#include <optional>

#include "meshgap/ompl/CertifiedPathRepair.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(ClearancePathOptimizer);

    /**
       @anchor mgClearancePathOptimizer
       @par Short description
       Raises the minimum clearance of a feasible path (from any planner), as ompl::geometric::PathSimplifier shortens
       one: the path's interior states are moved up the exact clearance gradient (ClearanceField::gradient(), an
       epsilon-subgradient where obstacles nearly tie) with a backtracking line search; a state is inserted where a
       motion's clearance dips between its ends (at the dip); states and stretches of path are removed where a single
       motion is no less clear (redundant states, random shortcuts). Every change it accepts keeps every motion of the
       path accepted by the certified motion validator (ClearanceMotionValidator, conservative advancement on exact
       clearance: the path is collision-free everywhere, not only at samples), keeps the path within its length cap, and
       does not lower the clearance of the stretch it replaces. For that it keeps, for each motion, a certified lower
       bound on its clearance, by Lipschitz branch and bound along the motion (clearance is 1-Lipschitz in the robot's
       displacement and ClearanceField::sweep() bounds the displacement, so an interval of the motion whose ends have
       clearances ca, cb is no less clear than (ca + cb - sweep * length) / 2; the most promising interval is halved
       until the bound is within 2% of the least clear sample, or a sample falls below what the change must keep): a
       change is accepted only if the bounds of the motions it creates are at least the smallest bound of the motions it
       removes (and, for a moved state, its own clearance rises). So the path's certified lower bound never falls. At
       the end the path is measured again from scratch with minClearance(), and if it is below the input's measured the
       same way (at the start), the input is returned unchanged: the result is never less clear than the input by that
       measure.

       minClearance() is the measure: the minimum over the path's motions of each motion's least clear sample,
       the same branch and bound run until no interval's bound is more than max(tolerance, 1e-3 * the sample)
       below it: an upper estimate of the true minimum, which is at least it minus that tolerance.

       Parameters (OMPL ParamSet, params(); setters alike): time_limit (s, default 5), target_clearance (stop once the
       minimum reaches it; default infinity), max_length_factor (the path may grow to this times its input length;
       default 3), seed (of the shortcuts' random pairs; default 1), max_rounds (default 1000), shortcut (default true),
       tolerance (of minClearance(); 0, the default: 1e-3 times the input's smallest state clearance, at least 1e-9
       times the robot's length scale), repair (default true). The result depends only on the input, the parameters and
       the seed when no time limit cuts it short (max_rounds reached, or converged: a round accepted no change), and the
       input needs no replanning (CertifiedPathRepair's RRTConnect draws from OMPL's global random seed). The same for
       every robot (ClearanceField): one rigid body (ClearanceChecker in CERTIFIED mode: its gradient in SE(3) or SE(2),
       ClearanceMotionValidator) or a robot of many bodies (RobotChecker: the whole robot's clearance, every link,
       payloads and self pairs, its gradient in joint space (and an SE(3) or SE(2) pose's tangent space),
       RobotMotionValidator); the robot's length scale is ClearanceField::lengthScale(). Needs a certified field (a
       FAST ClearanceChecker throws); an input path with a state out of bounds or in collision throws meshgap::Exception
       naming it. A motion of the input the certified validator refuses (a planner with OMPL's sampled validator may
       pass one that cuts a thin obstacle or grazes one between two checked states) is first repaired by
       CertifiedPathRepair (bisection with the new states pushed up the clearance gradient, else RRTConnect with the
       certified validator), within the same time limit; the optimiser then starts from the repaired path, and every
       "before" figure of lastStats() is of it (Stats::repair says what was repaired). A motion that cannot be repaired
       in time throws meshgap::Exception naming it ("motion i→j"), the path left as it was; with repair (parameter
       "repair") off, any refused motion throws. Not thread-safe (one path at a time); the checker it shares is.
    */
    class ClearancePathOptimizer
    {
    public:
        /** \brief What the last optimize() did. */
        struct Stats
        {
            double minClearanceBefore{0.0}, minClearanceAfter{0.0};
            double lengthBefore{0.0}, lengthAfter{0.0};
            unsigned rounds{0}, moves{0}, inserted{0}, removed{0}, shortcuts{0};
            unsigned statesBefore{0}, statesAfter{0};
            /** \brief The certified lower bound on the result's clearance the optimiser ended with (before the
                final measurement). */
            double lowerBoundAfter{0.0};
            /** \brief The result measured less clear than the input (roundoff): the input was returned. */
            bool restored{false};
            /** \brief What was done to the input's motions the certified validator refused before optimising. */
            CertifiedPathRepair::Stats repair;
            double seconds{0.0};
        };

        /** \brief \e checker: the space's validity checker as a clearance field (a ClearanceChecker in CERTIFIED
            mode for one rigid body, a RobotChecker for a robot of many bodies). */
        ClearancePathOptimizer(const ompl::base::SpaceInformationPtr &si, ClearanceFieldPtr checker);

        /** \brief Optimise \e path in place within time_limit, the whole call included: the rounds stop early enough
            to leave the final measurement of the path (twice as long as the input's took) its time. Returns true if
            its minimum clearance rose. */
        bool optimize(ompl::geometric::PathGeometric &path);
        /** \brief Optimise \e path in place until \e ptc (or max_rounds, target_clearance, convergence). */
        bool optimize(ompl::geometric::PathGeometric &path, const ompl::base::PlannerTerminationCondition &ptc);

        /** \brief The measure optimize() never lowers (see the class description): each motion's minimum to within
            the larger of \e tolerance (0: the default rule applied to this path) and 1e-3 of that minimum. */
        double minClearance(const ompl::geometric::PathGeometric &path, double tolerance = 0.0) const;

        const Stats &lastStats() const { return stats_; }

        /** \brief Called with the two states of every motion optimize() accepts into the path (input motions are
            not reported). For tests and visualisation. */
        void setAcceptedMotionCallback(std::function<void(const ompl::base::State *, const ompl::base::State *)> f)
        {
            onMotion_ = std::move(f);
        }

        ompl::base::ParamSet &params() { return params_; }
        const ompl::base::ParamSet &params() const { return params_; }

        void setTimeLimit(double seconds) { timeLimit_ = seconds; }
        double getTimeLimit() const { return timeLimit_; }
        void setTargetClearance(double c) { target_ = c; }
        double getTargetClearance() const { return target_; }
        void setMaxLengthFactor(double f) { maxLengthFactor_ = f; }
        double getMaxLengthFactor() const { return maxLengthFactor_; }
        void setSeed(unsigned long seed) { seed_ = seed; }
        unsigned long getSeed() const { return seed_; }
        void setMaxRounds(unsigned rounds) { maxRounds_ = rounds; }
        unsigned getMaxRounds() const { return maxRounds_; }
        void setShortcut(bool on) { shortcut_ = on; }
        bool getShortcut() const { return shortcut_; }
        void setTolerance(double t) { tolerance_ = t; }
        double getTolerance() const { return tolerance_; }
        /** \brief Repair the input's motions the certified validator refuses (default true) rather than throw. */
        void setRepair(bool on) { repair_ = on; }
        bool getRepair() const { return repair_; }

    private:
        struct Work;
        /** \brief What motionBound() found along one motion. */
        struct MotionBound
        {
            double lower{0.0};    ///< certified: no state of the motion is less clear (-infinity if refuted)
            double best{0.0};     ///< the least clear state sampled (an upper bound on the minimum)
            double at{0.0};       ///< its fraction of the motion
            bool refuted{false};  ///< a sample below refuteBelow was found (the search stopped there)
        };
        static constexpr unsigned MAX_SAMPLES_PER_MOTION = 4000;
        /** \brief minClearance()'s relative tolerance: a motion's minimum is found to within the larger of the
            tolerance and this fraction of it. */
        static constexpr double MEASURE_RELATIVE_TOLERANCE = 1e-3;
        /** \brief The minimum clearance along s1 -> s2 (clearances \e c1, \e c2 at the ends) by Lipschitz branch
            and bound, until best - lower <= max(tolerance, relative * best), or a sample below \e refuteBelow. */
        MotionBound motionBound(const ompl::base::State *s1, const ompl::base::State *s2, double c1, double c2,
                                double tolerance, double relative = 0.0,
                                double refuteBelow = -std::numeric_limits<double>::infinity()) const;
        /** \brief minClearance(), and into \e bounds (when given) what the branch and bound found along each motion. */
        double measure(const ompl::geometric::PathGeometric &path, double tolerance,
                       std::vector<MotionBound> *bounds) const;
        /** \brief 1e-3 times the smallest of \e clearances (at least 1e-9 times the robot's length scale). */
        double defaultTolerance(const std::vector<double> &clearances) const;
        void validateInput(const ompl::geometric::PathGeometric &path) const;
        /** \brief optimize()'s rounds over \e w until done, converged or out of rounds. */
        void improve(Work &w);
        /** \brief Measure the result as the input was measured (\e inputMeasure): if less clear, put \e input
            back. Fills the after-statistics. */
        void keepTheClearer(ompl::geometric::PathGeometric &path, const ompl::geometric::PathGeometric &input,
                            double inputMeasure, double tolerance);

        ompl::base::SpaceInformationPtr si_;
        ClearanceFieldPtr checker_;
        ompl::base::MotionValidatorPtr validator_;
        ompl::base::ParamSet params_;
        std::function<void(const ompl::base::State *, const ompl::base::State *)> onMotion_;
        Stats stats_;
        /** \brief The termination condition while optimize() changes the path (motionBound() gives up when it
            fires), else null. */
        const ompl::base::PlannerTerminationCondition *ptc_{nullptr};

        double timeLimit_{5.0};
        /** \brief When the timed optimize() must be done by; none for a caller's own termination condition. */
        std::optional<std::chrono::steady_clock::time_point> deadline_;
        double target_{std::numeric_limits<double>::infinity()};
        double maxLengthFactor_{3.0};
        unsigned long seed_{1};
        unsigned maxRounds_{1000};
        bool shortcut_{true};
        double tolerance_{0.0};
        bool repair_{true};
    };
}  // namespace meshgap

#endif
