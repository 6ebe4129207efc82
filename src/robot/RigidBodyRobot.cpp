#include "meshgap/robot/RigidBodyRobot.h"

namespace meshgap
{
    std::size_t rigidSpaceDimension(RigidSpace space)
    {
        return space == RigidSpace::SE2 ? 3 : 7;
    }

    Eigen::Isometry3d rigidPose(RigidSpace space, const double *state)
    {
        return space == RigidSpace::SE2 ? poseFromSE2(state) : poseFromSE3(state);
    }

    RigidBodyRobot::RigidBodyRobot(BodyConstPtr body, RigidSpace space, const std::string &name) : space_(space)
    {
        where_ = "robot '" + name + "'";
        addLink(name, std::move(body), addFrame(name, NONE), Eigen::Isometry3d::Identity(), false);
        setDimension(rigidSpaceDimension(space));
    }

    void RigidBodyRobot::computeFrames(const double *state, Eigen::Isometry3d *frames) const
    {
        frames[0] = rigidPose(space_, state);
    }
}  // namespace meshgap
