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
#include "meshgap/robot/Joint.h"

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
        /** \brief FIXED, ROTATION (about an axis through the frame's origin, by scale times the state number's
            change), TRANSLATION (along a unit axis, the same), SE2 ("x y theta" from \e variable on, x and y linear,
            theta along the shorter arc), SE3 ("x y z qx qy qz qw" from \e variable on, the rotation by slerp). */
        using Kind = JointMotion;
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

    /** \brief How a frame hangs from its parent (the world, for a root): fixed at \e origin, then moved by its joint's
        values (the child's pose: parent * origin * joint motion). A mimic joint's one value is multiplier * (state
        number \e variable) + offset. */
    struct FrameJoint
    {
        /** \brief The joint's name (a URDF joint's; "base" for a floating base; a rigid body's name). */
        std::string name;
        /** \brief Null: fixed at \e origin. */
        JointConstPtr joint;
        Eigen::Isometry3d origin{Eigen::Isometry3d::Identity()};
        /** \brief The state number of its first value (a mimic joint: its source's), or RobotModel::NONE. */
        std::size_t variable{std::numeric_limits<std::size_t>::max()};
        /** \brief A mimic joint: the frame whose joint it follows; RobotModel::NONE otherwise. */
        std::size_t mimics{std::numeric_limits<std::size_t>::max()};
        double multiplier{1.0}, offset{0.0};
    };

    /** \brief A run of state numbers one OMPL space holds (RobotStateSpace): the numbers first, ..., first +
        names.size() - 1, their names ("shoulder", "base.qw") and limits (infinite where the problem's bounds
        or nothing bound them). REAL blocks hold consecutive one-value joints; SO2, SE2 and SE3 blocks one joint. */
    struct StateBlock
    {
        JointSpace space;
        std::size_t first;
        std::vector<std::string> names;
        std::vector<double> lower, upper;
    };

    /** \brief Two links a query checks against each other (first < second, indices in RobotModel::links()). */
    using LinkPair = std::pair<std::size_t, std::size_t>;

    /** \brief A robot of one or many bodies: its frames, the map from a state (a vector of doubles) to every frame's
        world pose, the link bodies in those frames, and which link pairs are checked against each other (every
        link is checked against the obstacles; two links are, unless their pair is allowed to touch).

        Each frame hangs from its parent by a FrameJoint (a Joint, one class per type: revolute, continuous,
        prismatic, fixed, planar, floating), from which the model answers what tools need: the frame poses, the
        motion bound's frame motions, the state's OMPL spaces (stateBlocks()) and Jacobians. Kinds (their own
        files) build the frames: RigidBodyRobot (one body in SE(2) or SE(3): a planar or floating joint from the
        world), MultiBodyRobot (several such), UrdfRobot (a kinematic tree read from a URDF). Configure a model
        (attach(), allowCollision()) before sharing it; once shared it is only read, and every query is thread-safe
        (RobotScene copies the links and pairs it is built with). */
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
        /** \brief The nearest frame above both frames \e a and \e b (themselves included), or NONE when they hang
            from two roots. */
        std::size_t commonFrame(std::size_t a, std::size_t b) const;

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

        /** \brief How frame \e frame (an index in frames()) hangs from its parent. */
        const FrameJoint &frameJoint(std::size_t frame) const { return joints_[frame]; }

        /** \brief How frame \e frame (an index in frames()) moves relative to its parent as the state changes: by
            default its joint's motion (a mimic joint driven by its source's state number, |multiplier| times as
            far, an angle when its source is one), its reach the joint origin's distance from the parent frame plus
            the joint's own (Joint::reach(), over its source's limits mapped by a mimic's multiplier and offset). */
        virtual FrameMotion frameMotion(std::size_t frame) const;

        /** \brief The state's numbers in runs, each held by one OMPL space (RobotStateSpace builds the space from
            them): by default from the frames' joints, in state order. */
        virtual std::vector<StateBlock> stateBlocks() const;
        /** \brief State number \e number's name ("elbow", "base.qw"), limits (infinite where none). */
        const std::string &stateName(std::size_t number) const { return numbers_[number].name; }
        double stateLower(std::size_t number) const { return numbers_[number].lower; }
        double stateUpper(std::size_t number) const { return numbers_[number].upper; }
        /** \brief True when a frame moves free in SE(2) or SE(3) (a rigid body, a floating base, a planar or floating
            joint): the problem must bound its position. */
        bool movesFree() const;

        /** \brief The world-frame velocity of the point \e p (world), fixed to frame \e frame, per unit change of each
            state number at \e state: a 3 x dimension() Jacobian into \e J, from the frame poses \e frames at that
            state (framePoses()). By default each joint from \e frame up adds its columns (Joint::addJacobian(); a
            mimic joint adds its multiplier times its own to its source's). */
        virtual void pointJacobian(const double *state, const std::vector<Eigen::Isometry3d> &frames,
                                   std::size_t frame, const Eigen::Vector3d &p, Eigen::Matrix3Xd &J) const;

        /** \brief What the robot is, in a few words, for a tool's summary: by default "N links"; each kind says
            more ("URDF 'arm', 6 joints", "2 bodies in SE(2)", "one body in SE(3)"). */
        virtual std::string description() const;

        /** \brief The link of frame \e frame or, when that frame has none, of its nearest ancestor with one (NONE
            if none has): what a body fixed to that frame is adjacent to. */
        std::size_t ownerLink(std::size_t frame) const;

    protected:
        RobotModel() = default;

        /** \brief Throws meshgap::Exception naming \e where for a state (dimension() numbers, finite) this kind of
            robot does not take; by default one with a number outside its limits (stateLower(), stateUpper(), to
            1e-9 of the larger of 1 and the limit: the roundoff of an interpolation between two states at the limits
            passes), naming the joint, its value and limits. */
        virtual void checkStateLimits(const double *state, const std::string &where) const;

        /** \brief Every frame's world pose at \e state (dimension() numbers, finite, checked by the caller): by
            default a walk down the frames, parent before child, through their joints. */
        virtual void computeFrames(const double *state, Eigen::Isometry3d *frames) const;

        /** \brief Set how frame \e frame hangs from its parent (a frame added by addFrame() is fixed at the
            identity). Call before setDimension(). */
        void setFrameJoint(std::size_t frame, FrameJoint joint);

        /** \brief Add a frame (a parent's index must be below the new one's); returns its index. */
        std::size_t addFrame(const std::string &name, std::size_t parent);
        /** \brief Add a link body in frame \e frame; returns its index. Throws for a name already taken. */
        std::size_t addLink(const std::string &name, BodyConstPtr body, std::size_t frame,
                            const Eigen::Isometry3d &X_FL, bool payload);
        /** \brief Set the state's size, once the frames' joints are set; throws meshgap::Exception unless the
            joints' values cover the numbers 0 .. dimension - 1 once each. */
        void setDimension(std::size_t dimension);

        /** \brief What error messages call this model (the file it came from, or its kind). */
        std::string where_{"RobotModel"};

    private:
        std::size_t dimension_{0};
        std::vector<RobotFrame> frames_;
        std::vector<FrameJoint> joints_;
        /** \brief How computeFrames() moves a frame after its origin: not at all, by Joint::pose() alone (a root
            whose origin is the identity), a turn about or a slide along the joint's axis by its one value (inline),
            or by Joint::move(). */
        enum class Step : unsigned char
        {
            FIXED,
            ROOT,
            ROTATE,
            SLIDE,
            MOVE
        };
        std::vector<Step> steps_;
        /** \brief Per state number: its name, limits, and the limits checkState() takes (with their slack). */
        struct Number
        {
            std::string name;
            double lower, upper, low, high;
        };
        std::vector<Number> numbers_;
        /** \brief The numbers with a finite limit, and the limits checkState() takes: all it looks at. */
        struct Limit
        {
            std::size_t number;
            double low, high;
        };
        std::vector<Limit> limited_;
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
