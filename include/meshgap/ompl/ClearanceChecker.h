#ifndef MESHGAP_OMPL_CLEARANCE_CHECKER_H
#define MESHGAP_OMPL_CLEARANCE_CHECKER_H

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "meshgap/ThreadCounters.h"
#include "meshgap/ompl/ClearanceField.h"
#include "meshgap/scene/Scene.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(ClearanceChecker);

    /** \brief The robot's world pose for an SE(3) state (x y z, quaternion) or an SE(2) state (x y, yaw about z: a
        planar problem is a 3D scene with the robot moving in the plane, as OMPL.app does), or a compound state whose
        component 0 is one of these (a control model's pose with its velocities: ControlModels.h). Throws for other
        spaces. */
    Eigen::Isometry3d poseFromState(const ompl::base::StateSpace &space, const ompl::base::State *state);

    /** \brief The inverse of poseFromState(): set an SE(3) state to \e X, or an SE(2) state to X's x, y and its yaw
        (the rotation's angle about z; any z translation or tilt is dropped); of a compound state, component 0 (the
        others are left as they are). Throws for other spaces. */
    void stateFromPose(const ompl::base::StateSpace &space, const Eigen::Isometry3d &X, ompl::base::State *state);

    /** \brief The farthest any point within \e radius of the robot's origin moves along OMPL's interpolation from
        \e s1 to \e s2 (SE(3): translation linear, rotation by slerp; SE(2): x, y linear, yaw along the shorter
        arc): |p2 - p1| + radius * theta, theta the rotation angle between the two states (an arc is longer than
        its chord). A fraction df of the motion moves no such point further than df times this, so the clearance
        (1-Lipschitz in the robot's displacement) changes by at most that much. */
    double sweepBound(const ompl::base::StateSpace &space, const ompl::base::State *s1, const ompl::base::State *s2,
                      double radius);

    /** \brief Counters summed over all threads, for benchmark run properties. */
    struct CheckerStats
    {
        std::uint64_t validityCalls{0}, clearanceCalls{0}, evaluations{0}, warmStartHits{0};
        /** \brief Certified queries by what their warm start did (SceneResult::warmStartUse): carried from a
            recent certificate, wrote a fresh one, or answered cold (a pose unrelated to the recent ones). */
        std::uint64_t carried{0}, written{0}, cold{0};
        double seconds{0.0};  ///< time spent in queries, summed over threads
    };

    /**
       @anchor mgClearanceChecker
       @par Short description
       An OMPL state validity checker backed by a meshgap Scene. isValid() is exact (triangle intersection and
       containment; a state in collision is never valid) and stops at the first colliding obstacle, in both modes.
       clearance() is the distance to the nearest obstacle. In CERTIFIED mode it is the exact surface distance,
       proven by a BVH traversal (specs: EXACT), with a warm start per thread (the last answer of the same thread,
       paper III-D). In FAST mode it is an upper bound from a node-level solver (specs: APPROXIMATE; never below the
       exact value). FAST mode's default solver is "warm-fast" (WarmFast.h, the paper's warm start, III-D/E): per
       obstacle it climbs from this thread's last node pair and reports the exact distance of the nearest surface
       triangles it reached, so its answer depends on the thread's history (one state asked twice may get two
       answers, both at or above the exact one). It never searches from scratch (SceneRequest::fallBack): a state
       far from the thread's last one gets the exact query, a pair due for a global search the exact pair query,
       which seeds its climb. Any other SolverFactory name (e.g. "comb-GA-wl", the paper's solver) has no run to
       follow: those states get the exact query (the node search from scratch costs 1.4-140 times it). Which to
       use when (bench/README.md, "Fast mode against the exact query"; bench/paper/README.md, "Warm-fast"):
       CERTIFIED by default and wherever the clearance is a guarantee (ClearanceMotionValidator, a clearance
       constraint, a proven path clearance), and where the certified query is already a few microseconds (the
       OMPL.app problems: along paths the climbs cost about what the warm certified query costs). FAST along
       runs of nearby states near large contact areas, where the certified query costs tens to hundreds of
       microseconds (the paper's maps: median 0.004-0.12, mean 0.16-0.43 of the certified query on battery_fixture,
       hand_bowl, slotted_wall), and only the collision verdict must be exact; the checker's jumps cost what
       certified queries cost. clearance() is signed: it returns SceneResult::distance
       as the scene computes it, which in collision is the penetration depth as a negative number (or 0 where the
       scene computes no depth). clearance(state, validState, validStateAvailable) (specs: hasValidDirectionComputation)
       also proposes a valid state away from the nearest obstacle (validStateAway()). Thread-safe: the scene is
       immutable, warm starts live per thread, counters are per thread (ThreadCounters).
    */
    class ClearanceChecker : public ompl::base::StateValidityChecker, public ClearanceField
    {
    public:
        enum class Mode
        {
            CERTIFIED,
            FAST
        };

        /** \brief \e fastSolver: the node-level solver of FAST mode, by its SolverFactory name (an unknown name
            throws, listing the valid ones); "warm-fast", warm-started per thread, unless named. */
        ClearanceChecker(const ompl::base::SpaceInformationPtr &si, SceneConstPtr scene, Mode mode = Mode::CERTIFIED,
                         std::string fastSolver = "warm-fast");

        bool isValid(const ompl::base::State *state) const override;
        bool isValid(const ompl::base::State *state, double &dist) const override;
        /** \brief Signed distance to the nearest obstacle: SceneResult::distance, negative (or 0) in collision. */
        double clearance(const ompl::base::State *state) const override;
        /** \brief clearance() of a free state; for a state in collision a negative number (CONTACT_DISTANCE)
            without the depth, found at about the price of isValid(): for a caller that only needs "in collision"
            there. Counted as a clearance call. */
        double clearanceOrContact(const ompl::base::State *state) const override;
        /** \brief min(clearanceOrContact(state), bound), found only as far as needed: once the clearance is proven
            at least \e bound the search stops (cheap when the robot is far from everything; SceneRequest::upperBound;
            \e bound must be positive). Counted as a clearance call. */
        double clearanceBelow(const ompl::base::State *state, double bound) const override;
        /** \brief clearance(state), and in \e validState a state away from the nearest obstacle
            (validStateAway()); \e validStateAvailable is true only if that state is valid (isValid()). */
        double clearance(const ompl::base::State *state, ompl::base::State *validState,
                         bool &validStateAvailable) const override;
        /** \brief Fill \e out with \e state translated away from the nearest obstacle of \e r (the answer for
            \e state): along onA - onB (from the obstacle's witness point to the robot's), reversed in collision
            (so the robot moves out), or, where the witness points coincide, from the witness point towards the
            robot's origin. The first translation tried is |distance| plus a margin of 2% of the robot's radius,
            then doubled up to four times, each clamped to the bounds; the first one that is valid, and (for a valid
            \e state) strictly clearer, is kept. Returns false, leaving \e out unspecified, if none is; a true answer
            is always a valid state. The rotation is kept; an SE(2) state moves in its plane. */
        bool validStateAway(const ompl::base::State *state, const SceneResult &r, ompl::base::State *out) const;

        /** \brief Whether clearance() of a state in collision finds its penetration depth (true, the default: a
            negative signed distance) or gives the verdict alone (false: CONTACT_DISTANCE, a zero below zero, as
            FCL's distance answers 0 in collision; free states are answered as before, at lower cost in collision).
            isValid(state, dist), clearanceOrContact() and clearanceBelow() never find a depth. Set it before
            planning (not while other threads query). */
        void setComputeDepth(bool computeDepth) { computeDepth_ = computeDepth; }
        bool computeDepth() const { return computeDepth_; }

        /** \brief ClearanceField: CERTIFIED mode is exact; the length scale is the robot's radius about its origin
            (1 for a point robot); sweep() is sweepBound() with it; the gradient is clearanceGradient()'s, in
            tangentDimension()'s coordinates, its steps ascentStep() and applyTangentStep(). */
        bool certified() const override { return mode_ == Mode::CERTIFIED; }
        std::uint64_t fieldId() const override { return id_; }
        double lengthScale() const override;
        double sweep(const ompl::base::State *s1, const ompl::base::State *s2) const override;
        unsigned gradientDimension() const override;
        double gradient(const ompl::base::State *state, std::vector<double> &gradient,
                        const ClearanceGradientOptions &options = {},
                        ClearanceGradientInfo *info = nullptr) const override;
        double gradientNorm2(const std::vector<double> &gradient) const override;
        void ascentStep(const std::vector<double> &gradient, double alpha, std::vector<double> &step) const override;
        void applyStep(const ompl::base::State *state, const double *step, ompl::base::State *out) const override;

        Mode mode() const { return mode_; }
        /** \brief Unique per checker, never reused (a later checker may reuse this one's address, never its id). */
        std::uint64_t id() const { return id_; }
        const Scene &scene() const { return *scene_; }
        /** \brief The space information this checker was made for (OMPL 1.5's checker has no getter). */
        const ompl::base::SpaceInformation &spaceInformation() const { return *si_; }
        CheckerStats stats() const;

        /** \brief The full answer for one state (the same query clearance() makes). */
        SceneResult query(const ompl::base::State *state) const;
        /** \brief The answer for one state to \e request (its stopBelow, upperBound, computeDepth; this checker's mode,
            fast solver and setComputeDepth() apply), counted as a clearance call: computeDepth false for a caller
            that needs the verdict in collision and the clearance of a free state (ClearanceMotionValidator). */
        SceneResult query(const ompl::base::State *state, const SceneRequest &request) const;

    private:
        /** \brief The query, counted as a validity or a clearance call: \e request (its stopBelow, upperBound)
            with this checker's mode and fast solver. */
        SceneResult query(const ompl::base::State *state, bool countAsValidity,
                          SceneRequest request = SceneRequest()) const;

        SceneConstPtr scene_;
        Mode mode_;
        std::string fastSolver_;
        bool computeDepth_{true};
        std::uint64_t id_;  ///< unique per checker: keys this checker's per-thread warm starts
        /** \brief What stats() sums, counted per thread (ThreadCounters): indices are the Count values. */
        enum Count : std::size_t
        {
            VALIDITY_CALLS,
            CLEARANCE_CALLS,
            EVALUATIONS,
            WARM_HITS,
            CARRIED,
            WRITTEN,
            COLD,
            NANOSECONDS,
            COUNTS
        };
        mutable ThreadCounters<COUNTS> counts_;
    };
}  // namespace meshgap

#endif
