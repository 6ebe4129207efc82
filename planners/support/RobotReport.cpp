#include "support/RobotReport.h"

#include <cmath>
#include <fstream>
#include <ompl/base/StateSpace.h>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    namespace
    {
        /** \brief The dense states of \e states in \e space: \e dense per validity-check segment of each motion. */
        std::vector<std::vector<double>> interpolate(const ompl::base::StateSpace &space,
                                                     const std::vector<std::vector<double>> &states, unsigned dense,
                                                     std::vector<double> &arcLength)
        {
            ompl::base::State *a = space.allocState(), *b = space.allocState(), *s = space.allocState();
            std::vector<std::vector<double>> out{states.front()};
            arcLength = {0.0};
            std::vector<double> q;
            for (std::size_t k = 1; k < states.size(); ++k)
            {
                robotStateFromVector(space, states[k - 1], a);
                robotStateFromVector(space, states[k], b);
                const unsigned steps = std::max(1u, space.validSegmentCount(a, b) * dense);
                const double length = space.distance(a, b);
                for (unsigned j = 1; j <= steps; ++j)
                {
                    space.interpolate(a, b, double(j) / steps, s);
                    robotStateToVector(space, s, q);
                    out.push_back(q);
                    arcLength.push_back(arcLength.back() + length / steps);
                }
            }
            space.freeState(a);
            space.freeState(b);
            space.freeState(s);
            return out;
        }

        /** \brief The unit box a fixed-base robot's space is given (it has no translation), else one around the
            states' positions, which only the segment count depends on. */
        ompl::base::RealVectorBounds boundsAround(const std::vector<std::vector<double>> &states)
        {
            ompl::base::RealVectorBounds bounds(3);
            bounds.setLow(-1.0);
            bounds.setHigh(1.0);
            for (const std::vector<double> &q : states)
                for (std::size_t k = 0; k < 3 && k < q.size(); ++k)
                {
                    bounds.low[k] = std::min(bounds.low[k], q[k] - 1.0);
                    bounds.high[k] = std::max(bounds.high[k], q[k] + 1.0);
                }
            return bounds;
        }
    }  // namespace

    PlanReportData robotReportFromPath(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                       unsigned dense, std::vector<std::pair<std::string, std::string>> summary)
    {
        // The space alone (set up for its validity-check resolution): no SpaceInformation, which would warn that
        // it has no validity checker.
        const ompl::base::StateSpacePtr space = robotStateSpace(scene.robot(), boundsAround(states));
        space->setup();
        PlanReportData r;
        const std::vector<std::vector<double>> path = interpolate(*space, states, dense, r.arcLength);
        RobotRequest request;
        request.everyPair = true;
        RobotWarmStart warm;
        RobotResult result;
        std::vector<Eigen::Isometry3d> frames, poses;
        std::size_t argmin = 0, collisions = 0;
        for (std::size_t k = 0; k < path.size(); ++k)
        {
            scene.distance(path[k].data(), path[k].size(), request, warm, result);
            scene.robot().linkPoses(path[k].data(), path[k].size(), frames, poses);
            r.poses.insert(r.poses.end(), poses.begin(), poses.end());
            r.linkClearance.insert(r.linkClearance.end(), result.linkClearance.begin(), result.linkClearance.end());
            r.clearance.push_back(result.distance);
            r.inCollision.push_back(result.inCollision ? 1 : 0);
            r.onRobot.push_back(result.onLink);
            r.onObstacle.push_back(result.onOther);
            collisions += result.inCollision ? 1 : 0;
            argmin = result.distance < r.clearance[argmin] ? k : argmin;
        }
        for (const RobotLink &link : scene.links())
            r.linkNames.push_back(link.name);
        std::ostringstream mc;
        mc.precision(6);
        mc << r.clearance[argmin] << " (exact, at arc length " << r.arcLength[argmin] << " of " << r.arcLength.back()
           << ")";
        summary.emplace_back("min clearance", mc.str());
        summary.emplace_back("dense path free", collisions == 0 ? std::string("yes") :
                                                    "NO: " + std::to_string(collisions) + " states collide");
        r.summary = std::move(summary);
        r.title = r.summary.empty() ? std::string("meshgap plan") : r.summary.front().second;
        return r;
    }
}  // namespace meshgap
