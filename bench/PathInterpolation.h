// The benches' one way of spreading states along a path: shared by meshgap_bench_queries, _warm_fast and _reliability.
#ifndef MESHGAP_BENCH_PATH_INTERPOLATION_H
#define MESHGAP_BENCH_PATH_INTERPOLATION_H

#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

namespace meshgap::bench
{
    /** \brief \e count states spread evenly along \e path by arc length, rotation counted in radians beside the
        translation (so states spread along turns too): linear translation, slerp rotation. A path of fewer than two
        states, or a count below two, is returned as it is. */
    inline std::vector<Eigen::Isometry3d> interpolatePath(const std::vector<Eigen::Isometry3d> &path,
                                                          std::size_t count)
    {
        if (path.size() < 2 || count < 2)
            return path;
        std::vector<double> s{0.0};
        for (std::size_t i = 1; i < path.size(); ++i)
        {
            const double dt = (path[i].translation() - path[i - 1].translation()).norm();
            const double dr =
                Eigen::Quaterniond(path[i].linear()).angularDistance(Eigen::Quaterniond(path[i - 1].linear()));
            s.push_back(s.back() + dt + dr + 1e-12);
        }
        std::vector<Eigen::Isometry3d> out;
        std::size_t seg = 0;
        for (std::size_t k = 0; k < count; ++k)
        {
            const double at = s.back() * double(k) / double(count - 1);
            while (seg + 2 < path.size() && s[seg + 1] < at)
                ++seg;
            const double t = std::clamp((at - s[seg]) / (s[seg + 1] - s[seg]), 0.0, 1.0);
            const Eigen::Quaterniond q0(path[seg].linear()), q1(path[seg + 1].linear());
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q0.slerp(t, q1).toRotationMatrix();
            X.translation() = (1 - t) * path[seg].translation() + t * path[seg + 1].translation();
            out.push_back(X);
        }
        return out;
    }
}  // namespace meshgap::bench

#endif
