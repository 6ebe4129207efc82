#ifndef MESHGAP_SCENE_PROBLEM_CONFIG_H
#define MESHGAP_SCENE_PROBLEM_CONFIG_H

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meshgap
{
    /** \brief An OMPL.app problem file (.cfg), read unchanged: [problem] with robot, world, start/goal (position
        plus axis-angle in radians), volume, objective and sampler; [benchmark] and [planner] are kept as key/value
        lists in file order. Mesh paths are resolved against the .cfg's folder.

        A file without start.z is a planar (SE(2)) problem, as OMPL.app's 2D problems are: start.x, start.y,
        start.theta (the yaw about z, radians), the same for the goal, and volume.min.x/y, volume.max.x/y; the robot
        moves in the plane z = 0 of the 3D world. start and goal are then poses at z = 0 rotated about z, and the
        volume's z range is [0, 0]. */
    struct ProblemConfig
    {
        std::string file;    ///< the .cfg path
        std::string name;    ///< problem name (the file's stem when absent)
        bool planar{false};  ///< SE(2): no start.z in the file
        std::string robot;   ///< robot mesh path, resolved
        std::string world;   ///< world mesh path, resolved
        Eigen::Isometry3d start{Eigen::Isometry3d::Identity()};
        std::optional<Eigen::Isometry3d> goal;
        std::optional<Eigen::AlignedBox3d> volume;
        std::string objective;  ///< e.g. "length", "max_min_clearance"; empty if absent
        std::optional<double> objectiveThreshold;
        std::string sampler;
        /** \brief OMPL.app's control model (its "control" key: kinematic_car, dynamic_car, blimp, quadrotor); empty
            for a geometric problem. */
        std::string control;
        std::vector<std::pair<std::string, std::string>> benchmark;  ///< [benchmark] entries
        std::vector<std::pair<std::string, std::string>> planners;   ///< [planner] entries
    };

    /** \brief Read a .cfg. Throws meshgap::Exception naming "file:line" for a malformed line, an unknown section or
        [problem] key, a value that is not a number where one is needed, a zero rotation axis, a 3D key (goal.z,
        *.axis.*, volume.*.z) in a planar file, and "file" for a missing required key (robot, world, start.x/y, and
        start.z unless planar) or a mesh file that does not exist, and "file:line" for a key of a robot problem
        (robotProblemKey(): robot.urdf, start.joints, robot.1, ...; those files are read by readRobotProblem()), and a
        "control" model other than controlModelNames(). */
    ProblemConfig readProblemConfig(const std::string &path);

    /** \brief The control models OMPL.app's "control" key names: kinematic_car, dynamic_car, blimp, quadrotor. */
    const std::vector<std::string> &controlModelNames();
}  // namespace meshgap

#endif
