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
        lists in file order. Mesh paths are resolved against the .cfg's folder. */
    struct ProblemConfig
    {
        std::string file;    ///< the .cfg path
        std::string name;    ///< problem name (the file's stem when absent)
        std::string robot;   ///< robot mesh path, resolved
        std::string world;   ///< world mesh path, resolved
        Eigen::Isometry3d start{Eigen::Isometry3d::Identity()};
        std::optional<Eigen::Isometry3d> goal;
        std::optional<Eigen::AlignedBox3d> volume;
        std::string objective;  ///< e.g. "length", "max_min_clearance"; empty if absent
        std::optional<double> objectiveThreshold;
        std::string sampler;
        std::vector<std::pair<std::string, std::string>> benchmark;  ///< [benchmark] entries
        std::vector<std::pair<std::string, std::string>> planners;   ///< [planner] entries
    };

    /** \brief Read a .cfg. Throws meshgap::Exception naming "file:line" for a malformed line, an unknown section or
        [problem] key, a value that is not a number where one is needed, a zero rotation axis, and "file" for a
        missing required key (robot, world, start.x/y/z) or a mesh file that does not exist. */
    ProblemConfig readProblemConfig(const std::string &path);
}  // namespace meshgap

#endif
