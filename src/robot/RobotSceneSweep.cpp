// RobotScene's question about a piece of motion as a whole (sweptApart()): each link's convex hull swept between its
// places at the piece's two ends, grown by how far its points may stray from those straight lines.
#include <algorithm>
#include <cmath>

#include "meshgap/geometry/ConvexHull.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    namespace
    {
        /** \brief The least gap that counts as apart: roundoff in the poses and grown radii, 1e-12 of the sizes and
            coordinates involved (far above it, far below any gap that matters). */
        double apartPad(const ConvexHull &hull, const Eigen::Isometry3d &X0, const Eigen::Isometry3d &X1)
        {
            return 1e-12 * (1.0 + hull.reach() + X0.translation().norm() + X1.translation().norm()) + 1e-300;
        }
    }  // namespace

    void RobotScene::placeEnds(const double *state, std::size_t size, Placement &at) const
    {
        robot_->framePoses(state, size, at.frames);
        at.links.resize(links_.size());
        for (std::size_t i = 0; i < links_.size(); ++i)
            at.links[i] = at.frames[links_[i].frame] * links_[i].X_FL;
    }

    bool RobotScene::sweptApart(std::size_t k, const Placement &at0, const Placement &at1, double grow,
                                double growOther, RobotWarmStart &warm, bool stays, bool staysOther) const
    {
        if (k < links_.size())
        {
            const ConvexHull *hull = links_[k].body->coarseHull();
            if (!hull)
                return false;
            const Eigen::Isometry3d &X0 = at0.links[k], &X1 = stays ? X0 : at1.links[k];
            const double pad = apartPad(*hull, X0, X1);
            // The swept hull's axis-aligned box: a ball about the link's origin, at both ends, grown.
            const double r = hull->reach() + hull->margin() + grow + pad;
            const Eigen::AlignedBox3d around(X0.translation().cwiseMin(X1.translation()).array() - r,
                                             X0.translation().cwiseMax(X1.translation()).array() + r);
            Eigen::Vector3d *axis = warm.sweepAxes.data() + sweepOffset_[k];
            for (std::size_t o : linkObstacles_[k])
            {
                const Body &obstacle = *obstacles_[o];
                Eigen::Vector3d *axes = axis;
                axis += std::max<std::size_t>(1, obstacle.primitives().size());
                if (!around.intersects(obstacleBounds_[o].aabb))
                    continue;
                if (!obstacle.primitives().empty())
                {
                    for (const Primitive &p : obstacle.primitives())
                        if (!(sweptHullPrimitiveGap(*hull, X0, X1, grow, p, pad, axes++) > pad))
                            return false;
                    continue;
                }
                const ConvexHull *other = obstacle.coarseHull();
                const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
                if (!other || !(sweptHullGap(*hull, X0, X1, grow, *other, I, I, 0.0, pad, axes) > pad))
                    return false;
            }
            return true;
        }
        const std::size_t p = k - links_.size();
        const auto [a, b] = selfPairs_[p];
        const ConvexHull *ha = links_[a].body->coarseHull(), *hb = links_[b].body->coarseHull();
        if (!ha || !hb)
            return false;
        // Both links in the frame of their nearest common ancestor, where their bends are measured.
        const std::size_t c = selfAncestor_[p];
        const Eigen::Isometry3d C0 = c == RobotModel::NONE ? Eigen::Isometry3d::Identity() : at0.frames[c].inverse();
        const Eigen::Isometry3d C1 = c == RobotModel::NONE ? Eigen::Isometry3d::Identity() : at1.frames[c].inverse();
        const Eigen::Isometry3d A0 = C0 * at0.links[a], A1 = stays ? A0 : Eigen::Isometry3d(C1 * at1.links[a]);
        const Eigen::Isometry3d B0 = C0 * at0.links[b], B1 = staysOther ? B0 : Eigen::Isometry3d(C1 * at1.links[b]);
        const double pad = apartPad(*ha, A0, A1) + apartPad(*hb, B0, B1);
        return sweptHullGap(*ha, A0, A1, grow, *hb, B0, B1, growOther, pad,
                            &warm.sweepAxes[sweepOffset_[links_.size()] + p]) > pad;
    }
}  // namespace meshgap
