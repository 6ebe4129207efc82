#ifndef MESHGAP_OMPL_ROBOT_MOTION_VALIDATOR_H
#define MESHGAP_OMPL_ROBOT_MOTION_VALIDATOR_H

#include <ompl/base/MotionValidator.h>

#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/robot/MotionBound.h"

namespace meshgap
{
    /**
       @anchor mgRobotMotionValidator
       @par Short description
       A certified motion validator for fixed-base URDF robots in a space made by robotStateSpace(): a motion is
       valid when it is proven free. Each pair's clearance is 1-Lipschitz in the displacement of its bodies, which
       MotionBound bounds along the motion; a segment is free when, for every pair, the clearances at its two ends
       add up to more than the displacement bound of the pair over the segment (for two links, how far either moves
       in the frame of their nearest common ancestor, MotionBound::pairDisplacement(); a link's own bound for a link
       against the obstacles). Else it is split in two, down to a depth of 30; a state in collision on the
       way makes the motion invalid, and so does reaching that depth (conservative). Clearances are exact
       (RobotScene, every pair, pruned at the bound each pair needs).
       @par External documentation
       F. Schwarzer, M. Saha, J.-C. Latombe, Adaptive dynamic collision checking for single and multiple
       articulated robots in complex environments, IEEE Transactions on Robotics 21(3), 2005.
    */
    class RobotMotionValidator : public ompl::base::MotionValidator
    {
    public:
        RobotMotionValidator(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene,
                             const UrdfRobot &robot);

        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
        /** \brief As checkMotion(s1, s2); on failure \e lastValid holds s1 and fraction 0 (no partial motion is
            claimed). */
        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                         std::pair<ompl::base::State *, double> &lastValid) const override;

    private:
        /** \brief Every pair's clearance at \e q into \e pairs, exact below \e needed and a lower bound (at least
            \e needed) above it; false for a collision. */
        bool pairClearances(const std::vector<double> &q, double needed, std::vector<double> &pairs) const;

        RobotSceneConstPtr scene_;
        MotionBound bound_;
    };
}  // namespace meshgap

#endif
