#include "meshgap/distance/PenetrationDepth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "meshgap/ThreadScratch.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/RecentInsideTests.h"
#include "meshgap/geometry/SurfaceGrid.h"
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
            std::uint32_t node{0};                             ///< node of the other body (the mover)
            std::uint32_t position{0};                         ///< its index in the mover's clusterOrder()
            std::uint32_t cluster{0};                          ///< the mover's cluster holding it
            std::uint32_t triangle{0};                         ///< host surface triangle nearest to it
            Eigen::Vector3d point{Eigen::Vector3d::Zero()};    ///< the node, host frame
            Eigen::Vector3d closest{Eigen::Vector3d::Zero()};  ///< nearest host surface point, host frame
        };

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

        /** \brief A cluster of the mover placed in the host's frame, that may hold a node inside the host. */
        struct Placed
        {
            const SurfaceGrid::Cell *cell;  ///< the host grid's cell holding the cluster's centre, or null
            std::uint32_t cluster;
        };

        /** \brief The search for the nodes of \e mover (placed in the host's frame by \e X_HM) inside the closed
            \e host that are deeper than the deepest so far. Branch and bound over the mover's node clusters: a
            cluster (centre c, radius r) whose centre is at distance d from the host's surface holds no node deeper
            than d + r. Clusters are visited in decreasing order of that bound as the grid gives it (the centre's cell's
            hi for d: reach()) until it falls to the deepest node so far; a cluster's centre is measured when its turn
            comes, and the cluster skipped when d + r (r - d, outside) does not beat the deepest; and when d > r no
            surface crosses the cluster's ball, so all its nodes are on the same side as c: one inside test for them
            all. Inside tests: localSide() first, a filter; what it calls outside is skipped,
            anything else is confirmed by insideClosedBody() (or by a grid cell or an earlier test whose ball free of
            surface holds the point: RecentInsideTests). So no outside node ever counts; where the filter is wrong
            (overlapping shells, mixed winding) an inside node may be skipped, which only lowers the estimate.

            What run() returns is a function of the pose and of nothing else: the first node, in the visiting order
            (clusters by decreasing reach(), ties by index; nodes in clusterOrder()), of those it accepts at the largest
            depth. Every node's depth and verdict are functions of the pose (bvhPointDistance() gives the same
            nearest triangle whatever bounds it is given, as long as the distance lies between them), and a bound
            prunes only with a pad above roundoff (pad()), so a node deeper than the deepest so far is never skipped.
            Hence starting from any depth below the answer's (a warm start's lower bound) gives the same node: it only
            skips nodes that cannot win. */
        class NodeSearch
        {
        public:
            /** \brief \e nearest: a triangle of the host per position of the mover's clusterOrder(), and
                \e clusterNearest one per cluster of the mover, or null (see PenetrationWarmStart::nearest). */
            NodeSearch(const Body &host, const Body &mover, const Eigen::Isometry3d &X_HM, bool hostIsA,
                       PenetrationEstimate &estimate, std::uint32_t *nearest, std::uint32_t *clusterNearest,
                       std::vector<Placed> &placed)
                : host_(host),
                  mover_(mover),
                  root_(host.bvh().nodes()[0]),
                  grid_(host.surfaceGrid()),
                  R_(X_HM.linear()),
                  t_(X_HM.translation()),
                  orient_(host.orientation()),
                  slack_(1e-12 * (root_.center.norm() + root_.half.norm()) + 1e-300),
                  hostIsA_(hostIsA),
                  estimate_(estimate),
                  nearest_(nearest),
                  clusterNearest_(clusterNearest),
                  placed_(placed),
                  sides_(slack_)
            {
            }

            /** \brief The mover's clusters that may hold a node inside the host deeper than \e floor (a depth in
                hand, or 0), placed (place() made once, before seedFromGrid() and run()): a descent of the mover's
                cluster tree that skips every ball lying beyond the host's box, wholly outside the host by its grid
                cell, or no deeper than \e floor by that cell (run() would skip its clusters: their nodes cannot win).
                Also notes the cluster whose centre the grid finds deepest inside. */
            void place(double floor)
            {
                placed_.clear();
                gridDeepest_ = 0.0;
                gridCluster_ = NONE;
                const std::vector<ClusterBall> &tree = mover_.clusterTree();
                // The maps from the mover's frame to the host's root box and to its grid, each folded into one.
                const Eigen::Matrix3d boxAxes =
                    root_.aligned ? Eigen::Matrix3d::Identity() : Eigen::Matrix3d(root_.axes.transpose());
                const Eigen::Matrix3d Rbox = boxAxes * R_, Rgrid = grid_.toGrid().linear() * R_;
                const Eigen::Vector3d tbox = boxAxes * (t_ - root_.center), tgrid = grid_.toGrid() * t_;
                const double outsideReach = grid_.outsideReach();
                // Entries before this one lie in a ball wholly inside the box: their nodes too, so no box test.
                std::uint32_t inBox = 0;
                for (std::uint32_t e = 0; e < tree.size();)
                {
                    const ClusterBall &ball = tree[e];
                    const double r = ball.radius;
                    if (e >= inBox)
                    {
                        // Beyond the box: skipped; wholly inside it: its subtree needs no box test.
                        const Eigen::Vector3d q = (Rbox * ball.center + tbox).cwiseAbs() - root_.half;
                        if (q.cwiseMax(0.0).squaredNorm() > r * r)
                        {
                            e = ball.skip;
                            continue;
                        }
                        if (q.maxCoeff() <= -r)
                            inBox = ball.skip;
                    }
                    // Wholly outside by its cell, or no deeper than floor (looked up for every cluster, and for a
                    // larger ball where a cell can say so: a radius below the largest lo of a cell outside, or below
                    // floor).
                    const bool leaf = ball.skip == e + 1, looked = leaf || pad(r) < outsideReach || r < floor;
                    const SurfaceGrid::Cell *cell = looked ? grid_.cellAt(Rgrid * ball.center + tgrid) : nullptr;
                    if ((cell && cell->side == SurfaceGrid::Side::OUTSIDE && pad(r) < cell->lo) ||
                        (looked && pad(reach(cell, r)) <= floor))
                    {
                        e = ball.skip;
                        continue;
                    }
                    if (leaf)
                    {
                        placed_.push_back({cell, ball.firstCluster});
                        if (cell && cell->side == SurfaceGrid::Side::INSIDE && cell->lo > gridDeepest_)
                        {
                            gridDeepest_ = cell->lo;
                            gridCluster_ = ball.firstCluster;
                        }
                    }
                    ++e;
                }
            }

            /** \brief Visit the nodes that may be deeper than \e best (its depth is a lower bound, found or not);
                \e best becomes the deepest found, if any is deeper. */
            void run(Deepest &best)
            {
                // The placed clusters by the grid's bound on how deep their nodes can lie (reach()), deepest first,
                // ties by cluster index: a fixed order (the answer is a function of the pose). A cluster's centre is
                // measured (candidate()) only when its turn comes and best is still below its reach.
                ThreadScratch<std::vector<Reach>> scratch;  // a warmed-up thread allocates nothing here
                std::vector<Reach> &order = scratch.get();
                order.clear();
                for (std::uint32_t i = 0; i < placed_.size(); ++i)
                {
                    const double bound = reach(placed_[i]);
                    if (pad(bound) > best.depth)
                        order.push_back({bound, placed_[i].cluster, i});
                }
                std::sort(order.begin(), order.end(),
                          [](const Reach &x, const Reach &y)
                          { return x.bound > y.bound || (x.bound == y.bound && x.cluster < y.cluster); });
                // The triangle nearest to the last centre measured (a deep one, as the next): it bounds the next
                // centre's point query.
                std::uint32_t hint = NONE;
                Candidate candidate;
                for (const Reach &next : order)
                {
                    if (pad(next.bound) <= best.depth)
                        break;  // neither this cluster nor any later one holds a deeper node
                    if ((mover_.clusters()[next.cluster].radius > 2.0 * grid_.cellSize() &&
                         !nodeCellsReach(next.cluster, best.depth)) ||
                        !this->candidate(placed_[next.placed], best.depth, candidate, hint))
                        continue;
                    hint = candidate.nearest.triangle;
                    if (pad(candidate.bound) <= best.depth)
                        continue;  // not this cluster, measured
                    if (candidate.oneSide && !centreInside(candidate))
                        continue;  // a ball wholly outside
                    visit(candidate, best);
                }
            }

            /** \brief The depth run() gives the node at \e position of the mover's clusterOrder(), in cluster \e k, if
                it would accept it (the same tests on the same points; the bounds change no result); 0 if it would
                not. A lower bound on what run() finds, then. */
            double depthOf(std::uint32_t k, std::uint32_t position)
            {
                Candidate c;
                Eigen::Vector3d p;
                BvhPointResult r;
                std::uint32_t hint = NONE;
                const Eigen::Vector3d centre = R_ * mover_.clusters()[k].center + t_;
                return !beyondBox(centre, mover_.clusters()[k].radius) &&
                               candidate({grid_.cell(centre), k}, 0.0, c, hint) &&
                               deeper(c, position, 0.0, p, r, hint)
                           ? r.distance
                           : 0.0;
            }

            /** \brief A depth some node reaches, as run() finds it (0 if none is found): the node whose grid cell
                is the deepest of those in the cluster whose centre lies deepest by the grid (after place()). A lower
                bound on what run() finds, then, found with one cluster's point queries; 0 without them when that
                node's cell says it lies no deeper than \e known (a depth already in hand). */
            double seedFromGrid(double known)
            {
                if (gridCluster_ == NONE)
                    return 0.0;
                const NodeCluster &cluster = mover_.clusters()[gridCluster_];
                double deepest = 0.0;
                std::uint32_t position = NONE;
                for (std::uint32_t k = cluster.begin; k < cluster.end; ++k)
                {
                    const SurfaceGrid::Cell *cell = grid_.cell(R_ * mover_.node(mover_.clusterOrder()[k]) + t_);
                    if (cell && cell->side == SurfaceGrid::Side::INSIDE && cell->lo >= deepest)
                    {
                        deepest = cell->lo;
                        position = k;
                    }
                }
                return position == NONE || !(deepest > known) ? 0.0 : depthOf(gridCluster_, position);
            }

        private:
            /** \brief \e x raised above the roundoff of the distances it bounds (relative, and absolute at the scale
                of the host's coordinates): a node whose computed depth exceeds a depth d has a padded bound above d. */
            double pad(double x) const { return x * (1.0 + 1e-9) + slack_; }

            /** \brief No triangle (a hint or a cache entry that names none). */
            static constexpr std::uint32_t NONE = UINT32_MAX;

            /** \brief The distance from \e p to host triangle \e t: the value the point query gives that triangle, so
                an upper bound on \e p's distance to the surface, exactly. */
            double toTriangle(const Eigen::Vector3d &p, std::uint32_t t)
            {
                const Mesh &m = host_.surface();
                const Triangle &f = m.triangles[t];
                Eigen::Vector3d on;
                ++estimate_.triangleTests;
                return pointTriangleDistance(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], on);
            }

            /** \brief A cluster of the mover that may hold nodes inside the host, at this pose. */
            struct Candidate
            {
                /** \brief No node of the cluster inside the host is deeper than this: dc + r with the centre inside;
                    r - dc with the centre outside (the segment from an inside node to the centre crosses the
                    surface, at least dc from the centre); negative when the ball is wholly outside. */
                double bound;
                double centreDistance;  ///< dc: from the centre to the host's surface
                std::uint32_t cluster;
                BvhPointResult nearest;  ///< of the centre
                Eigen::Vector3d centre;  ///< host frame
                bool oneSide;            ///< dc > r: the surface does not cross the ball
                /** \brief The local side test at the centre's nearest point (localSide()) says outside. It decides
                    which bound applies; the nodes' verdicts then include that bound (deeper()). */
                bool centreOutside;
                int inside{-1};  ///< the centre's inside test (insideClosedBody()), made when first needed: 0, 1
            };

            /** \brief A placed cluster (index \e placed in place()'s list) and the grid's bound on how deep a node of
                it can lie inside the host (reach()). */
            struct Reach
            {
                double bound;
                std::uint32_t cluster, placed;
            };

            /** \brief How deep, at most, a node of the placed cluster can lie inside the host, by its centre's grid
                cell alone: every point of the ball is within r of the centre, whose distance to the surface is at
                most the cell's hi; a centre outside the host (a cell wholly outside, at least lo from the surface, or
                beyond the grid, which lies beyond the host's box) leaves r - lo, or r, for a node inside (the segment
                from it to the centre crosses the surface). A function of the pose; a bound on the exact depth of
                every node inside, and so (padded) on every depth run() accepts. */
            double reach(const Placed &placed) const
            {
                return reach(placed.cell, mover_.clusters()[placed.cluster].radius);
            }

            /** \brief The same for a ball of radius \e r whose centre lies in \e cell (null: beyond the grid). */
            static double reach(const SurfaceGrid::Cell *cell, double r)
            {
                if (!cell)
                    return r;
                if (cell->side == SurfaceGrid::Side::OUTSIDE)
                    return r - cell->lo;
                return cell->hi + r;
            }

            /** \brief Whether a node of cluster \e k may lie inside the host deeper than \e floor by its own grid cell:
                no node is deeper than its cell's hi, and none inside in an outside cell or beyond the grid (beyond the
                host's box). A look-up per node, cheaper than measuring the centre, and tighter than the centre's cell
                for a large cluster. */
            bool nodeCellsReach(std::uint32_t k, double floor) const
            {
                const NodeCluster &cluster = mover_.clusters()[k];
                for (std::uint32_t i = cluster.begin; i < cluster.end; ++i)
                {
                    const SurfaceGrid::Cell *cell = grid_.cell(R_ * mover_.node(mover_.clusterOrder()[i]) + t_);
                    if (cell && cell->side != SurfaceGrid::Side::OUTSIDE && pad(cell->hi) > floor)
                        return true;
                }
                return false;
            }

            /** \brief The nodes of \e candidate's cluster deeper than \e best, in clusterOrder(): \e best becomes the
                first of the deepest. */
            void visit(Candidate &candidate, Deepest &best)
            {
                const NodeCluster &cluster = mover_.clusters()[candidate.cluster];
                std::uint32_t last = NONE;  // the triangle nearest to the last node measured: near the next one
                for (std::uint32_t k = cluster.begin; k < cluster.end; ++k)
                {
                    Eigen::Vector3d p;
                    BvhPointResult r;
                    if (!deeper(candidate, k, best.depth, p, r, last))
                        continue;
                    best.depth = r.distance;
                    best.found = true;
                    best.hostIsA = hostIsA_;
                    best.node = mover_.clusterOrder()[k];
                    best.position = k;
                    best.cluster = candidate.cluster;
                    best.triangle = r.triangle;
                    best.point = p;
                    best.closest = r.closest;
                }
            }

            /** \brief The centre's inside test, made once. */
            bool centreInside(Candidate &c)
            {
                if (c.inside < 0)
                    c.inside = sides_.inside(host_, c.centre, c.centreDistance, estimate_.insideTests) ? 1 : 0;
                return c.inside == 1;
            }

            /** \brief Whether the node at \e position of the mover's clusterOrder() (in cluster \e c) lies inside the
                host deeper than \e floor: then \e p is the node and \e r its nearest surface point. Every test that
                rules it out before the exact distance is a sound bound, so the verdict and \e r do not depend on
                \e floor, for a node deeper than it. \e hint: a host triangle near the node, or NONE; set to the
                triangle nearest to the node when its point query is made. */
            bool deeper(Candidate &c, std::uint32_t position, double floor, Eigen::Vector3d &p, BvhPointResult &r,
                        std::uint32_t &hint)
            {
                p = R_ * mover_.node(mover_.clusterOrder()[position]) + t_;
                if (root_.outside(p))
                    return false;
                // The node's cell bounds its distance to the surface, roundoff included.
                const SurfaceGrid::Cell *cell = grid_.cell(p);
                if (cell && pad(cell->hi) <= floor)
                    return false;
                const double dc = c.centreDistance, offset = (p - c.centre).norm();
                // Depth bounds, as the cluster's (Candidate::bound) with |p - c| for the radius (never above it, so
                // that the cluster's bound is never below its nodes').
                const double bound = dc + offset, beyond = std::min(offset, mover_.clusters()[c.cluster].radius) - dc;
                if (pad(c.centreOutside ? beyond : bound) <= floor)
                    return false;
                double upper = pad(bound);
                // The distance to one host triangle: the same value the search would give that triangle, so the
                // node's distance is at most that, exactly. False when that rules the node out.
                auto boundedBy = [&](std::uint32_t triangle)
                {
                    const double d = toTriangle(p, triangle);
                    upper = std::min(upper, pad(d));
                    return d > floor;
                };
                // The triangle nearest to this node at an earlier pose, then the one nearest to the node measured
                // before it (both usually tight), then the centre's nearest triangle.
                const std::uint32_t cached = nearest_ ? nearest_[position] : NONE;
                if (cached < host_.surface().triangles.size() && !boundedBy(cached))
                    return false;
                if (hint != NONE && hint != cached && !boundedBy(hint))
                    return false;
                if (!c.oneSide && c.nearest.triangle != hint && c.nearest.triangle != cached &&
                    !boundedBy(c.nearest.triangle))
                    return false;
                // The triangle nearest to the node's grid cell's centre, when none of those was it.
                if (cell && cell->triangle != hint && cell->triangle != cached &&
                    cell->triangle != c.nearest.triangle && !boundedBy(cell->triangle))
                    return false;
                ++estimate_.nodesTested;
                bvhPointDistance(host_.bvh(), p, upper, floor, r);
                if (!r.found)
                    bvhPointDistance(host_.bvh(), p, std::numeric_limits<double>::infinity(), floor, r);  // never
                estimate_.triangleTests += r.triangleTests;
                hint = r.triangle;
                if (nearest_)
                    nearest_[position] = r.triangle;
                if (!(r.distance > floor))
                    return false;
                if (c.centreOutside)
                    // Beyond the bound of an outside centre no node counts, whatever its own test says: the bound
                    // that prunes is then part of the verdict, so a pruned node is never one that would count.
                    return !(r.distance > pad(beyond)) && (!c.oneSide && inside(p, r, cell));
                if (c.oneSide)
                    return centreInside(c);  // the whole ball is on the centre's side
                // Within dc of an inside centre there is no surface between: inside too.
                return (pad(offset) < dc && centreInside(c)) || inside(p, r, cell);
            }

            /** \brief A ball (host frame) that lies wholly beyond the host's bounding box: it holds no node inside. */
            bool beyondBox(const Eigen::Vector3d &centre, double radius) const
            {
                return (root_.local(centre).cwiseAbs() - root_.half).cwiseMax(0.0).norm() > radius;
            }

            /** \brief The placed cluster \e placed as a candidate (false when none of its nodes can be deeper than
                \e floor, or inside). \e hint: a host triangle near the cluster, or NONE. */
            bool candidate(const Placed &placed, double floor, Candidate &out, std::uint32_t hint)
            {
                const std::uint32_t k = placed.cluster;
                const NodeCluster &cluster = mover_.clusters()[k];
                out.centre = R_ * cluster.center + t_;
                // The grid's bounds: no node deeper than the cell's hi + r, none inside when the ball lies in a cell
                // wholly outside more than r from the surface. Either way run() would skip the cluster.
                const SurfaceGrid::Cell *cell = placed.cell;
                if (cell && (pad(cell->hi + cluster.radius) <= floor ||
                             (cell->side == SurfaceGrid::Side::OUTSIDE && pad(cluster.radius) < cell->lo)))
                    return false;
                // A centre within floor - r of the surface: no node of the cluster is deeper than \e floor (whatever
                // side the centre is on), and run() would skip it; the point query may stop as soon as it knows.
                // Dropping such a cluster leaves the others' order as it was.
                const double stop = floor > 0.0 ? (floor - slack_) / (1.0 + 1e-9) - cluster.radius : -1.0;
                const double infinity = std::numeric_limits<double>::infinity();
                double upper = infinity;
                std::uint32_t *cached = clusterNearest_ ? clusterNearest_ + k : nullptr;
                // The triangle nearest to the centre at an earlier pose, and the hint: dc is at most their distances
                // (the values the query would give them), which may settle the cluster at once, and bounds the query.
                const std::uint32_t last = cached ? *cached : NONE, triangles = host_.surface().triangles.size();
                // and the triangle nearest to its grid cell's centre.
                const std::uint32_t near = cell ? cell->triangle : NONE;
                for (const std::uint32_t t :
                     {last, hint != last ? hint : NONE, near != last && near != hint ? near : NONE})
                {
                    if (t >= triangles)
                        continue;
                    const double d = toTriangle(out.centre, t);
                    if (pad(d + cluster.radius) <= floor)
                        return false;
                    upper = std::min(upper, pad(d));
                }
                bvhPointDistance(host_.bvh(), out.centre, upper, stop, out.nearest);
                estimate_.triangleTests += out.nearest.triangleTests;
                if (out.nearest.found && out.nearest.distance <= stop &&
                    pad(out.nearest.distance + cluster.radius) <= floor)
                {
                    if (cached)
                        *cached = out.nearest.triangle;
                    return false;
                }
                if (!out.nearest.found || out.nearest.distance <= stop)
                {
                    bvhPointDistance(host_.bvh(), out.centre, infinity, -1.0, out.nearest);  // roundoff: never seen
                    estimate_.triangleTests += out.nearest.triangleTests;
                }
                if (cached)
                    *cached = out.nearest.triangle;
                out.cluster = k;
                out.centreDistance = out.nearest.distance;
                out.oneSide = out.centreDistance > cluster.radius;
                out.centreOutside =
                    localSide(host_, out.centre, out.nearest.triangle, out.nearest.closest, orient_) > 0;
                // A centre in a cell the surface does not reach lies on that cell's side: insideClosedBody()'s
                // answer, known (the winding number is the same all over a region free of surface).
                const SurfaceGrid::Side side = cell ? cell->side : SurfaceGrid::Side::UNKNOWN;
                out.inside = side == SurfaceGrid::Side::INSIDE ? 1 : side == SurfaceGrid::Side::OUTSIDE ? 0 : -1;
                out.bound =
                    out.centreOutside ? cluster.radius - out.centreDistance : out.centreDistance + cluster.radius;
                return true;
            }

            /** \brief Whether the point \e p, whose nearest surface point is \e nearest, in grid cell \e cell (or
                null) counts as inside: not if localSide() says outside, else by insideClosedBody(), whose answer a
                cell the surface does not reach already holds. */
            bool inside(const Eigen::Vector3d &p, const BvhPointResult &nearest, const SurfaceGrid::Cell *cell)
            {
                if (localSide(host_, p, nearest.triangle, nearest.closest, orient_) > 0)
                    return false;
                if (cell && (cell->side == SurfaceGrid::Side::INSIDE || cell->side == SurfaceGrid::Side::OUTSIDE))
                    return cell->side == SurfaceGrid::Side::INSIDE;
                return sides_.inside(host_, p, nearest.distance, estimate_.insideTests);
            }

            const Body &host_, &mover_;
            const TriangleBvh::Node &root_;
            const SurfaceGrid &grid_;
            const Eigen::Matrix3d R_;
            const Eigen::Vector3d t_;
            const double orient_, slack_;
            const bool hostIsA_;
            PenetrationEstimate &estimate_;
            std::uint32_t *const nearest_, *const clusterNearest_;
            std::vector<Placed> &placed_;      ///< place()'s clusters
            double gridDeepest_{0.0};          ///< the largest lo of a grid cell inside holding a placed centre
            std::uint32_t gridCluster_{NONE};  ///< that centre's cluster, or NONE
            RecentInsideTests<8> sides_;       ///< the inside tests made, the last few kept
        };

        /** \brief A surface triangle holding node \e i of \e body. */
        std::uint32_t triangleOfNode(const Body &body, std::uint32_t i)
        {
            return body.beginNodeTriangles(i) != body.endNodeTriangles(i) ? *body.beginNodeTriangles(i) : 0u;
        }

        /** \brief \e estimate from the deepest node found: its depth, and as witnesses the node and its nearest
            point on the other surface (points of A and of B, in A's frame). */
        void setDeepest(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const Deepest &best,
                        PenetrationEstimate &estimate)
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
        }

        /** \brief \e estimate when no node lies inside the other body: depth 0, and as witness the touching pair
            bvhCollide() meets first (a fixed traversal order: a function of the pose). */
        void setTouching(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, PenetrationEstimate &estimate)
        {
            estimate.kind = a.isClosed() || b.isClosed() ? Penetration::NO_NODE_INSIDE : Penetration::OPEN_BODIES;
            std::uint32_t ta = 0, tb = 0;
            if (!bvhCollide(a.bvh(), b.bvh(), X_AB, &ta, &tb))
                return;
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

        /** \brief Just below the depth of the node \e warm names (a node of \e mover, searched for by \e search) at
            this pose, found as the search would find it; 0 when \e warm names no node of \e mover or it is not
            inside. */
        double warmSeed(const PenetrationWarmStart &warm, const Body &mover, NodeSearch &search)
        {
            if (warm.cluster >= mover.clusters().size() || warm.position < mover.clusters()[warm.cluster].begin ||
                warm.position >= mover.clusters()[warm.cluster].end)
                return 0.0;
            const double seed = search.depthOf(warm.cluster, warm.position);
            return seed > 0.0 ? std::nextafter(seed, 0.0) : 0.0;
        }
    }  // namespace

    PenetrationEstimate penetrationDepth(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB,
                                         PenetrationWarmStart *warm)
    {
        PenetrationEstimate estimate;
        const bool closedA = a.isClosed() && !a.surface().triangles.empty(),
                   closedB = b.isClosed() && !b.surface().triangles.empty();
        const Eigen::Isometry3d X_BA = X_AB.inverse();
        // Per node and per cluster centre, the host triangle last found nearest to it: B's nodes (inside A), A's,
        // then B's clusters, A's.
        std::uint32_t *nearest = nullptr;
        const std::size_t nodes = std::size_t(a.numNodes()) + b.numNodes(),
                          slots = nodes + a.clusters().size() + b.clusters().size();
        if (warm)
        {
            if (warm->nearest.size() != slots)
                warm->nearest.assign(slots, UINT32_MAX);  // first use only
            nearest = warm->nearest.data();
        }
        auto at = [nearest](std::size_t offset) { return nearest ? nearest + offset : nullptr; };
        // The search in each closed host (B's nodes inside A, A's inside B), its clusters placed once.
        ThreadScratch<std::array<std::vector<Placed>, 2>> scratch;  // a warmed-up thread allocates nothing here
        std::optional<NodeSearch> searches[2];
        if (closedA)
            searches[0].emplace(a, b, X_AB, true, estimate, at(0), at(nodes), scratch.get()[0]);
        if (closedB)
            searches[1].emplace(b, a, X_BA, false, estimate, at(b.numNodes()), at(nodes + b.clusters().size()),
                                scratch.get()[1]);
        // A lower bound to start from, just below a depth found exactly as the search would find it (NodeSearch says
        // why the answer stays the cold one): the last deepest node's depth at this pose, and the deepest node the
        // grids point to, where its cell says it may lie deeper still (along a run of poses the carried node is as
        // deep, and costs less; on poses far apart the grid's is the deeper). Each search places its clusters with
        // the bound in hand, so that the second skips what the first's seed rules out.
        Deepest best;
        if (warm && warm->valid && searches[warm->hostIsA ? 0 : 1])
            best.depth = warmSeed(*warm, warm->hostIsA ? b : a, *searches[warm->hostIsA ? 0 : 1]);
        for (std::optional<NodeSearch> &search : searches)
            if (search)
            {
                search->place(best.depth);
                const double seed = search->seedFromGrid(best.depth);
                if (seed > 0.0)
                    best.depth = std::max(best.depth, std::nextafter(seed, 0.0));
            }
        const bool seeded = best.depth > 0.0;
        for (std::optional<NodeSearch> &search : searches)
            if (search)
                search->run(best);
        if (seeded && !best.found)
        {
            // Cannot happen (the seed itself is found); if it did, the cold search gives the answer.
            best = Deepest();
            for (std::optional<NodeSearch> &search : searches)
                if (search)
                {
                    search->place(0.0);
                    search->run(best);
                }
        }
        if (warm)
        {
            warm->valid = best.found;
            warm->hostIsA = best.hostIsA;
            warm->cluster = best.cluster;
            warm->position = best.position;
        }

        if (best.found)
            setDeepest(a, b, X_AB, best, estimate);
        else
            setTouching(a, b, X_AB, estimate);
        return estimate;
    }

    void setPenetration(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result,
                        PenetrationWarmStart *warm)
    {
        const PenetrationEstimate e = penetrationDepth(a, b, X_AB, warm);
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
