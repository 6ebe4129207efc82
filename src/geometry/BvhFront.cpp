#include "meshgap/geometry/BvhFront.h"

#include <algorithm>
#include <cmath>

#include "meshgap/geometry/TriangleBvh.h"

namespace meshgap
{
    double nodeMotionBound(const Eigen::Vector3d &center, double radius, const Eigen::Isometry3d &from,
                           const Eigen::Isometry3d &to)
    {
        const Eigen::Vector3d shift = to * center - from * center;
        // |R_to - R_from|_2 = 2 sin(theta / 2) = sqrt(3 - trace(R_from^T R_to)); the trace is the sum of the
        // elementwise product.
        const double trace = from.linear().cwiseProduct(to.linear()).sum();
        const double turn = std::sqrt(std::max(0.0, 3.0 - trace));
        // Roundoff: in the trace (a few 1e-16, whose square root can reach 1e-8 of a small turn: pad the turn by
        // 1e-7) and in the shift (relative to the coordinates).
        const double scale = center.norm() + radius + from.translation().norm() + to.translation().norm();
        return (shift.norm() + radius * (turn + 1e-7 * (turn > 0.0))) * (1.0 + 1e-12) + 1e-12 * scale;
    }

    double motionBound(const TriangleBvh &b, const Eigen::Isometry3d &from, const Eigen::Isometry3d &to)
    {
        if (b.nodes().empty())
            return 0.0;
        return nodeMotionBound(b.nodes()[0].center, b.nodes()[0].radius, from, to);
    }
}  // namespace meshgap
