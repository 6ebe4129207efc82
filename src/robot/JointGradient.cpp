#include "meshgap/robot/JointGradient.h"

#include <algorithm>
#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/robot/MotionBound.h"

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
        const Eigen::Vector3d gap = result.onA - result.onB;
        if (result.inCollision || result.atLeast || !(result.distance > 0.0) || !(gap.norm() > 0.0))
            return false;
        const Eigen::Vector3d n = gap / gap.norm();
        gradient = pointJacobian(robot, state, frames, scene.links()[result.link].frame, result.onA).transpose() * n;
        if (result.selfPair)
            gradient -=
                pointJacobian(robot, state, frames, scene.links()[result.other].frame, result.onB).transpose() * n;
        return true;
    }

    namespace
    {
        /** \brief The first state numbers of the robot's SE(3) poses, in increasing order. */
        std::vector<std::size_t> se3Blocks(const RobotModel &robot)
        {
            std::vector<std::size_t> blocks;
            for (std::size_t f = 0; f < robot.frames().size(); ++f)
            {
                const FrameMotion m = robot.frameMotion(f);
                if (m.kind == FrameMotion::Kind::SE3)
                    blocks.push_back(m.variable);
            }
            std::sort(blocks.begin(), blocks.end());
            return blocks;
        }

        /** \brief The tangent coordinate of state number \e v (the first of an SE(3) pose's rotation for its qx). */
        std::size_t tangentIndex(const std::vector<std::size_t> &blocks, std::size_t v)
        {
            std::size_t before = 0;
            for (std::size_t b : blocks)
                before += b + 7 <= v;
            return v - before;
        }

        /** \brief Frame \e f's columns of the Jacobian of the point \e p: how it moves with \e f's own motion. */
        void addFrameColumns(const RobotModel &robot, const std::vector<Eigen::Isometry3d> &frames,
                             const std::vector<std::size_t> &blocks, std::size_t f, const Eigen::Vector3d &p,
                             Eigen::Matrix3Xd &J)
        {
            const FrameMotion m = robot.frameMotion(f);
            const Eigen::Vector3d r = p - frames[f].translation();
            const auto col = [&](std::size_t v) { return static_cast<Eigen::Index>(tangentIndex(blocks, v)); };
            switch (m.kind)
            {
                case FrameMotion::Kind::FIXED:
                    return;
                case FrameMotion::Kind::ROTATION:
                case FrameMotion::Kind::TRANSLATION:
                {
                    const FrameJoint &j = robot.frameJoint(f);
                    const Eigen::Vector3d axis = frames[f].linear() * j.joint->axis();
                    const Eigen::Vector3d column =
                        m.kind == FrameMotion::Kind::TRANSLATION ? axis : Eigen::Vector3d(axis.cross(r));
                    J.col(col(m.variable)) += (j.mimics != RobotModel::NONE ? j.multiplier : 1.0) * column;
                    return;
                }
                case FrameMotion::Kind::SE2:
                    J.col(col(m.variable)) += Eigen::Vector3d::UnitX();
                    J.col(col(m.variable) + 1) += Eigen::Vector3d::UnitY();
                    J.col(col(m.variable) + 2) += Eigen::Vector3d::UnitZ().cross(r);
                    return;
                case FrameMotion::Kind::SE3:
                    for (int k = 0; k < 3; ++k)
                    {
                        J.col(col(m.variable) + k) += Eigen::Vector3d::Unit(k);
                        J.col(col(m.variable) + 3 + k) += Eigen::Vector3d::Unit(k).cross(r);
                    }
                    return;
            }
        }
    }  // namespace

    std::size_t robotTangentDimension(const RobotModel &robot)
    {
        return robot.dimension() - se3Blocks(robot).size();
    }

    Eigen::Matrix3Xd robotPointJacobian(const RobotModel &robot, const std::vector<Eigen::Isometry3d> &frames,
                                        std::size_t frame, const Eigen::Vector3d &p)
    {
        const std::vector<std::size_t> blocks = se3Blocks(robot);
        Eigen::Matrix3Xd J = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(robot.dimension() - blocks.size()));
        for (std::size_t f = frame; f != RobotModel::NONE; f = robot.frames()[f].parent)
        {
            const FrameMotion::Kind kind = robot.frameMotion(f).kind;
            const bool free = kind == FrameMotion::Kind::SE2 || kind == FrameMotion::Kind::SE3;
            if (free && robot.frames()[f].parent != RobotModel::NONE)
                throw Exception("robotPointJacobian",
                                "frame '" + robot.frames()[f].name + "' moves free below another frame");
            addFrameColumns(robot, frames, blocks, f, p, J);
        }
        return J;
    }

    void applyRobotStep(const RobotModel &robot, const double *state, const double *step, double *out)
    {
        const std::vector<std::size_t> blocks = se3Blocks(robot);
        const std::size_t n = robot.dimension();
        std::vector<bool> angle(n, false), inBlock(n, false);
        for (std::size_t f = 0; f < robot.frames().size(); ++f)
        {
            const FrameMotion m = robot.frameMotion(f);
            if (m.kind == FrameMotion::Kind::ROTATION && m.angle)
                angle[m.variable] = true;
            if (m.kind == FrameMotion::Kind::SE2)
                angle[m.variable + 2] = true;
        }
        for (std::size_t b : blocks)
        {
            const std::size_t t = tangentIndex(blocks, b);
            for (std::size_t k = 0; k < 7; ++k)
                inBlock[b + k] = true;
            const Eigen::Vector3d w(step[t + 3], step[t + 4], step[t + 5]);
            Eigen::Quaterniond q(state[b + 6], state[b + 3], state[b + 4], state[b + 5]);
            q.normalize();
            if (w.norm() > 0.0)
                q = Eigen::Quaterniond(Eigen::AngleAxisd(w.norm(), w / w.norm())) * q;
            q.normalize();
            const double values[7] = {
                state[b] + step[t], state[b + 1] + step[t + 1], state[b + 2] + step[t + 2], q.x(), q.y(), q.z(), q.w()};
            std::copy(values, values + 7, out + b);
        }
        for (std::size_t v = 0; v < n; ++v)
            if (!inBlock[v])
            {
                const double x = state[v] + step[tangentIndex(blocks, v)];
                out[v] = angle[v] ? std::remainder(x, 2.0 * M_PI) : x;
            }
    }

    std::vector<double> robotTangentLevers(const RobotModel &robot)
    {
        const std::vector<std::size_t> blocks = se3Blocks(robot);
        const MotionBound bound(robot);
        std::vector<double> a(robot.dimension(), 0.0), b, moves;
        for (std::size_t s : blocks)
            a[s + 6] = 1.0;  // the identity rotation
        std::vector<double> levers(robotTangentDimension(robot), 0.0), step(levers.size(), 0.0);
        b.resize(a.size());
        for (std::size_t t = 0; t < levers.size(); ++t)
        {
            step.assign(levers.size(), 0.0);
            step[t] = 1.0;
            applyRobotStep(robot, a.data(), step.data(), b.data());
            bound.linkDisplacements(a, b, moves);
            for (double m : moves)
                levers[t] = std::max(levers[t], m);
        }
        return levers;
    }

    bool robotClearanceGradient(const RobotModel &robot, const RobotScene &scene,
                                const std::vector<Eigen::Isometry3d> &frames, const RobotResult &result,
                                Eigen::VectorXd &gradient)
    {
        gradient = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robotTangentDimension(robot)));
        const Eigen::Vector3d gap = result.onA - result.onB;
        if (result.inCollision || result.atLeast || !(result.distance > 0.0) || !(gap.norm() > 0.0))
            return false;
        const Eigen::Vector3d n = gap / gap.norm();
        gradient = robotPointJacobian(robot, frames, scene.links()[result.link].frame, result.onA).transpose() * n;
        if (result.selfPair)
            gradient -=
                robotPointJacobian(robot, frames, scene.links()[result.other].frame, result.onB).transpose() * n;
        return true;
    }
}  // namespace meshgap
