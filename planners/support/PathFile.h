#ifndef MESHGAP_PLANNERS_SUPPORT_PATH_FILE_H
#define MESHGAP_PLANNERS_SUPPORT_PATH_FILE_H

#include <ompl/geometric/PathGeometric.h>
#include <string>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief Read a path in OMPL's .path format (what meshgap_plan --out and OMPL.app write: one state a line, x y z
        qx qy qz qw for an SE(3) space, x y theta for SE(2); blank lines and '#' lines skipped) as a path of \e si's
        states. Throws meshgap::Exception naming "file:line" for a line with the wrong count of numbers, a
        non-number, NaN, or a quaternion not of unit length, and "file" for a missing file or one without states. */
    ompl::geometric::PathGeometric readPathFile(const std::string &file, const ompl::base::SpaceInformationPtr &si);

    /** \brief One state of \e robot from \e text: robot.dimension() finite numbers (as start.joints: a floating
        base's pose first, then the joints; per body its pose for several bodies). Throws meshgap::Exception naming
        \e where for a non-number, a number not finite, another count, a state RobotModel::checkState() refuses
        (a joint outside its limits, a number beyond MAX_MAGNITUDE), or a pose (a single body's, a free base's, a
        body's in SE(3)) whose quaternion is not of unit length within 1e-3. */
    std::vector<double> parseRobotState(const std::string &text, const RobotModel &robot, const std::string &where);

    /** \brief The states of a robot problem's .path file: one state a line (parseRobotState(), naming "file:line");
        blank and '#' lines skipped. Throws meshgap::Exception naming "file" for a missing file or one without
        states. */
    std::vector<std::vector<double>> readRobotPathFile(const std::string &file, const RobotModel &robot);
}  // namespace meshgap

#endif
