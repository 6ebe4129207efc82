#include "meshgap/distance/MeshMoves.h"

#include <algorithm>
#include <string>

#include "meshgap/Exception.h"
#include "meshgap/distance/HillClimb.h"

namespace meshgap
{
    namespace
    {
        /** \brief Number of leading entries of \e cumulative (non-decreasing) that are <= \e radius. */
        std::size_t countWithin(const std::vector<double> &cumulative, double radius)
        {
            std::size_t k = 0;
            while (k < cumulative.size() && cumulative[k] <= radius)
                ++k;
            return k;
        }
    }  // namespace

    double matingRadius(double delta, double d2Fitter, double d2Other)
    {
        const double sum = d2Fitter + d2Other;
        return sum > 0.0 ? delta * (d2Fitter / sum) : 0.0;
    }

    void pathDistances(const SurfaceGraph &graph, const std::vector<std::uint32_t> &path, std::vector<double> &out)
    {
        out.clear();
        if (path.empty())
            return;
        out.push_back(0.0);
        for (std::size_t k = 1; k < path.size(); ++k)
        {
            const std::uint32_t u = path[k - 1], v = path[k];
            const std::uint32_t *begin = graph.beginNeighbours(u), *end = graph.endNeighbours(u);
            const std::uint32_t *it = begin;
            while (it != end && *it != v)
                ++it;
            if (it == end)
                throw Exception("pathDistances", "nodes " + std::to_string(u) + " and " + std::to_string(v) +
                                                     " are consecutive on a path but not adjacent");
            out.push_back(out.back() + graph.lengths()[graph.offsets()[u] + (it - begin)]);
        }
    }

    std::uint32_t meshMate(const MeshDistances &distances, std::uint32_t fitter, std::uint32_t other, double d2Fitter,
                           double d2Other, QueryRng &rng, MoveScratch &scratch)
    {
        if (fitter == other)
            return fitter;
        std::vector<std::uint32_t> &path = scratch.path;
        distances.path(fitter, other, path);
        if (path.empty())
        {
            // Different components: jump to the other parent's node with the other parent's share of eq. 5.
            const double share = d2Fitter + d2Other > 0.0 ? d2Fitter / (d2Fitter + d2Other) : 0.0;
            return std::uniform_real_distribution<double>(0.0, 1.0)(rng) < share ? other : fitter;
        }
        pathDistances(distances.graph(), path, scratch.cumulative);
        const double r = matingRadius(scratch.cumulative.back(), d2Fitter, d2Other);
        // The fitter parent (distance 0) is always eligible.
        const std::size_t eligible = std::max<std::size_t>(1, countWithin(scratch.cumulative, r));
        return path[std::uniform_int_distribution<std::size_t>(0, eligible - 1)(rng)];
    }

    std::uint32_t randomMove(const MeshDistances &distances, std::uint32_t start, double radius, QueryRng &rng,
                             MoveScratch &scratch)
    {
        const std::uint32_t n = distances.graph().numNodes();
        if (n <= 1)
            return start;
        // Uniform over the other n - 1 nodes.
        std::uint32_t target = std::uniform_int_distribution<std::uint32_t>(0, n - 2)(rng);
        if (target >= start)
            ++target;
        const SurfaceGraph &graph = distances.graph();
        if (graph.component(target) != graph.component(start))
        {
            // Another component is farther than any radius. Jump with probability 2 radius / max(D) (1 at the GA's
            // fixed r_max = max(D)/2), so comb-SA's cooling also cools the jumps; otherwise redraw the target in
            // start's own component (a few tries: a tiny component keeps its jump).
            const double maxD = distances.maxDistance();
            const double jump = maxD > 0.0 ? std::min(1.0, 2.0 * radius / maxD) : 1.0;
            if (std::uniform_real_distribution<double>(0.0, 1.0)(rng) < jump)
                return target;
            for (int attempt = 0; attempt < 64 && graph.component(target) != graph.component(start); ++attempt)
            {
                target = std::uniform_int_distribution<std::uint32_t>(0, n - 2)(rng);
                if (target >= start)
                    ++target;
            }
            if (graph.component(target) != graph.component(start))
                return target;
        }
        std::vector<std::uint32_t> &path = scratch.path;
        distances.path(start, target, path);
        pathDistances(distances.graph(), path, scratch.cumulative);
        // Candidates are path[1 .. k]; at least the first step, even when it is longer than the radius.
        const std::size_t within = countWithin(scratch.cumulative, radius);  // path[0 .. within-1] are in the radius
        const std::size_t k = within >= 2 ? within - 1 : 1;
        return path[std::uniform_int_distribution<std::size_t>(1, k)(rng)];
    }
}  // namespace meshgap
