#ifndef MESHGAP_SCENE_POSE_H
#define MESHGAP_SCENE_POSE_H

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace meshgap
{
    /** \brief Parse "x y z qx qy qz qw" (OMPL's SE3 state order and OMPL.app's .path format: quaternion scalar
        last). The quaternion is normalised; one whose norm is not within 1e-3 of 1, or any non-finite number, or a
        count other than seven, throws meshgap::Exception naming \e where. */
    Eigen::Isometry3d parsePose(const std::string &text, const std::string &where);

    /** \brief Read one pose per line (OMPL.app .path format); blank lines and lines starting with '#' are skipped.
        Errors name the file and line. */
    std::vector<Eigen::Isometry3d> readPoses(const std::string &path);

    /** \brief "x y z qx qy qz qw" with full precision. */
    std::string formatPose(const Eigen::Isometry3d &pose);

    /** \brief Rotation by \e theta radians about \e axis (normalised, at any magnitude), as OMPL.app's
        start.theta/start.axis.*. Throws meshgap::Exception for theta != 0 with a zero or non-finite axis or a
        non-finite theta. */
    Eigen::Isometry3d poseFromAxisAngle(const Eigen::Vector3d &position, double theta, const Eigen::Vector3d &axis);
}  // namespace meshgap

#endif
