#include "meshgap/robot/RobotModel.h"

#include <cmath>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/Limits.h"
#include "meshgap/Text.h"

namespace meshgap
{
    std::size_t RobotModel::findFrame(const std::string &name) const
    {
        for (std::size_t i = 0; i < frames_.size(); ++i)
            if (frames_[i].name == name)
                return i;
        return NONE;
    }

    std::size_t RobotModel::findLink(const std::string &name) const
    {
        for (std::size_t i = 0; i < links_.size(); ++i)
            if (links_[i].name == name)
                return i;
        return NONE;
    }

    void RobotModel::checkState(const double *state, std::size_t size) const
    {
        if (size != dimension_)
            throw Exception(where_, "a state of " + std::to_string(size) + " numbers, where this robot has " +
                                        std::to_string(dimension_));
        for (std::size_t i = 0; i < size; ++i)
        {
            if (!std::isfinite(state[i]))
                throw Exception(where_, "state number " + std::to_string(i) + " is not finite");
            if (std::abs(state[i]) > MAX_MAGNITUDE)
            {
                std::ostringstream text;
                text << "state number " << i << " = " << state[i] << " is beyond 1e12 in magnitude, the largest "
                     << "meshgap's geometry answers reliably";
                throw Exception(where_, text.str());
            }
        }
        checkStateLimits(state, where_);
    }

    void RobotModel::framePoses(const double *state, std::size_t size, std::vector<Eigen::Isometry3d> &frames) const
    {
        checkState(state, size);
        frames.resize(frames_.size());
        computeFrames(state, frames.data());
    }

    void RobotModel::linkPoses(const double *state, std::size_t size, std::vector<Eigen::Isometry3d> &frames,
                               std::vector<Eigen::Isometry3d> &links) const
    {
        framePoses(state, size, frames);
        links.resize(links_.size());
        for (std::size_t i = 0; i < links_.size(); ++i)
            links[i] = frames[links_[i].frame] * links_[i].X_FL;
    }

    std::vector<Eigen::Isometry3d> RobotModel::linkPoses(const std::vector<double> &state) const
    {
        std::vector<Eigen::Isometry3d> frames, links;
        linkPoses(state.data(), state.size(), frames, links);
        return links;
    }

    std::size_t RobotModel::ownerLink(std::size_t frame) const
    {
        for (std::size_t f = frame; f != NONE; f = frames_[f].parent)
            for (std::size_t i = 0; i < links_.size(); ++i)
                if (links_[i].frame == f && !links_[i].payload)
                    return i;
        return NONE;
    }

    std::size_t RobotModel::attach(const std::string &name, Mesh mesh, const std::string &parent,
                                   const Eigen::Isometry3d &X_FP, const BodyOptions &options)
    {
        const std::size_t frame = findFrame(parent);
        if (frame == NONE)
            throw Exception(where_, "payload " + quote(name) + " attached to " + quote(parent) +
                                        ", which is no link of this robot");
        if (findLink(name) != NONE)
            throw Exception(where_, "payload " + quote(name) + ": a link of that name exists already");
        if (!X_FP.matrix().allFinite())
            throw Exception(where_, "payload " + quote(name) + ": its transform is not finite");
        mesh.validate();
        const std::size_t owner = ownerLink(frame);
        const std::size_t index = addLink(name, Body::build(std::move(mesh), options), frame, X_FP, true);
        if (owner != NONE)
            allowCollision(owner, index);
        return index;
    }

    void RobotModel::allowCollision(const std::string &a, const std::string &b)
    {
        // A name stands for its link or, for a frame, every link in that frame (none for a frame without geometry).
        auto linksNamed = [&](const std::string &name)
        {
            std::vector<std::size_t> found;
            const std::size_t link = findLink(name);
            if (link != NONE)
                found.push_back(link);
            else
            {
                const std::size_t frame = findFrame(name);
                if (frame == NONE)
                    throw Exception(where_, "no link named " + quote(name));
                for (std::size_t i = 0; i < links_.size(); ++i)
                    if (links_[i].frame == frame && !links_[i].payload)
                        found.push_back(i);
            }
            return found;
        };
        const std::vector<std::size_t> as = linksNamed(a), bs = linksNamed(b);
        for (std::size_t i : as)
            for (std::size_t j : bs)
                allowCollision(i, j);
    }

    void RobotModel::allowCollision(std::size_t a, std::size_t b)
    {
        if (a >= links_.size() || b >= links_.size())
            throw Exception(where_, "no link " + std::to_string(std::max(a, b)) + " (the robot has " +
                                        std::to_string(links_.size()) + ")");
        if (a == b)
            return;
        allowed_[std::max(a, b)][std::min(a, b)] = true;
    }

    bool RobotModel::isAllowed(std::size_t a, std::size_t b) const
    {
        return a == b || allowed_[std::max(a, b)][std::min(a, b)];
    }

    std::vector<LinkPair> RobotModel::selfPairs() const
    {
        std::vector<LinkPair> pairs;
        for (std::size_t a = 0; a < links_.size(); ++a)
            for (std::size_t b = a + 1; b < links_.size(); ++b)
                if (!isAllowed(a, b))
                    pairs.emplace_back(a, b);
        return pairs;
    }

    std::size_t RobotModel::addFrame(const std::string &name, std::size_t parent)
    {
        if (parent != NONE && parent >= frames_.size())
            throw Exception(where_, "frame " + quote(name) + ": its parent is not defined before it");
        frames_.push_back({name, parent});
        return frames_.size() - 1;
    }

    std::size_t RobotModel::addLink(const std::string &name, BodyConstPtr body, std::size_t frame,
                                    const Eigen::Isometry3d &X_FL, bool payload)
    {
        if (!body)
            throw Exception(where_, "link " + quote(name) + " has no body");
        if (frame >= frames_.size())
            throw Exception(where_, "link " + quote(name) + " is in no frame of this robot");
        if (findLink(name) != NONE)
            throw Exception(where_, "two links named " + quote(name));
        const std::size_t index = links_.size();
        links_.push_back({name, std::move(body), frame, X_FL, payload});
        allowed_.emplace_back(index, false);
        // Bodies of one frame never move relative to each other: checking them against each other says nothing.
        for (std::size_t i = 0; i < index; ++i)
            if (links_[i].frame == frame)
                allowed_[index][i] = true;
        return index;
    }

    Eigen::Isometry3d poseFromSE3(const double *state)
    {
        Eigen::Quaterniond q(state[6], state[3], state[4], state[5]);
        const double norm = q.norm();
        if (!(norm > 0.0) || !std::isfinite(norm))
            throw Exception("SE(3) state", "the quaternion (" + std::to_string(state[3]) + ", " +
                                               std::to_string(state[4]) + ", " + std::to_string(state[5]) + ", " +
                                               std::to_string(state[6]) + ") is zero or not finite");
        q.coeffs() /= norm;
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = q.toRotationMatrix();
        X.translation() = Eigen::Vector3d(state[0], state[1], state[2]);
        return X;
    }

    Eigen::Isometry3d poseFromSE2(const double *state)
    {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = Eigen::AngleAxisd(state[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
        X.translation() = Eigen::Vector3d(state[0], state[1], 0.0);
        return X;
    }
}  // namespace meshgap
