#ifndef MESHGAP_ROBOT_JOINT_H
#define MESHGAP_ROBOT_JOINT_H

#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(Joint);

    /** \brief The OMPL space that holds a joint's values (RobotStateSpace builds it; the robot layer names it only). */
    enum class JointSpace
    {
        NONE,  ///< no values (a fixed joint)
        REAL,  ///< one bounded number per value (consecutive ones share one RealVectorStateSpace)
        SO2,   ///< one angle, unbounded, interpolated along the shorter arc (SO2StateSpace)
        SE2,   ///< "x y theta" (SE2StateSpace: x and y within the problem's bounds, theta along the shorter arc)
        SE3    ///< "x y z qx qy qz qw" (SE3StateSpace: the position within the problem's bounds, slerp)
    };

    /** \brief How a joint moves its child frame as OMPL interpolates its values, for the motion bound
        (MotionBound, RobotModel::frameMotion()). */
    enum class JointMotion
    {
        FIXED,        ///< not at all
        ROTATION,     ///< about an axis through the child frame's origin, by the value's change
        TRANSLATION,  ///< along a unit axis, by the value's change
        // A joint of one value that is a ROTATION turns by its value about axis(), a TRANSLATION moves by it along
        // axis(): RobotModel applies these two inline, without move().
        SE2,          ///< free in a plane: "x y theta", x and y linear, theta along the shorter arc
        SE3           ///< free: "x y z qx qy qz qw", the position linear, the rotation along the shorter great arc
    };

    /** \brief What a joint type is built from: the URDF joint element's numbers. */
    struct JointSpec
    {
        /** \brief The joint's axis in the joint frame (URDF's default 1 0 0), unit (or zero, which a type that
            needs an axis refuses). */
        Eigen::Vector3d axis{Eigen::Vector3d::UnitX()};
        /** \brief The URDF's limits, when it gives them (a revolute or prismatic joint must). */
        bool hasLimits{false};
        double lower{0.0}, upper{0.0};
    };

    /** \brief One type of joint: how its values (0 to 7 numbers of a state) move the child frame relative to the
        joint frame (the child's pose is parent * origin * motion(values)), their limits, the OMPL space that holds
        them, how far the motion moves points (the motion bound) and their velocity (the Jacobian). One class per
        type, each in its own file under src/robot/joints/, registered by its URDF type name (makeJoint()). A joint
        is immutable once built and shared between robots and threads. */
    class Joint
    {
    public:
        virtual ~Joint() = default;

        /** \brief The URDF type name ("revolute", "planar", ...). */
        virtual const char *type() const = 0;
        /** \brief Numbers of a state it takes. */
        virtual std::size_t size() const = 0;
        virtual JointSpace space() const = 0;
        virtual JointMotion motion() const = 0;
        /** \brief The name of value \e k within the joint ("" for a joint of one value, "x", "qw", ...). */
        virtual std::string valueName(std::size_t /*k*/) const { return ""; }
        /** \brief The limits of value \e k that a state must keep (infinite where there are none: an angle, a
            planar or floating joint's position, whose bounds the problem gives). */
        virtual double lower(std::size_t /*k*/) const { return -std::numeric_limits<double>::infinity(); }
        virtual double upper(std::size_t /*k*/) const { return std::numeric_limits<double>::infinity(); }
        /** \brief A neutral value of value \e k: 0 within the limits (the middle of them when 0 is outside), the
            identity rotation's numbers. */
        virtual double neutral(std::size_t k) const;

        /** \brief \e X = \e X * motion(\e q), \e q its size() values (finite). */
        virtual void move(const double *q, Eigen::Isometry3d &X) const = 0;
        /** \brief motion(\e q) alone (a root frame's pose, its origin the identity). */
        virtual Eigen::Isometry3d pose(const double *q) const
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            move(q, X);
            return X;
        }

        /** \brief How far the child frame's origin gets from the joint frame's origin, its value within
            [\e lowest, \e highest] (its limits, or a mimic joint's map of its source's limits); infinite for a joint
            of several values, which the problem's bounds limit. */
        virtual double reach(double /*lowest*/, double /*highest*/) const { return 0.0; }

        /** \brief Adds \e scale times the world-frame velocity of the point \e p (world) fixed to the child frame,
            per unit change of each value, to the columns \e column, ... of \e J: the child frame is at \e X_WC (world)
            with the values \e q. */
        virtual void addJacobian(const double *q, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d &p,
                                 double scale, Eigen::Matrix3Xd &J, Eigen::Index column) const = 0;

        /** \brief The unit axis it was built with (a planar joint's normal; unused by a fixed or floating one). */
        const Eigen::Vector3d &axis() const { return axis_; }

    protected:
        explicit Joint(const Eigen::Vector3d &axis) : axis_(axis) {}

    private:
        Eigen::Vector3d axis_;
    };

    /** \brief One registered joint type: its URDF name and how to build it from a spec (throws meshgap::Exception,
        without a place, for a spec it cannot take: a zero axis, missing limits). */
    struct JointType
    {
        const char *name;
        JointConstPtr (*make)(const JointSpec &spec);
    };

    /** \brief Every registered joint type (the files of src/robot/joints/, listed by the build). */
    const std::vector<const JointType *> &jointTypes();

    /** \brief A joint of the type named \e type (a URDF type name) from \e spec. Throws meshgap::Exception for an
        unknown type (naming the known ones) or a spec the type refuses. */
    JointConstPtr makeJoint(const std::string &type, const JointSpec &spec = JointSpec());

    /** \brief The known type names, "a, b, c". */
    std::string jointTypeNames();

    /** \brief The spec's axis, normalised (stable: "1 0 1e300" and "1e-200 0 0" keep their direction). Throws
        meshgap::Exception for a zero or non-finite axis (a type that moves along or about its axis). */
    Eigen::Vector3d unitAxis(const JointSpec &spec);
}  // namespace meshgap

/** \brief Define, inside namespace meshgap, the registered joint type \e Name (a class \e Name deriving from Joint,
    with a constructor from a JointSpec) under the URDF type name \e urdf, in the type's own file src/robot/joints/
    Name.cpp: the build lists the files of that folder and registers what each defines. */
#define MESHGAP_REGISTER_JOINT(Name, urdf)                                                                             \
    const JointType &Name##Type()                                                                                      \
    {                                                                                                                  \
        static const JointType type{urdf, [](const JointSpec &spec) -> JointConstPtr                                   \
                                    { return std::make_shared<const Name>(spec); }};                                   \
        return type;                                                                                                   \
    }

#endif
