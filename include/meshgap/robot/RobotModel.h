#ifndef MESHGAP_ROBOT_ROBOT_MODEL_H
#define MESHGAP_ROBOT_ROBOT_MODEL_H

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/geometry/Body.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(RobotModel);

    /** \brief A frame of a robot: a rigid body's frame, or a URDF link's frame. Frames form a forest (parent before
        child); a link body sits in one frame. */
    struct RobotFrame
    {
        std::string name;
        /** \brief The frame this one moves with or relative to (RobotModel::NONE for a root). */
        std::size_t parent;
    };

    /** \brief One body of a robot that collision and distance queries see: a URDF link's geometry, a rigid body, or
        an attached payload. */
    struct RobotLink
    {
        std::string name;
        BodyConstPtr body;
        std::size_t frame;      ///< index in RobotModel::frames()
        Eigen::Isometry3d X_FL;  ///< the body's pose in its frame
        bool payload;           ///< attached with RobotModel::attach()
    };

    /** \brief How a frame moves relative to its parent frame (the world, for a root) along a straight motion
        between two states, as OMPL's interpolation moves it: what bounds the displacement of the points fixed to
        it (MotionBound). */
    struct FrameMotion
    {
        enum class Kind
        {
            FIXED,        ///< not at all
            ROTATION,     ///< about an axis through the frame's origin, by scale times the state number's change
            TRANSLATION,  ///< along a unit axis, by scale times the state number's change
            SE2,          ///< free in the plane: "x y theta" from \e variable on, x and y linear, theta along the
                          ///< shorter arc
            SE3           ///< free: "x y z qx qy qz qw" from \e variable on, the position linear, the rotation along
                          ///< the shorter great arc (slerp)
        };
        Kind kind{Kind::FIXED};
        /** \brief The state number that drives it (the first of an SE(2) or SE(3) pose). */
        std::size_t variable{std::numeric_limits<std::size_t>::max()};
        /** \brief How much the joint moves per unit change of the state number, at most (a mimic joint's
            |multiplier|; 1 otherwise). */
        double scale{1.0};
        /** \brief ROTATION by an unbounded angle (a continuous joint, or one mimicking it): the state number moves
            along the shorter arc. */
        bool angle{false};
        /** \brief The farthest the frame's origin gets from its parent frame's origin, over every state (infinite
            for SE2 and SE3). */
        double reach{0.0};
        /** \brief ROTATION and TRANSLATION: the axis, a unit vector in the frame's own coordinates; a rotation turns
            the frame about the line through its origin along it. */
        Eigen::Vector3d axis{Eigen::Vector3d::UnitZ()};
    };

    /** \brief Two links a query checks against each other (first < second, indices in RobotModel::links()). */
    using LinkPair = std::pair<std::size_t, std::size_t>;

    /** \brief A robot of one or many bodies: its frames, the map from a state (a vector of doubles) to every frame's
        world pose, the link bodies in those frames, and which link pairs are checked against each other (every
        link is checked against the obstacles; two links are, unless their pair is allowed to touch).

        Kinds (their own files): RigidBodyRobot (one body in SE(2) or SE(3)), MultiBodyRobot (several, each in SE(2)
        or SE(3)), UrdfRobot (a kinematic tree read from a URDF). Configure a model (attach(), allowCollision())
        before sharing it; once shared it is only read, and every query is thread-safe (RobotScene copies the links
        and pairs it is built with). */
    class RobotModel
    {
    public:
        static constexpr std::size_t NONE = std::numeric_limits<std::size_t>::max();

        virtual ~RobotModel() = default;

        /** \brief Numbers in a state. */
        std::size_t dimension() const { return dimension_; }
        const std::vector<RobotFrame> &frames() const { return frames_; }
        const std::vector<RobotLink> &links() const { return links_; }

        /** \brief Index of the frame (a URDF link, a rigid body) named \e name, or NONE. */
        std::size_t findFrame(const std::string &name) const;
        /** \brief Index of the link body named \e name, or NONE. */
        std::size_t findLink(const std::string &name) const;

        /** \brief Throws meshgap::Exception unless \e state (\e size numbers) is a state of this robot: dimension()
            numbers, each finite and within MAX_MAGNITUDE (meshgap/Limits.h), and what the kind of robot requires
            more (a UrdfRobot: every joint within its limits, naming the joint and the limits). */
        void checkState(const double *state, std::size_t size) const;

        /** \brief Every frame's world pose at \e state (\e size numbers, dimension()) into \e frames (resized to
            frames().size(); no allocation once it has that size). Throws meshgap::Exception for a state checkState()
            refuses. */
        void framePoses(const double *state, std::size_t size, std::vector<Eigen::Isometry3d> &frames) const;
        /** \brief Every link body's world pose at \e state into \e links, the frame poses into \e frames (both
            resized; no allocation once they have their size). Throws as framePoses(). */
        void linkPoses(const double *state, std::size_t size, std::vector<Eigen::Isometry3d> &frames,
                       std::vector<Eigen::Isometry3d> &links) const;
        /** \brief The same, allocating: every link body's world pose. */
        std::vector<Eigen::Isometry3d> linkPoses(const std::vector<double> &state) const;

        /** \brief Attach a payload: \e mesh (in its own frame) fixed to the frame \e parent (a URDF link, a rigid
            body, by name) at \e X_FP. It becomes a link named \e name, checked against the obstacles and every
            link but its parent's (the link of frame \e parent or, for a frame without geometry, of its nearest
            ancestor that has some) and the other bodies of the same frame. Returns its link index. Throws
            meshgap::Exception for an unknown parent, a name already taken or an invalid mesh. */
        std::size_t attach(const std::string &name, Mesh mesh, const std::string &parent,
                           const Eigen::Isometry3d &X_FP, const BodyOptions &options = BodyOptions());

        /** \brief Never check links \e a and \e b (names of links or frames: a frame stands for the links in it)
            against each other. Throws meshgap::Exception naming an unknown name. */
        void allowCollision(const std::string &a, const std::string &b);
        /** \brief The same by link index. */
        void allowCollision(std::size_t a, std::size_t b);
        /** \brief True when links \e a and \e b are not checked against each other (a link with itself is
            always allowed). */
        bool isAllowed(std::size_t a, std::size_t b) const;
        /** \brief The link pairs checked against each other: every pair not allowed, in increasing order. */
        std::vector<LinkPair> selfPairs() const;

        /** \brief How frame \e frame (an index in frames()) moves relative to its parent as the state changes. */
        virtual FrameMotion frameMotion(std::size_t frame) const = 0;

        /** \brief The link of frame \e frame or, when that frame has none, of its nearest ancestor with one (NONE
            if none has): what a body fixed to that frame is adjacent to. */
        std::size_t ownerLink(std::size_t frame) const;

    protected:
        RobotModel() = default;

        /** \brief Throws meshgap::Exception naming \e where for a state (dimension() numbers, finite) this kind of
            robot does not take; by default none. */
        virtual void checkStateLimits(const double * /*state*/, const std::string & /*where*/) const
        {
        }

        /** \brief Every frame's world pose at \e state (dimension() numbers, finite, checked by the caller). */
        virtual void computeFrames(const double *state, Eigen::Isometry3d *frames) const = 0;

        /** \brief Add a frame (a parent's index must be below the new one's); returns its index. */
        std::size_t addFrame(const std::string &name, std::size_t parent);
        /** \brief Add a link body in frame \e frame; returns its index. Throws for a name already taken. */
        std::size_t addLink(const std::string &name, BodyConstPtr body, std::size_t frame,
                            const Eigen::Isometry3d &X_FL, bool payload);
        void setDimension(std::size_t dimension) { dimension_ = dimension; }

        /** \brief What error messages call this model (the file it came from, or its kind). */
        std::string where_{"RobotModel"};

    private:
        std::size_t dimension_{0};
        std::vector<RobotFrame> frames_;
        std::vector<RobotLink> links_;
        /** \brief Allowed link pairs, a triangular bit matrix grown with the links. */
        std::vector<std::vector<bool>> allowed_;
    };

    /** \brief The SE(3) pose "x y z qx qy qz qw" (OMPL's order, scalar last) at \e state; the quaternion is
        normalised (a zero or non-finite one throws meshgap::Exception). */
    Eigen::Isometry3d poseFromSE3(const double *state);
    /** \brief The SE(2) pose "x y theta" at \e state, in the plane z = 0 (as OMPL.app's SE(2) problems). */
    Eigen::Isometry3d poseFromSE2(const double *state);
}  // namespace meshgap

#endif
