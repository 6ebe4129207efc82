#ifndef MESHGAP_PLANNERS_SUPPORT_PATH_FILE_H
#define MESHGAP_PLANNERS_SUPPORT_PATH_FILE_H

#include <ompl/geometric/PathGeometric.h>
#include <string>

namespace meshgap
{
    /** \brief Read a path in OMPL's .path format (what meshgap_plan --out and OMPL.app write: one state a line, x y z
        qx qy qz qw for an SE(3) space, x y theta for SE(2); blank lines and '#' lines skipped) as a path of \e si's
        states. Throws meshgap::Exception naming "file:line" for a line with the wrong count of numbers, a
        non-number, NaN, or a quaternion not of unit length, and "file" for a missing file or one without states. */
    ompl::geometric::PathGeometric readPathFile(const std::string &file, const ompl::base::SpaceInformationPtr &si);
}  // namespace meshgap

#endif
