#ifndef MESHGAP_PLANNERS_FCL_CHECKER_H
#define MESHGAP_PLANNERS_FCL_CHECKER_H

// The peer checker of meshgap_benchmark, for a problem of any kind (a single body is a robot of one link): FCL 0.7 as
// MoveIt uses it (FclRobotScene.h). Header-only (every planners/*.cpp is an executable); needs MESHGAP_HAVE_FCL and
// the fcl target.

#ifdef MESHGAP_HAVE_FCL
#include <atomic>
#include <chrono>
#include <memory>
#include <ompl/base/StateValidityChecker.h>
#include <vector>

#include "FclRobotScene.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    /**
       @anchor mgFclChecker
       @par Short description
       A state validity checker for a robot in a space made by robotStateSpace() (or the space of its one state
       block: a single body's SE(2) or SE(3)), by FCL as MoveIt's collision_detection_fcl checks a state:
       FclRobotScene (the obstacles in one broad-phase manager, the links in another updated to each state's link
       poses, the pairs RobotScene checks put to FCL's narrow phase; primitive solids as FCL's own shapes, other bodies
       as BVHModel<OBBRSS>). A single body is its mesh, centred as OMPL.app centres it, against the world's connected
       parts, each the BVHModel<OBBRSS> of its triangles: the same triangles OMPL.app's FCL checker is given, placed
       at the same pose for the same state. isValid() is FCL's collide, stopping at the first contact; clearance()
       FCL's least distance (0 in collision, as FCL answers). A state out of the space's bounds is invalid. Counts its
       queries and their time (CheckerStats: evaluations and warm-start hits stay 0); thread-safe.
    */
    class FclChecker : public ompl::base::StateValidityChecker
    {
    public:
        FclChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene)
          : ompl::base::StateValidityChecker(si), fcl_(std::move(scene))
        {
            specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
        }

        bool isValid(const ompl::base::State *state) const override
        {
            const auto start = std::chrono::steady_clock::now();
            ++validityCalls_;
            const bool valid = si_->satisfiesBounds(state) && !inCollision(threadPose(state));
            addTime(start);
            return valid;
        }

        bool isValid(const ompl::base::State *state, double &dist) const override
        {
            const bool valid = isValid(state);
            dist = valid ? clearance(state) : 0.0;
            return valid;
        }

        double clearance(const ompl::base::State *state) const override
        {
            const auto start = std::chrono::steady_clock::now();
            ++clearanceCalls_;
            const double d = distance(threadPose(state));
            addTime(start);
            return d;
        }

        CheckerStats stats() const
        {
            CheckerStats s;
            s.validityCalls = validityCalls_;
            s.clearanceCalls = clearanceCalls_;
            s.seconds = 1e-9 * static_cast<double>(nanoseconds_.load());
            return s;
        }

        /** \brief Every link's world pose at \e state (the link's mesh frame). */
        std::vector<Eigen::Isometry3d> pose(const ompl::base::State *state) const { return threadPose(state); }

        /** \brief FclRobotScene::inCollision() (no counting). */
        bool inCollision(const std::vector<Eigen::Isometry3d> &X) const { return fcl_.inCollision(X); }

        /** \brief FclRobotScene::distance() (no counting), below \e below. */
        double distance(const std::vector<Eigen::Isometry3d> &X,
                        double below = std::numeric_limits<double>::infinity()) const
        {
            return fcl_.distance(X, below);
        }

    private:
        /** \brief pose() into this thread's buffers (no allocation once they have their size), valid until the
            thread's next call. */
        const std::vector<Eigen::Isometry3d> &threadPose(const ompl::base::State *state) const
        {
            thread_local std::vector<double> q;
            thread_local std::vector<Eigen::Isometry3d> frames, links;
            robotStateToVector(*si_->getStateSpace(), state, q);
            fcl_.scene().robot().linkPoses(q.data(), q.size(), frames, links);
            return links;
        }

        void addTime(std::chrono::steady_clock::time_point start) const
        {
            nanoseconds_ += static_cast<std::uint64_t>(
                std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
        }

        FclRobotScene fcl_;
        mutable std::atomic<std::uint64_t> validityCalls_{0}, clearanceCalls_{0}, nanoseconds_{0};
    };
}  // namespace meshgap
#endif

#endif
