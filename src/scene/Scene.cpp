#include "meshgap/scene/Scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

// Boost 1.74's Boost.Geometry includes a header Boost itself marks deprecated (a message, not a warning).
#ifndef BOOST_ALLOW_DEPRECATED_HEADERS
#define BOOST_ALLOW_DEPRECATED_HEADERS
#endif
#include <boost/geometry.hpp>  // all of it: the box-box distance strategies the R-tree's nearest query needs
#include <boost/geometry/index/rtree.hpp>

#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/distance/SolverFactory.h"

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace meshgap
{
    namespace
    {
        using Point = bg::model::point<double, 3, bg::cs::cartesian>;
        using Box = bg::model::box<Point>;
        using Entry = std::pair<Box, std::size_t>;  ///< an obstacle's world-frame box and its index
        using RTree = bgi::rtree<Entry, bgi::rstar<16>>;

        constexpr std::uint32_t NONE = std::numeric_limits<std::uint32_t>::max();

        Box toBox(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi)
        {
            return Box(Point(lo.x(), lo.y(), lo.z()), Point(hi.x(), hi.y(), hi.z()));
        }

        /** \brief For each surface triangle of \e body, the node in it that lies in the fewest surface triangles (an
            inner node if it has one, else an edge node, else a corner): a warm start's node for that triangle whose
            seed in refineExact() costs the fewest triangle tests. */
        std::vector<std::uint32_t> seedNodes(const Body &body)
        {
            const std::size_t n = body.surface().triangles.size();
            std::vector<std::uint32_t> node(n, NONE);
            std::vector<std::ptrdiff_t> count(n, std::numeric_limits<std::ptrdiff_t>::max());
            for (std::uint32_t i = 0; i < body.numNodes(); ++i)
            {
                const std::ptrdiff_t c = body.endNodeTriangles(i) - body.beginNodeTriangles(i);
                for (const std::uint32_t *t = body.beginNodeTriangles(i); t != body.endNodeTriangles(i); ++t)
                    if (c < count[*t])
                    {
                        count[*t] = c;
                        node[*t] = i;
                    }
            }
            return node;
        }
    }  // namespace

    std::vector<Mesh> splitComponents(const Mesh &mesh)
    {
        const std::size_t n = mesh.vertices.size();
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t v : t)
                if (v >= n)
                    throw Exception(mesh.source, "triangle index " + std::to_string(v) + " out of range (" +
                                                     std::to_string(n) + " vertices)");
        // Union-find over the vertices, joined along triangle edges.
        std::vector<std::uint32_t> parent(n);
        std::iota(parent.begin(), parent.end(), 0u);
        auto find = [&parent](std::uint32_t x)
        {
            while (parent[x] != x)
                x = parent[x] = parent[parent[x]];
            return x;
        };
        for (const Triangle &t : mesh.triangles)
            for (int k = 0; k < 2; ++k)
            {
                const std::uint32_t a = find(t[k]), b = find(t[k + 1]);
                if (a != b)
                    parent[a] = b;
            }

        // Parts numbered in order of first triangle.
        std::vector<std::uint32_t> partOfRoot(n, NONE), partOfTriangle(mesh.triangles.size());
        std::uint32_t numParts = 0;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        {
            const std::uint32_t r = find(mesh.triangles[t][0]);
            if (partOfRoot[r] == NONE)
                partOfRoot[r] = numParts++;
            partOfTriangle[t] = partOfRoot[r];
        }
        std::vector<Mesh> parts(numParts);
        for (std::uint32_t p = 0; p < numParts; ++p)
            parts[p].source = numParts == 1 ? mesh.source : mesh.source + "#" + std::to_string(p);
        // Each part's vertices in their original order; vertices no triangle uses are dropped.
        std::vector<std::uint32_t> local(n, NONE);
        for (std::uint32_t v = 0; v < n; ++v)
        {
            const std::uint32_t p = partOfRoot[find(v)];
            if (p == NONE)
                continue;
            local[v] = static_cast<std::uint32_t>(parts[p].vertices.size());
            parts[p].vertices.push_back(mesh.vertices[v]);
        }
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        {
            const Triangle &f = mesh.triangles[t];
            parts[partOfTriangle[t]].triangles.push_back({local[f[0]], local[f[1]], local[f[2]]});
        }
        return parts;
    }

    struct Scene::Impl
    {
        Impl(const Body &robot, const std::vector<BodyConstPtr> &obstacles, const std::vector<Entry> &entries)
            : tree(entries.begin(), entries.end())  // packed build
              ,
              robotSeeds(seedNodes(robot))
        {
            obstacleSeeds.reserve(obstacles.size());
            for (const BodyConstPtr &o : obstacles)
                obstacleSeeds.push_back(seedNodes(*o));
            for (const Entry &e : entries)
                for (const Point &p : {e.first.min_corner(), e.first.max_corner()})
                    extent =
                        std::max({extent, std::abs(bg::get<0>(p)), std::abs(bg::get<1>(p)), std::abs(bg::get<2>(p))});
        }

        /** \brief The broad phase both query modes share: visit obstacle \e first (the warm start's; none if out of
            range), then the others in increasing box distance from \e box, until the next box is farther than
            bestDistance() (nothing there can be closer) or visit() has returned true (the caller needs no more).
            Returns true if it ended on visit()'s word with an obstacle left that might be closer. */
        template <typename BestDistance, typename Visit>
        bool visitNearestFirst(const Box &box, std::size_t first, BestDistance bestDistance, Visit visit) const
        {
            const std::size_t count = tree.size();
            bool ended = first < count && visit(first);
            for (auto it = tree.qbegin(bgi::nearest(box, static_cast<unsigned>(count))); it != tree.qend(); ++it)
            {
                if (it->second == first)
                    continue;
                if (bg::distance(box, it->first) > bestDistance())
                    return false;  // this box and every later one are farther than the best
                if (ended)
                    return true;
                ended = visit(it->second);
            }
            return false;
        }

        /** \brief The robot's world-frame box at \e X_WR: its BVH root box (an oriented box in the world) and its
            root sphere, each bounded by an axis-aligned box, intersected, then padded so that roundoff in the
            transform (and in Boost.Geometry's box distance) can never make the box miss part of the robot. */
        Box robotBox(const Body &robot, const Eigen::Isometry3d &X_WR) const
        {
            const TriangleBvh::Node &root = robot.bvh().nodes()[0];
            const Eigen::Vector3d c = X_WR * root.center;
            const Eigen::Vector3d half = X_WR.linear().cwiseAbs() * root.half;
            const Eigen::Vector3d r = Eigen::Vector3d::Constant(root.radius);
            // Roundoff in the box distances is relative to the largest coordinate involved, the robot's or the
            // obstacles'; 1e-9 of it is far above roundoff and far below any useful pruning margin.
            const double pad =
                1e-9 * (root.radius + root.half.norm() + std::max(c.cwiseAbs().maxCoeff(), extent)) + 1e-300;
            const Eigen::Vector3d pads = Eigen::Vector3d::Constant(pad);
            return toBox((c - half).cwiseMax(c - r) - pads, (c + half).cwiseMin(c + r) + pads);
        }

        RTree tree;
        double extent{0.0};  ///< largest absolute coordinate of any obstacle box
        /** \brief seedNodes() of the robot and of each obstacle. */
        std::vector<std::uint32_t> robotSeeds;
        std::vector<std::vector<std::uint32_t>> obstacleSeeds;
        /** \brief comb-GA-wl for fast mode: solve() is const and keeps all per-query state in the call, so one
            instance serves every thread. */
        DistanceSolverConstPtr fast{allocSolver("comb-GA-wl")};
    };

    Scene::Scene(BodyConstPtr robot, std::vector<BodyConstPtr> obstacles)
        : robot_(std::move(robot)), obstacles_(std::move(obstacles))
    {
        if (!robot_)
            throw Exception("Scene", "no robot body");
        std::vector<Entry> entries;
        entries.reserve(obstacles_.size());
        for (std::size_t k = 0; k < obstacles_.size(); ++k)
        {
            if (!obstacles_[k])
                throw Exception("Scene", "obstacle " + std::to_string(k) + " is null");
            // The vertices' exact extremes: no roundoff in the obstacle's box.
            const Eigen::AlignedBox3d b = obstacles_[k]->surface().bounds();
            entries.emplace_back(toBox(b.min(), b.max()), k);
        }
        impl_ = std::make_shared<const Impl>(*robot_, obstacles_, entries);
    }

    ScenePtr Scene::fromMeshes(const Mesh &robot, const Mesh &world, const BodyOptions &options)
    {
        world.validate();
        BodyConstPtr robotBody = Body::build(robot, options);
        std::vector<BodyConstPtr> obstacles;
        for (Mesh &part : splitComponents(world))
            obstacles.push_back(Body::build(std::move(part), options));  // a relative grid size is per part
        return std::make_shared<Scene>(std::move(robotBody), std::move(obstacles));
    }

    std::size_t Scene::firstCollision(const Eigen::Isometry3d &X_WR) const
    {
        // Touching or intersecting bodies, or one inside the other, have overlapping boxes.
        const Box box = impl_->robotBox(*robot_, X_WR);
        for (auto it = impl_->tree.qbegin(bgi::intersects(box)); it != impl_->tree.qend(); ++it)
            if (meshgap::inCollision(*obstacles_[it->second], *robot_, X_WR))
                return it->second;
        return obstacles_.size();
    }

    std::size_t Scene::deepestCollision(const Eigen::Isometry3d &X_WR, std::size_t known, DistanceResult &best,
                                        std::size_t &pairsChecked) const
    {
        // Every colliding obstacle has a box overlapping the robot's: test them all, in R-tree order; the order
        // cannot matter, since the most negative value wins and ties go to the smallest index.
        const Box box = impl_->robotBox(*robot_, X_WR);
        std::size_t bestK = obstacles_.size();
        for (auto it = impl_->tree.qbegin(bgi::intersects(box)); it != impl_->tree.qend(); ++it)
        {
            const std::size_t k = it->second;
            const Body &obstacle = *obstacles_[k];
            if (k != known)
            {
                ++pairsChecked;
                if (!meshgap::inCollision(obstacle, *robot_, X_WR))
                    continue;
            }
            DistanceResult r;
            setPenetration(obstacle, *robot_, X_WR, r);
            r.certified = true;
            if (bestK == obstacles_.size() || r.distance < best.distance || (r.distance == best.distance && k < bestK))
            {
                best = r;
                bestK = k;
            }
        }
        return bestK;
    }

    bool Scene::inCollision(const Eigen::Isometry3d &X_WR) const
    {
        return firstCollision(X_WR) < obstacles_.size();
    }

    void Scene::distance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                         SceneResult &result) const
    {
        result = SceneResult();
        if (obstacles_.empty())
        {
            result.certified = request.exact;  // nothing to be near: infinity is the exact answer
            warm.valid = false;
            return;
        }
        if (request.exact)
            exactDistance(X_WR, request, warm, result);
        else
            fastDistance(X_WR, request, warm, result);
    }

    // Both modes share the visiting order: the warm start's obstacle first, then the R-tree's incremental nearest
    // query (increasing box distance), stopping at the first box farther than the best distance so far. Every box
    // distance is below its obstacle's true distance by at least the robot box's pad, so roundoff in the ordering
    // or in the distance cannot skip an obstacle that could be closer. Per call the R-tree's query iterators still
    // allocate (3 allocations per exact query, measured by bench/scaling.cpp); the BVH traversal stacks are per thread.

    void Scene::exactDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                              SceneResult &result) const
    {
        const bool warmValid = warm.valid && warm.obstacle < obstacles_.size();
        const bool mayStop = request.stopBelow >= 0.0;
        DistanceResult best;
        std::size_t bestK = obstacles_.size();
        bool complete = true;  // every visited pair completed

        // Returns true when the query can end: a collision, or the early stop reached.
        auto visit = [&](std::size_t k)
        {
            const Body &obstacle = *obstacles_[k];
            DistanceResult r;
            if (warmValid && k == warm.obstacle && warm.nodes.a < obstacle.numNodes() &&
                warm.nodes.b < robot_->numNodes())
            {
                r.nodes = warm.nodes;
                r.distance = (obstacle.node(warm.nodes.a) - X_WR * robot_->node(warm.nodes.b)).norm();
            }
            // Without an early stop, a collision still ends the walk at once (stopBelow 0: no depth yet): the
            // depth pass below then looks at every obstacle that might collide.
            // The best distance so far bounds this obstacle's search: only a closer pair can change the answer.
            refineExact(obstacle, *robot_, X_WR, r, mayStop ? request.stopBelow : 0.0,
                        bestK == obstacles_.size() ? std::numeric_limits<double>::infinity() : best.distance);
            ++result.pairsChecked;
            complete = complete && r.certified;
            if (bestK == obstacles_.size() || r.distance < best.distance)
            {
                best = r;
                bestK = k;
            }
            return best.inCollision || (mayStop && best.distance <= request.stopBelow);
        };

        // Ending early (a collision, or the early stop) with an obstacle left that might be closer leaves the
        // distance uncertified; a collision is certified by its own pair.
        if (impl_->visitNearestFirst(impl_->robotBox(*robot_, X_WR), warmValid ? warm.obstacle : obstacles_.size(),
                                     [&] { return best.distance; }, visit))
            complete = false;
        if (best.inCollision && !mayStop)
        {
            // The signed distance: the deepest penetration over all colliding obstacles, whichever was met first.
            DistanceResult deepest;
            bestK = deepestCollision(X_WR, bestK, deepest, result.pairsChecked);
            best = deepest;
        }

        result.distance = best.distance;
        result.obstacle = bestK;
        result.onObstacle = best.onA;
        result.onRobot = best.onB;
        result.inCollision = best.inCollision;
        result.penetrationDepth = best.penetrationDepth;
        result.penetration = best.penetration;
        result.certified = best.inCollision ? best.certified : complete;
        result.warmStartHit = warmValid && bestK == warm.obstacle;
        if (bestK == obstacles_.size())
            throw Exception("Scene", "no obstacle visited");  // cannot happen: the nearest one is always visited

        const NodePair nodes{impl_->obstacleSeeds[bestK][best.triangleA], impl_->robotSeeds[best.triangleB]};
        warm.valid = nodes.a != NONE && nodes.b != NONE;
        warm.obstacle = bestK;
        warm.nodes = nodes;
    }

    void Scene::fastDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                             SceneResult &result) const
    {
        const bool warmValid = warm.valid && warm.obstacle < obstacles_.size();
        result.certified = false;  // a node-level answer is never proven

        // The collision verdict is exact whatever the node search would say, and the signed distance in collision
        // is the exact mode's (no depth with an early stop).
        const bool mayStop = request.stopBelow >= 0.0;
        DistanceResult deepest;
        const std::size_t hit = mayStop ? firstCollision(X_WR)
                                        : deepestCollision(X_WR, obstacles_.size(), deepest, result.pairsChecked);
        if (hit < obstacles_.size())
        {
            if (mayStop)
            {
                result.distance = kContactDistance;
                result.penetration = Penetration::NotComputed;
            }
            else
            {
                result.distance = deepest.distance;
                result.penetrationDepth = deepest.penetrationDepth;
                result.penetration = deepest.penetration;
                result.onObstacle = deepest.onA;
                result.onRobot = deepest.onB;
            }
            result.obstacle = hit;
            result.inCollision = true;
            result.warmStartHit = warmValid && hit == warm.obstacle;
            if (!result.warmStartHit)
            {
                // No node pair is known there: start from its first nodes, a valid if arbitrary guess.
                warm.valid = true;
                warm.obstacle = hit;
                warm.nodes = NodePair();
            }
            return;
        }

        DistanceResult best;
        std::size_t bestK = obstacles_.size();
        auto visit = [&](std::size_t k)
        {
            const Body &obstacle = *obstacles_[k];
            DistanceRequest pairRequest;
            pairRequest.seed = request.seed;
            if (warmValid && k == warm.obstacle && warm.nodes.a < obstacle.numNodes() &&
                warm.nodes.b < robot_->numNodes())
                pairRequest.start = warm.nodes;
            DistanceResult r;
            impl_->fast->solve(obstacle, *robot_, X_WR, pairRequest, r);
            ++result.pairsChecked;
            result.evaluations += r.evaluations;
            if (bestK == obstacles_.size() || r.distance < best.distance)
            {
                best = r;
                bestK = k;
            }
            return mayStop && best.distance <= request.stopBelow;
        };

        // A node distance is never below its pair's exact distance, nor that below the box distance: pruning by
        // box distance against the best node distance skips no obstacle whose node answer could be smaller.
        impl_->visitNearestFirst(impl_->robotBox(*robot_, X_WR), warmValid ? warm.obstacle : obstacles_.size(),
                                 [&] { return best.distance; }, visit);

        result.distance = best.distance;
        result.obstacle = bestK;
        result.onObstacle = best.onA;
        result.onRobot = best.onB;
        result.warmStartHit = warmValid && bestK == warm.obstacle;
        warm.valid = true;
        warm.obstacle = bestK;
        warm.nodes = best.nodes;
    }
}  // namespace meshgap
