#include "support/DenseClearance.h"

#include <algorithm>

#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    DenseClearance denseClearance(const ompl::geometric::PathGeometric &solution, const Scene &scene,
                                  unsigned perSegment)
    {
        namespace ob = ompl::base;
        DenseClearance d(solution);
        const ob::SpaceInformationPtr &si = solution.getSpaceInformation();
        unsigned count = 1;
        for (std::size_t i = 1; i < solution.getStateCount(); ++i)
            count += perSegment * std::max(1u, si->getStateSpace()->validSegmentCount(solution.getState(i - 1),
                                                                                      solution.getState(i)));
        d.path.interpolate(count);
        SceneRequest request;  // exact
        SceneWarmStart warm;
        double s = 0.0;
        for (std::size_t i = 0; i < d.path.getStateCount(); ++i)
        {
            if (i > 0)
                s += si->distance(d.path.getState(i - 1), d.path.getState(i));
            SceneResult r;
            scene.distance(poseFromState(*si->getStateSpace(), d.path.getState(i)), request, warm, r);
            d.arcLength.push_back(s);
            d.clearance.push_back(r.distance);
            d.inCollision.push_back(r.inCollision);
            d.onRobot.push_back(r.onRobot);
            d.onObstacle.push_back(r.onObstacle);
            d.collisions += r.inCollision;
            if (r.distance < d.minClearance)
            {
                d.minClearance = r.distance;
                d.argmin = i;
            }
        }
        return d;
    }
}  // namespace meshgap
