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

    FrameMotion rigidMotion(RigidSpace space, std::size_t variable)
    {
        FrameMotion m;
        m.kind = space == RigidSpace::SE2 ? FrameMotion::Kind::SE2 : FrameMotion::Kind::SE3;
        m.variable = variable;
        m.reach = std::numeric_limits<double>::infinity();
        return m;
    }

    RigidBodyRobot::RigidBodyRobot(BodyConstPtr body, RigidSpace space, const std::string &name) : space_(space)
    {
        where_ = "robot " + quote(name);
        addLink(name, std::move(body), addFrame(name, NONE), Eigen::Isometry3d::Identity(), false);
        setDimension(rigidSpaceDimension(space));
    }

    void RigidBodyRobot::computeFrames(const double *state, Eigen::Isometry3d *frames) const
    {
        frames[0] = rigidPose(space_, state);
    }

    FrameMotion RigidBodyRobot::frameMotion(std::size_t /*frame*/) const
    {
        return rigidMotion(space_, 0);
    }
}  // namespace meshgap
