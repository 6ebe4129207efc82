#ifndef MESHGAP_PLANNERS_FCL_CHECKER_H
#define MESHGAP_PLANNERS_FCL_CHECKER_H

// The peer checker of meshgap_benchmark: FCL 0.7 as OMPL.app uses it. Header-only (every planners/*.cpp is an
// executable); needs MESHGAP_HAVE_FCL and the fcl target.

#ifdef MESHGAP_HAVE_FCL
#include <atomic>
#include <chrono>
#include <fcl/fcl.h>
#include <memory>
#include <ompl/base/StateValidityChecker.h>

#include "meshgap/mesh/Mesh.h"
#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    /** \brief An FCL BVHModel<OBBRSS> of a mesh, in the mesh's own frame. */
    inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclModelOf(const Mesh &mesh)
    {
        auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
        const std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
        std::vector<fcl::Triangle> triangles;
        triangles.reserve(mesh.triangles.size());
        for (const Triangle &t : mesh.triangles)
            triangles.emplace_back(t[0], t[1], t[2]);
        model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
        model->addSubModel(points, triangles);
        model->endModel();
        model->computeLocalAABB();
        return model;
    }

    /** \brief What the FCL peer checkers share: isValid() (within the space's bounds, and Derived::inCollision()
        false at Derived::pose()) and clearance() (Derived::distance() there), each counted and timed;
        thread-safe. */
    template <typename Derived>
    class FclTimedChecker : public ompl::base::StateValidityChecker
    {
    public:
        explicit FclTimedChecker(const ompl::base::SpaceInformationPtr &si) : ompl::base::StateValidityChecker(si)
        {
            specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
        }

        bool isValid(const ompl::base::State *state) const override
        {
            const auto start = std::chrono::steady_clock::now();
            ++validityCalls_;
            const bool valid = si_->satisfiesBounds(state) && !self().inCollision(self().pose(state));
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
            const double d = self().distance(self().pose(state));
            addTime(start);
            return d;
        }

        /** \brief Counters in ClearanceChecker's form (evaluations and warm-start hits stay 0). */
        CheckerStats stats() const
        {
            CheckerStats s;
            s.validityCalls = validityCalls_;
            s.clearanceCalls = clearanceCalls_;
            s.seconds = 1e-9 * static_cast<double>(nanoseconds_.load());
            return s;
        }

    private:
        const Derived &self() const { return static_cast<const Derived &>(*this); }

        void addTime(std::chrono::steady_clock::time_point start) const
        {
            nanoseconds_ += static_cast<std::uint64_t>(
                std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
        }

        mutable std::atomic<std::uint64_t> validityCalls_{0}, clearanceCalls_{0}, nanoseconds_{0};
    };

    /**
       @anchor mgFclChecker
       @par Short description
       A state validity checker built the way OMPL.app builds its own: the robot and the whole world as FCL
       BVHModel<OBBRSS>, isValid() by fcl::collide (first contact), clearance() by fcl::distance (nearest points
       requested, as OMPL.app does). The robot mesh must be in OMPL.app's robot frame (loadRobotMesh()), the world
       as loaded, so a state places the robot exactly where ClearanceChecker places it (poseFromState()). A state out
       of the space's bounds is invalid, as for ClearanceChecker. Counts its queries and their time; thread-safe.
    */
    class FclChecker : public FclTimedChecker<FclChecker>
    {
    public:
        using Model = fcl::BVHModel<fcl::OBBRSSd>;

        FclChecker(const ompl::base::SpaceInformationPtr &si, const Mesh &robot, const Mesh &world)
          : FclTimedChecker(si), robot_(fclModelOf(robot)), world_(fclModelOf(world))
        {
        }

        /** \brief fcl::collide of the robot at \e X with the world (no counting). */
        bool inCollision(const Eigen::Isometry3d &X) const
        {
            const fcl::CollisionRequestd request;  // one contact is enough
            fcl::CollisionResultd result;
            fcl::collide(robot_.get(), X, world_.get(), fcl::Transform3d::Identity(), request, result);
            return result.isCollision();
        }

        /** \brief fcl::distance of the robot at \e X from the world, at least 0 (no counting). */
        double distance(const Eigen::Isometry3d &X) const
        {
            const fcl::DistanceRequestd request(true);
            fcl::DistanceResultd result;
            fcl::distance(robot_.get(), X, world_.get(), fcl::Transform3d::Identity(), request, result);
            return std::max(0.0, result.min_distance);
        }

        /** \brief The robot's pose at \e state. */
        Eigen::Isometry3d pose(const ompl::base::State *state) const
        {
            return poseFromState(*si_->getStateSpace(), state);
        }

    private:
        std::shared_ptr<Model> robot_, world_;
    };
}  // namespace meshgap
#endif

#endif
