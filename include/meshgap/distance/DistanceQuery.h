#ifndef MESHGAP_DISTANCE_DISTANCE_QUERY_H
#define MESHGAP_DISTANCE_DISTANCE_QUERY_H

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace meshgap
{
    /** \brief A trial point of the paper (Section III-A): one node index on each body. */
    struct NodePair
    {
        std::uint32_t a{0};  ///< node of body A
        std::uint32_t b{0};  ///< node of body B
        bool operator==(const NodePair &o) const { return a == o.a && b == o.b; }
    };

    /** \brief What one query should do. The pose is not part of it: solvers take X_AB, the pose of body B in body
        A's frame (the paper's eq. 4: only B's nodes are transformed). Every query's request extends it (SceneRequest,
        RobotRequest), each saying how its fields apply there. */
    struct DistanceRequest
    {
        /** \brief Seed of the query's random numbers: the same seed gives the same result, bit for bit. */
        std::uint64_t seed{1};
        /** \brief A first candidate (warm start, paper III-D), or the start of a hill climb. */
        std::optional<NodePair> start;
        /** \brief Cap on node-pair distance evaluations; 0 means none. */
        std::size_t maxEvaluations{0};
        /** \brief Record the best value after every iteration/generation in DistanceResult::history. */
        bool recordHistory{false};
        /** \brief Exact stage and scene: stop as soon as a distance at or below this is known (a validity check
            needs no more); the answer is then an upper bound, not certified, and a collision gets no depth.
            Negative (the default): never stop early. Node-level solvers ignore it. */
        double stopBelow{-1.0};
        /** \brief Exact stage and scene: only a distance below this matters to the caller, so everything at or
            above it is pruned (cheap when the bodies are far apart); when nothing is closer the answer says so
            (refineExact(): distance infinity; Scene: SceneResult::atLeast) and is proven. The collision verdict
            is exact whatever the bound. Infinity (the default): no bound. Node-level solvers ignore it. */
        double upperBound{std::numeric_limits<double>::infinity()};
        /** \brief Exact stage and scene: in collision, find the penetration depth behind the signed distance (true,
            the default), or answer the verdict alone (false: distance CONTACT_DISTANCE, a zero that is negative,
            penetration NOT_COMPUTED, as FCL's distance answers 0 in collision). A free answer is the same either
            way; a caller that needs only the verdict and the clearance of free poses saves the depth's cost.
            Node-level solvers ignore it. */
        bool computeDepth{true};
        /** \brief Exact stage and scene, for bounded questions (a finite upperBound): give up on a pair after this
            many box and triangle tests (bvhDistance()'s budget), the answer then not certified (a Scene's
            SceneResult::atLeast may still be set, with certified false: a caller reads both). A caller that can
            ask a cheaper question instead (a smaller bound) saves the price of one whose answer lies just beyond
            its bound. 0 (the default): no limit. */
        std::size_t maxTests{0};
        /** \brief Exact stage and scene, for bounded questions (a finite upperBound): first ask the bodies' convex
            outer bounds (a body's solids, Body::primitives(), else its hull grown by its margin, Body::convexHull())
            by GJK; when every pair of them is more than upperBound apart, nothing is closer (proven: the same
            answer as the traversal's, distance infinity, certified) and no triangle is visited. Otherwise the
            question is answered as without it. Pays when the bodies are near but their hulls are not (a link close
            to a table); costs a GJK per pair otherwise. */
        bool outerBoundFirst{false};
    };

    /** \brief What a colliding pair's (negative) distance is: how its penetration depth was found. */
    enum class Penetration
    {
        NONE,           ///< not in collision (or collision not decided): distance is a distance, >= 0
        DEEPEST_NODE,   ///< depth of the deepest node of one body inside the other, closed, one (PenetrationDepth.h)
        /** \brief in collision, no node inside the other, closed, body (crossing or touching surfaces): depth 0 */
        NO_NODE_INSIDE,
        OPEN_BODIES,    ///< in collision, both bodies open (no inside, so no depth): depth 0
        NOT_COMPUTED    ///< in collision, depth not asked for (stopBelow >= 0, or computeDepth false): depth 0
    };

    /** \brief The distance reported for a collision whose depth is 0 or not known (Penetration other than
        DEEPEST_NODE): the largest double below zero that is normal (-2.2e-308), so that the sign alone says
        "in collision" (distance < 0 if and only if inCollision) while the magnitude claims no depth. */
    constexpr double CONTACT_DISTANCE = -std::numeric_limits<double>::min();

    /** \brief What one query found, and what it cost.

        Witness points, one naming for every pair query (DistanceResult, SceneResult, RobotResult): onA lies on the
        side the question is asked about, onB on what it is measured against. Here A and B are the pair's bodies
        (X_AB places B in A's frame); in a SceneResult A is the robot and B the obstacle of the answer; in a
        RobotResult A is the link RobotResult::link and B what it is measured against, an obstacle or the link
        RobotResult::other. Free, |onA - onB| is the distance and onA - onB points from B to A (the way A moves to
        get away); in collision they are the deepest node and its nearest point on the other surface, or a touching
        point (refineExact(), step 3). */
    struct DistanceResult
    {
        /** \brief Paper's flop estimate per d^2 evaluation (Section III-A, eq. 4). */
        static constexpr std::size_t FLOPS_PER_EVALUATION = 26;

        /** \brief The distance found: node to node for node-level solvers, the exact surface distance after the
            exact stage; negative in collision once the exact stage has decided it (see inCollision). */
        double distance{std::numeric_limits<double>::infinity()};
        NodePair nodes;                                            ///< the node pair at that distance
        /** \brief Witness points on A and on B (the naming above), both expressed in A's frame (which is the world
            frame when A is the world or any body at the identity pose, as in the command-line tools). */
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
        std::size_t evaluations{0};  ///< d^2 evaluations (the paper's cost unit)
        std::size_t localSteps{0};   ///< hill-climbing moves accepted
        std::size_t iterations{0};   ///< generations (GA), iterations (SA) or rounds (hill climb)
        std::size_t convergedAt{0};  ///< iteration at which the final best value was first reached
        double seconds{0.0};         ///< wall time of the query
        /** \brief True only when the answer is proven to be the minimum over all node pairs (enumeration). */
        bool nodeOptimal{false};

        // Filled by the exact stage (refineExact(), the "exact" solver); untouched by node-level solvers.
        /** \brief The node-to-node distance the exact stage started from (infinity if it had no seed). */
        double nodeDistance{std::numeric_limits<double>::infinity()};
        /** \brief distance is the exact surface distance, proven by a completed bounding-volume traversal (or, for
            a collision, by an intersecting triangle pair or a contained body). */
        bool certified{false};
        /** \brief The bodies intersect, touch, or one (closed) body lies inside the other. distance is then
            negative (a signed distance): -penetrationDepth, or CONTACT_DISTANCE when that depth is 0 or not known.
            Always equal to distance < 0 once the exact stage has run; kept as a flag because a node-level answer
            (no exact stage) has decided nothing, and the flag says so where the sign could not. */
        bool inCollision{false};
        /** \brief In collision: the penetration depth estimate (>= 0; a lower bound on the translational penetration
            depth, see penetrationDepth() in PenetrationDepth.h) and how it was found. Outside collision: 0, None. */
        double penetrationDepth{0.0};
        Penetration penetration{Penetration::NONE};
        /** \brief Set by the exact stage when either body is not closed (Body::isClosed() false: boundary or
            non-manifold edges), whatever the verdict. Such an "open" body has no inside, so the answer means less
            than between closed bodies, though it is exact for what it means: inCollision is surface contact (an
            intersecting or touching triangle pair), or a part of either body wholly inside the other when that
            one is closed, never a part "inside" the open one (a closed box inside a box without a lid is free, its
            distance the gap to the nearest wall); the depth counts nodes of either body inside the other, closed,
            one only (an open sheet through a closed box has a depth: its deepest node's, as for closed bodies),
            and is 0 when there is none (distance CONTACT_DISTANCE; penetration NO_NODE_INSIDE, or OPEN_BODIES when
            both are open). Between two closed bodies it is false and nothing above applies. */
        bool openBody{false};
        /** \brief Closest surface triangles (Body::surface() indices); for a body answered as its primitive solids
            (Body::primitives()), by an exact query, the index of its closest solid. */
        std::uint32_t triangleA{0}, triangleB{0};
        std::size_t triangleTests{0};              ///< exact triangle-pair (and point-triangle) tests made
        std::size_t boxTests{0};                   ///< bounding-volume pairs tested by the distance traversal
        /** \brief Questions answered by the convex outer bounds alone (DistanceRequest::outerBoundFirst). */
        std::size_t outerBoundProofs{0};
        /** \brief Best value after each iteration, when DistanceRequest::recordHistory is set. */
        std::vector<double> history;

        std::size_t flops() const { return FLOPS_PER_EVALUATION * evaluations; }
    };
}  // namespace meshgap

#endif
