#ifndef MESHGAP_SCENE_PROBLEM_CONFIG_H
#define MESHGAP_SCENE_PROBLEM_CONFIG_H

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace meshgap
{
    struct ConfigFile;
    class ConfigKeys;

    /** \brief What every problem file gives, whatever its kind (a single body, ProblemConfig; a robot, RobotProblem):
        the file, its name, whether it is planar (SE(2)), the world mesh, the volume, the objective, the sampler, and
        the [benchmark] and [planner] sections (key/value lists in file order). Read once by readProblemSettings(),
        so the kinds share one model of these fields rather than copies of them. */
    struct ProblemSettings
    {
        std::string file;    ///< the .cfg path
        std::string name;    ///< problem name (the file's stem when absent)
        bool planar{false};  ///< SE(2): no start.z (start.N.z) in the file
        std::string world;   ///< world mesh path, resolved (empty for a MoveIt scene's obstacles alone)
        /** \brief volume.min.x .. volume.max.z (x and y only when planar: z is then [0, 0]). */
        std::optional<Eigen::AlignedBox3d> volume;
        std::string objective;  ///< e.g. "length", "max_min_clearance"; empty if absent
        std::optional<double> objectiveThreshold;
        std::string sampler;
        std::vector<std::pair<std::string, std::string>> benchmark;  ///< [benchmark] entries
        std::vector<std::pair<std::string, std::string>> planners;   ///< [planner] entries
    };

    /** \brief Read the keys every kind of problem shares into \e settings (its planar flag set first): name (else
        \e file's stem), volume, objective, objective.threshold, sampler, and the [benchmark] and [planner] sections.
        Throws meshgap::Exception naming "file:line" for a number that is not one, a volume.*.z key in a planar
        problem, or a volume.max not above its volume.min, and the file for a volume given in part. */
    void readProblemSettings(const ConfigFile &file, const ConfigKeys &keys, ProblemSettings &settings);

    /** \brief An OMPL.app problem file (.cfg), read unchanged: [problem] with robot, world, start/goal (position
        plus axis-angle in radians), volume, objective and sampler (ProblemSettings); [benchmark] and [planner] are
        kept as key/value lists in file order. Mesh paths are resolved against the .cfg's folder.

        A file without start.z is a planar (SE(2)) problem, as OMPL.app's 2D problems are: start.x, start.y,
        start.theta (the yaw about z, radians), the same for the goal, and volume.min.x/y, volume.max.x/y; the robot
        moves in the plane z = 0 of the 3D world. start and goal are then poses at z = 0 rotated about z, and the
        volume's z range is [0, 0]. */
    struct ProblemConfig : ProblemSettings
    {
        std::string robot;  ///< robot mesh path, resolved
        Eigen::Isometry3d start{Eigen::Isometry3d::Identity()};
        std::optional<Eigen::Isometry3d> goal;
        /** \brief OMPL.app's control model (its "control" key: kinematic_car, dynamic_car, blimp, quadrotor); empty
            for a geometric problem. */
        std::string control;
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
