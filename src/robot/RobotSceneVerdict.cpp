// The collision verdict of RobotScene (inCollision(), pairCollides()): a broad phase shared by every link (each
// link's BVH root box placed in the world once a state, against each obstacle's boxes), obstacles of boxes answered
// as the solid boxes they are, self pairs tested by spheres and boxes before the exact layer.
#include <algorithm>
#include <cmath>
#include <limits>

#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    namespace
    {
        /** \brief Pad against roundoff, 1e-9 of the sizes and coordinates involved: far above roundoff, far below
            any gap that matters. */
        double padFor(double scale)
        {
            return 1e-9 * scale + 1e-300;
        }

        /** \brief The box of a primitive solid (its frame's axes, centred on its origin), placed by its pose. */
        WorldBox primitiveBox(const Primitive &p)
        {
            const double r = p.size.x(), half = 0.5 * p.size.y();
            WorldBox box;
            box.center = p.pose.translation();
            box.axes = p.pose.linear();
            switch (p.kind)
            {
                case Primitive::Kind::BOX:
                    box.half = 0.5 * p.size;
                    break;
                case Primitive::Kind::SPHERE:
                    box.half = Eigen::Vector3d::Constant(r);
                    break;
                case Primitive::Kind::CYLINDER:
                case Primitive::Kind::CONE:
                    box.half = Eigen::Vector3d(r, r, half);
                    break;
                case Primitive::Kind::CAPSULE:
                    box.half = Eigen::Vector3d(r, r, half + r);
                    break;
            }
            return box;
        }

        /** \brief A BVH node's box placed by \e X. */
        WorldBox placedNode(const TriangleBvh::Node &n, const Eigen::Isometry3d &X)
        {
            return {X * n.center, X.linear() * n.axes, n.half};
        }

        /** \brief The axis-aligned box around \e box, padded. */
        Eigen::AlignedBox3d aroundBox(const WorldBox &box)
        {
            const Eigen::Vector3d reach = box.axes.cwiseAbs() * box.half;
            const Eigen::Vector3d pad =
                Eigen::Vector3d::Constant(padFor(box.center.cwiseAbs().maxCoeff() + box.half.sum()));
            return Eigen::AlignedBox3d(box.center - reach - pad, box.center + reach + pad);
        }

        /** \brief Whether triangle \e t of \e mesh (its frame M) touches the solid box \e solid; \e Rt takes M's
            directions to the box's axes, \e c is the box's centre and \e h its half extents (M's frame). */
        bool triangleTouchesBox(const Mesh &mesh, std::uint32_t t, const Eigen::Matrix3d &Rt, const Eigen::Vector3d &c,
                                const Eigen::Vector3d &h, double pad, const Primitive &solid,
                                const Eigen::Isometry3d &X_MW)
        {
            const Triangle &f = mesh.triangles[t];
            Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
            for (int k = 0; k < 3; ++k)
            {
                const Eigen::Vector3d p = Rt * (mesh.vertices[f[k]] - c);
                if ((p.cwiseAbs() - h).maxCoeff() < -pad)
                    return true;  // a corner inside the box
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
            if ((lo - h).maxCoeff() > pad || (-hi - h).maxCoeff() > pad)
                return false;  // apart along one of the box's axes
            const Eigen::Vector3d &a = mesh.vertices[f[0]], &b = mesh.vertices[f[1]], &d = mesh.vertices[f[2]];
            return primitiveTriangleGap(solid, X_MW, a, b, d, std::numeric_limits<double>::min()).distance == 0.0;
        }

        /** \brief Whether some triangle of \e body (whose frame M is placed in the world by the inverse of \e X_MW)
            touches or lies inside the solid box \e solid (\e box, its box in the world): a traversal of the BVH
            that prunes a node whose box is apart from the solid's along one of either box's axes, and stops at the
            first node whose box lies inside it (its triangles are) or the first touching triangle. */
        bool meshTouchesBox(const Body &body, const Eigen::Isometry3d &X_MW, const WorldBox &box,
                            const Primitive &solid, std::vector<std::uint32_t> &stack)
        {
            const TriangleBvh &bvh = body.bvh();
            const TriangleBvh::Node *nodes = bvh.nodes().data();
            const Eigen::Matrix3d Rt = (X_MW.linear() * box.axes).transpose();
            const Eigen::Vector3d c = X_MW * box.center;
            const Eigen::Vector3d &h = box.half;
            const double pad = padFor(c.cwiseAbs().maxCoeff() + h.sum() + nodes[0].radius + nodes[0].center.norm());
            stack.clear();
            stack.push_back(0);
            while (!stack.empty())
            {
                const TriangleBvh::Node &n = nodes[stack.back()];
                stack.pop_back();
                const Eigen::Vector3d d = Rt * (n.center - c);  // the node's centre along the box's axes
                const Eigen::Matrix3d M = n.aligned ? Rt : Eigen::Matrix3d(Rt * n.axes);
                const Eigen::Vector3d reach = M.cwiseAbs() * n.half;
                if ((d.cwiseAbs() - reach - h).maxCoeff() > pad)
                    continue;  // apart along one of the box's axes
                if (((M.transpose() * d).cwiseAbs() - M.cwiseAbs().transpose() * h - n.half).maxCoeff() > pad)
                    continue;  // apart along one of the node's axes
                if ((d.cwiseAbs() + reach - h).maxCoeff() < -pad)
                    return true;  // the node's box, and every triangle in it, inside the solid
                if (!n.isLeaf())
                {
                    stack.push_back(n.first + 1);
                    stack.push_back(n.first);
                    continue;
                }
                for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
                    if (triangleTouchesBox(bvh.mesh(), bvh.order()[k], Rt, c, h, pad, solid, X_MW))
                        return true;
            }
            return false;
        }

        /** \brief With no triangle of \e body touching the solid box: whether the box lies inside the closed body
            (one point of it decides, its centre). */
        bool boxInsideBody(const Body &body, const Eigen::Isometry3d &X_MW, const WorldBox &box)
        {
            if (!body.isClosed())
                return false;
            const Eigen::Vector3d c = X_MW * box.center;
            return !body.bvh().nodes()[0].outside(c) && insideClosedBody(body, c);
        }
    }  // namespace

    double boxGap(const WorldBox &a, const WorldBox &b)
    {
        const Eigen::Matrix3d R = a.axes.transpose() * b.axes;
        const Eigen::Matrix3d Q = R.cwiseAbs();
        const Eigen::Vector3d t = a.axes.transpose() * (b.center - a.center);
        double gap = -std::numeric_limits<double>::infinity();
        for (int i = 0; i < 3; ++i)
        {
            gap = std::max(gap, std::abs(t[i]) - a.half[i] - Q.row(i).dot(b.half));
            gap = std::max(gap, std::abs(t.dot(R.col(i))) - Q.col(i).dot(a.half) - b.half[i]);
        }
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
            {
                // The axis a_i x b_j, of length sqrt(1 - R_ij^2): skipped when nearly parallel (the others bound).
                const double n2 = 1.0 - R(i, j) * R(i, j);
                if (!(n2 > 1e-6))
                    continue;
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                const double ra = a.half[i1] * Q(i2, j) + a.half[i2] * Q(i1, j);
                const double rb = b.half[j1] * Q(i, j2) + b.half[j2] * Q(i, j1);
                const double projected = std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j));
                gap = std::max(gap, (projected - ra - rb) / std::sqrt(n2));
            }
        const double scale =
            a.center.cwiseAbs().maxCoeff() + b.center.cwiseAbs().maxCoeff() + a.half.sum() + b.half.sum();
        return gap - padFor(scale);
    }

    void RobotScene::buildVerdictBounds()
    {
        for (const BodyConstPtr &o : obstacles_)
        {
            ObstacleBounds bounds;
            const Eigen::AlignedBox3d b = o->surface().bounds();  // the vertices' exact extremes
            const Eigen::Vector3d pad = Eigen::Vector3d::Constant(
                padFor(b.min().cwiseAbs().maxCoeff() + b.max().cwiseAbs().maxCoeff() + b.sizes().sum()));
            bounds.aabb = Eigen::AlignedBox3d(b.min() - pad, b.max() + pad);
            bounds.boxes = !o->primitives().empty();
            for (const Primitive &p : o->primitives())
            {
                bounds.parts.push_back(primitiveBox(p));
                bounds.boxes = bounds.boxes && p.kind == Primitive::Kind::BOX;
            }
            if (o->primitives().empty())
                bounds.parts.push_back(placedNode(o->bvh().nodes()[0], Eigen::Isometry3d::Identity()));
            obstacleBounds_.push_back(std::move(bounds));
        }
        rigidClearance_.assign(selfPairs_.size(), 0.0);
        for (std::size_t p = 0; p < selfPairs_.size(); ++p)
            rigidClearance_[p] = rigidPairClearance(selfPairs_[p].first, selfPairs_[p].second);
        pairOffset_.assign(1, 0);
        for (const std::vector<std::size_t> &obstacles : linkObstacles_)
            pairOffset_.push_back(pairOffset_.back() + obstacles.size());
    }

    double RobotScene::rigidPairClearance(std::size_t a, std::size_t b) const
    {
        // Each link's pose relative to the first frame above it that a joint moves (or its root), through frames
        // fixed to their parents (computeFrames(): such a frame's pose is its parent's times its origin).
        auto hang = [&](std::size_t link, std::size_t &top)
        {
            Eigen::Isometry3d X = links_[link].X_FL;
            std::size_t f = links_[link].frame;
            while (!robot_->frameJoint(f).joint && robot_->frameMotion(f).kind == JointMotion::FIXED &&
                   robot_->frames()[f].parent != RobotModel::NONE)
            {
                X = robot_->frameJoint(f).origin * X;
                f = robot_->frames()[f].parent;
            }
            top = f;
            return X;
        };
        std::size_t topA = 0, topB = 0;
        const Eigen::Isometry3d X_TA = hang(a, topA), X_TB = hang(b, topB);
        if (topA != topB)
            return 0.0;  // a joint between them: their relative pose changes with the state
        DistanceRequest request;
        request.upperBound = RIGID_CLEARANCE_CAP;
        request.computeDepth = false;
        DistanceResult r;
        refineExact(*links_[a].body, *links_[b].body, X_TA.inverse() * X_TB, r, request);
        if (r.inCollision || !r.certified)
            return 0.0;
        // Less a pad far above the roundoff between this pose and the one placed at a state.
        const double scale = X_TA.translation().norm() + X_TB.translation().norm() +
                             links_[a].body->bvh().nodes()[0].radius + links_[b].body->bvh().nodes()[0].radius;
        const double clearance = std::min(r.distance, RIGID_CLEARANCE_CAP) - padFor(scale);
        return clearance > 0.0 ? clearance : 0.0;
    }

    void RobotScene::placeBounds(RobotWarmStart &warm) const
    {
        warm.boxes.resize(links_.size());
        warm.aabbs.resize(links_.size());
        warm.centers.resize(links_.size());
        warm.obstaclePairs.resize(pairOffset_.back());
        for (std::size_t i = 0; i < links_.size(); ++i)
        {
            const TriangleBvh::Node &root = links_[i].body->bvh().nodes()[0];
            warm.boxes[i] = placedNode(root, warm.poses[i]);
            warm.centers[i] = warm.boxes[i].center;
            // The tighter of the root box's and the root sphere's axis-aligned boxes (both hold the link).
            const Eigen::AlignedBox3d around = aroundBox(warm.boxes[i]);
            const Eigen::Vector3d r = Eigen::Vector3d::Constant(root.radius * (1.0 + 1e-9));
            warm.aabbs[i] = Eigen::AlignedBox3d(around.min().cwiseMax(warm.centers[i] - r),
                                                around.max().cwiseMin(warm.centers[i] + r));
        }
    }

    bool RobotScene::linkCollides(std::size_t i, RobotWarmStart &warm) const
    {
        const Body &link = *links_[i].body;
        const std::vector<std::size_t> &obstacles = linkObstacles_[i];
        Eigen::Isometry3d X_LW;
        bool inverted = false;
        for (std::size_t j = 0; j < obstacles.size(); ++j)
        {
            const ObstacleBounds &bounds = obstacleBounds_[obstacles[j]];
            if (!bounds.aabb.intersects(warm.aabbs[i]))
                continue;
            const Body &obstacle = *obstacles_[obstacles[j]];
            bool near = false;
            for (std::size_t k = 0; k < bounds.parts.size(); ++k)
            {
                if (boxGap(warm.boxes[i], bounds.parts[k]) > 0.0)
                    continue;
                near = true;
                if (!bounds.boxes)
                    break;  // answered by the exact layer below
                if (!inverted)
                {
                    X_LW = warm.poses[i].inverse();
                    inverted = true;
                }
                if (meshTouchesBox(link, X_LW, bounds.parts[k], obstacle.primitives()[k], warm.stack) ||
                    boxInsideBody(link, X_LW, bounds.parts[k]))
                    return true;
            }
            if (near && !bounds.boxes &&
                meshgap::inCollision(obstacle, link, warm.poses[i], &warm.obstaclePairs[pairOffset_[i] + j]))
                return true;
        }
        return false;
    }

    bool RobotScene::boundsApart(std::size_t i, double bound, const RobotWarmStart &warm) const
    {
        for (std::size_t o : linkObstacles_[i])
        {
            const ObstacleBounds &bounds = obstacleBounds_[o];
            const Eigen::Vector3d outside = (bounds.aabb.min() - warm.aabbs[i].max())
                                                .cwiseMax(warm.aabbs[i].min() - bounds.aabb.max())
                                                .cwiseMax(0.0);
            if (outside.norm() * (1.0 - 1e-12) > bound)
                continue;
            for (const WorldBox &part : bounds.parts)
                if (!(boxGap(warm.boxes[i], part) > bound))
                    return false;
        }
        return true;
    }

    bool RobotScene::selfVerdict(std::size_t p, RobotWarmStart &warm) const
    {
        if (rigidClearance_[p] > 0.0)
            return false;  // fixed to one another, proven apart once
        if (table_ && table_->apartAt(p, warm.state.data()))
            return false;  // in a cell of joint space where the pair is proven apart
        double gap;
        if (spheresApart(p, warm, 0.0, gap) && gap > 0.0)
            return false;
        const auto [a, b] = selfPairs_[p];
        if (boxGap(warm.boxes[a], warm.boxes[b]) > 0.0)
            return false;
        const Eigen::Isometry3d X_AB = warm.poses[a].inverse() * warm.poses[b];
        const ConvexHull *ha = links_[a].body->convexHull(), *hb = links_[b].body->convexHull();
        if (ha && hb && hullGap(*ha, *hb, X_AB, 0.0) > 0.0)
            return false;
        return meshgap::inCollision(*links_[a].body, *links_[b].body, X_AB, &warm.self[p]);
    }
}  // namespace meshgap
