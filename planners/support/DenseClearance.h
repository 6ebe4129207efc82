#ifndef MESHGAP_PLANNERS_SUPPORT_DENSE_CLEARANCE_H
#define MESHGAP_PLANNERS_SUPPORT_DENSE_CLEARANCE_H

#include <Eigen/Geometry>
#include <limits>
#include <ompl/geometric/PathGeometric.h>
#include <string>
#include <vector>

#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    /** \brief A solution path interpolated densely and the exact signed clearance of the whole robot at each of its
        states (a single body is a robot of one link), with the closest-point segment (witness points, world frame)
        of the pair that attains it, every link's pose and clearance: what meshgap_plan prints and writes as CSV, the
        plan report draws, and the Python module's plan() returns, for every kind of problem. */
    struct DenseClearance
    {
        explicit DenseClearance(const ompl::geometric::PathGeometric &solution) : path(solution) {}

        ompl::geometric::PathGeometric path;  ///< the dense path
        std::vector<double> arcLength, clearance;
        std::vector<char> inCollision;
        /** \brief Witness points at each dense state: on the link (A) and on what it is measured against (B), as
            RobotResult names them. */
        std::vector<Eigen::Vector3d> onA, onB;
        /** \brief Every link's pose at every dense state (state-major: state k's link i at k * links + i). */
        std::vector<Eigen::Isometry3d> linkPoses;
        /** \brief Every link's clearance at every dense state (the order of linkPoses); with everyLink only. */
        std::vector<double> linkClearance;
        double minClearance{std::numeric_limits<double>::infinity()};
        std::size_t argmin{0}, collisions{0};
        RobotResult worst;  ///< the answer at the least clear state (argmin): its pair
    };

    /** \brief \e solution interpolated with \e perSegment states per OMPL validity-check segment (1 +
        perSegment * max(1, validSegmentCount()) per motion states in all, PathGeometric::interpolate()) and the
        exact signed clearance of the whole robot at each state (RobotScene::distance(), exact, one warm start
        carried along), every pair answered (each link's clearance) when \e everyLink. Arc length is the state
        space's distance summed along the dense path. \e solution's space is one robotStateToVector() reads (one made
        by robotStateSpace(), or a single body's SE(2) or SE(3) space). */
    DenseClearance denseClearance(const ompl::geometric::PathGeometric &solution, const RobotScene &scene,
                                  unsigned perSegment, bool everyLink = true);

    /** \brief The pair \e r names in \e scene, as meshgap_plan and meshgap_distance print it: "link 'a' and obstacle
        3" or "links 'a' and 'b'" (or that the robot has no pair to check). */
    std::string pairText(const RobotScene &scene, const RobotResult &r);
}  // namespace meshgap

#endif
