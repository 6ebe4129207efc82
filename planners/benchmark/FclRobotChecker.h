#ifndef MESHGAP_PLANNERS_BENCHMARK_FCL_ROBOT_CHECKER_H
#define MESHGAP_PLANNERS_BENCHMARK_FCL_ROBOT_CHECKER_H

// The peer checker of meshgap_benchmark on a robot of many bodies: FCL 0.7 checking the pairs RobotScene checks, the
// same way. Header-only (every planners/*.cpp is an executable); needs MESHGAP_HAVE_FCL and the fcl target.

#ifdef MESHGAP_HAVE_FCL
#include <algorithm>
#include <fcl/fcl.h>
#include <limits>
#include <memory>
#include <ompl/base/StateValidityChecker.h>
#include <vector>

#include "FclChecker.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    /**
       @anchor mgFclRobotChecker
       @par Short description
       A state validity checker for a robot of many bodies in a space made by robotStateSpace(), by FCL: every link
       of \e scene an FCL BVHModel<OBBRSS> of its mesh (its own frame) placed at the link pose the model gives, every
       obstacle one too (world frame), and the pairs RobotScene checks: every link against every obstacle not allowed
       with it (RobotScene::linkObstacles()), then the model's self pairs (RobotScene::selfPairs()). isValid() runs
       fcl::collide pair by pair up to the first contact; clearance() fcl::distance on every pair, the least kept (0
       in collision, as FCL answers). A state out of the space's bounds is invalid. Counts its queries and their time;
       thread-safe.
    */
    class FclRobotChecker : public FclTimedChecker<FclRobotChecker>
    {
    public:
        using Model = fcl::BVHModel<fcl::OBBRSSd>;

        FclRobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene)
          : FclTimedChecker(si), scene_(std::move(scene))
        {
            for (const RobotLink &link : scene_->links())
                links_.push_back(fclModelOf(link.body->surface()));
            for (const BodyConstPtr &o : scene_->obstacles())
                obstacles_.push_back(fclModelOf(o->surface()));
        }

        /** \brief Every link's world pose at \e state (the link's mesh frame). */
        std::vector<Eigen::Isometry3d> pose(const ompl::base::State *state) const
        {
            std::vector<double> q;
            robotStateToVector(*si_->getStateSpace(), state, q);
            return scene_->robot().linkPoses(q);
        }

        /** \brief fcl::collide on every pair, up to the first contact (no counting). */
        bool inCollision(const std::vector<Eigen::Isometry3d> &X) const
        {
            const fcl::CollisionRequestd request;  // one contact is enough
            auto collide = [&](const Model *a, const Eigen::Isometry3d &Xa, const Model *b, const Eigen::Isometry3d &Xb)
            {
                fcl::CollisionResultd result;
                fcl::collide(a, Xa, b, Xb, request, result);
                return result.isCollision();
            };
            for (std::size_t i = 0; i < links_.size(); ++i)
                for (std::size_t o : scene_->linkObstacles(i))
                    if (collide(links_[i].get(), X[i], obstacles_[o].get(), Eigen::Isometry3d::Identity()))
                        return true;
            for (const LinkPair &p : scene_->selfPairs())
                if (collide(links_[p.first].get(), X[p.first], links_[p.second].get(), X[p.second]))
                    return true;
            return false;
        }

        /** \brief fcl::distance on every pair, the least, at least 0 (no counting). */
        double distance(const std::vector<Eigen::Isometry3d> &X) const
        {
            const fcl::DistanceRequestd request(true);
            double least = std::numeric_limits<double>::infinity();
            auto pair = [&](const Model *a, const Eigen::Isometry3d &Xa, const Model *b, const Eigen::Isometry3d &Xb)
            {
                fcl::DistanceResultd result;
                fcl::distance(a, Xa, b, Xb, request, result);
                least = std::min(least, std::max(0.0, result.min_distance));
            };
            for (std::size_t i = 0; i < links_.size(); ++i)
                for (std::size_t o : scene_->linkObstacles(i))
                    pair(links_[i].get(), X[i], obstacles_[o].get(), Eigen::Isometry3d::Identity());
            for (const LinkPair &p : scene_->selfPairs())
                pair(links_[p.first].get(), X[p.first], links_[p.second].get(), X[p.second]);
            return least;
        }

    private:
        RobotSceneConstPtr scene_;
        std::vector<std::shared_ptr<Model>> links_, obstacles_;
    };
}  // namespace meshgap
#endif

#endif
