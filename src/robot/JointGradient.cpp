#include "meshgap/robot/JointGradient.h"

#include "meshgap/Exception.h"

namespace meshgap
{
    Eigen::Matrix3Xd pointJacobian(const RobotModel &robot, const std::vector<double> &state,
                                   const std::vector<Eigen::Isometry3d> &frames, std::size_t frame,
                                   const Eigen::Vector3d &p)
    {
        if (state.size() != robot.dimension() || frames.size() != robot.frames().size() ||
            frame >= robot.frames().size())
            throw Exception("pointJacobian", "a state, frame poses or frame that are not the robot's");
        Eigen::Matrix3Xd J;
        robot.pointJacobian(state.data(), frames, frame, p, J);
        return J;
    }

    bool clearanceGradient(const RobotModel &robot, const RobotScene &scene, const std::vector<double> &state,
                           const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                           Eigen::VectorXd &gradient)
    {
        gradient = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.dimension()));
        const Eigen::Vector3d gap = result.onLink - result.onOther;
        if (result.inCollision || result.atLeast || !(result.distance > 0.0) || !(gap.norm() > 0.0))
            return false;
        const Eigen::Vector3d n = gap / gap.norm();
        gradient = pointJacobian(robot, state, frames, scene.links()[result.link].frame, result.onLink).transpose() * n;
        if (result.selfPair)
            gradient -=
                pointJacobian(robot, state, frames, scene.links()[result.other].frame, result.onOther).transpose() * n;
        return true;
    }
}  // namespace meshgap
