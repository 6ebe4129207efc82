#ifndef MESHGAP_DISTANCE_MESH_MOVES_H
#define MESHGAP_DISTANCE_MESH_MOVES_H

#include <cstdint>
#include <random>
#include <vector>

#include "meshgap/ThreadScratch.h"
#include "meshgap/distance/PairEvaluator.h"
#include "meshgap/mesh/MeshDistances.h"

namespace meshgap
{
    /** \brief The random numbers of one query (seeded from DistanceRequest::seed; never shared between queries). */
    using QueryRng = std::mt19937_64;

    /** \brief Scratch space of the moves (a path and its mesh distances), reused between calls to save allocations.
        Used by one query at a time; the solvers keep one per thread (ThreadScratch) with capacity for the longest
        path, so moves never allocate. */
    struct MoveScratch
    {
        std::vector<std::uint32_t> path;
        std::vector<double> cumulative;

        /** \brief Capacity for a path of \e numNodes nodes (the most a mesh path of that graph has). */
        void reserve(std::size_t numNodes)
        {
            path.reserve(numNodes);
            cumulative.reserve(numNodes);
        }
    };

    /** \brief Radius of mesh mating, the paper's eq. 5: r = delta_{1->2} d1^2 / (d1^2 + d2^2), where parent 1 is the
        fitter one (d1^2 <= d2^2, so r <= delta_{1->2} / 2). Both parents at distance 0 give r = 0. */
    double matingRadius(double delta, double d2Fitter, double d2Other);

    /** \brief Mesh mating of one gene (paper III-B.2): the offspring's node on one body, from the nodes \e fitter
        and \e other the two parents have on that body (\e fitter belongs to the parent of smaller d^2, \e d2Fitter;
        the other parent's is \e d2Other).

        The shortest mesh path from \e fitter to \e other is taken from the body's mesh distances (D and P), and the
        offspring is drawn uniformly among the nodes of that path whose mesh distance from \e fitter is at most the
        radius of eq. 5 (matingRadius()). \e fitter itself is always eligible, so the choice is never empty; equal
        nodes give that node.

        Where the paper is silent, the two nodes lie in different connected components of the body (no path, infinite
        mesh distance). Then the offspring takes \e other's node with probability d2Fitter / (d2Fitter + d2Other) (the
        share eq. 5 gives the other parent's side of the path, at most 1/2) and \e fitter's otherwise: a jump between
        components, at random, as DESIGN.md asks of every move that needs a path. */
    std::uint32_t meshMate(const MeshDistances &distances, std::uint32_t fitter, std::uint32_t other, double d2Fitter,
                           double d2Other, QueryRng &rng, MoveScratch &scratch);

    /** \brief The random move of one gene (paper III-B.3; the mutation of comb-GA and the trial-point generator of
        comb-SA): draw a random node of the body (uniformly among all its nodes other than \e start), take the shortest
        mesh path from \e start towards it, and return a node drawn uniformly among the nodes of that path, \e start
        excluded, whose mesh distance from \e start is at most \e radius.

        Where the paper is silent:
        - \e start is not a candidate: a move moves (the paper's "random displacement"), and an unchanged node would
          cost an evaluation for nothing.
        - If even the path's first step is longer than \e radius (comb-SA shrinks its radius as it cools, down below
          one edge), the move takes that first step: the smallest move the mesh allows. Without it the search would
          freeze once the radius drops below the grid size.
        - If the drawn node lies in another connected component (no path, infinite mesh distance), the move jumps to
          it with probability min(1, 2 radius / max(D)), else the target is redrawn in \e start's component (up to
          64 draws; a body whose component is that small keeps the jump). At the GA's fixed r_max = max(D)/2 a move
          thus leaves its component with probability (nodes outside it) / (all nodes but \e start), as DESIGN.md
          says of moves that need a path (they jump components at random); comb-SA's shrinking radius makes jumps
          rarer as it cools, where jumping regardless made it a random restart on many-part bodies (the hand's six
          shells: 83% of moves).
        - A body of one node returns \e start. */
    std::uint32_t randomMove(const MeshDistances &distances, std::uint32_t start, double radius, QueryRng &rng,
                             MoveScratch &scratch);

    /** \brief Mesh distance of every node of \e path from its first node, accumulated along the path's edges (the
        same sums Dijkstra formed, so they equal MeshDistances::distance() from the first node). The first entry is
        0. \e path must be a path of \e graph (consecutive nodes adjacent). */
    void pathDistances(const SurfaceGraph &graph, const std::vector<std::uint32_t> &path, std::vector<double> &out);

}  // namespace meshgap

#endif
