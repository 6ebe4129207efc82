#ifndef MESHGAP_DISTANCE_PAIR_EVALUATOR_H
#define MESHGAP_DISTANCE_PAIR_EVALUATOR_H

#include <Eigen/Geometry>

#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/geometry/Body.h"

namespace meshgap
{
    /** \brief The paper's objective (eq. 2), d^2 between node i of A and node j of B, with B's node carried into A's
        frame by X_AB (eq. 4). Counts every evaluation. One per query; not shared between threads. */
    class PairEvaluator
    {
    public:
        PairEvaluator(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
          : a_(a), b_(b), R_(X_AB.linear()), t_(X_AB.translation())
        {
        }

        double d2(std::uint32_t i, std::uint32_t j)
        {
            ++evaluations_;
            return (a_.node(i) - (R_ * b_.node(j) + t_)).squaredNorm();
        }
        double d2(const NodePair &p) { return d2(p.a, p.b); }
        /** \brief d2(i, j) with node j of B already in A's frame (\e bInA, from bInA(j)): the same value bit for bit,
            without carrying j again (a climb moving A's node against a fixed node of B). */
        double d2ToB(std::uint32_t i, const Eigen::Vector3d &bInA)
        {
            ++evaluations_;
            return (a_.node(i) - bInA).squaredNorm();
        }

        /** \brief Node j of B expressed in A's frame. */
        Eigen::Vector3d bInA(std::uint32_t j) const { return R_ * b_.node(j) + t_; }

        /** \brief Fill the result's distance, nodes and witness points for pair \e p at squared distance \e d2. */
        void fill(const NodePair &p, double d2, DistanceResult &result) const
        {
            result.distance = std::sqrt(d2);
            result.nodes = p;
            result.onA = a_.node(p.a);
            result.onB = bInA(p.b);
            result.evaluations = evaluations_;
        }

        const Body &a() const { return a_; }
        const Body &b() const { return b_; }
        std::size_t evaluations() const { return evaluations_; }

    private:
        const Body &a_;
        const Body &b_;
        Eigen::Matrix3d R_;
        Eigen::Vector3d t_;
        std::size_t evaluations_{0};
    };
}  // namespace meshgap

#endif
