#ifndef MESHGAP_OMPL_CONTROL_MODELS_H
#define MESHGAP_OMPL_CONTROL_MODELS_H

#include <ompl/base/spaces/RealVectorBounds.h>
#include <ompl/control/SpaceInformation.h>
#include <string>
#include <vector>

namespace meshgap
{
    /** \brief The vehicle models of OMPL.app's control problems (its "control" key), with OMPL.app's state spaces,
        control bounds and equations of motion:

        - kinematic_car: state SE(2) (x, y, theta); controls u0 in [-5, 5] (speed) and u1 in [-30, 30] degrees
          (steering angle); x' = u0 cos(theta), y' = u0 sin(theta), theta' = u0 tan(u1) / L, L = 1.
        - dynamic_car: state SE(2) x (v, phi), v in [-1, 1], phi in [-30, 30] degrees (weights 1 and 0.3); controls
          u0 in [-0.5, 0.5] (acceleration), u1 in [-2, 2] degrees per unit time (steering rate); x' = v cos(theta),
          y' = v sin(theta), theta' = v m tan(phi) / L, v' = u0, phi' = u1, m = L = 1.
        - blimp: state SE(3) x R^3 (velocity, each in [-1, 1]) x R (yaw rate omega in [-0.2, 0.2]) (weights 1, 0.3,
          0.3); controls u0, u1 in [-1, 1], u2 in [-0.3, 0.3]; x'' = u0 cos(theta), y'' = u0 sin(theta), z'' = u1,
          theta'' = u2, theta the heading: the blimp only turns about z. The heading is the yaw of the SE(3)
          rotation, whose quaternion (0, 0, sin(theta/2), cos(theta/2)) turns at omega / 2. (OMPL.app's code reads
          the heading from the quaternion's x component and writes a rotation about z by it after each propagation:
          its heading starts from zero at every propagation step; here it is the rotation's own yaw.)
        - quadrotor: state SE(3) x R^6 (velocity and angular velocity, each in [-1, 1]) (weights 1 and 0.3); controls
          u0 in [5, 15] (thrust), u1, u2, u3 in [-1, 1] (angular acceleration); m p'' = -u0 n - beta p' - m g, omega'
          = (u1, u2, u3), m = beta = 1, g = 9.81 along -z, n the body's z axis in the world frame: the thrust acts
          along the body's -z, so the quadrotor hovers with its body z axis pointing down. The orientation q turns
          as q' = (0, omega) q / 2, omega in the world frame. (OMPL.app's code takes q' = (omega / 2, 0) less its
          component along q, which agrees only at the identity.)

        After each propagation, as OMPL.app does: the car's yaw wrapped into (-pi, pi], the blimp's rotation made a
        rotation about z again and the quadrotor's quaternion normalised; the velocities of the dynamic models clamped
        into their bounds. Every model is integrated with OMPL's ODEBasicSolver (Boost odeint's Runge-Kutta 4, step
        0.01). As OMPL.app leaves them to OMPL's defaults: controls last 1 to 10 propagation steps, and a step is 0.01
        times the state space's maximum extent. The pose (SE(2) or SE(3)) is the space itself or its subspace 0, which
        poseFromState() reads; a compound space gets a default projection on the pose's own (x, y or x, y, z), as
        KPIECE and the other projection-based planners need. Throws meshgap::Exception naming the model for a model
        not modelled and for pose bounds of the wrong dimension (2 for the cars, 3 for the blimp and quadrotor). */
    ompl::control::SpaceInformationPtr controlSpaceInformation(const std::string &model,
                                                               const ompl::base::RealVectorBounds &poseBounds);

    /** \brief The models controlSpaceInformation() builds: kinematic_car, dynamic_car, blimp, quadrotor. */
    const std::vector<std::string> &modelledControlNames();

    /** \brief Whether \e model moves in the plane (SE(2): the cars) rather than in space (SE(3): blimp, quadrotor). */
    bool controlModelIsPlanar(const std::string &model);
}  // namespace meshgap

#endif
