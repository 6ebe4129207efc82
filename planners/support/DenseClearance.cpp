#include "support/DenseClearance.h"

#include <algorithm>

#include "meshgap/Text.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    DenseClearance denseClearance(const ompl::geometric::PathGeometric &solution, const RobotScene &scene,
                                  unsigned perSegment, bool everyLink)
    {
        namespace ob = ompl::base;
        DenseClearance d(solution);
        const ob::SpaceInformationPtr &si = solution.getSpaceInformation();
        unsigned count = 1;
        for (std::size_t i = 1; i < solution.getStateCount(); ++i)
            count += perSegment * std::max(1u, si->getStateSpace()->validSegmentCount(solution.getState(i - 1),
                                                                                      solution.getState(i)));
        d.path.interpolate(count);
        RobotRequest request;  // exact
        request.everyPair = everyLink;
        RobotWarmStart warm;
        RobotResult r;
        std::vector<double> q;
        std::vector<Eigen::Isometry3d> frames, poses;
        double s = 0.0;
        for (std::size_t i = 0; i < d.path.getStateCount(); ++i)
        {
            if (i > 0)
                s += si->distance(d.path.getState(i - 1), d.path.getState(i));
            robotStateToVector(*si->getStateSpace(), d.path.getState(i), q);
            scene.distance(q.data(), q.size(), request, warm, r);
            scene.robot().linkPoses(q.data(), q.size(), frames, poses);
            d.linkPoses.insert(d.linkPoses.end(), poses.begin(), poses.end());
            if (everyLink)
                d.linkClearance.insert(d.linkClearance.end(), r.linkClearance.begin(), r.linkClearance.end());
            d.arcLength.push_back(s);
            d.clearance.push_back(r.distance);
            d.inCollision.push_back(r.inCollision);
            d.onA.push_back(r.onA);
            d.onB.push_back(r.onB);
            d.collisions += r.inCollision;
            if (i == 0 || r.distance < d.minClearance)
            {
                d.minClearance = r.distance;
                d.argmin = i;
                d.worst = r;
            }
        }
        return d;
    }

    std::string pairText(const RobotScene &scene, const RobotResult &r)
    {
        if (r.link >= scene.links().size() || (scene.obstacles().empty() && scene.selfPairs().empty()))
            return "no pair (the robot has neither obstacles nor self pairs to check)";
        const std::string link = quote(scene.links()[r.link].name);
        return r.selfPair ? "links " + link + " and " + quote(scene.links()[r.other].name)
                          : "link " + link + " and obstacle " + std::to_string(r.other);
    }
}  // namespace meshgap
