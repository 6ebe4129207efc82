#ifndef MESHGAP_ROBOT_URDF_ROBOT_H
#define MESHGAP_ROBOT_URDF_ROBOT_H

#include <string>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(UrdfRobot);

    /** \brief How to read a URDF. */
    struct UrdfOptions
    {
        /** \brief Folders that hold the packages "package://" URIs name (resolveRobotUri()); empty: the folders of
            ROS_PACKAGE_PATH. The URDF's own folder and its parents are searched after them in either case. */
        std::vector<std::string> packagePath;
        /** \brief The root link moves free in SE(3), its pose the state's first seven numbers ("x y z qx qy qz
            qw"); else it is fixed at the world origin. */
        bool floatingBase{false};
        /** \brief Facets around a cylinder and a sphere (cylinderMesh(), sphereMesh()). */
        unsigned int segments{32};
        /** \brief A link of boxes, cylinders and spheres keeps them as solids (Body::primitives()), which the exact
            queries answer as the shapes they are (refineExact(), 5); false: its circumscribed mesh alone (what an
            oracle on the same triangles, FCL's BVHModel, answers). */
        bool solids{true};
        /** \brief How each link's mesh becomes a body. */
        BodyOptions body;
    };

    /** \brief One joint of a UrdfRobot, as the forward kinematics uses it: the child frame's pose is the parent
        frame's pose, then origin, then the joint's motion (Joint::move() of its values). */
    struct UrdfJoint
    {
        std::string name;
        /** \brief Its type (revolute, continuous, prismatic, fixed, planar, floating: Joint::type()), axis and
            limits. */
        JointConstPtr joint;
        std::size_t parent, child;  ///< frames (RobotModel::frames())
        Eigen::Isometry3d origin;   ///< the joint frame in the parent frame
        Eigen::Vector3d axis;       ///< unit, in the joint frame (Joint::axis())
        /** \brief Where its first value is in a state (a movable joint's), or RobotModel::NONE (a fixed or mimic
            joint). */
        std::size_t variable;
        /** \brief A mimic joint: the value is multiplier * (the value of joint \e mimics) + offset, \e mimics a
            movable joint's index in joints() (chains of mimic joints resolved; both of one value);
            RobotModel::NONE otherwise. */
        std::size_t mimics;
        double multiplier, offset;
    };

    /** \brief A kinematic tree read from a URDF (urdfdom): one frame per URDF link, one link body per URDF link with
        geometry (its collision elements merged; its visual elements when it has no collision element), meshes
        and boxes, cylinders and spheres alike (a link of boxes, cylinders and spheres only keeps them as solids in
        its body's frame, Body::primitives()). The state: a floating base's pose first (UrdfOptions::floatingBase),
        then the values of every movable joint (not fixed, not mimic) in the order the URDF lists them: one for a
        revolute, continuous or prismatic joint, "x y theta" for a planar joint, "x y z qx qy qz qw" for a floating
        one (src/robot/joints/: URDF gives these two no limits, the problem's bounds bound their positions in OMPL's
        space). Forward kinematics is a walk down the tree, parent before child. Links joined by a joint are allowed
        to touch (a link with no geometry is skipped: its children are adjacent to its nearest ancestor with
        geometry); readSrdf() allows more. */
    class UrdfRobot : public RobotModel
    {
    public:
        /** \brief Read \e path. Throws meshgap::Exception naming the file and the problem: unreadable XML, a joint type
            not registered (jointTypes(): revolute, continuous, prismatic, fixed, planar, floating), joints that do not
            form one tree (a cycle, a link with two parent joints, several roots, an unknown link), a mimic joint of an
            unknown joint or of or by a joint not of one value (fixed, planar, floating), a zero axis, a joint origin
            coordinate, limit or (composed) mimic multiplier or offset above 1e9 in magnitude, a name urdfdom reads
            differently from the XML (an unknown entity), a mesh that cannot be found or read, a bad primitive, and
            whatever else urdfdom rejects. Throws also for what urdfdom drops with a message and reads on without: a
            <collision> or <visual> element whose origin or shape has a number that is not one, not finite, beyond
            MAX_MAGNITUDE (meshgap/Limits.h), not positive where a size must be, or too few or too many of them, an
            unknown shape or a mesh without a file name (naming file:line and the element); and a robot without any
            collision geometry. */
        static UrdfRobotPtr load(const std::string &path, const UrdfOptions &options = UrdfOptions());

        /** \brief Every joint, parent before child (the order of the forward kinematics). */
        const std::vector<UrdfJoint> &joints() const { return joints_; }
        /** \brief The joint (index in joints()) behind each joint value of a state, in state order (a joint of
            several values once per value). */
        const std::vector<std::size_t> &variables() const { return variables_; }
        /** \brief Where the joint values start in a state: 7 with a floating base, else 0. */
        std::size_t jointOffset() const { return floatingBase_ ? 7 : 0; }
        /** \brief The joint named \e name (index in joints()), or RobotModel::NONE. */
        std::size_t findJoint(const std::string &name) const;
        bool floatingBase() const { return floatingBase_; }
        /** \brief The URDF's robot name. */
        const std::string &name() const { return name_; }

        /** \brief "URDF 'NAME', floating base, N joints" (N: the joint values of a state). */
        std::string description() const override;

    private:
        UrdfRobot() = default;
        friend struct UrdfBuilder;

        std::string name_;
        bool floatingBase_{false};
        std::vector<UrdfJoint> joints_;
        std::vector<std::size_t> variables_;
    };
}  // namespace meshgap

#endif
