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
        A's frame (the paper's eq. 4: only B's nodes are transformed). */
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
    };

    /** \brief What one query found, and what it cost. */
    struct DistanceResult
    {
        /** \brief Paper's flop estimate per d^2 evaluation (Section III-A, eq. 4). */
        static constexpr std::size_t FLOPS_PER_EVALUATION = 26;

        double distance{std::numeric_limits<double>::infinity()};  ///< node-to-node distance found
        NodePair nodes;                                            ///< the node pair at that distance
        /** \brief Witness points on A and on B, both expressed in A's frame (which is the world frame when A is
            the world or any body at the identity pose, as in the command-line tools). */
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
        /** \brief The bodies intersect, touch, or one (closed) body lies inside the other. distance is then 0. */
        bool inCollision{false};
        std::uint32_t triangleA{0}, triangleB{0};  ///< closest surface triangles (Body::surface() indices)
        std::size_t triangleTests{0};              ///< exact triangle-pair tests made
        /** \brief Best value after each iteration, when DistanceRequest::recordHistory is set. */
        std::vector<double> history;

        std::size_t flops() const { return FLOPS_PER_EVALUATION * evaluations; }
    };
}  // namespace meshgap

#endif
