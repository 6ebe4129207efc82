#include "meshgap/distance/HillClimb.h"

#include <chrono>
#include <limits>
#include <random>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        // Steepest descent of one node of the pair while the other stays fixed. Returns the moves made; sets
        // \e stopped when the evaluation cap prevented an evaluation (the best pair so far is kept).
        template <bool MoveA>
        std::size_t descend(PairEvaluator &evaluator, const SurfaceGraph &graph, NodePair &pair, double &d2,
                            std::size_t cap, bool &stopped)
        {
            std::size_t moves = 0;
            for (;;)
            {
                const std::uint32_t here = MoveA ? pair.a : pair.b;
                std::uint32_t bestNode = here;
                double best = d2;
                // Moving A's node: B's node is carried into A's frame once per step, not once per neighbour.
                const Eigen::Vector3d fixedB = MoveA ? evaluator.bInA(pair.b) : Eigen::Vector3d::Zero();
                for (const std::uint32_t *n = graph.beginNeighbours(here); n != graph.endNeighbours(here); ++n)
                {
                    if (evaluator.evaluations() >= cap)
                    {
                        stopped = true;
                        break;
                    }
                    const double d = MoveA ? evaluator.d2ToB(*n, fixedB) : evaluator.d2(pair.a, *n);
                    if (d < best)
                    {
                        best = d;
                        bestNode = *n;
                    }
                }
                if (bestNode != here)
                {
                    (MoveA ? pair.a : pair.b) = bestNode;
                    d2 = best;
                    ++moves;
                }
                if (stopped || bestNode == here)
                    return moves;
            }
        }
    }  // namespace

    std::size_t hillClimb(PairEvaluator &evaluator, NodePair &pair, double &d2, std::size_t maxEvaluations)
    {
        const std::size_t cap = maxEvaluations == 0 ? std::numeric_limits<std::size_t>::max() : maxEvaluations;
        std::size_t total = 0;
        bool stopped = false;
        for (;;)
        {
            total += descend<true>(evaluator, evaluator.a().graph(), pair, d2, cap, stopped);
            if (stopped)
                return total;
            const std::size_t onB = descend<false>(evaluator, evaluator.b().graph(), pair, d2, cap, stopped);
            total += onB;
            // B's descent ended with no improving move for B; if it moved at all, A may improve again.
            if (stopped || onB == 0)
                return total;
        }
    }

    void HillClimb::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                          DistanceResult &result) const
    {
        const auto start = std::chrono::steady_clock::now();
        result = DistanceResult();
        checkRequest(a, b, request);
        NodePair pair;
        if (request.start)
            pair = *request.start;
        else
        {
            std::mt19937_64 rng(request.seed);
            pair.a = std::uniform_int_distribution<std::uint32_t>(0, a.numNodes() - 1)(rng);
            pair.b = std::uniform_int_distribution<std::uint32_t>(0, b.numNodes() - 1)(rng);
        }
        PairEvaluator evaluator(a, b, X_AB);
        double d2 = evaluator.d2(pair);
        result.localSteps = hillClimb(evaluator, pair, d2, request.maxEvaluations);
        evaluator.fill(pair, d2, result);
        result.iterations = 1;
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}  // namespace meshgap
