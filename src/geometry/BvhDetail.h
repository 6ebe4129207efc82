#ifndef MESHGAP_GEOMETRY_BVH_DETAIL_H
#define MESHGAP_GEOMETRY_BVH_DETAIL_H

// What the traversals over triangle BVHs share (src/geometry/Bvh*.cpp): box bounds, the relative pose, triangle
// separation, the traversal stacks and the front bookkeeping. Internal: not installed, not part of the API.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/geometry/BoxBound.h"
#include "meshgap/geometry/TriangleBvh.h"

namespace meshgap
{
    namespace bvh
    {
        /** \brief A node of B placed in A's frame at one query's pose: its box axes and its centre. */
        struct PlacedNode
        {
            Eigen::Matrix3d axes;
            Eigen::Vector3d center;
        };

        /** \brief This thread's nodes of B placed at the current query's pose, each worked out at its first use in
            the query (a node meets many of A's) and stamped with the query it belongs to: an entry stamped by another
            query (an earlier one, or one on another tree) is worked out again. The capacity is kept across queries:
            once warm, a query allocates nothing. */
        struct PlacementCache
        {
            std::vector<PlacedNode> placed;
            std::vector<std::uint32_t> stamps;
            /** \brief B's triangles placed likewise (the distance traversal's leaves): corners, then the normal. */
            std::vector<std::array<Eigen::Vector3d, 4>> corners;
            std::vector<std::uint32_t> cornerStamps;
            std::uint32_t stamp{0};

            static PlacementCache &ofThisThread()
            {
                thread_local PlacementCache cache;
                return cache;
            }
            /** \brief A new query over \e nodes nodes and \e triangles triangles of B: its stamp. */
            std::uint32_t begin(std::size_t nodes, std::size_t triangles)
            {
                if (stamps.size() < nodes)
                {
                    stamps.resize(nodes, 0u);
                    placed.resize(nodes);
                }
                if (cornerStamps.size() < triangles)
                {
                    cornerStamps.resize(triangles, 0u);
                    corners.resize(triangles);
                }
                if (++stamp == 0)  // wrapped around: no entry may look current
                {
                    std::fill(stamps.begin(), stamps.end(), 0u);
                    std::fill(cornerStamps.begin(), cornerStamps.end(), 0u);
                    stamp = 1;
                }
                return stamp;
            }
        };

        /** \brief The pose of B in A, and B's nodes placed at it once per query (place()). */
        class RelativePose
        {
        public:
            Eigen::Matrix3d R;
            Eigen::Vector3d t;
            /** \brief The pose \e X of tree \e b in A's frame. */
            RelativePose(const Eigen::Isometry3d &X, const TriangleBvh &b)
                : R(X.linear()),
                  t(X.translation()),
                  nodes_(b.nodes().data()),
                  cache_(PlacementCache::ofThisThread()),
                  stamp_(cache_.begin(b.nodes().size(), b.mesh().triangles.size()))
            {
            }
            RelativePose(const RelativePose &) = delete;
            RelativePose &operator=(const RelativePose &) = delete;

            /** \brief Node \e n of B placed in A's frame (valid until the next call). */
            const PlacedNode &place(const TriangleBvh::Node &n) const
            {
                const auto i = static_cast<std::size_t>(&n - nodes_);
                PlacedNode &p = cache_.placed[i];
                if (cache_.stamps[i] != stamp_)
                {
                    cache_.stamps[i] = stamp_;
                    p.center = R * n.center + t;
                    if (n.aligned)
                        p.axes = R;
                    else
                        p.axes.noalias() = R * n.axes;
                }
                return p;
            }

            /** \brief Triangle \e triangle of B (\e tree's) placed in A's frame: its three corners (R v + t) and its
                unit normal (R n), worked out at its first use in the query. */
            const std::array<Eigen::Vector3d, 4> &placeTriangle(const TriangleBvh &tree, std::uint32_t triangle) const
            {
                std::array<Eigen::Vector3d, 4> &p = cache_.corners[triangle];
                if (cache_.cornerStamps[triangle] != stamp_)
                {
                    cache_.cornerStamps[triangle] = stamp_;
                    const Mesh &m = tree.mesh();
                    for (int k = 0; k < 3; ++k)
                        p[k] = R * m.vertices[m.triangles[triangle][k]] + t;
                    p[3] = R * tree.normals()[triangle];
                }
                return p;
            }

        private:
            const TriangleBvh::Node *nodes_;
            PlacementCache &cache_;
            const std::uint32_t stamp_;
        };

        /** \brief Box \e b (placed by X: \e placed) seen from box \e a: the rotation C from b's box axes to a's and
            the centre offset T along a's axes; an aligned \e a uses the placed node's own (nothing computed, nothing
            copied). */
        struct BoxPair
        {
            Eigen::Matrix3d ownC;
            Eigen::Vector3d ownT;
            const Eigen::Matrix3d *C;
            const Eigen::Vector3d *T;
            BoxPair(const TriangleBvh::Node &a, const PlacedNode &placed, const Eigen::Vector3d &offset)
            {
                if (a.aligned)
                {
                    C = &placed.axes;
                    T = &offset;
                    return;
                }
                ownC.noalias() = a.axes.transpose() * placed.axes;
                ownT.noalias() = a.axes.transpose() * offset;
                C = &ownC;
                T = &ownT;
            }
        };

        /** \brief Lower bound on the distance between anything in box \e a and anything in box \e b (B's frame),
            from the gap along the direction between the boxes' nearest points, then the gaps on b's face axes
            (boxbound::pairBound(), the namespace's two directions); <= 0 means the boxes may touch. Once the first
            exceeds \e enough (the caller prunes above it) it is returned: still a lower bound, just not the better of
            the two. The order by how often each prunes where the caller prunes (the nearest direction alone prunes
            94-99.6 % of the pairs the tests prune, on flat CAD parts and on twisted's slender slanted triangles
            alike); no bounding-sphere test first (it pruned 0.3-2.8 % of the pairs, and its square root cost more than
            it spared on 8 of 9 measured streams); b's face axes rather than a's: bench/README.md, "Instruction
            counts". */
        inline double lowerBound(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                                 double enough = std::numeric_limits<double>::infinity())
        {
            const PlacedNode &placed = X.place(b);
            const Eigen::Vector3d offset = placed.center - a.center;
            return boxbound::pairBound({&a.half, &b.half, a.aligned ? nullptr : &a.axes, &placed.axes, &offset},
                                       enough);
        }

        /** \brief lowerBound() of the node pairs (a0, b0) and (a1, b1) at once (boxbound::pairBounds(): both in the
            lanes of one vector register): \e out[k] is pair \e k's; with FACES false, the gap along the nearest
            direction alone (a lower bound all the same). */
        template <bool FACES = true>
        inline void lowerBounds(const TriangleBvh::Node &a0, const TriangleBvh::Node &b0, const TriangleBvh::Node &a1,
                                const TriangleBvh::Node &b1, const RelativePose &X, double enough, double out[2])
        {
            const PlacedNode &placed0 = X.place(b0);
            const PlacedNode &placed1 = X.place(b1);  // another cache entry (or the same node): placed0 stays valid
            const Eigen::Vector3d offset0 = placed0.center - a0.center, offset1 = placed1.center - a1.center;
            boxbound::pairBounds<FACES>(
                {&a0.half, &b0.half, a0.aligned ? nullptr : &a0.axes, &placed0.axes, &offset0},
                {&a1.half, &b1.half, a1.aligned ? nullptr : &a1.axes, &placed1.axes, &offset1}, enough, out);
        }

        /** \brief The gap between triangles p and q along unit axis \e n, either way round, and that axis pointing
            from p's side to q's (a lower bound on their distance; 0 and no axis when the projections overlap). */
        struct Separation
        {
            double gap{0.0};
            Eigen::Vector3d axis{Eigen::Vector3d::Zero()};

            /** \brief Along \e n of length \e length (gaps divided by it; the axis normalised only if kept). */
            void consider(const Eigen::Vector3d &n, const Eigen::Vector3d *p, const Eigen::Vector3d *q,
                          double length = 1.0)
            {
                const double p0 = n.dot(p[0]), p1 = n.dot(p[1]), p2 = n.dot(p[2]);
                const double q0 = n.dot(q[0]), q1 = n.dot(q[1]), q2 = n.dot(q[2]);
                const double up = (std::min({q0, q1, q2}) - std::max({p0, p1, p2})) / length;    // q beyond p
                const double down = (std::min({p0, p1, p2}) - std::max({q0, q1, q2})) / length;  // p beyond q
                if (up > gap)
                {
                    gap = up;
                    axis = n / length;
                }
                if (down > gap)
                {
                    gap = down;
                    axis = -n / length;
                }
            }
        };

        /** \brief The separating-axis gap of triangles p and q (unit normals \e np and \e nq): along either normal,
            the unit axis \e extra if given, then the nine edge-cross axes until one proves more than \e enough (a
            lower bound on their distance; 0 when no axis separates them, as when they intersect). */
        inline Separation triangleSeparation(const Eigen::Vector3d &np, const Eigen::Vector3d &nq,
                                             const Eigen::Vector3d *p, const Eigen::Vector3d *q, double enough,
                                             const Eigen::Vector3d *extra = nullptr)
        {
            Separation s;
            s.consider(np, p, q);
            s.consider(nq, p, q);
            if (extra && !(s.gap > enough))
                s.consider(*extra, p, q);
            for (int m = 0; m < 9 && !(s.gap > enough); ++m)
            {
                const Eigen::Vector3d n = (p[(m / 3 + 1) % 3] - p[m / 3]).cross(q[(m % 3 + 1) % 3] - q[m % 3]);
                const double length = n.norm();
                if (length > 0.0)  // else parallel edges: no axis
                    s.consider(n, p, q, length);
            }
            return s;
        }

        struct PairEntry
        {
            std::uint32_t a, b;
        };

        /** \brief A traversal stack of this thread, emptied, its capacity kept from earlier calls: once warm, a query
            allocates nothing for it. Each call site has its own \e Site (unique across the files that use it), so no
            traversal ever shares a stack with another one running at the same time (none of them is re-entered). */
        template <typename T, int Site>
        std::vector<T> &threadStack()
        {
            thread_local std::vector<T> stack;
            stack.clear();
            return stack;
        }

        /** \brief Split the pair on the node with the larger sphere (a leaf cannot be split). */
        inline bool splitA(const TriangleBvh::Node &a, const TriangleBvh::Node &b)
        {
            return !a.isLeaf() && (b.isLeaf() || a.radius >= b.radius);
        }

        /** \brief B's motion from an earlier pose \e P to \e X (both B in A's frame), to bound how far the points of a
            node of B moved: nodeMotionBound() with the rotation's part worked out once. */
        struct StepMotion
        {
            Eigen::Matrix3d dR;
            Eigen::Vector3d dt;
            double turn{0.0}, pad{0.0};
            StepMotion(const Eigen::Isometry3d &P, const Eigen::Isometry3d &X, const TriangleBvh::Node &rootB)
                : dR(X.linear() - P.linear()), dt(X.translation() - P.translation())
            {
                const double t = std::sqrt(std::max(0.0, 3.0 - P.linear().cwiseProduct(X.linear()).sum()));
                turn = t + 1e-7 * (t > 0.0);
                pad = 1e-12 * (rootB.center.norm() + rootB.radius + P.translation().norm() + X.translation().norm());
            }
            double displacement(const TriangleBvh::Node &n) const
            {
                return ((dR * n.center + dt).norm() + n.radius * turn) * (1.0 + 1e-12) + pad;
            }
        };

        /** \brief After \e front answered a query: whether it stays valid (\e lasts); when fronts keep failing
            within two queries (motions as large as the gaps they hold), the next traversals from the roots write
            none for a while (BvhFront::backoff). */
        inline void afterUse(BvhFront &front, bool lasts)
        {
            front.valid = lasts;
            ++front.uses;
            if (!lasts && front.uses <= 2)
                front.wait = front.backoff = std::min(2 * front.backoff + 1, 64u);  // it did not pay: wait
            else if (front.uses > 2)
                front.backoff = 0;
        }
    }  // namespace bvh
}  // namespace meshgap

#endif
