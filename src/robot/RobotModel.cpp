#include "meshgap/robot/RobotModel.h"

#include <algorithm>
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

    std::size_t RobotModel::commonFrame(std::size_t a, std::size_t b) const
    {
        for (std::size_t f = a; f != NONE; f = frames_[f].parent)
            for (std::size_t g = b; g != NONE; g = frames_[g].parent)
                if (f == g)
                    return f;
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
                text << "state number " << i << " (" << stateName(i) << ") = " << state[i]
                     << " is beyond 1e12 in magnitude, the largest "
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

    std::string RobotModel::description() const
    {
        return std::to_string(links_.size()) + " links";
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
        joints_.emplace_back();
        joints_.back().name = name;
        steps_.push_back(Step::FIXED);
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

    void RobotModel::setFrameJoint(std::size_t frame, FrameJoint joint)
    {
        if (joint.joint && joint.joint->size() == 0)
            joint.joint.reset();  // fixed
        if (!joint.joint)
            joint.variable = joint.mimics = NONE;
        Step step = Step::FIXED;
        if (joint.joint && frames_.at(frame).parent == NONE && joint.origin.matrix() == Eigen::Matrix4d::Identity())
            step = Step::ROOT;
        else if (joint.joint && joint.joint->size() == 1 && joint.joint->motion() == JointMotion::ROTATION)
            step = Step::ROTATE;
        else if (joint.joint && joint.joint->size() == 1 && joint.joint->motion() == JointMotion::TRANSLATION)
            step = Step::SLIDE;
        else if (joint.joint)
            step = Step::MOVE;
        steps_.at(frame) = step;
        joints_.at(frame) = std::move(joint);
    }

    void RobotModel::setDimension(std::size_t dimension)
    {
        std::vector<Number> numbers(dimension, Number{"", 0.0, 0.0, 0.0, 0.0});
        std::vector<bool> covered(dimension, false);
        for (const FrameJoint &j : joints_)
        {
            if (!j.joint || j.mimics != NONE)
                continue;
            for (std::size_t k = 0; k < j.joint->size(); ++k)
            {
                const std::size_t i = j.variable + k;
                if (j.variable == NONE || i >= dimension || covered[i])
                    throw Exception(where_, "joint '" + j.name + "' has no place of its own in a state of " +
                                                std::to_string(dimension) + " numbers");
                covered[i] = true;
                const std::string value = j.joint->valueName(k);
                const double lo = j.joint->lower(k), hi = j.joint->upper(k);
                const double slack = 1e-9 * std::max({1.0, std::abs(lo), std::abs(hi)});
                numbers[i] = {value.empty() ? j.name : j.name + "." + value, lo, hi, lo - slack, hi + slack};
            }
        }
        for (std::size_t i = 0; i < dimension; ++i)
            if (!covered[i])
                throw Exception(where_, "state number " + std::to_string(i) + " moves no joint");
        limited_.clear();
        for (std::size_t i = 0; i < dimension; ++i)
            if (std::isfinite(numbers[i].low) || std::isfinite(numbers[i].high))
                limited_.push_back({i, numbers[i].low, numbers[i].high});
        numbers_ = std::move(numbers);
        dimension_ = dimension;
    }

    void RobotModel::checkStateLimits(const double *state, const std::string &where) const
    {
        for (const Limit &l : limited_)
        {
            const std::size_t i = l.number;
            if (state[i] < l.low || state[i] > l.high)
            {
                const Number &n = numbers_[i];
                std::ostringstream text;
                text << "joint " << quote(n.name) << " = " << state[i] << " is outside its limits [" << n.lower << ", "
                     << n.upper << "]";
                throw Exception(where, text.str());
            }
        }
    }

    void RobotModel::computeFrames(const double *state, Eigen::Isometry3d *frames) const
    {
        for (std::size_t f = 0; f < frames_.size(); ++f)
        {
            const FrameJoint &j = joints_[f];
            const Step step = steps_[f];
            double mimicked = 0.0;
            const double *q = nullptr;
            if (step != Step::FIXED)
            {
                if (j.mimics == NONE)
                    q = state + j.variable;
                else
                {
                    mimicked = j.multiplier * state[j.variable] + j.offset;
                    q = &mimicked;
                }
            }
            if (step == Step::ROOT)  // a rigid body: its pose is its joint's motion
            {
                frames[f] = j.joint->pose(q);
                continue;
            }
            const std::size_t parent = frames_[f].parent;
            Eigen::Isometry3d &X = frames[f];
            if (parent == NONE)
                X = j.origin;
            else  // frames[parent] * j.origin, spelt out: inline, which Eigen's product is not here (the last row
            {     // of an Isometry3d is always 0 0 0 1)
                const Eigen::Isometry3d &P = frames[parent];
                X.linear().noalias() = P.linear() * j.origin.linear();
                X.translation().noalias() = P.linear() * j.origin.translation();
                X.translation() += P.translation();
            }
            // A turn about, or a slide along, the axis inline (an arm's every joint); other types through move().
            if (step == Step::ROTATE)
                X.rotate(Eigen::AngleAxisd(*q, j.joint->axis()));
            else if (step == Step::SLIDE)
                X.translate(*q * j.joint->axis());
            else if (step == Step::MOVE)
                j.joint->move(q, X);
        }
    }

    FrameMotion RobotModel::frameMotion(std::size_t frame) const
    {
        const FrameJoint &j = joints_.at(frame);
        FrameMotion m;
        m.reach = j.origin.translation().norm();
        if (!j.joint)
            return m;
        const Joint &source = j.mimics != NONE ? *joints_[j.mimics].joint : *j.joint;
        m.kind = j.joint->motion();
        m.variable = j.variable;
        m.scale = std::abs(j.multiplier);
        m.angle = source.space() == JointSpace::SO2;
        m.axis = j.joint->axis();
        // The values it takes: its source's limits mapped by the mimic's multiplier and offset.
        double lo = source.lower(0), hi = source.upper(0);
        if (j.mimics != NONE)
        {
            lo = j.multiplier == 0.0 ? j.offset : j.multiplier * lo + j.offset;
            hi = j.multiplier == 0.0 ? j.offset : j.multiplier * hi + j.offset;
        }
        m.reach += j.joint->reach(std::min(lo, hi), std::max(lo, hi));
        return m;
    }

    std::vector<StateBlock> RobotModel::stateBlocks() const
    {
        // The joint that owns each state number, in state order.
        std::vector<const FrameJoint *> owner(dimension_, nullptr);
        for (const FrameJoint &j : joints_)
            if (j.joint && j.mimics == NONE)
                owner[j.variable] = &j;
        std::vector<StateBlock> blocks;
        for (std::size_t i = 0; i < dimension_;)
        {
            const FrameJoint &j = *owner[i];
            const JointSpace space = j.joint->space();
            if (space != JointSpace::REAL || blocks.empty() || blocks.back().space != JointSpace::REAL)
                blocks.push_back({space, i, {}, {}, {}});
            for (std::size_t k = 0; k < j.joint->size(); ++k, ++i)
            {
                blocks.back().names.push_back(numbers_[i].name);
                blocks.back().lower.push_back(numbers_[i].lower);
                blocks.back().upper.push_back(numbers_[i].upper);
            }
        }
        return blocks;
    }

    bool RobotModel::movesFree() const
    {
        for (const FrameJoint &j : joints_)
            if (j.joint && (j.joint->space() == JointSpace::SE2 || j.joint->space() == JointSpace::SE3))
                return true;
        return false;
    }

    void RobotModel::pointJacobian(const double *state, const std::vector<Eigen::Isometry3d> &frames,
                                   std::size_t frame, const Eigen::Vector3d &p, Eigen::Matrix3Xd &J) const
    {
        J.setZero(3, static_cast<Eigen::Index>(dimension_));
        for (std::size_t f = frame; f != NONE; f = frames_[f].parent)
        {
            const FrameJoint &j = joints_[f];
            if (!j.joint)
                continue;
            const auto column = static_cast<Eigen::Index>(j.variable);
            if (j.mimics == NONE)
                j.joint->addJacobian(state + j.variable, frames[f], p, 1.0, J, column);
            else
            {
                const double q = j.multiplier * state[j.variable] + j.offset;
                j.joint->addJacobian(&q, frames[f], p, j.multiplier, J, column);
            }
        }
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
