#ifndef MESHGAP_OMPL_CLEARANCE_CHECKER_H
#define MESHGAP_OMPL_CLEARANCE_CHECKER_H

#include <atomic>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "meshgap/scene/Scene.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(ClearanceChecker);

    /** \brief The robot's world pose for an SE(3) state (x y z, quaternion) or an SE(2) state (x y, yaw about z: a
        planar problem is a 3D scene with the robot moving in the plane, as OMPL.app does). Throws for other
        spaces. */
    Eigen::Isometry3d poseFromState(const ompl::base::StateSpace &space, const ompl::base::State *state);

    /** \brief Counters summed over all threads, for benchmark run properties. */
    struct CheckerStats
    {
        std::uint64_t validityCalls{0}, clearanceCalls{0}, evaluations{0}, warmStartHits{0};
        double seconds{0.0};  ///< time spent in queries, summed over threads
    };

    /**
       @anchor mgClearanceChecker
       @par Short description
       An OMPL state validity checker backed by a meshgap Scene. isValid() is exact (triangle intersection and
       containment; a state in collision is never valid) and stops at the first colliding obstacle. clearance() is
       the distance to the nearest obstacle: in CERTIFIED mode the exact surface distance, proven by a BVH traversal
       (specs: EXACT), with a warm start per thread (the last answer of the same thread, paper III-D); in FAST mode
       the paper's node-to-node distance from comb-GA-wl (specs: APPROXIMATE; never below the exact value), seeded
       from the state's own coordinates and not warm-started, so it is a pure function of the state, as
       RRT*'s and PRM*'s repeated cost comparisons need. In collision clearance() is 0 (a penetration depth is not
       computed yet). Thread-safe: the scene is immutable, warm starts live per thread, counters are atomic.
    */
    class ClearanceChecker : public ompl::base::StateValidityChecker
    {
    public:
        enum class Mode
        {
            CERTIFIED,
            FAST
        };

        ClearanceChecker(const ompl::base::SpaceInformationPtr &si, SceneConstPtr scene, Mode mode = Mode::CERTIFIED);

        bool isValid(const ompl::base::State *state) const override;
        bool isValid(const ompl::base::State *state, double &dist) const override;
        double clearance(const ompl::base::State *state) const override;

        Mode mode() const { return mode_; }
        const Scene &scene() const { return *scene_; }
        CheckerStats stats() const;

        /** \brief The full answer for one state (the same query clearance() makes). */
        SceneResult query(const ompl::base::State *state) const;

    private:
        SceneResult query(const ompl::base::State *state, bool countAsValidity) const;

        SceneConstPtr scene_;
        Mode mode_;
        std::uint64_t id_;  ///< unique per checker: keys this checker's per-thread warm starts
        mutable std::atomic<std::uint64_t> validityCalls_{0}, clearanceCalls_{0}, evaluations_{0}, warmHits_{0};
        mutable std::atomic<std::uint64_t> nanoseconds_{0};
    };
}  // namespace meshgap

#endif
