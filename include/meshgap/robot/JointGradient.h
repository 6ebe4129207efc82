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
        RobotScene::distance() at \e state, whose frame poses are \e frames): n . (J_link(onLink) -
        J_other(onOther)), n the unit vector from the other witness to the link's, J_other zero for an obstacle.
        Returns false (and a zero gradient) when the answer is in collision, touching, or has no pair (atLeast): no
        direction is defined. */
    bool clearanceGradient(const RobotModel &robot, const RobotScene &scene, const std::vector<double> &state,
                           const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                           Eigen::VectorXd &gradient);
}  // namespace meshgap

#endif
