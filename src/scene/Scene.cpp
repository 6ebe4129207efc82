#include "meshgap/scene/Scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
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
#include "meshgap/Limits.h"
#include "meshgap/Text.h"
#include "meshgap/ThreadScratch.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/distance/WarmFast.h"
#include "meshgap/mesh/MeshOperations.h"

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

        std::atomic<std::uint64_t> nextSceneId{1};

        Box toBox(const Eigen::Vector3d &lo, const Eigen::Vector3d &hi)
        {
            return Box(Point(lo.x(), lo.y(), lo.z()), Point(hi.x(), hi.y(), hi.z()));
        }

        /** \brief An obstacle the nearest-first walk may visit: its box, its squared box distance from the robot's
            box (what the R-tree's nearest query ordered by), and its rank in R-tree order (the tie-break). */
        struct Candidate
        {
            double comparable;
            std::size_t rank;
            const Entry *entry;
        };
    }  // namespace

    struct Scene::Impl
    {
        explicit Impl(const std::vector<Entry> &entries) : tree(entries.begin(), entries.end())  // packed build
        {
            for (const Entry &e : entries)
                for (const Point &p : {e.first.min_corner(), e.first.max_corner()})
                    extent =
                        std::max({extent, std::abs(bg::get<0>(p)), std::abs(bg::get<1>(p)), std::abs(bg::get<2>(p))});
            inTreeOrder.reserve(entries.size());
            tree.query(bgi::satisfies([](const Entry &) { return true; }), std::back_inserter(inTreeOrder));
        }

        /** \brief The entries whose boxes intersect \e box, in R-tree order, into \e out (emptied first; capacity
            for every entry, so it never grows). Boost's spatial query visitor allocates nothing. */
        void intersecting(const Box &box, std::vector<Entry> &out) const
        {
            out.clear();
            out.reserve(tree.size());
            tree.query(bgi::intersects(box), std::back_inserter(out));
        }

        /** \brief The broad phase both query modes share: visit obstacle \e first (the warm start's; if out of range,
            the obstacle of the nearest box), then the others in increasing box distance from \e box, until the next
            box is farther than bestDistance() (nothing there can be closer) or visit() has returned true (the caller
            needs no more). Returns true if it ended on visit()'s word with an obstacle left that might be closer.
            Equal box distances go in R-tree order.

            The same walk as the R-tree's incremental nearest query gave, without its allocations: after the first
            visit, every box within the best distance so far lies in the robot's box grown by that distance (padded
            against roundoff); those alone are sorted by box distance, and the walk goes on while the next box
            distance is within the best distance, re-read after each visit (it only falls, so the candidates taken
            after the first visit are all that can qualify). A cold walk first finds the nearest box by a scan. */
        template <typename BestDistance, typename Visit>
        bool visitNearestFirst(const Box &box, std::size_t first, BestDistance bestDistance, Visit visit) const
        {
            const std::size_t count = inTreeOrder.size();
            if (first >= count)
            {
                // Cold: the nearest box (the first in R-tree order among equals) is visited first.
                if (count == 0)
                    return false;
                std::size_t nearest = 0;
                double least = bg::comparable_distance(box, inTreeOrder[0].first);
                for (std::size_t i = 1; i < count; ++i)
                {
                    const double c = bg::comparable_distance(box, inTreeOrder[i].first);
                    if (c < least)
                    {
                        least = c;
                        nearest = i;
                    }
                }
                if (bg::distance(box, inTreeOrder[nearest].first) > bestDistance())
                    return false;
                first = inTreeOrder[nearest].second;
            }
            bool ended = visit(first);

            const double bound = bestDistance();
            if (bound < 0.0)
                return false;  // a collision: every other box is farther
            // Per-thread vectors (the visits and the narrow phase never query a Scene, but a nested walk would get
            // fresh ones rather than these).
            ThreadScratch<std::vector<Entry>> hitsScratch;
            ThreadScratch<std::vector<Candidate>> candidatesScratch;
            std::vector<Candidate> &candidates = candidatesScratch.get();
            candidates.clear();
            candidates.reserve(count);
            auto take = [&](const std::vector<Entry> &entries)
            {
                for (std::size_t i = 0; i < entries.size(); ++i)
                    if (entries[i].second != first)
                        candidates.push_back({bg::comparable_distance(box, entries[i].first), i, &entries[i]});
            };
            if (bound < std::numeric_limits<double>::infinity())
            {
                // Every box at distance <= bound from the robot's is within bound of it along each axis. The pad
                // covers roundoff in the box distance (relative to the bound) and in the grown box's corners
                // (relative to the coordinates): 1e-9 of either is far above roundoff.
                const Point &lo = box.min_corner(), &hi = box.max_corner();
                const double scale =
                    std::max({extent, std::abs(bg::get<0>(lo)), std::abs(bg::get<1>(lo)), std::abs(bg::get<2>(lo)),
                              std::abs(bg::get<0>(hi)), std::abs(bg::get<1>(hi)), std::abs(bg::get<2>(hi))});
                const double grow = bound + 1e-9 * (bound + scale) + 1e-300;
                const Box grown(Point(bg::get<0>(lo) - grow, bg::get<1>(lo) - grow, bg::get<2>(lo) - grow),
                                Point(bg::get<0>(hi) + grow, bg::get<1>(hi) + grow, bg::get<2>(hi) + grow));
                intersecting(grown, hitsScratch.get());
                take(hitsScratch.get());
            }
            else
                take(inTreeOrder);  // no bound (or NaN): every box qualifies
            std::sort(candidates.begin(), candidates.end(),
                      [](const Candidate &p, const Candidate &q)
                      { return p.comparable < q.comparable || (p.comparable == q.comparable && p.rank < q.rank); });

            for (const Candidate &c : candidates)
            {
                if (bg::distance(box, c.entry->first) > bestDistance())
                    return false;  // this box and every later one are farther than the best
                if (ended)
                    return true;
                ended = visit(c.entry->second);
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
            const Eigen::Vector3d half = (X_WR.linear() * root.axes).cwiseAbs() * root.half;
            const Eigen::Vector3d r = Eigen::Vector3d::Constant(root.radius);
            // Roundoff in the box distances is relative to the largest coordinate involved, the robot's or the
            // obstacles'; 1e-9 of it is far above roundoff and far below any useful pruning margin.
            const double pad =
                1e-9 * (root.radius + root.half.norm() + std::max(c.cwiseAbs().maxCoeff(), extent)) + 1e-300;
            const Eigen::Vector3d pads = Eigen::Vector3d::Constant(pad);
            return toBox((c - half).cwiseMax(c - r) - pads, (c + half).cwiseMin(c + r) + pads);
        }

        RTree tree;
        /** \brief Every entry, in R-tree order (the order of the tree's spatial queries). */
        std::vector<Entry> inTreeOrder;
        double extent{0.0};  ///< largest absolute coordinate of any obstacle box
        /** \brief The node-level solvers fast mode may name (solve() is const and keeps all per-query state in
            the call, so one instance serves every thread), found by name without allocating. */
        std::vector<std::pair<std::string, DistanceSolverConstPtr>> solvers = []
        {
            std::vector<std::pair<std::string, DistanceSolverConstPtr>> all;
            for (const std::string &name : solverNames())
                all.emplace_back(name, allocSolver(name));
            return all;
        }();

        /** \brief warm-fast that only climbs (no global search: fast mode's fall-back gives the exact pair
            query instead, SceneRequest::fallBack). */
        std::shared_ptr<WarmFast> climber = []
        {
            auto w = std::make_shared<WarmFast>();
            w->setGlobalEvery(0);
            w->setGapTolerance(std::numeric_limits<double>::infinity());
            return w;
        }();

        const DistanceSolver &solver(const std::string &name) const
        {
            for (const auto &[known, solver] : solvers)
                if (known == name)
                    return *solver;
            allocSolver(name);  // throws, listing the valid names
            throw Exception("Scene", "no solver " + quote(name));
        }
    };

    SceneWarmStart::Use SceneWarmStart::choose(const Eigen::Isometry3d &X_WR, const Eigen::Vector3d &center,
                                               double radius)
    {
        ++queries;
        const double limit = COHERENCE * radius;
        auto motion = [&](const Eigen::Isometry3d &from) { return nodeMotionBound(center, radius, from, X_WR); };
        // The nearest certificate by the motion bound: the one in use, or a recent one swapped into use.
        double nearest = posed ? motion(pose) : std::numeric_limits<double>::infinity();
        std::size_t chosen = recent.size();
        for (std::size_t i = 0; i < recent.size(); ++i)
            if (recent[i].posed)
            {
                const double m = motion(recent[i].pose);
                if (m < nearest)
                {
                    nearest = m;
                    chosen = i;
                }
            }
        if (lastPoses.size() != capacity_)
            lastPoses.resize(capacity_);  // once: a warm start that never chooses allocates nothing
        if (nearest <= limit)
        {
            lastPoses[posesSeen++ % lastPoses.size()] = X_WR;
            if (chosen < recent.size())
                std::swap(static_cast<SceneCertificate &>(*this), recent[chosen]);
            ++carried;
            return Use::CARRY;
        }
        bool nearRecent = false;  // near one of the last capacity() queries' poses (asked only when not carrying)
        for (std::size_t i = 0; i < posesSeen && i < lastPoses.size() && !nearRecent; ++i)
            nearRecent = motion(lastPoses[i]) <= limit;
        lastPoses[posesSeen++ % lastPoses.size()] = X_WR;
        if (!nearRecent)
        {
            ++cold;
            return Use::COLD;
        }
        // A run of nearby poses starts here: write a certificate in place of the least recently used one.
        if (posed && capacity_ > 1)
        {
            if (recent.size() + 1 < capacity_)
            {
                recent.reserve(capacity_ - 1);
                recent.emplace_back();
            }
            std::size_t oldest = 0;
            for (std::size_t i = 1; i < recent.size(); ++i)
                if (recent[oldest].posed && (!recent[i].posed || recent[i].lastUse < recent[oldest].lastUse))
                    oldest = i;
            std::swap(static_cast<SceneCertificate &>(*this), recent[oldest]);
        }
        SceneCertificate::reset();
        ++written;
        return Use::WRITE;
    }

    Scene::Scene(BodyConstPtr robot, std::vector<BodyConstPtr> obstacles)
        : robot_(std::move(robot)), obstacles_(std::move(obstacles)), id_(nextSceneId++)
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
        impl_ = std::make_shared<const Impl>(entries);
    }

    Scene::Scene(BodyConstPtr robot, const Scene &others)
        : robot_(std::move(robot)), obstacles_(others.obstacles_), id_(nextSceneId++), impl_(others.impl_)
    {
        if (!robot_)
            throw Exception("Scene", "no robot body");
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

    std::size_t Scene::firstCollision(const Eigen::Isometry3d &X_WR, SceneWarmStart *warm) const
    {
        // Touching or intersecting bodies, or one inside the other, have overlapping boxes.
        ThreadScratch<std::vector<Entry>> hits;
        impl_->intersecting(impl_->robotBox(*robot_, X_WR), hits.get());
        for (const Entry &e : hits.get())
            if (meshgap::inCollision(*obstacles_[e.second], *robot_, X_WR, warm ? &warm->pairs[e.second] : nullptr))
                return e.second;
        return obstacles_.size();
    }

    void Scene::bind(SceneWarmStart &warm) const
    {
        if (warm.scene == id_ && warm.pairs.size() == obstacles_.size())
            return;
        // First query with this warm start, or one made with another scene: nothing carries over.
        warm.reset();
        warm.pairs.clear();
        warm.pairs.resize(obstacles_.size());
        warm.fast.clear();
        for (SceneCertificate &c : warm.recent)
        {
            c.pairs.clear();
            c.pairs.resize(obstacles_.size());
            c.fast.clear();
        }
        warm.scene = id_;
    }

    std::size_t Scene::deepestCollision(const Eigen::Isometry3d &X_WR, std::size_t known, DistanceResult &best,
                                        std::size_t &pairsChecked, SceneWarmStart *warm) const
    {
        // Every colliding obstacle has a box overlapping the robot's: test them all, in R-tree order; the order
        // cannot matter, since the most negative value wins and ties go to the smallest index.
        ThreadScratch<std::vector<Entry>> hits;
        impl_->intersecting(impl_->robotBox(*robot_, X_WR), hits.get());
        std::size_t bestK = obstacles_.size(), tests = 0;
        for (const Entry &e : hits.get())
        {
            const std::size_t k = e.second;
            const Body &obstacle = *obstacles_[k];
            if (k != known)
            {
                ++pairsChecked;
                if (!meshgap::inCollision(obstacle, *robot_, X_WR))
                    continue;
            }
            DistanceResult r;
            const bool carried = warm && warm->pairs.size() == obstacles_.size();  // fast mode's may be unbound
            setPenetration(obstacle, *robot_, X_WR, r, carried ? &warm->pairs[k].penetration : nullptr);
            r.certified = true;
            tests += r.triangleTests;
            if (bestK == obstacles_.size() || r.distance < best.distance || (r.distance == best.distance && k < bestK))
            {
                best = r;
                bestK = k;
            }
        }
        best.triangleTests = tests;  // the work of every depth found, not only the deepest's
        return bestK;
    }

    SceneWarmStart *Scene::choose(const Eigen::Isometry3d &X_WR, SceneWarmStart &warm, SceneWarmStart::Use *use) const
    {
        bind(warm);
        const TriangleBvh::Node &root = robot_->bvh().nodes()[0];
        const SceneWarmStart::Use chosen = warm.choose(X_WR, root.center, root.radius);
        if (use)
            *use = chosen;
        switch (chosen)
        {
            case SceneWarmStart::Use::COLD:
                return nullptr;
            case SceneWarmStart::Use::WRITE:
                // The fresh certificate needs its per-obstacle warm starts (sized once; no allocation after).
                if (warm.pairs.size() != obstacles_.size())
                {
                    warm.pairs.clear();
                    warm.pairs.resize(obstacles_.size());
                }
                return &warm;
            case SceneWarmStart::Use::CARRY:
                return &warm;
        }
        return nullptr;
    }

    namespace
    {
        /** \brief Throws unless \e X_WR is finite, its position within MAX_MAGNITUDE: beyond it the geometry's
            arithmetic overflows and answers wrong, where an error is the right answer. */
        void checkPose(const Eigen::Isometry3d &X_WR)
        {
            if (!X_WR.matrix().allFinite() || X_WR.translation().cwiseAbs().maxCoeff() > MAX_MAGNITUDE)
                throw Exception("Scene", "the robot's pose is not finite or its position is beyond 1e12 in "
                                         "magnitude, the largest meshgap's geometry answers reliably");
        }
    }  // namespace

    bool Scene::inCollision(const Eigen::Isometry3d &X_WR) const
    {
        checkPose(X_WR);
        return firstCollision(X_WR) < obstacles_.size();
    }

    bool Scene::inCollision(const Eigen::Isometry3d &X_WR, SceneWarmStart &warm) const
    {
        checkPose(X_WR);
        SceneWarmStart *carried = choose(X_WR, warm);
        const bool hit = firstCollision(X_WR, carried) < obstacles_.size();
        if (carried)
            carried->stamp(X_WR);
        return hit;
    }

    void Scene::distance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                         SceneResult &result) const
    {
        query(X_WR, request, &warm, result);
    }

    void Scene::distance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneResult &result) const
    {
        query(X_WR, request, nullptr, result);
    }

    void Scene::query(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart *warm,
                      SceneResult &result) const
    {
        checkPose(X_WR);
        result = SceneResult();
        if (obstacles_.empty())
        {
            result.certified = request.exact;  // nothing to be near: infinity is the exact answer
            if (warm)
                warm->valid = false;
            return;
        }
        if (!(request.upperBound > 0.0))
            throw Exception("Scene", "the upper bound of a distance query must be positive");
        if (request.exact)
            exactDistance(X_WR, request, warm, result);
        else
        {
            SceneWarmStart none;  // a node pair and no more: allocates nothing
            fastDistance(X_WR, request, warm ? *warm : none, warm != nullptr, result);
        }
        result.openBody = !robot_->isClosed() ||
                          (result.obstacle < obstacles_.size() && !obstacles_[result.obstacle]->isClosed());
    }

    // Both modes share the visiting order: the warm start's obstacle first, then increasing box distance (ties in
    // R-tree order), stopping at the first box farther than the best distance so far. Every box distance is below
    // its obstacle's true distance by at least the robot box's pad, so roundoff in the ordering or in the distance
    // cannot skip an obstacle that could be closer. No query allocates once its thread has warmed up: the broad
    // phase uses the R-tree's spatial query (a visitor, no allocation) into per-thread vectors; the BVH traversal
    // stacks, the penetration depth's cluster candidates, comb-GA's arrays and the on-demand Dijkstra's buffers are
    // per thread too (capacity kept); DistanceResult::history is only filled on request. tests/alloc checks every
    // query kind.

    // How a query is answered (Scene::distance()'s contract in Scene.h):
    // - Obstacles are visited in order of a lower bound on their distance (ties in R-tree order), the warm start's
    //   obstacle first, and skipped once that bound exceeds the best distance so far (or request.upperBound). The
    //   bound is the distance between world-frame axis-aligned boxes: the obstacle's, and the robot's (its BVH root
    //   box and bounding sphere carried to the world frame, intersected, padded against roundoff), so only
    //   obstacles that cannot be closer than the best so far are skipped.
    // - Exact mode: refineExact() per visited obstacle with the warm start's ExactWarmStart of that obstacle (its
    //   last closest triangle pair and traversal front). certified when every visited pair completed and none was
    //   left unvisited that could be closer. Containment is decided per obstacle: a robot inside a closed part of
    //   the world collides.
    // - In collision (both modes) the distance is the minimum over every colliding obstacle of its pair's signed
    //   distance (setPenetration(): minus the depth of the deepest node of one body inside the other, closed,
    //   body, a lower bound on the penetration depth; CONTACT_DISTANCE, -2.2e-308, when that depth is 0 or the
    //   bodies are open), ties to the smallest obstacle index. The first collision met ends the distance walk;
    //   then every obstacle whose box overlaps the robot's is tested (deepestCollision()), so the answer (distance,
    //   obstacle, penetration, witness points: the deepest node and its nearest surface point) does not depend on
    //   the warm start or the visiting order. certified (the verdict is proven).
    // - Fast mode: request.solver per visited obstacle (request.seed; the warm pair as the start on its obstacle;
    //   warm-fast follows the run of poses with a WarmFastState per obstacle in the warm start), never certified;
    //   the collision verdict is exact (decided first), so a colliding pose is never reported free, and its signed
    //   distance is the exact mode's.
    // - stopBelow: the query ends once the best distance is at or below it (an upper bound then, not certified; in
    //   exact mode, inCollision is then set only if a touching pair was met). A collision then gets no depth:
    //   distance CONTACT_DISTANCE, penetration NOT_COMPUTED, and the first collision met ends the query.
    // - computeDepth false: the same answer in collision (the verdict, CONTACT_DISTANCE, NOT_COMPUTED, from the first
    //   collision met); a free answer is unchanged.
    // - The warm start is updated to the closest obstacle (and, in exact mode, the pair and front of every obstacle
    //   visited; in fast mode, the node pair). Ties between triangle pairs are broken canonically (bvhDistance()),
    //   so a complete exact answer, its pair and witness points are the cold query's bit for bit.
    void Scene::exactDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart *warm,
                              SceneResult &result) const
    {
        if (warm)
            warm = choose(X_WR, *warm, &result.warmStartUse);  // null: a cold query
        const bool warmValid = warm && warm->valid && warm->obstacle < obstacles_.size();
        const bool mayStop = request.stopBelow >= 0.0;
        DistanceResult best;
        std::size_t bestK = obstacles_.size();
        bool complete = true;  // every visited pair completed

        // Only a pair below the best so far (and the caller's bound) can change the answer.
        auto bound = [&] { return bestK == obstacles_.size() ? request.upperBound : best.distance; };
        // Returns true when the query can end: a collision, or the early stop reached.
        auto visit = [&](std::size_t k)
        {
            const Body &obstacle = *obstacles_[k];
            DistanceResult r;
            // Without an early stop, a collision still ends the walk at once (stopBelow 0: no depth yet): the
            // depth pass below then looks at every obstacle that might collide.
            DistanceRequest pairRequest = request;
            pairRequest.stopBelow = mayStop ? request.stopBelow : 0.0;
            pairRequest.upperBound = bound();
            refineExact(obstacle, *robot_, X_WR, r, pairRequest, warm ? &warm->pairs[k] : nullptr);
            ++result.pairsChecked;
            result.triangleTests += r.triangleTests;
            result.boxTests += r.boxTests;
            complete = complete && r.certified;
            if (r.distance < bound())  // else nothing on this obstacle is below the bound (refineExact's infinity)
            {
                best = r;
                bestK = k;
            }
            return best.inCollision || (mayStop && best.distance <= request.stopBelow);
        };

        // Ending early (a collision, or the early stop) with an obstacle left that might be closer leaves the
        // distance uncertified; a collision is certified by its own pair.
        if (impl_->visitNearestFirst(impl_->robotBox(*robot_, X_WR), warmValid ? warm->obstacle : obstacles_.size(),
                                     bound, visit))
            complete = false;
        if (bestK == obstacles_.size())
        {
            // Nothing below the caller's bound (no obstacle is closer, none collides: a collision is below any
            // positive bound, and a containment is found by refineExact whatever its bound).
            if (!(request.upperBound < std::numeric_limits<double>::infinity()))
                throw Exception("Scene", "no obstacle visited");  // cannot happen: the nearest one is always visited
            result.distance = request.upperBound;
            result.obstacle = obstacles_.size();
            result.atLeast = true;
            result.certified = complete;
            if (warm)
                warm->stamp(X_WR);  // its fronts are this pose's; its obstacle stays as it was
            return;
        }
        if (best.inCollision && !mayStop && request.computeDepth)
        {
            // The signed distance: the deepest penetration over all colliding obstacles, whichever was met first.
            DistanceResult deepest;
            bestK = deepestCollision(X_WR, bestK, deepest, result.pairsChecked, warm);
            best = deepest;
            result.triangleTests += deepest.triangleTests;
        }

        result.distance = best.distance;
        result.obstacle = bestK;
        result.onA = best.onB;  // the pair was asked obstacle first (its A), the robot second
        result.onB = best.onA;
        result.inCollision = best.inCollision;
        result.penetrationDepth = best.penetrationDepth;
        result.penetration = best.penetration;
        result.certified = best.inCollision ? best.certified : complete;
        result.warmStartHit = warmValid && bestK == warm->obstacle;
        if (warm)
        {
            warm->valid = true;
            warm->obstacle = bestK;
            warm->stamp(X_WR);
        }
    }

    namespace
    {
        /** \brief Whether the robot at \e X_WR moved more than SceneWarmStart::COHERENCE radii from the pose \e from
            (its bounding sphere's motion bound). */
        bool movedFar(const Body &robot, const Eigen::Isometry3d &from, const Eigen::Isometry3d &X_WR)
        {
            const TriangleBvh::Node &root = robot.bvh().nodes()[0];
            return nodeMotionBound(root.center, root.radius, from, X_WR) > SceneWarmStart::COHERENCE * root.radius;
        }

        /** \brief Fast mode with warm-fast: whether the query at \e X_WR starts a run (no pose before it in \e warm,
            or one it moved far from); records \e X_WR as the last pose. */
        bool jumped(const Body &robot, const Eigen::Isometry3d &X_WR, SceneWarmStart &warm)
        {
            const bool far = !warm.posed || movedFar(robot, warm.pose, X_WR);
            warm.pose = X_WR;
            warm.posed = true;
            return far;
        }

        /** \brief The corner of surface triangle \e t of \e body (at \e X) nearest to \e point: a node (the node mesh
            keeps the surface's vertices first). */
        std::uint32_t nearestCorner(const Body &body, std::uint32_t t, const Eigen::Isometry3d &X,
                                    const Eigen::Vector3d &point)
        {
            const Triangle &triangle = body.surface().triangles[t];
            std::uint32_t best = triangle[0];
            for (int c = 1; c < 3; ++c)
                if ((X * body.surface().vertices[triangle[c]] - point).squaredNorm() <
                    (X * body.surface().vertices[best] - point).squaredNorm())
                    best = triangle[c];
            return best;
        }
    }  // namespace

    bool Scene::fastCollision(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                              bool warmValid, SceneResult &result) const
    {
        // The signed distance in collision is the exact mode's (no depth with an early stop or computeDepth false).
        const bool verdictOnly = request.stopBelow >= 0.0 || !request.computeDepth;
        DistanceResult deepest;
        const std::size_t hit = verdictOnly
                                    ? firstCollision(X_WR)
                                    : deepestCollision(X_WR, obstacles_.size(), deepest, result.pairsChecked, &warm);
        if (hit == obstacles_.size())
            return false;
        if (verdictOnly)
        {
            result.distance = CONTACT_DISTANCE;
            result.penetration = Penetration::NOT_COMPUTED;
        }
        else
        {
            result.distance = deepest.distance;
            result.penetrationDepth = deepest.penetrationDepth;
            result.penetration = deepest.penetration;
            result.onA = deepest.onB;  // the pair was asked obstacle first (its A), the robot second
            result.onB = deepest.onA;
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
        return true;
    }

    void Scene::fastDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                             bool carried, SceneResult &result) const
    {
        const DistanceSolver &fastSolver = impl_->solver(request.solver);  // an unknown name throws, whatever the pose
        // warm-fast follows a run of poses per obstacle (WarmFastState) when the caller carries a warm start.
        const auto *warmFast = carried ? dynamic_cast<const WarmFast *>(&fastSolver) : nullptr;
        if (request.fallBack && !warmFast)
        {
            // A node search from scratch: the exact query costs less (SceneRequest::fallBack).
            exactDistance(X_WR, request, carried ? &warm : nullptr, result);
            result.fellBack = true;
            return;
        }
        if (warmFast && (warm.scene != id_ || warm.fast.size() != obstacles_.size()))
        {
            warm.valid = false;
            warm.pairs.clear();
            warm.pairs.resize(obstacles_.size());
            warm.fast.assign(obstacles_.size(), WarmFastState());
            warm.scene = id_;
            warm.posed = false;
        }
        if (request.fallBack && warmFast && jumped(*robot_, X_WR, warm))
        {
            // Far from the last pose (or the first of a run): no pair would only climb (SceneRequest::fallBack).
            exactDistance(X_WR, request, nullptr, result);
            result.fellBack = true;
            return;
        }
        const bool warmValid = warm.valid && warm.obstacle < obstacles_.size();
        result.certified = false;  // a node-level answer is never proven

        // The collision verdict is exact whatever the node search would say.
        if (fastCollision(X_WR, request, warm, warmValid, result))
            return;
        const bool mayStop = request.stopBelow >= 0.0;

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
            if (warmFast)
                result.exactPairs += warmFastPair(k, X_WR, request, *warmFast, best.distance, warm.fast[k], r);
            else
                fastSolver.solve(obstacle, *robot_, X_WR, pairRequest, r);
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
        impl_->visitNearestFirst(
            impl_->robotBox(*robot_, X_WR), warmValid ? warm.obstacle : obstacles_.size(),
            [&] { return best.distance; }, visit);

        result.distance = best.distance;
        result.obstacle = bestK;
        result.onA = best.onB;  // the pair was asked obstacle first (its A), the robot second
        result.onB = best.onA;
        result.warmStartHit = warmValid && bestK == warm.obstacle;
        warm.valid = true;
        warm.obstacle = bestK;
        warm.nodes = best.nodes;
    }

    bool Scene::warmFastPair(std::size_t k, const Eigen::Isometry3d &X_WR, const SceneRequest &request,
                             const WarmFast &solver, double bound, WarmFastState &state, DistanceResult &r) const
    {
        const Body &obstacle = *obstacles_[k];
        if (!request.fallBack)
        {
            solver.solveWarm(obstacle, *robot_, X_WR, state, request.seed, r);
            return false;
        }
        // warm-fast's own rules for a global search (WarmFast.h): a cold state, the periodic one, the gap test.
        const bool due = !state.valid || movedFar(*robot_, state.X_AB, X_WR) ||
                         (solver.getGlobalEvery() > 0 && state.sinceGlobal + 1 >= solver.getGlobalEvery());
        if (!due)
        {
            impl_->climber->solveWarm(obstacle, *robot_, X_WR, state, request.seed, r);
            const double lower = state.globalDistance - state.drift;
            if (!(std::isfinite(solver.getGapTolerance()) && lower < (1.0 - solver.getGapTolerance()) * r.distance))
                return false;
        }
        // The exact pair query instead, below the best answer so far; it seeds the state at its closest triangles.
        DistanceRequest exact;
        exact.upperBound = bound;
        refineExact(obstacle, *robot_, X_WR, r, exact);
        if (!(r.distance < bound))
            return true;  // nothing on this obstacle below the bound: its state stays as it was
        state.valid = true;
        state.pair = NodePair{nearestCorner(obstacle, r.triangleA, Eigen::Isometry3d::Identity(), r.onA),
                              nearestCorner(*robot_, r.triangleB, X_WR, r.onB)};
        state.triangleA = r.triangleA;
        state.triangleB = r.triangleB;
        state.X_AB = X_WR;
        state.globalDistance = r.distance;
        state.drift = 0.0;
        state.sinceGlobal = 0;
        ++state.queries;
        return true;
    }
}  // namespace meshgap
