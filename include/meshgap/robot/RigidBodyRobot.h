#ifndef MESHGAP_ROBOT_RIGID_BODY_ROBOT_H
#define MESHGAP_ROBOT_RIGID_BODY_ROBOT_H

#include <string>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(RigidBodyRobot);

    /** \brief The space a rigid body moves in, and its state's numbers. */
    enum class RigidSpace
    {
        SE2,  ///< "x y theta": in the plane z = 0, turning about z (OMPL.app's SE(2) problems)
        SE3   ///< "x y z qx qy qz qw" (OMPL's SE(3) order, quaternion scalar last; normalised)
    };

    /** \brief Numbers in a state of \e space (3 or 7). */
    std::size_t rigidSpaceDimension(RigidSpace space);

    /** \brief The joint that moves a body free in \e space from the world: planar about z (SE2, poseFromSE2()) or
        floating (SE3, poseFromSE3()). */
    JointConstPtr rigidJoint(RigidSpace space);

    /** \brief The pose a state of \e space gives (poseFromSE2(), poseFromSE3()). */
    Eigen::Isometry3d rigidPose(RigidSpace space, const double *state);

    /** \brief The state of \e space that places a body at \e pose: SE2 "x y theta" (theta the yaw about z; the pose
        is taken to lie in the plane z = 0, turned about z), SE3 "x y z qx qy qz qw" (the inverse of rigidPose()). */
    std::vector<double> rigidState(RigidSpace space, const Eigen::Isometry3d &pose);

    /** \brief One rigid body flying free in SE(2) or SE(3): the robot of OMPL.app's rigid-body problems, a robot
        model with one frame and one link (both named \e name), whose pose is the state: the frame hangs from the world
        by rigidJoint(). */
    class RigidBodyRobot : public RobotModel
    {
    public:
        RigidBodyRobot(BodyConstPtr body, RigidSpace space, const std::string &name = "robot");

        RigidSpace space() const { return space_; }

        /** \brief "one body in SE(2)" or "one body in SE(3)". */
        std::string description() const override;

    private:
        RigidSpace space_;
    };
}  // namespace meshgap

#endif
