#ifndef MESHGAP_OMPL_CONTROL_MODELS_H
#define MESHGAP_OMPL_CONTROL_MODELS_H

#include <ompl/base/spaces/RealVectorBounds.h>
#include <ompl/control/SpaceInformation.h>
#include <string>

namespace meshgap
{
    /** \brief The vehicle models of OMPL.app's control problems (its "control" key), with OMPL.app's state spaces,
        control bounds and equations of motion:

        - kinematic_car: state SE(2) (x, y, theta); controls u0 in [-5, 5] (speed) and u1 in [-30, 30] degrees
          (steering angle); x' = u0 cos(theta), y' = u0 sin(theta), theta' = u0 tan(u1) / L, L = 1.
        - dynamic_car: state SE(2) x (v, phi), v in [-1, 1], phi in [-30, 30] degrees (weights 1 and 0.3); controls
          u0 in [-0.5, 0.5] (acceleration), u1 in [-2, 2] degrees per unit time (steering rate); x' = v cos(theta),
          y' = v sin(theta), theta' = v m tan(phi) / L, v' = u0, phi' = u1, m = L = 1.

        Both are integrated with OMPL's ODEBasicSolver (Boost odeint's Runge-Kutta 4, step 0.01), the yaw wrapped into
        (-pi, pi] after each propagation. As OMPL.app leaves them to OMPL's defaults: controls last 1 to 10
        propagation steps, and a step is 0.01 times the state space's maximum extent. The pose (SE(2)) is the space
        itself or its subspace 0, which poseFromState() reads; a compound space gets a default projection on the
        pose's own (x, y), as KPIECE and the other projection-based planners need. */
    ompl::control::SpaceInformationPtr controlSpaceInformation(const std::string &model,
                                                               const ompl::base::RealVectorBounds &poseBounds);

    /** \brief The models controlSpaceInformation() builds: kinematic_car, dynamic_car. */
    const std::vector<std::string> &modelledControlNames();
}  // namespace meshgap

#endif
