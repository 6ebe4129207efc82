#include "meshgap/robot/JointGradient.h"

#include "meshgap/Exception.h"

namespace meshgap
{
    Eigen::Matrix3Xd pointJacobian(const UrdfRobot &robot, const std::vector<Eigen::Isometry3d> &frames,
                                   std::size_t frame, const Eigen::Vector3d &p)
    {
        if (robot.floatingBase())
            throw Exception("pointJacobian", "a floating base has no joint-space Jacobian here (fixed bases only)");
        Eigen::Matrix3Xd J = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(robot.dimension()));
        std::vector<std::size_t> jointOf(robot.frames().size(), RobotModel::NONE);
        for (std::size_t k = 0; k < robot.joints().size(); ++k)
            jointOf[robot.joints()[k].child] = k;
        for (std::size_t f = frame; jointOf[f] != RobotModel::NONE; f = robot.frames()[f].parent)
        {
            const UrdfJoint &j = robot.joints()[jointOf[f]];
            if (j.type == JointType::FIXED)
                continue;
            // The child frame turns about (or slides along) the joint's axis through the child's origin.
            const Eigen::Vector3d axis = frames[j.child].linear() * j.axis;
            const Eigen::Vector3d column =
                j.type == JointType::PRISMATIC ? axis : Eigen::Vector3d(axis.cross(p - frames[j.child].translation()));
            const bool mimic = j.mimics != RobotModel::NONE;
            const std::size_t variable = mimic ? robot.joints()[j.mimics].variable : j.variable;
            J.col(static_cast<Eigen::Index>(variable)) += (mimic ? j.multiplier : 1.0) * column;
        }
        return J;
    }

    bool clearanceGradient(const UrdfRobot &robot, const RobotScene &scene,
                           const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                           Eigen::VectorXd &gradient)
    {
        gradient = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.dimension()));
        const Eigen::Vector3d gap = result.onLink - result.onOther;
        if (result.inCollision || result.atLeast || !(result.distance > 0.0) || !(gap.norm() > 0.0))
            return false;
        const Eigen::Vector3d n = gap / gap.norm();
        gradient = pointJacobian(robot, frames, scene.links()[result.link].frame, result.onLink).transpose() * n;
        if (result.selfPair)
            gradient -= pointJacobian(robot, frames, scene.links()[result.other].frame, result.onOther).transpose() * n;
        return true;
    }
}  // namespace meshgap
