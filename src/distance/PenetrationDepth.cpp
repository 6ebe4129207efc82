#include "meshgap/distance/PenetrationDepth.h"

#include <algorithm>
#include <cmath>
#include <vector>
#include <limits>

#include "meshgap/ThreadScratch.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        /** \brief The deepest node found so far, in the frame of the body it lies inside (the host). */
        struct Deepest
        {
            double depth{0.0};
            bool found{false};
            bool hostIsA{false};
            std::uint32_t node{0};                              ///< node of the other body (the mover)
            std::uint32_t triangle{0};                          ///< host surface triangle nearest to it
            Eigen::Vector3d point{Eigen::Vector3d::Zero()};    ///< the node, host frame
            Eigen::Vector3d closest{Eigen::Vector3d::Zero()};  ///< nearest host surface point, host frame
        };

        /** \brief +1 when \e body's triangles wind outward (positive signed volume), -1 when inward. */
        double orientation(const Body &body)
        {
            const Mesh &m = body.surface();
            double volume = 0.0;
            for (const Triangle &f : m.triangles)
                volume += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]]));
            return volume >= 0.0 ? 1.0 : -1.0;
        }

        /** \brief Which side of \e host's surface \e p is on, judged at its nearest surface point \e q (on triangle
            \e t): the sign of (p - q) against the angle-weighted pseudonormal of the feature q lies on (face, edge or
            corner; Baerentzen and Aanaes, 2005), times \e orient. -1 inside, +1 outside, 0 too close to call. Exact
            for a closed, consistently wound surface without self-intersections; a filter only (see deepestNodeIn()). */
        int localSide(const Body &host, const Eigen::Vector3d &p, std::uint32_t t, const Eigen::Vector3d &q,
                      double orient)
        {
            const Mesh &m = host.surface();
            const Triangle &f = m.triangles[t];
            const Eigen::Vector3d &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
            // Barycentric coordinates of q.
            const Eigen::Vector3d e0 = b - a, e1 = c - a, e2 = q - a;
            const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = e2.dot(e0), d21 = e2.dot(e1);
            const double den = d00 * d11 - d01 * d01;
            if (!(den > 0.0))
                return 0;
            const double wb = (d11 * d20 - d01 * d21) / den, wc = (d00 * d21 - d01 * d20) / den;
            const double w[3] = {1.0 - wb - wc, wb, wc};
            constexpr double tol = 1e-9;
            int zeros = 0, lone = -1, corner = -1;
            for (int k = 0; k < 3; ++k)
            {
                if (w[k] <= tol)
                {
                    ++zeros;
                    lone = k;  // with one zero: the corner opposite the edge q is on
                }
                else
                    corner = k;  // with two zeros: the corner q is at
            }
            const std::vector<Eigen::Vector3d> &normals = host.bvh().normals();
            Eigen::Vector3d N = normals[t];
            if (zeros == 1)
            {
                // On the edge opposite corner lone: add the normal of the other triangle holding that edge.
                const std::uint32_t i = f[(lone + 1) % 3], j = f[(lone + 2) % 3];
                for (const std::uint32_t *n = host.beginTriangleNeighbours(t); n != host.endTriangleNeighbours(t); ++n)
                {
                    const Triangle &g = m.triangles[*n];
                    const bool hasI = g[0] == i || g[1] == i || g[2] == i, hasJ = g[0] == j || g[1] == j || g[2] == j;
                    if (hasI && hasJ)
                        N += normals[*n];
                }
            }
            else if (zeros >= 2)
            {
                // At a corner v: the normals of every triangle around it, weighted by their angle at v.
                const std::uint32_t v = f[corner];
                auto angleAt = [&m](const Triangle &g, std::uint32_t vertex)
                {
                    const int k = g[0] == vertex ? 0 : g[1] == vertex ? 1 : 2;
                    const Eigen::Vector3d x = m.vertices[g[(k + 1) % 3]] - m.vertices[vertex],
                                          y = m.vertices[g[(k + 2) % 3]] - m.vertices[vertex];
                    return std::atan2(x.cross(y).norm(), x.dot(y));
                };
                N = angleAt(f, v) * normals[t];
                for (const std::uint32_t *n = host.beginTriangleNeighbours(t); n != host.endTriangleNeighbours(t); ++n)
                {
                    const Triangle &g = m.triangles[*n];
                    if (g[0] == v || g[1] == v || g[2] == v)
                        N += angleAt(g, v) * normals[*n];
                }
            }
            const Eigen::Vector3d away = p - q;
            const double side = away.dot(N);
            if (std::abs(side) <= 1e-9 * away.norm() * N.norm())
                return 0;
            return side * orient < 0.0 ? -1 : 1;
        }

        /** \brief Nodes of \e mover (placed in the host's frame by \e X_HM) inside the closed \e host, deeper than
            \e best. Branch and bound over the mover's node clusters: a cluster (centre c, radius r) whose centre is
            at distance d from the host's surface holds no node deeper than d + r, so clusters are visited in
            decreasing order of that bound until it falls to the deepest node so far; and when d > r no surface
            crosses the cluster's ball, so all its nodes are on the same side as c: one inside test for them all.
            Inside tests: localSide() first, a filter; what it calls outside is skipped, anything else is confirmed
            by insideClosedBody(). So no outside node ever counts; where the filter is wrong (overlapping shells,
            mixed winding) an inside node may be skipped, which only lowers the estimate. */
        void deepestNodeIn(const Body &host, const Body &mover, const Eigen::Isometry3d &X_HM, bool hostIsA,
                           Deepest &best, PenetrationEstimate &estimate)
        {
            const TriangleBvh::Node &root = host.bvh().nodes()[0];
            const Eigen::Matrix3d R = X_HM.linear();
            const Eigen::Vector3d t = X_HM.translation();
            const double infinity = std::numeric_limits<double>::infinity();
            const double orient = orientation(host);
            auto inside = [&](const Eigen::Vector3d &p, const BvhPointResult &nearest)
            {
                if (localSide(host, p, nearest.triangle, nearest.closest, orient) > 0)
                    return false;
                ++estimate.insideTests;
                return insideClosedBody(host, p);
            };
            struct Candidate
            {
                double bound, centreDistance;
                std::uint32_t cluster;
                BvhPointResult nearest;  ///< of the centre
            };
            ThreadScratch<std::vector<Candidate>> scratch;  // a warmed-up thread allocates nothing here
            std::vector<Candidate> &candidates = scratch.get();
            candidates.clear();
            for (std::uint32_t k = 0; k < mover.clusters().size(); ++k)
            {
                const NodeCluster &cluster = mover.clusters()[k];
                const Eigen::Vector3d c = R * cluster.center + t;
                if ((root.local(c).cwiseAbs() - root.half).cwiseMax(0.0).norm() > cluster.radius)
                    continue;  // no node of it in the host's box
                BvhPointResult r;
                bvhPointDistance(host.bvh(), c, infinity, -1.0, r);
                estimate.triangleTests += r.triangleTests;
                candidates.push_back({r.distance + cluster.radius, r.distance, k, r});
            }
            // Largest bound first; ties by cluster index (a fixed order: the answer is a function of the pose).
            std::sort(candidates.begin(), candidates.end(), [](const Candidate &x, const Candidate &y)
                      { return x.bound > y.bound || (x.bound == y.bound && x.cluster < y.cluster); });
            for (const Candidate &candidate : candidates)
            {
                if (candidate.bound <= best.depth)
                    break;  // neither this cluster nor any later one holds a deeper node
                const NodeCluster &cluster = mover.clusters()[candidate.cluster];
                // The ball (centre c, radius < distance to the surface) lies wholly inside or wholly outside.
                const bool oneSide = candidate.centreDistance > cluster.radius;
                const Eigen::Vector3d centre = R * cluster.center + t;
                if (oneSide && !inside(centre, candidate.nearest))
                    continue;
                for (std::uint32_t k = cluster.begin; k < cluster.end; ++k)
                {
                    const std::uint32_t i = mover.clusterOrder()[k];
                    const Eigen::Vector3d p = R * mover.node(i) + t;
                    if (root.outside(p))
                        continue;
                    // Nearer to the surface than the deepest so far: cannot be the deepest, inside or not. The
                    // centre's nearest point is at most |p - c| farther from p: a bound that may settle that at once,
                    // and otherwise prunes the search (padded so that the nearest triangle is found below it).
                    const double bound = candidate.centreDistance + (p - centre).norm();
                    if (bound <= best.depth)
                        continue;
                    ++estimate.nodesTested;
                    BvhPointResult r;
                    bvhPointDistance(host.bvh(), p, bound * (1.0 + 1e-9) + 1e-300, best.depth, r);
                    if (!r.found)
                        bvhPointDistance(host.bvh(), p, infinity, best.depth, r);  // roundoff; never seen
                    estimate.triangleTests += r.triangleTests;
                    if (!(r.distance > best.depth))
                        continue;
                    if (!oneSide && !inside(p, r))
                        continue;
                    best.depth = r.distance;
                    best.found = true;
                    best.hostIsA = hostIsA;
                    best.node = i;
                    best.triangle = r.triangle;
                    best.point = p;
                    best.closest = r.closest;
                }
            }
        }

        /** \brief A surface triangle holding node \e i of \e body. */
        std::uint32_t triangleOfNode(const Body &body, std::uint32_t i)
        {
            return body.beginNodeTriangles(i) != body.endNodeTriangles(i) ? *body.beginNodeTriangles(i) : 0u;
        }
    }  // namespace

    bool insideClosedBody(const Body &body, const Eigen::Vector3d &p)
    {
        if (!body.isClosed())
            return false;
        const TriangleBvh::Node &root = body.bvh().nodes()[0];
        if (root.outside(p))
            return false;  // outside the bounding box
        // Directions off every axis and diagonal (OMPL.app's walls are axis-aligned: a ray along an axis would graze
        // their edges).
        static const Eigen::Vector3d directions[] = {Eigen::Vector3d(0.5773, 0.6532, 0.4898),
                                                     Eigen::Vector3d(-0.3217, 0.8469, -0.4234),
                                                     Eigen::Vector3d(0.7071, -0.2764, -0.6508)};
        for (const Eigen::Vector3d &d : directions)
        {
            int winding = 0;
            if (bvhRayWinding(body.bvh(), p, d, winding))
                return winding != 0;
        }
        return containsPoint(body, p);
    }

    PenetrationEstimate penetrationDepth(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        PenetrationEstimate estimate;
        Deepest best;
        if (a.isClosed() && !a.surface().triangles.empty())
            deepestNodeIn(a, b, X_AB, true, best, estimate);
        if (b.isClosed() && !b.surface().triangles.empty())
            deepestNodeIn(b, a, X_AB.inverse(), false, best, estimate);

        if (best.found)
        {
            estimate.depth = best.depth;
            estimate.kind = Penetration::DEEPEST_NODE;
            estimate.witnessFound = true;
            if (best.hostIsA)
            {
                estimate.onA = best.closest;
                estimate.onB = best.point;
                estimate.triangleA = best.triangle;
                estimate.triangleB = triangleOfNode(b, best.node);
            }
            else
            {
                estimate.onA = a.node(best.node);
                estimate.onB = X_AB * best.closest;
                estimate.triangleA = triangleOfNode(a, best.node);
                estimate.triangleB = best.triangle;
            }
            return estimate;
        }
        estimate.kind = a.isClosed() || b.isClosed() ? Penetration::NO_NODE_INSIDE : Penetration::OPEN_BODIES;
        // Witness: the touching pair bvhCollide() meets first (a fixed traversal order: a function of the pose).
        std::uint32_t ta = 0, tb = 0;
        if (bvhCollide(a.bvh(), b.bvh(), X_AB, &ta, &tb))
        {
            const Mesh &sa = a.surface(), &sb = b.surface();
            const Triangle &fa = sa.triangles[ta], &fb = sb.triangles[tb];
            const Eigen::Matrix3d R = X_AB.linear();
            const Eigen::Vector3d t = X_AB.translation();
            triangleDistance(sa.vertices[fa[0]], sa.vertices[fa[1]], sa.vertices[fa[2]], R * sb.vertices[fb[0]] + t,
                             R * sb.vertices[fb[1]] + t, R * sb.vertices[fb[2]] + t, estimate.onA, estimate.onB);
            estimate.triangleA = ta;
            estimate.triangleB = tb;
            estimate.witnessFound = true;
            ++estimate.triangleTests;
        }
        return estimate;
    }

    void setPenetration(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result)
    {
        const PenetrationEstimate e = penetrationDepth(a, b, X_AB);
        result.inCollision = true;
        result.penetrationDepth = e.depth;
        result.penetration = e.kind;
        result.distance = e.depth > 0.0 ? -e.depth : CONTACT_DISTANCE;
        if (e.witnessFound)
        {
            result.onA = e.onA;
            result.onB = e.onB;
            result.triangleA = e.triangleA;
            result.triangleB = e.triangleB;
        }
        result.triangleTests += e.triangleTests;
    }
}  // namespace meshgap
