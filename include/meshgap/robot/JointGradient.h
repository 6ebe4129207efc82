#ifndef MESHGAP_ROBOT_JOINT_GRADIENT_H
#define MESHGAP_ROBOT_JOINT_GRADIENT_H

#include <Eigen/Core>
#include <vector>

#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    /** \brief The world-frame velocity of the point \e p, fixed to frame \e frame, per unit change of each state
        number: a 3 x dimension() Jacobian (RobotModel::pointJacobian(): revolute and continuous joints
        axis x (p - joint origin); prismatic the axis; planar and floating joints, rigid bodies and a floating base
        a column per number, the quaternion's numbers as they turn the frame once normalised; a mimic joint adds its
        multiplier times its own to its source's column), at \e state, whose frame poses are \e frames. */
    Eigen::Matrix3Xd pointJacobian(const RobotModel &robot, const std::vector<double> &state,
                                   const std::vector<Eigen::Isometry3d> &frames, std::size_t frame,
                                   const Eigen::Vector3d &p);

    /** \brief The gradient in state space of the whole robot's clearance \e result (a free answer of
        RobotScene::distance() at \e state, whose frame poses are \e frames): n . (J_link(onA) - J_other(onB)), n
        the unit vector from the other witness (onB) to the link's (onA), J_other zero for an obstacle.
        Returns false (and a zero gradient) when the answer is in collision, touching, or has no pair (atLeast): no
        direction is defined. */
    bool clearanceGradient(const RobotModel &robot, const RobotScene &scene, const std::vector<double> &state,
                           const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                           Eigen::VectorXd &gradient);

    /** \brief The tangent coordinates of a robot's state, what robotPointJacobian() differentiates by and
        applyRobotStep() steps along: every state number (a joint value; x, y, theta of an SE(2) pose), except that
        an SE(3) pose "x y z qx qy qz qw" (a rigid body's, a floating base's) has six, dx dy dz and then a
        world-frame rotation vector about its frame's origin. Their number. */
    std::size_t robotTangentDimension(const RobotModel &robot);

    /** \brief The world-frame velocity of the point \e p, fixed to frame \e frame, per unit of each tangent
        coordinate (robotTangentDimension()): a 3 x robotTangentDimension() Jacobian, for every kind of robot (a
        URDF tree with a fixed or a floating base, one or several rigid bodies), from the frame poses \e frames of
        the current state. Throws meshgap::Exception for a frame that moves free below another frame. */
    Eigen::Matrix3Xd robotPointJacobian(const RobotModel &robot, const std::vector<Eigen::Isometry3d> &frames,
                                        std::size_t frame, const Eigen::Vector3d &p);

    /** \brief \e out = \e state moved by \e step (robotTangentDimension() numbers): state numbers plus their
        step (angles of continuous joints and SE(2) yaws wrapped to [-pi, pi)); an SE(3) pose translated by its
        (dx dy dz) and turned by exp([wx wy wz]) about its origin (world frame). \e out may be \e state (each
        robot.dimension() numbers). Joint limits are not enforced. */
    void applyRobotStep(const RobotModel &robot, const double *state, const double *step, double *out);

    /** \brief Per tangent coordinate, how far a unit step of it moves any point of any link at most (MotionBound:
        a joint's lever, 1 for a translation): the metric that turns a tangent step into a displacement. */
    std::vector<double> robotTangentLevers(const RobotModel &robot);

    /** \brief clearanceGradient() in the tangent coordinates of robotTangentDimension(), for every kind of robot:
        n . (J_link(onA) - J_other(onB)) with robotPointJacobian(). Returns false (and a zero gradient) when the
        answer is in collision, touching, or has no pair. */
    bool robotClearanceGradient(const RobotModel &robot, const RobotScene &scene,
                                const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                                Eigen::VectorXd &gradient);
}  // namespace meshgap

#endif
