#ifndef MESHGAP_ROBOT_SRDF_H
#define MESHGAP_ROBOT_SRDF_H

#include <string>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief One disable_collisions element of an SRDF: two links never checked against each other. */
    struct SrdfDisabledPair
    {
        std::string link1, link2;
        int line;  ///< where it is in the file
    };

    /** \brief The disable_collisions elements of the SRDF \e path (plain XML, read with tinyxml2), as written.
        Throws meshgap::Exception naming the file (and line) for a missing or unreadable file, a root element other
        than robot, or an element without link1 or link2. */
    std::vector<SrdfDisabledPair> readSrdfDisabledCollisions(const std::string &path);

    /** \brief Allow every pair the SRDF \e path disables (RobotModel::allowCollision()); pairs naming a link
        without geometry change nothing. Throws meshgap::Exception naming the file, the line and the link when a
        pair names a link the robot does not have, and as readSrdfDisabledCollisions(). */
    void readSrdf(RobotModel &robot, const std::string &path);
}  // namespace meshgap

#endif
