// A conservative convex outer bound of a point set: qhull's hull vertices, and a margin that holds every point,
// certified by our own arithmetic (ConvexHull.h).

#include "meshgap/geometry/ConvexHull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <utility>

extern "C"
{
#include <libqhull_r/qhull_ra.h>
}

#include "SolidCore.h"
#include "meshgap/geometry/SolidAngle.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        using Triangle3 = std::array<std::uint32_t, 3>;

        /** \brief What qhull's triangulated hull gave: its triangles (indices of the points given, oriented by
            qhull) and each one's outward unit normal. */
        struct Hulled
        {
            std::vector<Triangle3> triangles;
            std::vector<Eigen::Vector3d> normals;
        };

        /** \brief Run qhull ("Qt": triangulated output) on \e points; false on any qhull error (a flat or tiny
            set, too few points), whose message goes to a memory stream that is dropped. */
        bool runQhull(const std::vector<Eigen::Vector3d> &points, Hulled &out)
        {
            if (points.size() < 4 || points.size() > static_cast<std::size_t>(INT32_MAX / 3))
                return false;
            std::vector<coordT> coords(3 * points.size());
            for (std::size_t i = 0; i < points.size(); ++i)
                for (int k = 0; k < 3; ++k)
                    coords[3 * i + k] = points[i][k];
            char *message = nullptr;
            std::size_t length = 0;
            FILE *errors = open_memstream(&message, &length);
            if (errors == nullptr)
                return false;
            qhT state;
            qhT *qh = &state;
            qh_zero(qh, errors);
            char options[] = "qhull Qt";
            bool ok = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr,
                                   errors) == 0;
            if (ok)
            {
                facetT *facet;
                FORALLfacets
                {
                    if (!facet->simplicial || facet->normal == nullptr || qh_setsize(qh, facet->vertices) != 3)
                    {
                        ok = false;
                        break;
                    }
                    // As qh_facet3vertex() orders a simplicial facet's vertices (qh_ORIENTclock is 0).
                    auto id = [&](int k)
                    {
                        const vertexT *vertex = SETelemt_(facet->vertices, k, vertexT);
                        return static_cast<std::uint32_t>(qh_pointid(qh, vertex->point));
                    };
                    const bool top = facet->toporient;
                    out.triangles.push_back({id(top ? 0 : 1), id(top ? 1 : 0), id(2)});
                    out.normals.emplace_back(facet->normal[0], facet->normal[1], facet->normal[2]);
                }
            }
            qh_freeqhull(qh, !qh_ALL);
            int longLeft = 0, totalLeft = 0;
            qh_memfreeshort(qh, &longLeft, &totalLeft);
            std::fclose(errors);
            std::free(message);
            return ok && out.triangles.size() >= 4;
        }

        /** \brief The points the triangles of \e hulled use, in increasing order. */
        std::vector<std::uint32_t> vertexIds(const Hulled &hulled)
        {
            std::vector<std::uint32_t> ids;
            for (const Triangle3 &t : hulled.triangles)
                ids.insert(ids.end(), t.begin(), t.end());
            std::sort(ids.begin(), ids.end());
            ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
            return ids;
        }

        /** \brief Replace the hull of \e ids (indices of \e points) by the hull of the vertices extreme along
            \e directions directions spread over the sphere (a Fibonacci lattice), fewer vertices; the points it
            leaves out are then covered by the margin, which build() computes over every point. */
        bool coarsen(const std::vector<Eigen::Vector3d> &points, std::vector<std::uint32_t> &ids, Hulled &hulled,
                     int directions)
        {
            std::vector<std::uint32_t> kept;
            const double golden = M_PI * (3.0 - std::sqrt(5.0));
            for (int k = 0; k < directions; ++k)
            {
                const double z = 1.0 - (2.0 * k + 1.0) / directions, r = std::sqrt(1.0 - z * z);
                const Eigen::Vector3d d(r * std::cos(golden * k), r * std::sin(golden * k), z);
                std::uint32_t best = ids[0];
                for (std::uint32_t i : ids)
                    if (d.dot(points[i]) > d.dot(points[best]))
                        best = i;
                kept.push_back(best);
            }
            std::sort(kept.begin(), kept.end());
            kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
            std::vector<Eigen::Vector3d> subset;
            for (std::uint32_t i : kept)
                subset.push_back(points[i]);
            Hulled coarse;
            if (!runQhull(subset, coarse))
                return false;
            for (Triangle3 &t : coarse.triangles)
                for (std::uint32_t &i : t)
                    i = kept[i];
            hulled = std::move(coarse);
            ids = vertexIds(hulled);
            return true;
        }

        /** \brief Every directed edge of \e triangles once, and its reverse once: a closed surface, oriented alike. */
        bool closedAndOriented(const std::vector<Triangle3> &triangles)
        {
            std::vector<std::pair<std::uint32_t, std::uint32_t>> edges, reversed;
            edges.reserve(3 * triangles.size());
            reversed.reserve(3 * triangles.size());
            for (const Triangle3 &t : triangles)
                for (int k = 0; k < 3; ++k)
                {
                    edges.emplace_back(t[k], t[(k + 1) % 3]);
                    reversed.emplace_back(t[(k + 1) % 3], t[k]);
                }
            std::sort(edges.begin(), edges.end());
            std::sort(reversed.begin(), reversed.end());
            return std::adjacent_find(edges.begin(), edges.end()) == edges.end() && edges == reversed;
        }


        /** \brief The triangles' normals and the level each triangle's vertices are all above, less the dot
            products' error bound: fl(n . p) < below[t] proves n . p < n . v for every vertex v of t. */
        struct Planes
        {
            std::vector<double> nx, ny, nz, below;

            Planes(const std::vector<Eigen::Vector3d> &points, const Hulled &hull, double tolerance)
            {
                for (std::size_t t = 0; t < hull.triangles.size(); ++t)
                {
                    const Eigen::Vector3d &n = hull.normals[t];
                    double least = std::numeric_limits<double>::infinity();
                    for (std::uint32_t v : hull.triangles[t])
                        least = std::min(least, n.dot(points[v]));
                    nx.push_back(n.x());
                    ny.push_back(n.y());
                    nz.push_back(n.z());
                    below.push_back(least - tolerance);
                }
            }

            /** \brief The largest of fl(n . p) - below over the triangles: negative proves \e p below them all. */
            double excess(const Eigen::Vector3d &p) const
            {
                double most = -std::numeric_limits<double>::infinity();
                const std::size_t n = below.size();
                for (std::size_t t = 0; t < n; ++t)
                    most = std::max(most, nx[t] * p.x() + ny[t] * p.y() + nz[t] * p.z() - below[t]);
                return most;
            }
        };

        /** \brief An upper bound of the distance from \e p to conv(hull vertices): 0 when \e p is proven below
            every triangle, else the least distance to a triangle it is not proven below. */
        double distanceToHull(const std::vector<Eigen::Vector3d> &points, const Hulled &hull, const Planes &planes,
                              const Eigen::Vector3d &p)
        {
            if (planes.excess(p) < 0.0)
                return 0.0;
            double least = std::numeric_limits<double>::infinity();
            for (std::size_t t = 0; t < hull.triangles.size(); ++t)
                if (planes.nx[t] * p.x() + planes.ny[t] * p.y() + planes.nz[t] * p.z() >= planes.below[t])
                {
                    const Triangle3 &f = hull.triangles[t];
                    Eigen::Vector3d on;
                    least = std::min(least, pointTriangleDistance(p, points[f[0]], points[f[1]], points[f[2]], on));
                }
            return least;
        }
    }  // namespace

    std::shared_ptr<const ConvexHull> ConvexHull::build(const std::vector<Eigen::Vector3d> &points,
                                                        std::size_t maxVertices, int directions)
    {
        double reach = 0.0;
        for (const Eigen::Vector3d &p : points)
        {
            if (!p.allFinite())
                return nullptr;
            reach = std::max(reach, p.norm());
        }
        Hulled hulled;
        if (!runQhull(points, hulled))
            return nullptr;
        std::vector<std::uint32_t> ids = vertexIds(hulled);
        if (ids.size() > maxVertices && !coarsen(points, ids, hulled, directions))
            return nullptr;
        if (!closedAndOriented(hulled.triangles))
            return nullptr;
        Eigen::Vector3d center = Eigen::Vector3d::Zero();
        for (std::uint32_t i : ids)
            center += points[i];
        center /= static_cast<double>(ids.size());

        // |fl(n . x) - n . x| <= gamma_3 sum |n_i x_i| <= 3.4e-16 |x| for a unit n; 1e-14 of the reach covers both
        // dot products of a comparison many times over.
        const Planes planes(points, hulled, 1e-14 * reach + 1e-300);
        if (!(planes.excess(center) < 0.0))
            return nullptr;  // the centre is not proven inside every triangle (a sliver of a hull)
        double angles = 0.0;
        for (const Triangle3 &t : hulled.triangles)
            angles += solidAngle(points[t[0]] - center, points[t[1]] - center, points[t[2]] - center);
        if (!(std::abs(angles) > 2.0 * M_PI))
            return nullptr;  // winding number 0 about the centre

        std::vector<bool> isVertex(points.size(), false);
        for (std::uint32_t i : ids)
            isVertex[i] = true;
        double epsilon = 0.0;
        for (std::size_t i = 0; i < points.size(); ++i)
            if (!isVertex[i])
                epsilon = std::max(epsilon, distanceToHull(points, hulled, planes, points[i]));
        if (!std::isfinite(epsilon))
            return nullptr;

        std::shared_ptr<ConvexHull> hull(new ConvexHull());
        std::vector<std::uint32_t> index(points.size(), 0);
        for (std::uint32_t i : ids)
        {
            index[i] = static_cast<std::uint32_t>(hull->vertices_.size());
            hull->vertices_.push_back(points[i]);
            hull->xs_.push_back(points[i].x());
            hull->ys_.push_back(points[i].y());
            hull->zs_.push_back(points[i].z());
            hull->reach_ = std::max(hull->reach_, points[i].norm());
        }
        for (const Triangle3 &t : hulled.triangles)
            hull->triangles_.push_back({index[t[0]], index[t[1]], index[t[2]]});
        hull->center_ = center;
        hull->margin_ = epsilon * (1.0 + 1e-9) + 1e-12 * reach;
        hull->cluster();
        hull->directionCells();
        return hull;
    }

    namespace
    {
        /** \brief The most vertices of a cluster (a hull of fewer than twice as many is not clustered): support()
            costs a dot product a cluster, then one a vertex of the clusters it opens. */
        constexpr std::size_t CLUSTER_SIZE = 16;
        /** \brief The most clusters (support() keeps their bounds on the stack): a hull of more is not clustered. */
        constexpr std::size_t MAX_CLUSTERS = 512;
    }  // namespace

    void ConvexHull::cluster()
    {
        const std::size_t n = vertices_.size();
        if (n < 2 * CLUSTER_SIZE)
            return;
        // Halve at the median of the widest extent until a part has at most CLUSTER_SIZE vertices (at least half
        // that): the parts, in order, are the clusters.
        std::vector<std::uint32_t> order(n);
        std::iota(order.begin(), order.end(), 0u);
        std::vector<std::pair<std::size_t, std::size_t>> todo{{0, n}}, parts;
        while (!todo.empty())
        {
            const std::pair<std::size_t, std::size_t> part = todo.back();
            todo.pop_back();
            if (part.second - part.first <= CLUSTER_SIZE)
            {
                parts.push_back(part);
                continue;
            }
            Eigen::AlignedBox3d box;
            for (std::size_t i = part.first; i < part.second; ++i)
                box.extend(vertices_[order[i]]);
            int axis = 0;
            box.sizes().maxCoeff(&axis);
            const std::size_t middle = part.first + (part.second - part.first) / 2;
            std::nth_element(order.begin() + part.first, order.begin() + middle, order.begin() + part.second,
                             [&](std::uint32_t a, std::uint32_t b) { return vertices_[a][axis] < vertices_[b][axis]; });
            todo.emplace_back(middle, part.second);
            todo.emplace_back(part.first, middle);
        }
        if (parts.size() > MAX_CLUSTERS)
            return;
        Clusters &c = clustered_;
        for (const std::pair<std::size_t, std::size_t> &part : parts)
        {
            Eigen::AlignedBox3d box;
            for (std::size_t i = part.first; i < part.second; ++i)
                box.extend(vertices_[order[i]]);
            const Eigen::Vector3d centre = box.center();
            double radius = 0.0;
            for (std::size_t i = part.first; i < part.second; ++i)
                radius = std::max(radius, (vertices_[order[i]] - centre).norm());
            c.first.push_back(static_cast<std::uint32_t>(part.first));
            c.cx.push_back(centre.x());
            c.cy.push_back(centre.y());
            c.cz.push_back(centre.z());
            c.radius.push_back(radius * (1.0 + 1e-12));  // over the roundoff of the norms
        }
        c.first.push_back(static_cast<std::uint32_t>(n));
        for (std::uint32_t i : order)
        {
            c.xs.push_back(vertices_[i].x());
            c.ys.push_back(vertices_[i].y());
            c.zs.push_back(vertices_[i].z());
            c.index.push_back(i);
        }
    }

    namespace
    {
        /** \brief The most vertices of a hull with a direction table (their indices held in 16 bits; its build
            costs about 30 dot products a vertex and cell). */
        constexpr std::size_t MAX_TABLE_VERTICES = 512;
        /** \brief Cells along a face's side: 6 x 16 x 16 cells. */
        constexpr int TABLE_SIDE = 16;
        /** \brief How far each cell is widened in (u, v): over the roundoff of u = d_b / |d_a| (1 ulp of 1). */
        constexpr double CELL_PAD = 1e-9;
        /** \brief The face and cell of \e d (not zero, finite): see ConvexHull::Cells. */
        std::size_t cellOf(const Eigen::Vector3d &d, int side)
        {
            const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
            const int a = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
            const double m = std::max(ax, std::max(ay, az));
            const double u = d[(a + 1) % 3] / m, v = d[(a + 2) % 3] / m;
            const auto cell = [side](double w)
            { return std::min(side - 1, std::max(0, static_cast<int>((w + 1.0) * 0.5 * side))); };
            const int face = 2 * a + (d[a] < 0.0 ? 1 : 0);
            return static_cast<std::size_t>((face * side + cell(u)) * side + cell(v));
        }
    }  // namespace

    void ConvexHull::directionCells()
    {
        const std::size_t n = vertices_.size();
        if (n > MAX_TABLE_VERTICES || n == 0)
            return;
        // A vertex x is left out of a cell when one vertex y beats it at the cell's four corners by more than tol:
        // (y - x).e is linear in (u, v), so it then exceeds tol over the whole square, and for any d = m e of the
        // cell (y - x).d > m tol, more than the roundoff of the two computed dot products (gamma_3 |d| 2 reach,
        // with |e| <= sqrt(3)) and of the corner values (a few ulps of 3 reach): y's computed product is then the
        // larger, and x is not scan()'s vertex.
        const double tol = 1e-13 * reach_ + 1e-300;
        const int side = TABLE_SIDE;
        Cells &t = cells_;
        t.side = side;
        t.first.reserve(6 * side * side + 1);
        std::vector<double> g(5 * n);
        for (int face = 0; face < 6; ++face)
        {
            const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
            const double sign = face % 2 ? -1.0 : 1.0;
            for (int i = 0; i < side; ++i)
                for (int j = 0; j < side; ++j)
                {
                    const double u0 = -1.0 + 2.0 * i / side - CELL_PAD, u1 = -1.0 + 2.0 * (i + 1) / side + CELL_PAD;
                    const double v0 = -1.0 + 2.0 * j / side - CELL_PAD, v1 = -1.0 + 2.0 * (j + 1) / side + CELL_PAD;
                    const double us[5] = {u0, u1, u0, u1, 0.5 * (u0 + u1)};
                    const double vs[5] = {v0, v0, v1, v1, 0.5 * (v0 + v1)};
                    std::size_t top[5] = {0, 0, 0, 0, 0};
                    for (std::size_t x = 0; x < n; ++x)
                        for (int k = 0; k < 5; ++k)
                        {
                            const Eigen::Vector3d &p = vertices_[x];
                            g[5 * x + k] = sign * p[a] + us[k] * p[b] + vs[k] * p[c];
                            if (g[5 * x + k] > g[5 * top[k] + k])
                                top[k] = x;
                        }
                    t.first.push_back(static_cast<std::uint32_t>(t.index.size()));
                    for (std::size_t x = 0; x < n; ++x)
                    {
                        bool beaten = false;
                        for (int y = 4; y >= 0 && !beaten; --y)  // the centre's first: it beats the most
                        {
                            const std::size_t w = top[y];
                            beaten = true;
                            for (int k = 0; k < 4 && beaten; ++k)
                                beaten = g[5 * w + k] - g[5 * x + k] > tol;
                        }
                        if (!beaten)
                            t.index.push_back(static_cast<std::uint16_t>(x));
                    }
                }
        }
        t.first.push_back(static_cast<std::uint32_t>(t.index.size()));
    }

    void ConvexHull::scanCluster(std::size_t k, const Eigen::Vector3d &d, double &best, std::uint32_t &where) const
    {
        const Clusters &c = clustered_;
        const double dx = d.x(), dy = d.y(), dz = d.z();
        for (std::size_t i = c.first[k]; i < c.first[k + 1]; ++i)
        {
            // The very expression scan() evaluates, hence the same rounded value for the same vertex.
            const double s = dx * c.xs[i] + dy * c.ys[i] + dz * c.zs[i];
            if (s > best || (s == best && c.index[i] < where))
            {
                best = s;
                where = c.index[i];
            }
        }
    }

    Eigen::Vector3d ConvexHull::support(const Eigen::Vector3d &d) const
    {
        const double scale = d.cwiseAbs().maxCoeff();
        // The table, where no product overflows and underflow's roundoff is far below the candidates' tolerance
        // (|d| reach between 1e-200 and 1e200); an overflow (not a number) is left to scan(), as below.
        if (cells_.side > 0 && d.allFinite() && scale * reach_ > 1e-200 && scale * reach_ < 1e200)
        {
            const std::size_t cell = cellOf(d, cells_.side);
            const double dx = d.x(), dy = d.y(), dz = d.z();
            double best = -std::numeric_limits<double>::infinity();
            std::uint32_t where = 0;
            for (std::uint32_t k = cells_.first[cell]; k < cells_.first[cell + 1]; ++k)
            {
                const std::uint32_t i = cells_.index[k];
                // The very expression scan() evaluates; ascending indices, so ties go to the smaller.
                const double s = dx * xs_[i] + dy * ys_[i] + dz * zs_[i];
                if (s > best)
                {
                    best = s;
                    where = i;
                }
            }
            if (std::isfinite(best))
                return vertices_[where];
        }
        // Cluster k's vertices x have d.x <= d.c_k + |d| r_k (its bounding sphere), so when the rounded bound plus
        // a tolerance is below the best computed dot product found so far, no vertex of the cluster can have the
        // largest computed one: |fl(d.x) - d.x| <= gamma_3 |d| |x| <= 3.4e-16 |d| reach, and the bound's own
        // roundoff is below 1.3e-15 |d| reach (|c_k| <= sqrt(3) reach, r_k <= 2 reach); the tolerance is 1e-14
        // |d| reach. The cluster of scan()'s vertex is hence opened, and the same ties rule (the smaller index in
        // vertices_) returns that very vertex.
        const Clusters &c = clustered_;
        const std::size_t clusters = c.radius.size();
        if (clusters == 0 || !(scale > 0.0) || !std::isfinite(scale))
            return scan(d);
        const double length = scale * (d / scale).norm() * (1.0 + 1e-15);  // at least |d|, never underflowing
        const double tolerance = 1e-14 * length * reach_ + 1e-300;
        const double dx = d.x(), dy = d.y(), dz = d.z();
        double bound[MAX_CLUSTERS];
        for (std::size_t k = 0; k < clusters; ++k)
            bound[k] = dx * c.cx[k] + dy * c.cy[k] + dz * c.cz[k] + length * c.radius[k];
        std::size_t top = 0;
        for (std::size_t k = 1; k < clusters; ++k)
            top = bound[k] > bound[top] ? k : top;
        double best = -std::numeric_limits<double>::infinity();
        std::uint32_t where = std::numeric_limits<std::uint32_t>::max();
        scanCluster(top, d, best, where);
        for (std::size_t k = 0; k < clusters; ++k)
            if (k != top && !(bound[k] + tolerance < best))
                scanCluster(k, d, best, where);
        if (!(best > -std::numeric_limits<double>::infinity()))
            return scan(d);  // every product -inf or not a number (an overflowing d): as scan() decides
        return vertices_[where];
    }

    Eigen::Vector3d ConvexHull::scan(const Eigen::Vector3d &d) const
    {
        // Four interleaved lanes, each keeping its largest value and where (branch-free: the compiler vectorises it),
        // then the largest of the four, ties to the smaller index.
        constexpr std::size_t LANES = 4;
        const std::size_t n = xs_.size();
        const double dx = d.x(), dy = d.y(), dz = d.z();
        double most[LANES];
        std::size_t where[LANES];
        std::fill(most, most + LANES, -std::numeric_limits<double>::infinity());
        std::fill(where, where + LANES, std::size_t{0});
        std::size_t i = 0;
        for (; i + LANES <= n; i += LANES)
            for (std::size_t k = 0; k < LANES; ++k)
            {
                const double s = dx * xs_[i + k] + dy * ys_[i + k] + dz * zs_[i + k];
                const bool above = s > most[k];
                most[k] = above ? s : most[k];
                where[k] = above ? i + k : where[k];
            }
        for (; i < n; ++i)
        {
            const double s = dx * xs_[i] + dy * ys_[i] + dz * zs_[i];
            if (s > most[i % LANES])
            {
                most[i % LANES] = s;
                where[i % LANES] = i;
            }
        }
        std::size_t best = 0;
        for (std::size_t k = 1; k < LANES; ++k)
            if (most[k] > most[best] || (most[k] == most[best] && where[k] < where[best]))
                best = k;
        return vertices_[where[best]];
    }

    namespace
    {
        /** \brief The lower bound of two placed solids' distance (their balls' radii subtracted), by GJK, from the
            first direction \e axis holds (if given and not zero; there the last one GJK looked along, when apart). */
        double coresGap(const solid::Core &a, const solid::Core &b, double enough, Eigen::Vector3d *axis = nullptr)
        {
            const double radii = a.radius + b.radius;
            const solid::CoreGap g = solid::gjk(a, b, std::max(a.reach(), b.reach()), enough + radii,
                                                axis ? *axis : Eigen::Vector3d::Zero());
            if (axis && !g.overlap)
                *axis = g.axis;
            return g.overlap ? 0.0 : std::max(0.0, g.lower - radii);
        }

        solid::Core hullCore(const ConvexHull &hull, const Eigen::Isometry3d &X)
        {
            solid::Core core;
            core.type = solid::Core::HULL;
            core.hull = &hull;
            core.R = X.linear();
            core.c = X.translation();
            core.radius = hull.margin();
            return core;
        }
    }  // namespace

    namespace
    {
        /** \brief \e hull swept from \e X0 to \e X1 (the hull of both placements), grown by its margin and
            \e grow; a hull that stays (X1 the very pose X0) placed once: its support is then one hull's, the point
            the sweep's would return (its two candidates tie, and it takes the first). */
        solid::Core sweptCore(const ConvexHull &hull, const Eigen::Isometry3d &X0, const Eigen::Isometry3d &X1,
                              double grow)
        {
            solid::Core core = hullCore(hull, X0);
            core.radius += grow;
            if (X0.matrix() == X1.matrix())
                return core;
            core.type = solid::Core::SWEPT;
            core.R1 = X1.linear();
            core.c1 = X1.translation();
            return core;
        }
    }  // namespace

    double sweptHullGap(const ConvexHull &a, const Eigen::Isometry3d &A0, const Eigen::Isometry3d &A1, double growA,
                        const ConvexHull &b, const Eigen::Isometry3d &B0, const Eigen::Isometry3d &B1, double growB,
                        double enough, Eigen::Vector3d *axis)
    {
        return coresGap(sweptCore(a, A0, A1, growA), sweptCore(b, B0, B1, growB), enough, axis);
    }

    double sweptHullPrimitiveGap(const ConvexHull &a, const Eigen::Isometry3d &A0, const Eigen::Isometry3d &A1,
                                 double grow, const Primitive &p, double enough, Eigen::Vector3d *axis)
    {
        return coresGap(sweptCore(a, A0, A1, grow), solid::coreOf(p, Eigen::Isometry3d::Identity()), enough, axis);
    }

    double hullGap(const ConvexHull &a, const ConvexHull &b, const Eigen::Isometry3d &X_AB, double enough)
    {
        return coresGap(hullCore(a, Eigen::Isometry3d::Identity()), hullCore(b, X_AB), enough);
    }

    double hullPrimitiveGap(const ConvexHull &a, const Primitive &p, const Eigen::Isometry3d &X_AP, double enough)
    {
        return coresGap(hullCore(a, Eigen::Isometry3d::Identity()), solid::coreOf(p, X_AP), enough);
    }
}  // namespace meshgap
