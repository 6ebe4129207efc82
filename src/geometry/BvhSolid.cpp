#include "meshgap/geometry/BvhSolid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "BvhDetail.h"
#include "meshgap/geometry/PrimitiveDistance.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        /** \brief A node still to open and the lower bound of its distance to the solid. */
        struct OpenNode
        {
            std::uint32_t node;
            double bound;
        };

        /** \brief A box holding the solid, placed in the mesh's frame: centre, axes (columns), half extents, and a
            pad over the roundoff of the gaps measured along its axes. */
        struct SolidBox
        {
            Eigen::Vector3d center;
            Eigen::Matrix3d axes;
            Eigen::Vector3d half;
            double pad;
        };

        /** \brief Lower bound of the distance between anything in node \e n's box and the solid held by the ball
            (\e c, \e r) and the box \e B: the largest of the gap to the ball and the gaps between the projections
            of the two boxes onto each box's three axes (a projection onto a unit axis never lengthens a distance).
            The ball alone is loose about a flat solid (a table: its ball holds the space above it), the boxes
            alone about a round one. */
        double nodeBound(const TriangleBvh::Node &n, const Eigen::Vector3d &c, double r, const SolidBox &B)
        {
            const double sphere = (c - n.center).norm() - n.radius - r;
            const Eigen::Vector3d outside = (n.local(c).cwiseAbs() - n.half).cwiseMax(0.0);
            const Eigen::Vector3d offset = B.center - n.center;
            // The solid's box in the node's axes (C: its axes there), then the node's in the solid's.
            const Eigen::Matrix3d C = n.aligned ? B.axes : Eigen::Matrix3d(n.axes.transpose() * B.axes);
            const Eigen::Matrix3d absC = C.cwiseAbs();
            const Eigen::Vector3d T = n.local(B.center);
            const double alongNode = (T.cwiseAbs() - n.half - absC * B.half).maxCoeff();
            const double alongSolid =
                ((B.axes.transpose() * offset).cwiseAbs() - B.half - absC.transpose() * n.half).maxCoeff();
            const double boxes = std::max(alongNode, alongSolid) - B.pad;
            return std::max(std::max(sphere, outside.norm() - r) * (1.0 - 1e-12), boxes);
        }

        /** \brief The distance from the origin to the triangle (\e p, \e q, \e r) of the plane; 0 when the origin
            is inside or on it, or it is flat. */
        double originTriangleDistance2d(const Eigen::Vector2d &p, const Eigen::Vector2d &q, const Eigen::Vector2d &r)
        {
            const Eigen::Vector2d corner[3] = {p, q, r};
            double side[3], nearest = std::numeric_limits<double>::infinity();
            for (int i = 0; i < 3; ++i)
            {
                const Eigen::Vector2d &u = corner[i], e = corner[(i + 1) % 3] - u;
                side[i] = e.x() * -u.y() - e.y() * -u.x();
                const double ee = e.squaredNorm();
                const double t = ee > 0.0 ? std::clamp(-u.dot(e) / ee, 0.0, 1.0) : 0.0;
                nearest = std::min(nearest, (u + t * e).norm());
            }
            const bool inside = (side[0] >= 0.0 && side[1] >= 0.0 && side[2] >= 0.0) ||
                                (side[0] <= 0.0 && side[1] <= 0.0 && side[2] <= 0.0);
            return inside ? 0.0 : nearest;
        }

        /** \brief Lower bound of the distance between triangle (\e a, \e b, \e c) and the solid \e s held by the
            box \e B: the gap between their projections onto each of the box's axes; for a box, also onto the
            triangle's normal and the nine cross products of an edge of each (every separating axis of a box and a
            triangle: the bound is above 0 whenever they are apart by more than roundoff); for a solid about the
            z axis within radius x (a cylinder, capsule or cone), also the triangle's distance to that axis, less
            the radius (the distance from the z axis is that in the projection along it). */
        double triangleSolidBound(const Eigen::Vector3d &a, const Eigen::Vector3d &b, const Eigen::Vector3d &c,
                                  const SolidBox &B, const Primitive &s)
        {
            const Eigen::Vector3d pa = B.axes.transpose() * (a - B.center), pb = B.axes.transpose() * (b - B.center),
                                  pc = B.axes.transpose() * (c - B.center);
            const Eigen::Vector3d lo = pa.cwiseMin(pb).cwiseMin(pc), hi = pa.cwiseMax(pb).cwiseMax(pc);
            double gap = std::max((lo - B.half).maxCoeff(), (-hi - B.half).maxCoeff());
            if (gap > 0.0 || s.kind == Primitive::Kind::SPHERE)
                return gap - B.pad;
            if (s.kind != Primitive::Kind::BOX)
            {
                const double radial = originTriangleDistance2d(pa.head<2>(), pb.head<2>(), pc.head<2>()) - s.size.x();
                return std::max(gap, radial) - B.pad;
            }
            // In the box's frame: along a unit axis L the triangle spans [min p.L, max p.L], the box |L|.half.
            auto along = [&](const Eigen::Vector3d &L)
            {
                const double length = L.norm();
                if (!(length > 1e-9 * (pa - pb).norm()))
                    return -std::numeric_limits<double>::infinity();  // an edge along a box axis: already tested
                const double x = pa.dot(L), y = pb.dot(L), z = pc.dot(L), r = L.cwiseAbs().dot(B.half);
                return std::max(std::min(x, std::min(y, z)) - r, -r - std::max(x, std::max(y, z))) / length;
            };
            const Eigen::Vector3d edges[3] = {pb - pa, pc - pb, pa - pc};
            gap = std::max(gap, along(edges[0].cross(edges[1])));
            for (int i = 0; i < 3 && !(gap > 0.0); ++i)
                for (const Eigen::Vector3d &e : edges)
                    gap = std::max(gap, along(Eigen::Vector3d::Unit(i).cross(e)));
            return gap - B.pad;
        }

        /** \brief The traversal: depth first, nearer child first, pruning above the best distance so far. */
        class SolidTraversal
        {
        public:
            SolidTraversal(const TriangleBvh &mesh, const Primitive &s, const Eigen::Isometry3d &X,
                           double stopBelow, BvhSolidResult &result, std::size_t budget)
                : mesh_(mesh), s_(s), X_(X), stopBelow_(stopBelow), result_(result), budget_(budget)
            {
                double radius;
                Eigen::Vector3d centre;
                primitiveBoundingBall(s, centre, radius);
                centre_ = X * centre;
                radius_ = radius;
                const Eigen::Isometry3d placed = X * s.pose;
                box_.center = placed.translation();
                box_.axes = placed.linear();
                box_.half = primitiveBoxHalf(s);
                // The projected gaps' roundoff: a few ulps of the coordinates and extents they are made of.
                const TriangleBvh::Node &root = mesh.nodes().empty() ? TriangleBvh::Node() : mesh.nodes()[0];
                box_.pad = 1e-12 * (box_.center.norm() + box_.half.sum() + root.center.norm() + root.radius) + 1e-300;
            }

            /** \brief Test triangle \e t; true when it became the best. */
            bool test(std::uint32_t t)
            {
                const Mesh &m = mesh_.mesh();
                const Triangle &f = m.triangles[t];
                const Eigen::Vector3d &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
                Eigen::Vector3d on;
                // The ball holding the solid first: a triangle farther from its centre than the best plus the radius
                // cannot win.
                if (result_.found || std::isfinite(result_.distance))
                    if (triangleSolidBound(a, b, c, box_, s_) > result_.distance ||
                        pointTriangleDistance(centre_, a, b, c, on) * (1.0 - 1e-12) - radius_ > result_.distance)
                        return false;
                ++result_.triangleTests;
                const SolidGap g = primitiveTriangleGap(s_, X_, a, b, c, result_.distance);
                const bool wins = g.distance < result_.distance ||
                                  (result_.found && g.distance == result_.distance && t < result_.triangle);
                if (!wins)
                    return false;
                result_.distance = g.distance;
                result_.found = true;
                result_.triangle = t;
                result_.onSolid = g.onA;
                result_.onMesh = g.onB;
                return true;
            }

            void run()
            {
                std::vector<OpenNode> &stack = bvh::threadStack<OpenNode, 7>();
                const TriangleBvh::Node *nodes = mesh_.nodes().data();
                stack.push_back({0u, nodeBound(nodes[0], centre_, radius_, box_)});
                while (!stack.empty())
                {
                    const OpenNode o = stack.back();
                    stack.pop_back();
                    if (done())
                        return;
                    if (o.bound > result_.distance)
                        continue;
                    const TriangleBvh::Node &n = nodes[o.node];
                    if (n.isLeaf())
                    {
                        for (std::uint32_t i = n.first; i < n.first + n.count && !done(); ++i)
                            test(mesh_.order()[i]);
                        continue;
                    }
                    result_.boxTests += 2;
                    OpenNode l{n.first, nodeBound(nodes[n.first], centre_, radius_, box_)};
                    OpenNode r{n.first + 1, nodeBound(nodes[n.first + 1], centre_, radius_, box_)};
                    if (l.bound < r.bound)
                        std::swap(l, r);  // the nearer one on top
                    stack.push_back(l);
                    stack.push_back(r);
                }
            }

        private:
            /** \brief The early stop reached, or the budget spent (then exhausted). */
            bool done()
            {
                if (result_.found && result_.distance <= stopBelow_)
                    return true;
                if (budget_ > 0 && result_.boxTests + result_.triangleTests >= budget_)
                    return (result_.exhausted = true);
                return false;
            }

            const TriangleBvh &mesh_;
            const Primitive &s_;
            const Eigen::Isometry3d &X_;
            const double stopBelow_;
            BvhSolidResult &result_;
            const std::size_t budget_;
            Eigen::Vector3d centre_;
            double radius_{0.0};
            SolidBox box_;
        };
    }  // namespace

    void bvhSolidDistance(const TriangleBvh &mesh, const Primitive &s, const Eigen::Isometry3d &X_MS,
                          double upperBound, double stopBelow, BvhSolidResult &result, std::uint32_t seed,
                          std::size_t budget)
    {
        result.distance = upperBound;
        result.found = false;
        if (mesh.nodes().empty())
            return;
        SolidTraversal traversal(mesh, s, X_MS, stopBelow, result, budget);
        if (seed < mesh.mesh().triangles.size())
            traversal.test(seed);
        traversal.run();
    }

    bool bvhSolidCollide(const TriangleBvh &mesh, const Primitive &s, const Eigen::Isometry3d &X_MS,
                         std::uint32_t *hit)
    {
        // Only a touching triangle counts: the bound is the least positive number (a node or triangle proven apart
        // by any gap is pruned), the search ends at the first distance 0.
        BvhSolidResult r;
        bvhSolidDistance(mesh, s, X_MS, std::numeric_limits<double>::min(), 0.0, r);
        if (r.found && hit)
            *hit = r.triangle;
        return r.found;
    }
}  // namespace meshgap
