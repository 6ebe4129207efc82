#ifndef MESHGAP_PLANNERS_SUPPORT_DENSE_CLEARANCE_H
#define MESHGAP_PLANNERS_SUPPORT_DENSE_CLEARANCE_H

#include <Eigen/Geometry>
#include <limits>
#include <ompl/geometric/PathGeometric.h>
#include <vector>

#include "meshgap/scene/Scene.h"

namespace meshgap
{
    /** \brief A solution path interpolated densely and the exact signed clearance at each of its states, with the
        closest-point segment (witness points, world frame) there: what meshgap_plan prints and writes as CSV, the
        plan report draws, and the Python module's plan() returns. */
    struct DenseClearance
    {
        explicit DenseClearance(const ompl::geometric::PathGeometric &solution) : path(solution) {}

        ompl::geometric::PathGeometric path;  ///< the dense path
        std::vector<double> arcLength, clearance;
        std::vector<char> inCollision;
        std::vector<Eigen::Vector3d> onRobot, onObstacle;  ///< witness points at each dense state
        double minClearance{std::numeric_limits<double>::infinity()};
        std::size_t argmin{0}, collisions{0};
    };

    /** \brief \e solution interpolated with \e perSegment states per OMPL validity-check segment (the state space's
        validSegmentCount() between consecutive states, at least one) and the exact signed clearance at each state
        (Scene::distance(), exact, one warm start carried along, whatever the checker's mode). Arc length is the
        state space's distance summed along the dense path. */
    DenseClearance denseClearance(const ompl::geometric::PathGeometric &solution, const Scene &scene,
                                  unsigned perSegment);
}  // namespace meshgap

#endif
