#include "meshgap/geometry/BvhDistance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "BvhDetail.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    using bvh::afterUse;
    using bvh::lowerBound;
    using bvh::lowerBounds;
    using bvh::PairEntry;
    using bvh::RelativePose;
    using bvh::Separation;
    using bvh::splitA;
    using bvh::StepMotion;
    using bvh::threadStack;
    using bvh::triangleSeparation;

    namespace
    {
        /** \brief The gap of triangles p and q along \e axis (unit, from p's side to q's): may be negative. */
        double gapAlong(const Eigen::Vector3d &axis, const Eigen::Vector3d *p, const Eigen::Vector3d *q)
        {
            return std::min({axis.dot(q[0]), axis.dot(q[1]), axis.dot(q[2])}) -
                   std::max({axis.dot(p[0]), axis.dot(p[1]), axis.dot(p[2])});
        }

        /** \brief A pair of nodes still to open, with its lower bound and its rank in a best-first search: the bound
            when the boxes are apart; among pairs whose boxes overlap (bound <= 0, nothing to choose by), the smaller
            pair first (-1 / the sum of the radii), so that the search goes down to leaves instead of across. */
        struct Open
        {
            double bound, rank;
            PairEntry pair;
        };

        double rank(double bound, const TriangleBvh::Node &a, const TriangleBvh::Node &b)
        {
            return bound > 0.0 ? bound : -1.0 / (a.radius + b.radius + std::numeric_limits<double>::min());
        }

        /** \brief Heap order: the least rank on top. */
        bool farther(const Open &x, const Open &y)
        {
            return x.rank > y.rank;
        }

        /** \brief One distance traversal: a search over node pairs (best first until a first exact distance when
            there is no bound yet, then depth first, nearer child first), pruning pairs
            whose lower bound exceeds the best distance (plus the tie slack); with \e record set, every pruned pair
            and every tested leaf pair goes there with its bound (key = bound + motion): the traversal's front. */
        class DistanceTraversal
        {
        public:
            DistanceTraversal(const TriangleBvh &a, const TriangleBvh &b, const RelativePose &X, double slack,
                              double stopBelow, BvhDistanceResult &result, std::uint32_t bestA, std::uint32_t bestB,
                              std::vector<BvhFront::Entry> *record, double motion, std::uint32_t stamp)
                : a_(a),
                  b_(b),
                  X_(X),
                  slack_(slack),
                  stopBelow_(stopBelow),
                  result_(result),
                  bestA_(bestA),
                  bestB_(bestB),
                  record_(record),
                  motion_(motion),
                  stamp_(stamp),
                  open_(threadStack<Open, 1>()),
                  seedA_(bestA),
                  seedB_(bestB),
                  seedDistance_(result.distance)
            {
            }

            /** \brief The seed pair's distance is the starting bound, computed by the caller exactly as leaves()
                would, and \e axis (unit, from A's point towards B's) its witness direction: it is not tested again. */
            void knowSeed(const Eigen::Vector3d *axis)
            {
                seedAxis_ = axis;
                if (axis)
                    bestAxis_ = *axis;
            }

            /** \brief Prune threshold: a pair whose bound is above it cannot beat or tie the best so far. */
            double enough() const { return result_.distance + slack_; }
            /** \brief Where a bound's computation may stop: once above enough() when no front is kept; when one is,
                the whole bound, which later poses reuse. */
            double exitAbove() const { return record_ ? std::numeric_limits<double>::infinity() : enough(); }
            bool stopped() const { return stopped_; }
            /** \brief Give up after \e budget box and triangle tests (0: never). */
            void setBudget(std::size_t budget) { budget_ = budget; }

            /** \brief The bound of pair \e e at this pose: its box bound, or for a leaf pair -infinity (the leaf
                test makes its own). */
            double bound(const PairEntry &e)
            {
                const TriangleBvh::Node &na = a_.nodes()[e.a], &nb = b_.nodes()[e.b];
                if (na.isLeaf() && nb.isLeaf())
                    return -std::numeric_limits<double>::infinity();
                ++result_.boxTests;
                return lowerBound(na, nb, X_, exitAbove());
            }

            /** \brief Keep pair \e e with lower bound \e bound (and the axis that gave it, for a pair of leaves) in
                the front, if one is recorded. The axis is kept in single precision and normalised again when read:
                any unit axis gives a lower bound. */
            void keep(const PairEntry &e, double bound, const Eigen::Vector3d &axis = Eigen::Vector3d::Zero())
            {
                if (record_)
                    record_->push_back(
                        {e.a,
                         e.b,
                         stamp_,
                         {static_cast<float>(axis.x()), static_cast<float>(axis.y()), static_cast<float>(axis.z())},
                         bound + motion_});
            }

            /** \brief The prune threshold of the triangle pair (ta, tb): above the best distance plus the slack if
                it ranks before the best pair (it would win a tie), minus the slack if after (it must be closer). */
            double limit(std::uint32_t ta, std::uint32_t tb) const
            {
                const bool ranksAfter = ta > bestA_ || (ta == bestA_ && tb >= bestB_);
                return ranksAfter ? result_.distance - slack_ : enough();
            }

            /** \brief A pair of leaves with a separating axis from an earlier pose: whether its gap along that axis
                now, or else along the best pair's witness direction (which proves the pairs tied with the best one
                around a shared closest vertex or edge), proves it cannot beat the best; the gap (a lower bound on
                the distance of its triangles) goes to \e gap, and the axis that proved it to the entry. */
            bool axisProves(BvhFront::Entry &e, double &gap) const
            {
                const Eigen::Vector3d axis(e.axis[0], e.axis[1], e.axis[2]);
                const double length = axis.norm();
                if (!(length > 0.0))
                    return false;
                const Mesh &ma = a_.mesh(), &mb = b_.mesh();
                const TriangleBvh::Node &na = a_.nodes()[e.a], &nb = b_.nodes()[e.b];
                const std::uint32_t ta = a_.order()[na.first], tb = b_.order()[nb.first];
                const Triangle &fa = ma.triangles[ta], &fb = mb.triangles[tb];
                const Eigen::Vector3d pa[3] = {ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]]};
                Eigen::Vector3d pb[3];
                for (int k = 0; k < 3; ++k)
                    pb[k] = X_.R * mb.vertices[fb[k]] + X_.t;
                gap = gapAlong(axis / length, pa, pb);
                const double limit = this->limit(ta, tb);
                if (gap > limit)
                    return true;
                if (bestAxis_.isZero())
                    return false;
                const double best = gapAlong(bestAxis_, pa, pb);
                if (!(best > limit))
                    return false;
                gap = best;
                for (int k = 0; k < 3; ++k)
                    e.axis[k] = static_cast<float>(bestAxis_[k]);
                return true;
            }

            /** \brief Search below pair \e start (lower bound \e startBound) to its end, or until the early stop. */
            void run(const PairEntry &start, double startBound)
            {
                // Without a bound to prune with yet (no seed: a cold query), best first until the first pair of
                // leaves is tested (the open pair of least bound next: that first exact distance then comes from
                // near the minimum, wherever it is among many parts, and prunes well) or the heap outgrows
                // BEST_FIRST_OPEN_LIMIT; depth first, nearer child first, from there on and whenever a bound is known
                // (no heap to keep: cheaper per pair).
                open_.push_back({startBound, startBound, start});
                bestFirst_ = !(enough() < std::numeric_limits<double>::infinity());
                while (!open_.empty())
                {
                    if (bestFirst_)
                        std::pop_heap(open_.begin(), open_.end(), farther);
                    const PairEntry e = open_.back().pair;
                    const double bound = open_.back().bound;
                    open_.pop_back();
                    if (budget_ > 0 && !stopped_ && result_.boxTests + result_.triangleTests >= budget_)
                    {
                        stopped_ = true;
                        result_.exhausted = true;
                    }
                    if (stopped_ || bound > enough())
                    {
                        // Left unexplored by the early stop, or nothing in this pair can beat or tie the best so
                        // far: its bound stays a lower bound.
                        keep(e, bound);
                        continue;
                    }
                    const TriangleBvh::Node &na = a_.nodes()[e.a], &nb = b_.nodes()[e.b];
                    if (na.isLeaf() && nb.isLeaf())
                    {
                        Eigen::Vector3d axis;
                        const double least = leaves(na, nb, bound, axis);
                        keep(e, least, axis);
                        if (bestFirst_)
                            goDepthFirst();
                        continue;
                    }
                    descend(e, na, nb);
                    if (bestFirst_ && open_.size() > BEST_FIRST_OPEN_LIMIT)
                        goDepthFirst();
                }
            }

        private:
            /** \brief The most open pairs a best-first search keeps in its heap (96 KiB of them: within a core's
                second-level cache). Between finely meshed bodies near each other (a part refined to 20k triangles,
                bench/scaling.md) the heap grew to 190,000 pairs before its first pair of leaves: the heap's pushes and
                pops, and the sort that turns it into a stack, then missed the caches on every step, and a cold query
                cost five times the depth-first search it gives way to here. The field and protocol pairs stay below
                the limit but for a few queries (bench/scaling.md, "The best-first heap"). */
            static constexpr std::size_t BEST_FIRST_OPEN_LIMIT = 4096;

            /** \brief Depth first from here on: the open pairs as a stack, the least bound on top. */
            void goDepthFirst()
            {
                std::sort(open_.begin(), open_.end(), [](const Open &x, const Open &y) { return x.bound > y.bound; });
                bestFirst_ = false;
            }

            /** \brief The triangle pair (ta, tb) at exact distance \e d (witnesses \e onA, \e onB) becomes the best
                if it is closer by more than the slack, or ties within it and ranks first (the canonical tie rule);
                returns whether it did. */
            bool offer(std::uint32_t ta, std::uint32_t tb, double d, const Eigen::Vector3d &onA,
                       const Eigen::Vector3d &onB)
            {
                const bool closer = d < result_.distance - slack_;
                const bool tieWins =
                    !closer && d <= result_.distance + slack_ && (ta < bestA_ || (ta == bestA_ && tb < bestB_));
                if (!closer && !tieWins)
                    return false;
                bestA_ = ta;
                bestB_ = tb;
                result_.distance = d;
                result_.found = true;
                result_.triangleA = ta;
                result_.triangleB = tb;
                result_.onA = onA;
                result_.onB = onB;
                bestAxis_ = d > 0.0 ? Eigen::Vector3d((onB - onA) / (onB - onA).norm()) : Eigen::Vector3d::Zero();
                return true;
            }

            /** \brief Test every triangle pair of two leaves; returns a lower bound on the leaf pair's distance
                (the least of each triangle pair's gap or distance; \e boxBound if the early stop cut it short) and,
                for a single pair of triangles, in \e axis the axis that gave it (zero if none). */
            double leaves(const TriangleBvh::Node &na, const TriangleBvh::Node &nb, double boxBound,
                          Eigen::Vector3d &axis)
            {
                const Mesh &ma = a_.mesh();
                double least = std::numeric_limits<double>::infinity();
                axis.setZero();
                Eigen::Vector3d onA, onB;
                for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
                {
                    const std::uint32_t tb = b_.order()[j];
                    // B's triangle placed once per query (it meets many of A's leaves).
                    const std::array<Eigen::Vector3d, 4> &placed = X_.placeTriangle(b_, tb);
                    const Eigen::Vector3d *pb = placed.data();
                    const Eigen::Vector3d &normalB = placed[3];
                    for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
                    {
                        const std::uint32_t ta = a_.order()[i];
                        if (seedAxis_ && ta == seedA_ && tb == seedB_)
                        {
                            // The caller's seed: its exact distance is known (and is the best unless a closer
                            // pair was found, which then ranks it out).
                            if (seedDistance_ < least)
                            {
                                least = seedDistance_;
                                axis = *seedAxis_;
                            }
                            continue;
                        }
                        const Triangle &fa = ma.triangles[ta];
                        const Eigen::Vector3d pa[3] = {ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]]};
                        // Cheap exact bounds first: separation along either triangle's normal, then along the
                        // nine edge-cross axes. A pair that ranks before the best one (the canonical tie rule) wins
                        // a tie, so it is pruned only above the best distance plus the slack (rounding never prunes
                        // a pair at exactly the best distance's value); a pair that ranks after it must be strictly
                        // closer, by more than the slack, so a gap at the best distance minus the slack already
                        // rules it out: the triangles that share a vertex or an edge closest to the other body,
                        // which all tie, then cost no exact test.
                        const double limit = this->limit(ta, tb);
                        const Separation s = triangleSeparation(a_.normals()[ta], normalB, pa, pb, limit,
                                                                bestAxis_.isZero() ? nullptr : &bestAxis_);
                        if (s.gap > limit)
                        {
                            if (s.gap < least)
                            {
                                least = s.gap;
                                axis = s.axis;
                            }
                            continue;
                        }
                        ++result_.triangleTests;
                        const double d = triangleDistance(pa[0], pa[1], pa[2], pb[0], pb[1], pb[2], onA, onB);
                        if (d < least)
                        {
                            least = d;
                            // The closest points' direction separates the triangles by exactly d.
                            axis =
                                d > 0.0 ? Eigen::Vector3d((onB - onA) / (onB - onA).norm()) : Eigen::Vector3d::Zero();
                        }
                        if (offer(ta, tb, d, onA, onB) && d <= stopBelow_)
                        {
                            stopped_ = true;
                            axis.setZero();
                            return boxBound;  // pairs of these leaves may be left untested
                        }
                    }
                }
                if (na.count != 1 || nb.count != 1)
                    axis.setZero();  // one axis per pair of triangles
                return least;
            }

            /** \brief Split the pair and push its children, the nearest on top; children that cannot beat the
                best so far are pruned (kept in the front) at once. While the search is best first (no bound to prune
                with yet), a pair of inner nodes of like size (spheres within a factor of BOTH_RATIO) has both split
                at once, into the four pairs of their children: the first pair of leaves, and with it the first
                bound, comes sooner. Otherwise the node of larger sphere alone, so that once a bound prunes, the pairs
                of its children with the other whole node are pruned before they are split further. Measured:
                bench/queries.md, "Both nodes split while searching best first". */
            void descend(const PairEntry &e, const TriangleBvh::Node &na, const TriangleBvh::Node &nb)
            {
                std::array<PairEntry, 4> children;
                std::size_t count = 0;
                constexpr double BOTH_RATIO = 4.0;
                if (bestFirst_ && !na.isLeaf() && !nb.isLeaf() &&
                    std::max(na.radius, nb.radius) < BOTH_RATIO * std::min(na.radius, nb.radius))
                    for (std::uint32_t i : {na.first, na.first + 1})
                        for (std::uint32_t j : {nb.first, nb.first + 1})
                            children[count++] = {i, j};
                else if (splitA(na, nb))
                {
                    children[count++] = {na.first, e.b};
                    children[count++] = {na.first + 1, e.b};
                }
                else
                {
                    children[count++] = {e.a, nb.first};
                    children[count++] = {e.a, nb.first + 1};
                }
                // A child above the best so far is pruned whatever its exact bound: stop computing it there. The
                // children sorted by bound, the greatest first (pushed first: the nearest ends on top).
                // Two pairs at a time (lowerBounds(): one vector register's two lanes). Without a front to keep, by
                // the gap along the nearest direction alone: the gap on B's faces, worked out for both lanes when
                // either is not pruned, cost more than the pairs it pruned (bench/queries.md, "Box-pair bounds two at
                // a time"). A front keeps both, as before: its entries' bounds are reused at later poses.
                // (Called through a pointer: two calls here made the traversal's loop too long to inline its pushes.)
                const auto boundTwo = record_ ? &lowerBounds<true> : &lowerBounds<false>;
                std::array<double, 4> bounds;
                for (std::size_t k = 0; k < count; k += 2)
                    boundTwo(a_.nodes()[children[k].a], b_.nodes()[children[k].b], a_.nodes()[children[k + 1].a],
                             b_.nodes()[children[k + 1].b], X_, exitAbove(), &bounds[k]);
                for (std::size_t k = 1; k < count; ++k)
                    for (std::size_t m = k; m > 0 && bounds[m - 1] < bounds[m]; --m)
                    {
                        std::swap(bounds[m - 1], bounds[m]);
                        std::swap(children[m - 1], children[m]);
                    }
                result_.boxTests += count;
                for (std::size_t k = 0; k < count; ++k)
                {
                    const PairEntry &c = children[k];
                    const double cb = bounds[k];
                    if (!(cb <= enough()))
                    {
                        keep(c, cb);
                        continue;
                    }
                    // The rank orders the heap only.
                    open_.push_back({cb, bestFirst_ ? rank(cb, a_.nodes()[c.a], b_.nodes()[c.b]) : cb, c});
                    if (bestFirst_)
                        std::push_heap(open_.begin(), open_.end(), farther);
                }
            }

            const TriangleBvh &a_, &b_;
            const RelativePose &X_;
            const double slack_, stopBelow_;
            BvhDistanceResult &result_;
            std::uint32_t bestA_, bestB_;  // UINT32_MAX: no pair yet (any real pair ranks before it)
            std::vector<BvhFront::Entry> *record_;
            const double motion_;
            const std::uint32_t stamp_;
            std::vector<Open> &open_;
            bool bestFirst_{true};
            std::size_t budget_{0};
            const std::uint32_t seedA_, seedB_;
            const double seedDistance_;
            const Eigen::Vector3d *seedAxis_{nullptr};
            Eigen::Vector3d bestAxis_{Eigen::Vector3d::Zero()};  // the best pair's witness direction (zero: none)
            bool stopped_{false};
        };

        /** \brief Re-test the entries of a valid distance front at the pose \e X_AB, \e motion (B's displacement
            summed since the front was written) later: an entry is kept while key - motion stays above the best so
            far; else while its bound lowered by its own node's displacement since it was computed does (re-based on
            this pose); else while the gap along its separating axis does; else the traversal runs below it and its
            sub-front (in traversal's record) replaces it. Returns the number of entries re-tested in full. */
        std::size_t retestFront(BvhFront &front, DistanceTraversal &traversal, const TriangleBvh &b,
                                const Eigen::Isometry3d &X_AB, double motion, std::uint32_t stamp)
        {
            const std::size_t count = front.entries.size();
            std::vector<BvhFront::Entry> &next = front.next;
            const double pad = 1e-12 * motion;  // the roundoff of the summed motion
            std::array<std::optional<StepMotion>, BvhFront::POSES> slots;
            std::size_t retested = 0;
            // An entry is still proven beyond the best when key - motion - pad > enough(): the scan skips those in
            // a tight loop against that threshold, worked out again whenever the best changes.
            double threshold = traversal.enough() + motion + pad;
            for (std::size_t i = 0; i < count; threshold = traversal.enough() + motion + pad, ++i)
            {
                while (i < count && front.entries[i].key > threshold)
                    ++i;
                if (i == count || traversal.stopped())
                    break;
                BvhFront::Entry &e = front.entries[i];
                // Its own node's displacement since its bound was computed, if that pose is still known (the
                // motion's difference worked out once per pose).
                const std::uint32_t age = stamp - e.stamp;
                if (age < BvhFront::POSES)
                {
                    const std::uint32_t slot = e.stamp % BvhFront::POSES;
                    if (!slots[slot])
                        slots[slot].emplace(front.poses[slot], X_AB, b.nodes()[0]);
                    // Its bound now, kept re-based on this pose (so the next queries' scan keeps it without any
                    // work); the extra pad covers the roundoff of taking the motion out and back in.
                    const double now = e.key - front.motions[slot] - slots[slot]->displacement(b.nodes()[e.b]) - pad -
                                       1e-15 * std::abs(e.key);
                    if (now > traversal.enough())
                    {
                        e.key = now + motion;
                        e.stamp = stamp;
                        continue;
                    }
                }
                // A pair of leaves: its gap along the axis that separated it last time.
                double gap;
                if (traversal.axisProves(e, gap))
                {
                    e.key = gap + motion;
                    e.stamp = stamp;
                    ++front.axisKept;
                    continue;
                }
                ++retested;
                const PairEntry pair{e.a, e.b};
                traversal.run(pair, traversal.bound(pair));
                // Its sub-front (at least one entry) replaces it: the last one in its place, the others appended.
                front.entries[i] = next.back();
                next.pop_back();
            }
            return retested;
        }
    }  // namespace

    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA, std::uint32_t seedB,
                     BvhFront *front, const Eigen::Vector3d *seedAxis, std::size_t budget)
    {
        result = BvhDistanceResult();
        result.distance = upperBound;
        if (a.nodes().empty() || b.nodes().empty())
        {
            if (front)
                front->valid = false;
            return;
        }
        const RelativePose X(X_AB, b);
        // Distances within this slack of each other are ties, broken by the smaller triangle pair (see the header).
        const TriangleBvh::Node &rootA = a.nodes()[0], &rootB = b.nodes()[0];
        const double slack =
            1e-12 * (rootA.center.norm() + rootA.radius + rootB.center.norm() + rootB.radius + X.t.norm());
        if (!front || budget > 0)
        {
            DistanceTraversal traversal(a, b, X, slack, stopBelow, result, seedA, seedB, nullptr, 0.0, 0);
            traversal.knowSeed(seedAxis);
            traversal.setBudget(budget);
            traversal.run({0u, 0u}, traversal.bound({0u, 0u}));
            return;
        }

        const std::uint32_t stamp = ++front->stamp;
        // Not a nearby pose (B moved further than the distance sought since the last query, as between a planner's
        // unrelated samples): no certificate carries over, and none is worth writing; a traversal from the roots.
        const double step = front->started ? motionBound(b, front->poses[(stamp - 1) % BvhFront::POSES], X_AB) : 0.0;
        front->started = true;
        if (step > upperBound || (!front->valid && front->wait > 0))
        {
            if (!front->valid && front->wait > 0)
                --front->wait;
            ++front->incoherent;
            front->valid = false;
            front->poses[stamp % BvhFront::POSES] = X_AB;
            DistanceTraversal traversal(a, b, X, slack, stopBelow, result, seedA, seedB, nullptr, 0.0, stamp);
            traversal.knowSeed(seedAxis);
            traversal.run({0u, 0u}, traversal.bound({0u, 0u}));
            return;
        }
        if (front->valid)
        {
            // Every entry's bound falls by at most B's displacement since it was computed.
            const double motion = front->motion + step;
            front->next.clear();
            DistanceTraversal traversal(a, b, X, slack, stopBelow, result, seedA, seedB, &front->next, motion, stamp);
            traversal.knowSeed(seedAxis);
            const std::size_t retested = retestFront(*front, traversal, b, X_AB, motion, stamp);
            front->reused += front->entries.size() - retested;
            front->retested += retested;
            front->entries.insert(front->entries.end(), front->next.begin(), front->next.end());
            front->motion = motion;
            front->poses[stamp % BvhFront::POSES] = X_AB;
            front->motions[stamp % BvhFront::POSES] = motion;
            // Rebuild next time when the front has grown well past a fresh one (a cut refined for motions that have
            // passed), or this motion made more full re-tests than half a fresh front: the front does not pay.
            afterUse(*front, front->entries.size() <= BvhFront::FRONT_GROWTH * front->freshSize + 16 &&
                                 retested <= front->freshSize / 2 + 16);
            return;
        }
        front->uses = 0;
        ++front->rebuilds;
        front->entries.clear();
        DistanceTraversal traversal(a, b, X, slack, stopBelow, result, seedA, seedB, &front->entries, 0.0, stamp);
        traversal.knowSeed(seedAxis);
        traversal.run({0u, 0u}, traversal.bound({0u, 0u}));
        front->motion = 0.0;
        front->poses[stamp % BvhFront::POSES] = X_AB;
        front->motions[stamp % BvhFront::POSES] = 0.0;
        front->freshSize = front->entries.size();
        front->valid = true;
    }
}  // namespace meshgap
