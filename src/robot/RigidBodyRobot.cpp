#include "meshgap/robot/RigidBodyRobot.h"

#include <cmath>
#include <limits>

#include "meshgap/Text.h"

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

    JointConstPtr rigidJoint(RigidSpace space)
    {
        JointSpec spec;
        spec.axis = Eigen::Vector3d::UnitZ();
        return makeJoint(space == RigidSpace::SE2 ? "planar" : "floating", spec);
    }

    RigidBodyRobot::RigidBodyRobot(BodyConstPtr body, RigidSpace space, const std::string &name) : space_(space)
    {
        where_ = "robot " + quote(name);
        addLink(name, std::move(body), addFrame(name, NONE), Eigen::Isometry3d::Identity(), false);
        FrameJoint joint;
        joint.name = name;
        joint.joint = rigidJoint(space);
        joint.variable = 0;
        setFrameJoint(0, joint);
        setDimension(rigidSpaceDimension(space));
    }
}  // namespace meshgap
