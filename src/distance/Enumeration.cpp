#include "meshgap/distance/Enumeration.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "meshgap/distance/PairEvaluator.h"

namespace meshgap
{
    namespace
    {
        struct ClusterPair
        {
            double lowerBound;
            std::uint32_t a, b;
        };
    }  // namespace

    void Enumeration::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &,
                            DistanceResult &result) const
    {
        const auto start = std::chrono::steady_clock::now();
        result = DistanceResult();
        const Eigen::Matrix3d R = X_AB.linear();
        const Eigen::Vector3d t = X_AB.translation();

        // B's nodes in A's frame, in B's cluster order (structure of arrays).
        const std::uint32_t nb = b.numNodes();
        std::vector<double> bx(nb), by(nb), bz(nb);
        for (std::uint32_t k = 0; k < nb; ++k)
        {
            const Eigen::Vector3d p = R * Eigen::Vector3d(b.xs()[k], b.ys()[k], b.zs()[k]) + t;
            bx[k] = p.x();
            by[k] = p.y();
            bz[k] = p.z();
        }

        // Lower bound on the distance between any node of cluster i (A) and any node of cluster j (B).
        const auto &ca = a.clusters(), &cb = b.clusters();
        std::vector<ClusterPair> pairs;
        pairs.reserve(ca.size() * cb.size());
        std::vector<Eigen::Vector3d> cbInA(cb.size());
        for (std::size_t j = 0; j < cb.size(); ++j)
            cbInA[j] = R * cb[j].center + t;
        for (std::uint32_t i = 0; i < ca.size(); ++i)
            for (std::uint32_t j = 0; j < cb.size(); ++j)
                pairs.push_back({(ca[i].center - cbInA[j]).norm() - ca[i].radius - cb[j].radius, i, j});
        std::sort(pairs.begin(), pairs.end(),
                  [](const ClusterPair &p, const ClusterPair &q) { return p.lowerBound < q.lowerBound; });
        // Rounding in the transforms is far below this slack, so the pruning never drops a closer pair.
        const double slack = 1e-9 * (t.norm() + a.radiusAboutOrigin() + b.radiusAboutOrigin());

        double best2 = std::numeric_limits<double>::infinity();
        std::uint32_t bestA = 0, bestB = 0;
        std::size_t evaluations = 0;
        const double *ax = a.xs().data(), *ay = a.ys().data(), *az = a.zs().data();
        for (const ClusterPair &p : pairs)
        {
            const double bound = p.lowerBound - slack;
            if (bound > 0.0 && bound * bound > best2)
                break;  // sorted: no later cluster pair can hold a closer node pair
            const NodeCluster &A = ca[p.a], &B = cb[p.b];
            evaluations += std::size_t(A.end - A.begin) * (B.end - B.begin);
            for (std::uint32_t i = A.begin; i < A.end; ++i)
            {
                const double x = ax[i], y = ay[i], z = az[i];
                double rowBest = std::numeric_limits<double>::infinity();
                std::uint32_t rowArg = B.begin;
                for (std::uint32_t j = B.begin; j < B.end; ++j)
                {
                    const double dx = x - bx[j], dy = y - by[j], dz = z - bz[j];
                    const double d2 = dx * dx + dy * dy + dz * dz;
                    if (d2 < rowBest)
                    {
                        rowBest = d2;
                        rowArg = j;
                    }
                }
                if (rowBest < best2)
                {
                    best2 = rowBest;
                    bestA = i;
                    bestB = rowArg;
                }
            }
        }

        PairEvaluator evaluator(a, b, X_AB);
        const NodePair best{a.clusterOrder()[bestA], b.clusterOrder()[bestB]};
        evaluator.fill(best, evaluator.d2(best), result);
        result.evaluations = evaluations;
        result.iterations = 1;
        result.nodeOptimal = true;
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}  // namespace meshgap
