#ifndef MESHGAP_PLANNERS_SUPPORT_ROBOT_REPORT_H
#define MESHGAP_PLANNERS_SUPPORT_ROBOT_REPORT_H

#include <string>
#include <utility>
#include <vector>

#include "meshgap/robot/RobotScene.h"
#include "support/PlanReport.h"

namespace meshgap
{
    /** \brief The report of a robot's path: \e states interpolated in the robot's state space (robotStateSpace(),
        so continuous joints and rotations take the short way) with \e dense states per OMPL validity-check
        segment, and at every dense state every link's pose and the exact answer of every pair
        (RobotRequest::everyPair): the whole robot's clearance, the attaining pair's witness points and each link's
        clearance. \e summary gets "min clearance" and "dense path free" rows. */
    PlanReportData robotReportFromPath(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                       unsigned dense, std::vector<std::pair<std::string, std::string>> summary);
}  // namespace meshgap

#endif
