#include "meshgap/robot/MultiBodyRobot.h"

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
            addLink(part.name, part.body, addFrame(part.name, NONE), Eigen::Isometry3d::Identity(), false);
            spaces_.push_back(part.space);
            offsets_.push_back(dimension);
            dimension += rigidSpaceDimension(part.space);
        }
        setDimension(dimension);
    }

    void MultiBodyRobot::computeFrames(const double *state, Eigen::Isometry3d *frames) const
    {
        for (std::size_t i = 0; i < spaces_.size(); ++i)
            frames[i] = rigidPose(spaces_[i], state + offsets_[i]);
    }

    FrameMotion MultiBodyRobot::frameMotion(std::size_t frame) const
    {
        return rigidMotion(spaces_[frame], offsets_[frame]);
    }
}  // namespace meshgap
