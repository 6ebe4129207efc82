#ifndef MESHGAP_ROBOT_MOVEIT_SCENE_H
#define MESHGAP_ROBOT_MOVEIT_SCENE_H

#include <string>
#include <vector>

#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/UrdfRobot.h"

namespace meshgap
{
    /** \brief The files of a problem posed as MoveIt poses it: a URDF robot (and its SRDF), a
        moveit_msgs/PlanningScene and a moveit_msgs/MotionPlanRequest, both in YAML. */
    struct MoveItFiles
    {
        std::string urdf;
        std::string srdf;     ///< optional: its disable_collisions pairs are allowed
        std::string scene;    ///< optional: no obstacles, the default robot state
        std::string request;  ///< optional: the start is the scene's robot state, no goal
        /** \brief Folders of the packages "package://" URIs name (the URDF's meshes, a mesh resource of the
            scene); empty: ROS_PACKAGE_PATH. */
        std::vector<std::string> packagePath;
        /** \brief Facets around a cylinder, a sphere and a cone (circumscribed: cylinderMesh(), ...). */
        unsigned int segments{32};
        /** \brief When set, a copy of this robot (the URDF and SRDF read once, for many problems of one robot) is
            used instead of reading urdf and srdf again. */
        UrdfRobotConstPtr robot;
    };

    /** \brief The robot of \e files: its URDF (fixed base) with its SRDF read. Throws as UrdfRobot::load() and
        readSrdf(). */
    UrdfRobotPtr readMoveItRobot(const MoveItFiles &files, const BodyOptions &options = BodyOptions());

    /** \brief Read a problem from MoveIt's formats into the RobotProblem a robot .cfg gives (a fixed-base
        UrdfRobot, the obstacles, start and goal joints).

        The scene (moveit_msgs/PlanningScene, as MotionBenchMaker and MoveIt write it in YAML):
        - world.collision_objects: each object's primitives (type box, sphere, cylinder or cone, by name or by
          shape_msgs/SolidPrimitive's number; dimensions as SolidPrimitive orders them: box x y z, sphere radius,
          cylinder and cone height radius) with primitive_poses, and its meshes (shape_msgs/Mesh: vertices and
          triangles' vertex_indices; or a "resource" file or package:// URI with an optional "scale") with
          mesh_poses, each pose within the object's own pose ("pose", identity when absent), in the frame of the
          object's header.frame_id: empty, a fixed_frame_transforms child frame (its transform applied) or a link of
          the robot (its pose at the scene's robot state). One obstacle body per primitive or mesh, named after its
          object (RobotProblem::obstacleNames). Each primitive is a body of its circumscribed mesh (cylinderMesh(),
          sphereMesh(), coneMesh(); boxMesh() exact) that keeps the primitive as the solid it is, in the world frame
          (Body::primitives()): the exact queries answer the solid (refineExact(), 5), the node solvers the mesh.
        - allowed_collision_matrix: entry_names and entry_values (rows as lists of booleans, or {enabled: [...]});
          default_entry_names and default_entry_values (a name allowed against everything). An allowed pair of two
          links is never checked (as the SRDF's disable_collisions, which are honoured too); of a link and an object,
          that link is not checked against that object's bodies (RobotProblem::allowedObstacles). Names that are
          neither a link (or frame) of the robot nor an object of the scene allow nothing and are ignored, as MoveIt
          keeps such names without effect.
        - robot_state.joint_state (name, position): the robot's state in the scene, over its default (every joint
          at 0, or at the middle of its limits when 0 is outside them).

        The request (moveit_msgs/MotionPlanRequest): start_state.joint_state over the scene's robot state is the
        start; goal_constraints[0].joint_constraints (joint_name, position) over the start is the goal (the first
        of several goal constraints, each of which MoveIt takes as a goal; position, orientation and visibility
        constraints are refused).

        Joint names: a movable joint takes the value; a mimic joint's value is ignored (it follows its joint); a
        fixed joint must be 0. Throws one meshgap::Exception naming the file (and line) and the entry for YAML that
        cannot be read, an entry of the wrong type or size, an unknown joint, link or frame, a joint value outside
        its limits, a mesh that cannot be found or read, an unknown primitive type, a quaternion that is not of unit
        length, attached collision objects or an octomap (not read), and whatever the URDF and SRDF readers reject.
        */
    RobotProblem readMoveItProblem(const MoveItFiles &files, const BodyOptions &options = BodyOptions());
}  // namespace meshgap

#endif
