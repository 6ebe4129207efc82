#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

#include "meshgap/distance/ExactDistance.h"

namespace meshgap
{
    /** \brief insideClosedBody() that keeps the answers of its last \e N tests. The winding number is the same all
        over a ball free of the surface, so a point within the ball of an earlier test (that point's distance to the
        surface, less a roundoff margin) takes the earlier answer without a ray cast. For one body and one search at
        a time (not thread-safe); no allocation. */
    template <std::uint32_t N = 8>
    class RecentInsideTests
    {
    public:
        /** \brief \e slack: an absolute bound on the roundoff of the body's point distances (at the scale of its
            coordinates); the distances given to inside() are also trusted to 1e-9 relative. */
        explicit RecentInsideTests(double slack) : slack_(slack) {}

        /** \brief insideClosedBody(\e body, \e q), where \e q lies \e distance from the body's surface (a point
            query's answer). \e rayCasts counts the tests made anew. */
        bool inside(const Body &body, const Eigen::Vector3d &q, double distance, std::size_t &rayCasts)
        {
            for (std::uint32_t i = 0; i < count_; ++i)
                if ((q - known_[i].point).squaredNorm() < known_[i].radiusSquared)
                    return known_[i].inside;
            ++rayCasts;
            const bool in = insideClosedBody(body, q);
            // The ball's radius less roundoff: a point closer than it to q is closer than distance, and so clear of
            // the surface, whatever the roundoff of distance.
            const double radius = (distance - slack_) / (1.0 + 1e-9);
            if (radius > 0.0)
            {
                known_[next_] = {q, radius * radius, in};
                next_ = (next_ + 1) % N;
                count_ = count_ < N ? count_ + 1 : N;
            }
            return in;
        }

    private:
        struct Known
        {
            Eigen::Vector3d point;
            double radiusSquared;
            bool inside;
        };
        std::array<Known, N> known_{};
        std::uint32_t count_{0}, next_{0};
        double slack_;
    };
}  // namespace meshgap
