#include "meshgap/robot/MultiBodyRobot.h"

#include <algorithm>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    MultiBodyRobot::MultiBodyRobot(const std::vector<Part> &parts)
    {
        where_ = "multi-body robot";
        if (parts.empty())
            throw Exception(where_, "no body");
        std::size_t dimension = 0;
        for (const Part &part : parts)
        {
            if (findFrame(part.name) != NONE)
                throw Exception(where_, "two bodies named " + quote(part.name));
            const std::size_t frame = addFrame(part.name, NONE);
            addLink(part.name, part.body, frame, Eigen::Isometry3d::Identity(), false);
            FrameJoint joint;
            joint.name = part.name;
            joint.joint = rigidJoint(part.space);
            joint.variable = dimension;
            setFrameJoint(frame, joint);
            spaces_.push_back(part.space);
            offsets_.push_back(dimension);
            dimension += rigidSpaceDimension(part.space);
        }
        setDimension(dimension);
    }

    std::string MultiBodyRobot::description() const
    {
        const auto planar = std::count(spaces_.begin(), spaces_.end(), RigidSpace::SE2);
        const std::size_t n = spaces_.size();
        return std::to_string(n) + " bodies in " +
               (planar == 0 ? "SE(3)" : std::size_t(planar) == n ? "SE(2)" : "SE(2) and SE(3)");
    }
}  // namespace meshgap
