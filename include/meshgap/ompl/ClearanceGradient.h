#ifndef MESHGAP_OMPL_CLEARANCE_GRADIENT_H
#define MESHGAP_OMPL_CLEARANCE_GRADIENT_H

#include <vector>

#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    // ClearanceGradientOptions and ClearanceGradientInfo: ClearanceField.h.

    /** \brief Coordinates of the gradient and of the steps applyTangentStep() takes: 6 for SE(3) (translation
        dx dy dz, then the rotation wx wy wz as a world-frame rotation vector about the robot's origin), 3 for SE(2)
        (dx dy dyaw). Throws for other spaces. */
    unsigned tangentDimension(const ompl::base::StateSpace &space);

    /** \brief \e out = \e state moved by \e step (tangentDimension() numbers): SE(3) translation t + (dx dy dz) and
        rotation exp([wx wy wz]) * R (a rotation of the robot about its own origin by the world-frame rotation
        vector w, angle |w|); SE(2) x + dx, y + dy, yaw + dyaw (wrapped to [-pi, pi)). \e out may be \e state.
        Bounds are not enforced. */
    void applyTangentStep(const ompl::base::StateSpace &space, const ompl::base::State *state, const double *step,
                          ompl::base::State *out);

    /**
       @anchor mgClearanceGradient
       @par Short description
       The exact (sub)gradient of the signed clearance (ClearanceChecker::clearance(), CERTIFIED mode) with respect
       to the robot's pose, in the coordinates of tangentDimension(): d clearance / d step of applyTangentStep() at
       step 0. From the answer ClearanceChecker::query() gives (warm-started per thread like clearance()):
       - free: n = (onA - onB) / |onA - onB| (SceneResult's witnesses: A on the robot, B on the obstacle), the
         unit vector from the obstacle's witness point to the robot's; translating the robot by dt changes the
         distance by n . dt, and rotating it by a world-frame rotation vector w about its origin x moves the
         witness point p = onA by w x (p - x), so the gradient is (n, (p - x) x n). SE(2): (n.x, n.y,
         ((p - x) x n).z).
       - in collision with a depth (Penetration::DEEPEST_NODE): the signed distance is minus the depth of the
         deepest node, which onA - onB pushes out when reversed (README "Penetration depth"); the same formula
         with n = (onB - onA) / |...| and p = onA (either the robot's node inside the obstacle or the point of the
         robot's surface nearest the obstacle's node) is the derivative of that signed distance. Other collisions
         have no depth (CONTACT_DISTANCE): gradient 0, hasDirection false.
       - ties: every other obstacle whose exact distance is within the tie tolerance of the minimum (refineExact()
         bounded by minimum + tolerance, so far obstacles cost a box test) contributes its own pair's gradient
         g_i, up to 8 pairs, the closest kept. The clearance is then the minimum of the pairs' smooth distances,
         whose one-sided derivative along a step v is min_i g_i . v. The subgradient returned is the minimum-norm
         element g* of the convex hull of the g_i in the metric ||g||^2 = |g_t|^2 + |g_w|^2 / L^2 (L the robot's
         radius about its origin: a rotation w moves no robot point further than L |w|), found exactly by trying
         every subset's affine minimum. Its ascent step v = M^-1 g* (ascentStep(): translation g*_t, rotation
         g*_w / L^2) raises every tied pair's distance at rate >= ||g*||^2, and g* = 0 exactly when no step does
         (a local maximum of the clearance, e.g. a robot centred between two equal walls). Two closest pairs on
         the same obstacle (a single BVH answer) are not detected by that test: there the canonical pair the exact
         query returns gives the gradient, unless probes are asked for (ClearanceGradientOptions::probes): steps
         along the ascent direction that meet another pair add it to the hull.
       Returns the signed clearance (as clearance()); \e gradient is resized to tangentDimension(). Thread-safe.
       Needs a checker in CERTIFIED mode (FAST mode's node pairs are not the closest points): throws otherwise.
    */
    double clearanceGradient(const ClearanceChecker &checker, const ompl::base::State *state,
                             std::vector<double> &gradient, const ClearanceGradientOptions &options = {},
                             ClearanceGradientInfo *info = nullptr);

    /** \brief The ascent step of length scale \e alpha along \e gradient in clearanceGradient()'s metric: \e step
        = alpha * (g_t, g_w / L^2) with L = \e lengthScale (the robot's radius about its origin); to first order
        the clearance rises by alpha * ||g||^2, and no robot point within L of the origin moves further than
        alpha * (|g_t| + |g_w| / L) <= alpha * sqrt(2) * ||g||. */
    void ascentStep(const std::vector<double> &gradient, double lengthScale, double alpha, std::vector<double> &step);
}  // namespace meshgap

#endif
