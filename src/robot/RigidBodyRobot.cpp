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

    std::vector<double> rigidState(RigidSpace space, const Eigen::Isometry3d &pose)
    {
        const Eigen::Vector3d t = pose.translation();
        if (space == RigidSpace::SE2)
            return {t.x(), t.y(), std::atan2(pose.linear()(1, 0), pose.linear()(0, 0))};
        const Eigen::Quaterniond q(pose.linear());
        return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
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

    std::string RigidBodyRobot::description() const
    {
        return space_ == RigidSpace::SE2 ? "one body in SE(2)" : "one body in SE(3)";
    }
}  // namespace meshgap
