#ifndef MESHGAP_OMPL_CLEARANCE_FIELD_H
#define MESHGAP_OMPL_CLEARANCE_FIELD_H

#include <ompl/base/State.h>

#include <cstdint>
#include <vector>

#include "meshgap/ClassForward.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(ClearanceField);

    /** \brief Settings of a clearance gradient (ClearanceField::gradient(), clearanceGradient()). */
    struct ClearanceGradientOptions
    {
        /** \brief Robot/obstacle pairs whose exact distance is within this of the minimum count as tied (active)
            and all enter the subgradient. Negative (the default): 1e-9 * (1 + the robot's radius about its origin),
            i.e. ties up to roundoff. A larger tolerance gives an epsilon-subgradient: a direction that also respects
            pairs nearly as close, which a line search along it appreciates. */
        double tieTolerance{-1.0};
        /** \brief Probes for near-ties within one obstacle (0, the default: none). A free state's ascent direction
            g is tried with a step that moves the robot by about probeStep; if the clearance there rises by less than
            half the first-order prediction, the closest pair found there joins the tied ones (its gradient, taken at
            the probe) and the minimum-norm element is formed again; up to this many probes. The result is then an
            estimate of the Goldstein epsilon-subgradient (epsilon = probeStep), as gradient sampling methods use. */
        unsigned probes{0};
        /** \brief Length of a probe's step; 0 (the default): 5% of the clearance. */
        double probeStep{0.0};
    };

    /** \brief What a clearance gradient found besides the gradient. */
    struct ClearanceGradientInfo
    {
        bool inCollision{false};
        /** \brief The gradient is a direction: false where the answer has no witness direction (no obstacle, an
            empty scene, or a collision of depth 0 or unknown: CONTACT_DISTANCE, where the reported signed distance
            is locally constant), and the gradient is then zero. */
        bool hasDirection{false};
        /** \brief Pairs combined: 1 where the clearance is smooth (one closest pair), more at a tie. */
        unsigned activePairs{0};
        /** \brief Of those, pairs found by probes (ClearanceGradientOptions::probes). */
        unsigned probedPairs{0};
    };

    /**
       @anchor mgClearanceField
       @par Short description
       The exact clearance as a function on a state space, what the clearance objectives (Objectives.h), the path
       optimiser (ClearancePathOptimizer), its repair (CertifiedPathRepair) and the optimising planner ask of it, for
       any robot: one rigid body (ClearanceChecker) or a robot of many bodies (RobotChecker: URDF arms, payloads,
       several bodies, floating bases; the whole robot's clearance, every link against the obstacles and every self
       pair). What they rely on:
       - clearance() is the exact signed clearance, negative (or 0) in collision; clearanceOrContact() and
         clearanceBelow() are the cheaper questions (the verdict without a depth; the clearance only where below a
         bound);
       - sweep(s1, s2) bounds how far the closest points of any pair move relative to each other along OMPL's
         interpolation from s1 to s2, linearly in the fraction of the motion: the clearance along the motion is
         Lipschitz with that constant, which certifies bounds between samples (branch and bound, the max-min
         objective's pruning);
       - gradient() is the (sub)gradient of the clearance in the tangent coordinates of applyStep(), whose metric
         gradientNorm2() and ascentStep() share: a step of metric length a moves no robot point further than
         about a (lengthScale() is the length that turns an angle into a displacement);
       - allocCertifiedMotionValidator() (MotionValidatorFactory.h) gives the certified motion validator of the
         same robot: a motion it accepts is proven free.
       Only a field whose certified() is true answers exactly (a fast-mode ClearanceChecker does not, and the
       objectives and the optimiser refuse it or fall back to OMPL's sampled ways). Thread-safe, as the checkers.
    */
    class ClearanceField
    {
    public:
        virtual ~ClearanceField() = default;

        /** \brief The exact collision verdict (false also out of the space's bounds). */
        virtual bool isValid(const ompl::base::State *state) const = 0;
        /** \brief The signed clearance: negative (or 0) in collision. */
        virtual double clearance(const ompl::base::State *state) const = 0;
        /** \brief clearance() of a free state; a negative number without the depth in collision. */
        virtual double clearanceOrContact(const ompl::base::State *state) const = 0;
        /** \brief min(clearanceOrContact(state), bound), found only as far as needed (\e bound > 0). */
        virtual double clearanceBelow(const ompl::base::State *state, double bound) const = 0;
        /** \brief True when clearance() is exact (proven), so Lipschitz in the robot's displacement. */
        virtual bool certified() const = 0;
        /** \brief Unique per field, never reused (keys caches of its answers). */
        virtual std::uint64_t fieldId() const = 0;

        /** \brief The robot's length scale: what turns a rotation into a displacement (one rigid body: its radius
            about its origin; a robot of many bodies: its longest lever). Positive. */
        virtual double lengthScale() const = 0;
        /** \brief How far, at most, the clearance changes per unit fraction along OMPL's interpolation from \e s1
            to \e s2 (a bound on the relative displacement of any pair checked). */
        virtual double sweep(const ompl::base::State *s1, const ompl::base::State *s2) const = 0;

        /** \brief Numbers of a gradient and of a step of applyStep(). */
        virtual unsigned gradientDimension() const = 0;
        /** \brief The signed clearance at \e state, and in \e gradient (resized to gradientDimension()) its
            (sub)gradient in applyStep()'s coordinates; \e info says whether it is a direction. */
        virtual double gradient(const ompl::base::State *state, std::vector<double> &gradient,
                                const ClearanceGradientOptions &options = {},
                                ClearanceGradientInfo *info = nullptr) const = 0;
        /** \brief The squared norm of \e gradient in the metric of the steps: to first order the step
            ascentStep(gradient, alpha) raises the clearance by alpha times this. */
        virtual double gradientNorm2(const std::vector<double> &gradient) const = 0;
        /** \brief The ascent step alpha * M^-1 gradient (M the metric) into \e step. */
        virtual void ascentStep(const std::vector<double> &gradient, double alpha, std::vector<double> &step) const = 0;
        /** \brief \e out = \e state moved by \e step (gradientDimension() numbers); \e out may be \e state. Bounds
            are not enforced (angles are wrapped). */
        virtual void applyStep(const ompl::base::State *state, const double *step, ompl::base::State *out) const = 0;
    };
}  // namespace meshgap

#endif
