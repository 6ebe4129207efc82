#ifndef MESHGAP_PLANNERS_BENCHMARK_FCL_ROBOT_CHECKER_H
#define MESHGAP_PLANNERS_BENCHMARK_FCL_ROBOT_CHECKER_H

// The peer checker of meshgap_benchmark on a robot of many bodies: FCL 0.7 as MoveIt uses it (FclRobotScene.h).
// Header-only (every planners/*.cpp is an executable); needs MESHGAP_HAVE_FCL and the fcl target.

#ifdef MESHGAP_HAVE_FCL
#include <memory>
#include <ompl/base/StateValidityChecker.h>
#include <vector>

#include "FclChecker.h"
#include "FclRobotScene.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    /**
       @anchor mgFclRobotChecker
       @par Short description
       A state validity checker for a robot of many bodies in a space made by robotStateSpace(), by FCL as MoveIt's
       collision_detection_fcl checks a state: FclRobotScene (the obstacles in one broad-phase manager, the links in
       another updated to each state's link poses, the pairs RobotScene checks put to FCL's narrow phase; primitive
       solids as FCL's own shapes, other bodies as BVHModel<OBBRSS>). isValid() stops at the first contact;
       clearance() is the least distance (0 in collision, as FCL answers). A state out of the space's bounds is
       invalid. Counts its queries and their time; thread-safe.
    */
    class FclRobotChecker : public FclTimedChecker<FclRobotChecker>
    {
    public:
        FclRobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene)
          : FclTimedChecker(si), fcl_(std::move(scene))
        {
        }

        /** \brief Every link's world pose at \e state (the link's mesh frame). */
        std::vector<Eigen::Isometry3d> pose(const ompl::base::State *state) const
        {
            std::vector<double> q;
            robotStateToVector(*si_->getStateSpace(), state, q);
            return fcl_.scene().robot().linkPoses(q);
        }

        /** \brief FclRobotScene::inCollision() (no counting). */
        bool inCollision(const std::vector<Eigen::Isometry3d> &X) const { return fcl_.inCollision(X); }

        /** \brief FclRobotScene::distance() (no counting). */
        double distance(const std::vector<Eigen::Isometry3d> &X) const { return fcl_.distance(X); }

    private:
        FclRobotScene fcl_;
    };
}  // namespace meshgap
#endif

#endif
