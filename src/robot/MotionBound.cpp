#include "meshgap/robot/MotionBound.h"

#include <cmath>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        /** \brief The largest |value| joint \e j can take (a prismatic joint's reach along its axis). */
        double largestValue(const UrdfRobot &robot, const UrdfJoint &j)
        {
            const UrdfJoint &source = j.mimics != RobotModel::NONE ? robot.joints()[j.mimics] : j;
            const double lo = j.multiplier * source.lower + j.offset, hi = j.multiplier * source.upper + j.offset;
            return std::max(std::abs(lo), std::abs(hi));
        }
    }  // namespace

    MotionBound::MotionBound(const UrdfRobot &robot)
    {
        if (robot.floatingBase())
            throw Exception("MotionBound", "a floating base is not bounded (fixed-base robots only)");
        continuous_.assign(robot.dimension(), false);
        for (const UrdfJoint &j : robot.joints())
            if (j.variable != RobotModel::NONE && j.type == JointType::CONTINUOUS)
                continuous_[j.variable] = true;
        // The joint whose child each frame is.
        std::vector<std::size_t> jointOf(robot.frames().size(), RobotModel::NONE);
        for (std::size_t k = 0; k < robot.joints().size(); ++k)
            jointOf[robot.joints()[k].child] = k;
        for (const RobotLink &link : robot.links())
        {
            double reach = 0.0;  // from the current joint's origin to any point of the link
            for (const Eigen::Vector3d &v : link.body->surface().vertices)
                reach = std::max(reach, (link.X_FL * v).norm());
            std::vector<Term> terms;
            for (std::size_t f = link.frame; jointOf[f] != RobotModel::NONE; f = robot.frames()[f].parent)
            {
                const UrdfJoint &j = robot.joints()[jointOf[f]];
                if (j.type != JointType::FIXED)
                {
                    const bool mimic = j.mimics != RobotModel::NONE;
                    const std::size_t variable = mimic ? robot.joints()[j.mimics].variable : j.variable;
                    const double factor = (j.type == JointType::PRISMATIC ? 1.0 : reach) * std::abs(j.multiplier);
                    terms.push_back({variable, factor, continuous_[variable]});
                }
                // The child frame's origin lies on the joint's axis (a rotation) or moves along it (a slide):
                // up to the joint frame, then up to the parent frame.
                if (j.type == JointType::PRISMATIC)
                    reach += largestValue(robot, j);
                reach += j.origin.translation().norm();
            }
            terms_.push_back(terms);
        }
    }

    void MotionBound::linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                                        std::vector<double> &out) const
    {
        out.resize(terms_.size());
        for (std::size_t i = 0; i < terms_.size(); ++i)
        {
            double d = 0.0;
            for (const Term &t : terms_[i])
            {
                double change = std::abs(b[t.variable] - a[t.variable]);
                if (t.angle)
                    change = std::min(change, std::abs(2.0 * M_PI - change));
                d += t.factor * change;
            }
            out[i] = d;
        }
    }
}  // namespace meshgap
