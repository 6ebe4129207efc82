#ifndef MESHGAP_ROBOT_ROBOT_PROBLEM_H
#define MESHGAP_ROBOT_ROBOT_PROBLEM_H

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshgap/geometry/Body.h"
#include "meshgap/robot/RobotModel.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/ProblemConfig.h"

namespace meshgap
{
    /** \brief A planning problem for a robot of many bodies, read from an OMPL.app-style .cfg (readRobotProblem()).

        A URDF robot: [problem] keys
        - robot.urdf = FILE; robot.srdf = FILE (optional: its disable_collisions pairs are allowed; they may name the
          payload);
          robot.package_path = DIR:DIR (optional; else ROS_PACKAGE_PATH; the URDF's folder and its parents are
          searched after either);
        - world = FILE (the obstacles: the mesh's connected parts, in the world frame, as for a single body);
        - scene = FILE, request = FILE (optional, instead of or beside world and the joints): a MoveIt planning
          scene and motion plan request in YAML, read as readMoveItProblem() reads them (obstacles, allowed
          collision matrix, start and goal); start.joints and goal.joints, when given too, replace theirs;
        - attach = MESH LINK x y z qx qy qz qw (optional): the payload MESH (in its own frame) fixed to link LINK at
          that pose; it becomes the link named "payload";
        - start.joints = v1 v2 ... and goal.joints = ... (goal optional): the URDF's movable joints (revolute,
          continuous, prismatic; not fixed, not mimic) in its order; seven more numbers first, "x y z qx qy qz qw",
          make the base float in SE(3) (its pose). A robot without movable joints needs no start.joints (its state
          has no numbers): its clearance can be asked, there is nothing to plan.
        Several rigid bodies (OMPL.app's multi-body problems): robot.1 = FILE, robot.2 = FILE, ... (numbered from 1,
        no gaps), world, and per body start.N.x, start.N.y, start.N.z, start.N.theta, start.N.axis.x/y/z (the same
        for goal.N): each body a mesh centred as OMPL.app centres a robot, its state its pose; an SE(2) body (x y
        theta, in the plane z = 0) when no body has start.N.z, as a planar single-body file; SE(3) otherwise
        (x y z qx qy qz qw; theta about the axis, as OMPL.app's start.theta and start.axis).
        Both: name, volume.min.x .. volume.max.z (x and y only when planar), objective, objective.threshold,
        sampler, and the [benchmark] and [planner] sections: ProblemSettings, as every kind reads them. Relative paths are relative
        to the .cfg's folder. */
    struct RobotProblem : ProblemSettings
    {
        /** \brief The robot: a UrdfRobot (SRDF read, payload attached), a MultiBodyRobot, or (rigidBodyProblem()) a
            RigidBodyRobot. */
        RobotModelPtr robot;
        bool urdf{false};  ///< robot is a UrdfRobot
        std::vector<BodyConstPtr> obstacles;  ///< the world's connected parts (a MoveIt scene's shapes)
        /** \brief Per obstacle, the collision object it belongs to (a MoveIt scene's); empty for a world mesh. */
        std::vector<std::string> obstacleNames;
        /** \brief (link, obstacle) pairs never checked (a MoveIt scene's allowed collision matrix): give them to
            RobotScene. */
        std::vector<LinkPair> allowedObstacles;
        std::string scene, request;  ///< the MoveIt scene and request (scene = FILE, request = FILE), resolved
        std::vector<double> start;   ///< robot->dimension() numbers
        std::optional<std::vector<double>> goal;
    };

    /** \brief A problem file of any kind, read once by readProblem(), the one place that tells the kinds apart:
        exactly one of the two is set. */
    struct Problem
    {
        /** \brief A single rigid body (robot = FILE: one mesh in SE(2) or SE(3), or OMPL.app's control problem), as
            readProblemConfig() reads it; rigidBodyProblem() gives it as a robot problem. */
        std::optional<ProblemConfig> rigidBody;
        /** \brief A robot problem (robot.urdf, robot.1, ...), as readRobotProblem() reads it. */
        std::optional<RobotProblem> robot;
    };

    /** \brief Read the problem \e path, whatever its kind (a robot problem's bodies built with \e options; a single
        body's meshes are not loaded). Throws as readProblemConfig() or readRobotProblem() for the kind the file is,
        and as readConfigFile() for a file that cannot be read. */
    Problem readProblem(const std::string &path, const BodyOptions &options = BodyOptions());

    /** \brief A single-body problem as a robot problem: a one-link RigidBodyRobot named "robot" (the robot mesh
        centred as OMPL.app centres it, in SE(2) when the problem is planar, else SE(3)), the world's connected parts
        as obstacles, the start and goal as states (rigidState()), and the settings (ProblemSettings: volume, objective,
        sampler, sections) as they are. A control problem's body too: its state is then the body's pose, the geometric part of the
        control state. Throws as the mesh loader does. */
    RobotProblem rigidBodyProblem(const ProblemConfig &config, const BodyOptions &options = BodyOptions());

    /** \brief Any problem as a robot problem: readProblem(), a single body through rigidBodyProblem(). */
    RobotProblem readAnyRobotProblem(const std::string &path, const BodyOptions &options = BodyOptions());

    /** \brief Read the robot problem \e path, building every body with \e options. Throws meshgap::Exception naming
        "file:line" for a malformed line or number, an unknown key, a single-body key (robot = FILE: such files are
        read by readProblemConfig()), a start.joints or goal.joints of the wrong count or outside a joint's limits,
        an attach line that is not a mesh, a link and seven numbers or names an unknown link, a numbered body with a
        gap, a missing file (URDF, SRDF, world, payload, a robot mesh), and whatever the URDF or SRDF reader
        rejects (a URDF mesh that cannot be found, ...). */
    RobotProblem readRobotProblem(const std::string &path, const BodyOptions &options = BodyOptions());

    /** \brief The robot scene the planning tools check \e problem with: its robot among its obstacles, its allowed
        pairs honoured, and its self pairs tabulated over their joints (RobotScene::tabulateSelfPairs(), a
        fraction of a second for an arm; nothing for a robot without self pairs). */
    RobotScenePtr planningScene(const RobotProblem &problem);
}  // namespace meshgap

#endif
