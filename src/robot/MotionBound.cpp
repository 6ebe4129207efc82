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
            std::vector<std::size_t> chain;
            for (std::size_t f = link.frame; f != RobotModel::NONE; f = robot.frames()[f].parent)
                chain.push_back(f);
            for (std::size_t f = link.frame, step = 0; jointOf[f] != RobotModel::NONE;
                 f = robot.frames()[f].parent, ++step)
            {
                const UrdfJoint &j = robot.joints()[jointOf[f]];
                if (j.type != JointType::FIXED)
                {
                    const bool mimic = j.mimics != RobotModel::NONE;
                    const std::size_t variable = mimic ? robot.joints()[j.mimics].variable : j.variable;
                    const double factor = (j.type == JointType::PRISMATIC ? 1.0 : reach) * std::abs(j.multiplier);
                    terms.push_back({variable, factor, continuous_[variable], step});
                }
                // The child frame's origin lies on the joint's axis (a rotation) or moves along it (a slide):
                // up to the joint frame, then up to the parent frame.
                if (j.type == JointType::PRISMATIC)
                    reach += largestValue(robot, j);
                reach += j.origin.translation().norm();
            }
            terms_.push_back(terms);
            chains_.push_back(chain);
        }
    }

    double MotionBound::termMove(const Term &t, const std::vector<double> &a, const std::vector<double> &b)
    {
        double change = std::abs(b[t.variable] - a[t.variable]);
        if (t.angle)
            change = std::min(change, std::abs(2.0 * M_PI - change));
        return t.factor * change;
    }

    double MotionBound::pairDisplacement(std::size_t first, std::size_t second, const std::vector<double> &a,
                                         const std::vector<double> &b) const
    {
        // The nearest common ancestor: its place on each link's way up (the root, at worst, is on both).
        const std::vector<std::size_t> &up1 = chains_[first], &up2 = chains_[second];
        std::size_t at1 = up1.size(), at2 = up2.size();
        for (std::size_t i = 0; i < up1.size() && at1 == up1.size(); ++i)
            for (std::size_t k = 0; k < up2.size(); ++k)
                if (up1[i] == up2[k])
                {
                    at1 = i;
                    at2 = k;
                    break;
                }
        double d = 0.0;
        for (const Term &t : terms_[first])
            if (t.step < at1)
                d += termMove(t, a, b);
        for (const Term &t : terms_[second])
            if (t.step < at2)
                d += termMove(t, a, b);
        return d;
    }

    void MotionBound::linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                                        std::vector<double> &out) const
    {
        out.resize(terms_.size());
        for (std::size_t i = 0; i < terms_.size(); ++i)
        {
            double d = 0.0;
            for (const Term &t : terms_[i])
                d += termMove(t, a, b);
            out[i] = d;
        }
    }
}  // namespace meshgap
