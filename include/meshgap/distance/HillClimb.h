#ifndef MESHGAP_DISTANCE_HILL_CLIMB_H
#define MESHGAP_DISTANCE_HILL_CLIMB_H

#include "meshgap/distance/DistanceSolver.h"
#include "meshgap/distance/PairEvaluator.h"

namespace meshgap
{
    /** \brief The paper's local optimisation (Section III-E), in place: move the node on A to its neighbour that
        most reduces the distance, again and again until no neighbour of it improves; then the same for the node on
        B; alternate until neither node has an improving neighbour. \e d2 is the pair's current squared distance
        (updated). Returns the number of moves accepted. Ties keep the current node, so the climb always ends.
        With \e maxEvaluations > 0 it stops, keeping the best pair so far, before an evaluation would take
        PairEvaluator::evaluations() above that total (the same moves in the same order until then). */
    std::size_t hillClimb(PairEvaluator &evaluator, NodePair &pair, double &d2, std::size_t maxEvaluations = 0);

    /**
       @anchor mgHillClimb
       @par Short description
       Hill climbing alone, from DistanceRequest::start or, without it, from a node pair drawn with the request's
       seed. Finds the global node minimum for convex bodies (paper III-E); a local one otherwise.
    */
    class HillClimb : public DistanceSolver
    {
    public:
        HillClimb() : DistanceSolver("hill-climb") {}
        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;
    };
}  // namespace meshgap

#endif
