#include "meshgap/geometry/TriangleBvh.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>

#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        /** \brief The box of the triangles order[first, first + count) of \e mesh: the tighter of the axis-aligned
            box and the box along the principal axes of their corners (kept only if clearly smaller, an aligned box
            making cheaper tests), with the bounding sphere about its centre; padded against roundoff. */
        TriangleBvh::Node fitNode(const Mesh &mesh, const std::vector<std::uint32_t> &order, std::uint32_t first,
                                  std::uint32_t count)
        {
            Eigen::AlignedBox3d box;
            Eigen::Vector3d mean = Eigen::Vector3d::Zero();
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                {
                    box.extend(mesh.vertices[v]);
                    mean += mesh.vertices[v];
                }
            mean /= 3.0 * count;
            TriangleBvh::Node node;
            node.center = box.center();
            node.half = 0.5 * box.sizes();
            // The principal box: along the eigenvectors of the corners' covariance. Kept if clearly smaller (an
            // aligned box makes cheaper tests).
            Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                {
                    const Eigen::Vector3d d = mesh.vertices[v] - mean;
                    covariance += d * d.transpose();
                }
            Eigen::Matrix3d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors();
            if (axes.determinant() < 0.0)
                axes.col(2) = -axes.col(2);
            Eigen::AlignedBox3d principal;
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                    principal.extend(Eigen::Vector3d(axes.transpose() * mesh.vertices[v]));
            const Eigen::Vector3d principalHalf = 0.5 * principal.sizes();
            auto measure = [](const Eigen::Vector3d &h) { return h.prod() + 1e-3 * h.squaredNorm() * h.minCoeff(); };
            if (axes.allFinite() && measure(principalHalf) < 0.8 * measure(node.half))
            {
                node.axes = axes;
                node.aligned = false;
                node.center = axes * principal.center();
                node.half = principalHalf;
            }
            double r2 = 0.0;
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                    r2 = std::max(r2, (mesh.vertices[v] - node.center).squaredNorm());
            // Rounding slack: bounds must never cut into the geometry they bound (a rotated box's corners are
            // projected with roundoff of a few 1e-16 of the coordinates).
            const double slack = 1e-12 * (node.center.norm() + node.half.norm() + mean.norm());
            node.radius = std::sqrt(r2) + slack;
            node.half.array() += slack;
            return node;
        }

        /** \brief Split the triangles order[first, first + count) in two by the surface area heuristic: along each
            of the node's box \e axes, the triangles sorted by centroid, the cut that minimises the sum over both
            sides of (surface area of the side's box along \e axes) x (its triangle count). The triangles are
            reordered, the first side first; returns its size (between 1 and count - 1). Boxes that fit their
            triangles tightly rather than halves of equal counts: on meshes of unequal density (a tube of slivers
            with capped ends, a fine part welded to a coarse one) far fewer box pairs overlap between two trees. */
        std::uint32_t splitBySurfaceArea(const Mesh &mesh, const std::vector<Eigen::Vector3d> &centroid,
                                         const Eigen::Matrix3d &axes, std::uint32_t first, std::uint32_t count,
                                         std::vector<std::uint32_t> &order)
        {
            // Each triangle's box and centroid along the node's axes, once.
            std::vector<Eigen::AlignedBox3d> boxes(count);
            std::vector<Eigen::Vector3d> centre(count);
            for (std::uint32_t k = 0; k < count; ++k)
            {
                for (std::uint32_t v : mesh.triangles[order[first + k]])
                    boxes[k].extend(Eigen::Vector3d(axes.transpose() * mesh.vertices[v]));
                centre[k] = axes.transpose() * centroid[order[first + k]];
            }
            auto area = [](const Eigen::AlignedBox3d &box)
            {
                const Eigen::Vector3d d = box.sizes();
                return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
            };
            // Sorted along an axis: by the centroid's coordinate, ties by triangle index (deterministic).
            std::vector<std::pair<double, std::uint32_t>> sorted(count), bestSorted;
            auto sortAlong = [&](int axis, std::vector<std::pair<double, std::uint32_t>> &keys)
            {
                for (std::uint32_t k = 0; k < count; ++k)
                    keys[k] = {centre[k][axis], k};
                std::sort(keys.begin(), keys.end(),
                          [&](const auto &x, const auto &y)
                          {
                              return x.first < y.first ||
                                     (x.first == y.first && order[first + x.second] < order[first + y.second]);
                          });
            };
            std::vector<double> leftArea(count);
            double bestCost = std::numeric_limits<double>::infinity();
            std::uint32_t bestCut = count / 2;
            for (int axis = 0; axis < 3; ++axis)
            {
                sortAlong(axis, sorted);
                Eigen::AlignedBox3d left, right;
                for (std::uint32_t k = 0; k < count; ++k)
                    leftArea[k] = area(left.extend(boxes[sorted[k].second]));
                bool better = false;
                for (std::uint32_t k = count - 1; k >= 1; --k)
                {
                    // The first k triangles on one side, the rest on the other.
                    const double cost = leftArea[k - 1] * k + area(right.extend(boxes[sorted[k].second])) * (count - k);
                    if (cost < bestCost)
                    {
                        bestCost = cost;
                        bestCut = k;
                        better = true;
                    }
                }
                if (better || bestSorted.empty())
                    bestSorted.swap(sorted);
                if (sorted.size() != count)
                    sorted.resize(count);
            }
            std::vector<std::uint32_t> reordered(count);
            for (std::uint32_t k = 0; k < count; ++k)
                reordered[k] = order[first + bestSorted[k].second];
            std::copy(reordered.begin(), reordered.end(), order.begin() + first);
            return bestCut;
        }
    }  // namespace

    TriangleBvh::TriangleBvh(const Mesh &mesh) : mesh_(&mesh)
    {
        const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
        order_.resize(n);
        std::vector<Eigen::Vector3d> centroid(n);
        for (std::uint32_t t = 0; t < n; ++t)
        {
            order_[t] = t;
            const Triangle &f = mesh.triangles[t];
            centroid[t] = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
        }
        normals_.resize(n);
        for (std::uint32_t t = 0; t < n; ++t)
        {
            const Triangle &f = mesh.triangles[t];
            const Eigen::Vector3d c =
                (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
            const double length = c.norm();
            normals_[t] = length > 0.0 ? Eigen::Vector3d(c / length) : Eigen::Vector3d::Zero();  // zero: no bound
        }
        if (n == 0)
            return;
        nodes_.reserve(2 * n / LEAF_SIZE + 2);
        // Build top-down; each stack entry is (node index, first, count).
        struct Work
        {
            std::uint32_t node, first, count;
        };
        nodes_.push_back(Node());
        std::vector<Work> stack{{0u, 0u, n}};
        while (!stack.empty())
        {
            const Work w = stack.back();
            stack.pop_back();
            Node node = fitNode(mesh, order_, w.first, w.count);
            if (w.count <= LEAF_SIZE)
            {
                node.first = w.first;
                node.count = w.count;
                nodes_[w.node] = node;
                continue;
            }
            const std::uint32_t half = splitBySurfaceArea(mesh, centroid, node.axes, w.first, w.count, order_);
            const auto left = static_cast<std::uint32_t>(nodes_.size());
            nodes_.push_back(Node());
            nodes_.push_back(Node());
            node.first = left;
            node.count = 0;
            nodes_[w.node] = node;
            stack.push_back({left, w.first, half});
            stack.push_back({left + 1, w.first + half, w.count - half});
        }
    }

    namespace
    {
        /** \brief The pose of B in A with |R| precomputed (padded so parallel axes never make a bound too large). */
        struct RelativePose
        {
            Eigen::Matrix3d R, absR;
            Eigen::Vector3d t;
            explicit RelativePose(const Eigen::Isometry3d &X)
                : R(X.linear()), absR(R.cwiseAbs().array() + 1e-12), t(X.translation())
            {
            }
        };

        /** \brief Box \e b (placed by X) seen from box \e a: the rotation C from b's box axes to a's, |C| padded
            (so parallel axes never make a bound too large), and the centre offset T along a's axes. Two aligned
            boxes use X's own (nothing computed, nothing copied). */
        struct BoxPair
        {
            Eigen::Matrix3d ownC, ownAbsC;
            Eigen::Vector3d ownT;
            const Eigen::Matrix3d *C, *absC;
            const Eigen::Vector3d *T;
            BoxPair(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                    const Eigen::Vector3d &offset)
            {
                if (a.aligned && b.aligned)
                {
                    C = &X.R;
                    absC = &X.absR;
                    T = &offset;
                    return;
                }
                ownC = a.axes.transpose() * (X.R * b.axes);
                ownAbsC = ownC.cwiseAbs().array() + 1e-12;
                ownT = a.aligned ? offset : Eigen::Vector3d(a.axes.transpose() * offset);
                C = &ownC;
                absC = &ownAbsC;
                T = &ownT;
            }
        };

        /** \brief The distance bound given by the gaps \e g of two boxes' projections on three orthonormal axes
            (one box's face axes): a point pair's offset has a component of at least g_i along each axis i where
            g_i > 0, so its length is at least the norm of the positive gaps (for boxes apart diagonally, up to
            sqrt(3) times the largest gap alone). The largest gap, <= 0, when the projections overlap on all three. */
        double gapOnAxes(const Eigen::Vector3d &g)
        {
            const double largest = g.maxCoeff();
            return largest > 0.0 ? g.cwiseMax(0.0).norm() : largest;
        }

        /** \brief Lower bound on the distance between anything in box \e a and anything in box \e b (B's frame),
            from the sphere gap (cheapest, and rotation-free), then the face-axis gaps of each box (gapOnAxes());
            <= 0 means the boxes may touch. Once a partial bound exceeds \e enough (the caller prunes above it) that
            one is returned: still a lower bound, just not the best of the three. */
        double lowerBound(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                          double enough = std::numeric_limits<double>::infinity())
        {
            const Eigen::Vector3d offset = X.R * b.center + X.t - a.center;
            double bound = offset.norm() - a.radius - b.radius;
            if (bound > enough)
                return bound;
            const BoxPair P(a, b, X, offset);
            const Eigen::Vector3d rb = *P.absC * b.half;  // B's box projected on A's axes
            bound = std::max(bound, gapOnAxes(P.T->cwiseAbs() - a.half - rb));
            if (bound > enough)
                return bound;
            const Eigen::Vector3d s = P.C->transpose() * *P.T;        // T on B's axes
            const Eigen::Vector3d ra = P.absC->transpose() * a.half;  // A's box projected on B's axes
            bound = std::max(bound, gapOnAxes(s.cwiseAbs() - ra - b.half));
            return bound;
        }

        /** \brief Full separating-axis test of the two oriented boxes (15 axes): true if they are disjoint. */
        bool separated(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X)
        {
            const Eigen::Vector3d offset = X.R * b.center + X.t - a.center;
            if (offset.norm() > a.radius + b.radius)
                return true;
            const BoxPair P(a, b, X, offset);
            const Eigen::Vector3d &T = *P.T;
            const Eigen::Matrix3d &C = *P.C, &absC = *P.absC;
            if (((T.cwiseAbs() - a.half - absC * b.half).array() > 0.0).any())
                return true;
            if ((((C.transpose() * T).cwiseAbs() - absC.transpose() * a.half - b.half).array() > 0.0).any())
                return true;
            const Eigen::Vector3d &ea = a.half, &eb = b.half;
            for (int i = 0; i < 3; ++i)
            {
                const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
                for (int j = 0; j < 3; ++j)
                {
                    const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                    const double ra = ea[i1] * absC(i2, j) + ea[i2] * absC(i1, j);
                    const double rb = eb[j1] * absC(i, j2) + eb[j2] * absC(i, j1);
                    if (std::abs(T[i2] * C(i1, j) - T[i1] * C(i2, j)) > ra + rb)
                        return true;
                }
            }
            return false;
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

        /** \brief The gap of triangles p and q along \e axis (unit, from p's side to q's): may be negative. */
        double gapAlong(const Eigen::Vector3d &axis, const Eigen::Vector3d *p, const Eigen::Vector3d *q)
        {
            return std::min({axis.dot(q[0]), axis.dot(q[1]), axis.dot(q[2])}) -
                   std::max({axis.dot(p[0]), axis.dot(p[1]), axis.dot(p[2])});
        }

        /** \brief The separating-axis gap of triangles p and q (unit normals \e np and \e nq): along either normal,
            the unit axis \e extra if given, then the nine edge-cross axes until one proves more than \e enough (a
            lower bound on their distance; 0 when no axis separates them, as when they intersect). */
        Separation triangleSeparation(const Eigen::Vector3d &np, const Eigen::Vector3d &nq, const Eigen::Vector3d *p,
                                      const Eigen::Vector3d *q, double enough,
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

        /** \brief A traversal stack of this thread, emptied, its capacity kept from earlier calls: once warm, a query
            allocates nothing for it. Each call site has its own \e Site, so no traversal ever shares a stack with
            another one running at the same time (none of them is re-entered). */
        template <typename T, int Site>
        std::vector<T> &threadStack()
        {
            thread_local std::vector<T> stack;
            stack.clear();
            return stack;
        }

        /** \brief Split the pair on the node with the larger sphere (a leaf cannot be split). */
        bool splitA(const TriangleBvh::Node &a, const TriangleBvh::Node &b)
        {
            return !a.isLeaf() && (b.isLeaf() || a.radius >= b.radius);
        }

        /** \brief Push the two children of pair \e e (nodes \e na, \e nb) split as splitA() says. */
        void pushChildren(std::vector<PairEntry> &stack, const PairEntry &e, const TriangleBvh::Node &na,
                          const TriangleBvh::Node &nb)
        {
            if (splitA(na, nb))
            {
                stack.push_back({na.first, e.b});
                stack.push_back({na.first + 1, e.b});
            }
            else
            {
                stack.push_back({e.a, nb.first});
                stack.push_back({e.a, nb.first + 1});
            }
        }
    }  // namespace

    double nodeMotionBound(const Eigen::Vector3d &center, double radius, const Eigen::Isometry3d &from,
                           const Eigen::Isometry3d &to)
    {
        const Eigen::Vector3d shift = to * center - from * center;
        // |R_to - R_from|_2 = 2 sin(theta / 2) = sqrt(3 - trace(R_from^T R_to)); the trace is the sum of the
        // elementwise product.
        const double trace = from.linear().cwiseProduct(to.linear()).sum();
        const double turn = std::sqrt(std::max(0.0, 3.0 - trace));
        // Roundoff: in the trace (a few 1e-16, whose square root can reach 1e-8 of a small turn: pad the turn by
        // 1e-7) and in the shift (relative to the coordinates).
        const double scale = center.norm() + radius + from.translation().norm() + to.translation().norm();
        return (shift.norm() + radius * (turn + 1e-7 * (turn > 0.0))) * (1.0 + 1e-12) + 1e-12 * scale;
    }

    double motionBound(const TriangleBvh &b, const Eigen::Isometry3d &from, const Eigen::Isometry3d &to)
    {
        if (b.nodes().empty())
            return 0.0;
        return nodeMotionBound(b.nodes()[0].center, b.nodes()[0].radius, from, to);
    }

    namespace
    {
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
                // near the minimum, wherever it is among many parts, and prunes well); depth first, nearer child
                // first, from there on and whenever a bound is known (no heap to keep: cheaper per pair).
                open_.push_back({startBound, startBound, start});
                bestFirst_ = !(enough() < std::numeric_limits<double>::infinity());
                while (!open_.empty())
                {
                    if (bestFirst_)
                        std::pop_heap(open_.begin(), open_.end(), farther);
                    const PairEntry e = open_.back().pair;
                    const double bound = open_.back().bound;
                    open_.pop_back();
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
                        {
                            // Depth first from here: the open pairs as a stack, the least bound on top.
                            std::sort(open_.begin(), open_.end(),
                                      [](const Open &x, const Open &y) { return x.bound > y.bound; });
                            bestFirst_ = false;
                        }
                        continue;
                    }
                    descend(e, na, nb);
                }
            }

        private:
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
                const Mesh &ma = a_.mesh(), &mb = b_.mesh();
                double least = std::numeric_limits<double>::infinity();
                axis.setZero();
                Eigen::Vector3d pb[3], onA, onB;
                for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
                {
                    const std::uint32_t tb = b_.order()[j];
                    for (int k = 0; k < 3; ++k)
                        pb[k] = X_.R * mb.vertices[mb.triangles[tb][k]] + X_.t;
                    const Eigen::Vector3d normalB = X_.R * b_.normals()[tb];
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

            /** \brief Split the pair and push its children, the nearer one on top; children that cannot beat the
                best so far are pruned (kept in the front) at once. */
            void descend(const PairEntry &e, const TriangleBvh::Node &na, const TriangleBvh::Node &nb)
            {
                PairEntry c1, c2;
                if (splitA(na, nb))
                {
                    c1 = {na.first, e.b};
                    c2 = {na.first + 1, e.b};
                }
                else
                {
                    c1 = {e.a, nb.first};
                    c2 = {e.a, nb.first + 1};
                }
                // A child above the best so far is pruned whatever its exact bound: stop computing it there.
                double b1 = lowerBound(a_.nodes()[c1.a], b_.nodes()[c1.b], X_, exitAbove());
                double b2 = lowerBound(a_.nodes()[c2.a], b_.nodes()[c2.b], X_, exitAbove());
                result_.boxTests += 2;
                if (b1 < b2)
                {
                    std::swap(c1, c2);
                    std::swap(b1, b2);
                }
                for (const auto &[c, cb] : {std::pair<PairEntry, double>{c1, b1}, {c2, b2}})
                    if (cb <= enough())
                    {
                        open_.push_back(
                            {cb, bestFirst_ ? rank(cb, a_.nodes()[c.a], b_.nodes()[c.b]) : cb, c});  // rank: heap only
                        if (bestFirst_)
                            std::push_heap(open_.begin(), open_.end(), farther);
                    }
                    else
                        keep(c, cb);
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
            const std::uint32_t seedA_, seedB_;
            const double seedDistance_;
            const Eigen::Vector3d *seedAxis_{nullptr};
            Eigen::Vector3d bestAxis_{Eigen::Vector3d::Zero()};  // the best pair's witness direction (zero: none)
            bool stopped_{false};
        };
    }  // namespace

    namespace
    {
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

    namespace
    {
        /** \brief After \e front answered a query: whether it stays valid (\e lasts); when fronts keep failing
            within two queries (motions as large as the gaps they hold), the next traversals from the roots write
            none for a while (BvhFront::backoff). */
        void afterUse(BvhFront &front, bool lasts)
        {
            front.valid = lasts;
            ++front.uses;
            if (!lasts && front.uses <= 2)
                front.wait = front.backoff = std::min(2 * front.backoff + 1, 64u);  // it did not pay: wait
            else if (front.uses > 2)
                front.backoff = 0;
        }
    }  // namespace

    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA, std::uint32_t seedB,
                     BvhFront *front, const Eigen::Vector3d *seedAxis)
    {
        result = BvhDistanceResult();
        result.distance = upperBound;
        if (a.nodes().empty() || b.nodes().empty())
        {
            if (front)
                front->valid = false;
            return;
        }
        const RelativePose X(X_AB);
        // Distances within this slack of each other are ties, broken by the smaller triangle pair (see the header).
        const TriangleBvh::Node &rootA = a.nodes()[0], &rootB = b.nodes()[0];
        const double slack =
            1e-12 * (rootA.center.norm() + rootA.radius + rootB.center.norm() + rootB.radius + X.t.norm());
        if (!front)
        {
            DistanceTraversal traversal(a, b, X, slack, stopBelow, result, seedA, seedB, nullptr, 0.0, 0);
            traversal.knowSeed(seedAxis);
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

    namespace
    {
        /** \brief Whether a triangle of leaf \e na and one of leaf \e nb (placed by \e X) intersect; the first such
            pair goes to \e hitA / \e hitB. */
        bool leavesIntersect(const TriangleBvh &a, const TriangleBvh &b, const RelativePose &X,
                             const TriangleBvh::Node &na, const TriangleBvh::Node &nb, std::uint32_t &hitA,
                             std::uint32_t &hitB)
        {
            const Mesh &ma = a.mesh(), &mb = b.mesh();
            Eigen::Vector3d pb[3];
            for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
            {
                const std::uint32_t tb = b.order()[j];
                for (int k = 0; k < 3; ++k)
                    pb[k] = X.R * mb.vertices[mb.triangles[tb][k]] + X.t;
                for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
                {
                    const Triangle &fa = ma.triangles[a.order()[i]];
                    if (trianglesIntersect(ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]], pb[0], pb[1],
                                           pb[2]))
                    {
                        hitA = a.order()[i];
                        hitB = tb;
                        return true;
                    }
                }
            }
            return false;
        }
    }  // namespace

    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, std::uint32_t *hitA,
                    std::uint32_t *hitB)
    {
        if (a.nodes().empty() || b.nodes().empty())
            return false;
        const RelativePose X(X_AB);
        std::vector<PairEntry> &stack = threadStack<PairEntry, 3>();
        stack.push_back({0u, 0u});
        while (!stack.empty())
        {
            const PairEntry e = stack.back();
            stack.pop_back();
            const TriangleBvh::Node &na = a.nodes()[e.a], &nb = b.nodes()[e.b];
            if (separated(na, nb, X))
                continue;
            if (na.isLeaf() && nb.isLeaf())
            {
                std::uint32_t ta, tb;
                if (leavesIntersect(a, b, X, na, nb, ta, tb))
                {
                    if (hitA)
                        *hitA = ta;
                    if (hitB)
                        *hitB = tb;
                    return true;
                }
                continue;
            }
            pushChildren(stack, e, na, nb);
        }
        return false;
    }
    namespace
    {
        /** \brief One collision test below a pair of nodes, depth first, writing a collision front: box pairs
            proven apart by more than \e margin + twice the motion of B's node by \e lookahead (the last step), and
            triangle pairs apart by more than \e margin, go to \e record with their gap (key = gap + motion), so that
            most of the front stays proven after a similar step; a pair of triangles apart by less is kept with gap 0
            (re-tested at the next pose). Pairs of triangles that might touch are decided by trianglesIntersect(). */
        class CollisionTraversal
        {
        public:
            CollisionTraversal(const TriangleBvh &a, const TriangleBvh &b, const RelativePose &X, double margin,
                               const StepMotion &lookahead, std::vector<BvhFront::Entry> *record, double motion,
                               std::uint32_t stamp)
                : a_(a),
                  b_(b),
                  X_(X),
                  margin_(margin),
                  lookahead_(lookahead),
                  record_(record),
                  motion_(motion),
                  stamp_(stamp),
                  stack_(threadStack<PairEntry, 6>())
            {
            }

            /** \brief True at the first intersecting pair of triangles below \e start (hitA / hitB name it). */
            bool run(const PairEntry &start)
            {
                stack_.clear();
                stack_.push_back(start);
                while (!stack_.empty())
                {
                    const PairEntry e = stack_.back();
                    stack_.pop_back();
                    const TriangleBvh::Node &na = a_.nodes()[e.a], &nb = b_.nodes()[e.b];
                    if (na.isLeaf() && nb.isLeaf())
                    {
                        if (leaves(e, na, nb))
                            return true;
                        continue;
                    }
                    const double bound = lowerBound(na, nb, X_);
                    // Kept when apart by the margin plus twice the last step's motion of B's node, so that it stays
                    // proven at the next pose or two.
                    if (bound > margin_ + 2.0 * lookahead_.displacement(nb))
                    {
                        keep(e, bound);
                        continue;
                    }
                    pushChildren(stack_, e, na, nb);
                }
                return false;
            }

            std::uint32_t hitA{0}, hitB{0};

        private:
            void keep(const PairEntry &e, double gap)
            {
                if (record_)
                    record_->push_back({e.a, e.b, stamp_, {0.0f, 0.0f, 0.0f}, gap + motion_});
            }

            /** \brief Every triangle pair of two leaves: the least separating-axis gap goes to the front when all are
                apart by more than the margin; true at an intersecting pair. */
            bool leaves(const PairEntry &e, const TriangleBvh::Node &na, const TriangleBvh::Node &nb)
            {
                const Mesh &ma = a_.mesh(), &mb = b_.mesh();
                double least = std::numeric_limits<double>::infinity();
                Eigen::Vector3d pb[3];
                for (std::uint32_t j = nb.first; j < nb.first + nb.count; ++j)
                {
                    const std::uint32_t tb = b_.order()[j];
                    for (int k = 0; k < 3; ++k)
                        pb[k] = X_.R * mb.vertices[mb.triangles[tb][k]] + X_.t;
                    const Eigen::Vector3d normalB = X_.R * b_.normals()[tb];
                    for (std::uint32_t i = na.first; i < na.first + na.count; ++i)
                    {
                        const std::uint32_t ta = a_.order()[i];
                        const Triangle &fa = ma.triangles[ta];
                        const Eigen::Vector3d pa[3] = {ma.vertices[fa[0]], ma.vertices[fa[1]], ma.vertices[fa[2]]};
                        const Separation s = triangleSeparation(a_.normals()[ta], normalB, pa, pb, margin_);
                        if (!(s.gap > margin_))
                        {
                            if (trianglesIntersect(pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]))
                            {
                                hitA = ta;
                                hitB = tb;
                                return true;
                            }
                            least = 0.0;  // apart, but not by the margin: decided again at the next pose
                        }
                        least = std::min(least, s.gap > margin_ ? s.gap : 0.0);
                    }
                }
                keep(e, least);
                return false;
            }

            const TriangleBvh &a_, &b_;
            const RelativePose &X_;
            const double margin_;
            const StepMotion &lookahead_;
            std::vector<BvhFront::Entry> *record_;
            const double motion_;
            const std::uint32_t stamp_;
            std::vector<PairEntry> &stack_;
        };

    }  // namespace

    namespace
    {
        /** \brief Re-test the entries of a valid collision front at the pose \e X_AB, \e motion (B's displacement
            summed since the front was written) later: an entry is kept while key - motion stays above the margin,
            else while its gap lowered by its own node's displacement since then does (re-based on this pose); else
            the traversal runs below it and its sub-front (in traversal's record) replaces it. True at the first
            intersecting pair (the front is then left as it is). \e retested counts the entries re-tested. */
        bool retestCollisionFront(BvhFront &front, CollisionTraversal &traversal, const TriangleBvh &b,
                                  const Eigen::Isometry3d &X_AB, double margin, double motion, std::uint32_t stamp,
                                  std::size_t &retested)
        {
            const double pad = 1e-12 * motion;  // the roundoff of the summed motion
            std::array<std::optional<StepMotion>, BvhFront::POSES> slots;
            const std::size_t count = front.entries.size();
            for (std::size_t i = 0; i < count; ++i)
            {
                // Still apart by the margin after every motion since its gap was found (key - motion > margin).
                while (i < count && front.entries[i].key > margin + motion + pad)
                    ++i;
                if (i == count)
                    break;
                BvhFront::Entry &e = front.entries[i];
                // Its own node's displacement since then, if that pose is still known; kept re-based on this pose.
                const std::uint32_t age = stamp - e.stamp;
                if (age < BvhFront::POSES && age > 0)
                {
                    const std::uint32_t slot = e.stamp % BvhFront::POSES;
                    if (!slots[slot])
                        slots[slot].emplace(front.poses[slot], X_AB, b.nodes()[0]);
                    const double now = e.key - front.motions[slot] - slots[slot]->displacement(b.nodes()[e.b]) - pad -
                                       1e-15 * std::abs(e.key);
                    if (now > margin)
                    {
                        e.key = now + motion;
                        e.stamp = stamp;
                        continue;
                    }
                }
                ++retested;
                if (traversal.run({e.a, e.b}))
                    return true;
                front.entries[i] = front.next.back();  // its sub-front replaces it (at least one entry)
                front.next.pop_back();
            }
            return false;
        }
    }  // namespace

    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, BvhFront &front,
                    std::uint32_t *hitA, std::uint32_t *hitB)
    {
        if (a.nodes().empty() || b.nodes().empty())
        {
            front.valid = false;
            return false;
        }
        const RelativePose X(X_AB);
        const TriangleBvh::Node &rootA = a.nodes()[0], &rootB = b.nodes()[0];
        // Ten times trianglesIntersect()'s contact tolerance at the largest coordinate scale of any pair: a pair
        // kept apart by more than this is apart for trianglesIntersect() too.
        const double margin = 10.0 * TRIANGLE_CONTACT_TOLERANCE *
                              (rootA.center.norm() + rootA.radius + rootB.center.norm() + rootB.radius + X.t.norm());
        const std::uint32_t stamp = ++front.stamp;
        const double step = front.started ? motionBound(b, front.poses[(stamp - 1) % BvhFront::POSES], X_AB)
                                          : std::numeric_limits<double>::infinity();
        front.started = true;
        front.poses[stamp % BvhFront::POSES] = X_AB;
        auto report = [&](const CollisionTraversal &t)
        {
            front.valid = false;
            if (hitA)
                *hitA = t.hitA;
            if (hitB)
                *hitB = t.hitB;
            return true;
        };
        // The last step's motion, node by node: the lookahead of the pairs written now.
        const bool small = step <= 0.1 * rootB.radius;
        std::optional<StepMotion> last;
        if (small)
            last.emplace(front.poses[(stamp - 1) % BvhFront::POSES], X_AB, rootB);
        if (front.valid && small)
        {
            const double motion = front.motion + step;
            front.next.clear();
            CollisionTraversal traversal(a, b, X, margin, *last, &front.next, motion, stamp);
            std::size_t retested = 0;
            if (retestCollisionFront(front, traversal, b, X_AB, margin, motion, stamp, retested))
                return report(traversal);
            front.reused += front.entries.size() - retested;
            front.retested += retested;
            front.entries.insert(front.entries.end(), front.next.begin(), front.next.end());
            front.motion = motion;
            front.motions[stamp % BvhFront::POSES] = motion;
            afterUse(front, front.entries.size() <= BvhFront::FRONT_GROWTH * front.freshSize + 16 &&
                                retested <= front.freshSize / 2 + 16);
            return false;
        }
        // From the roots. A fresh front is written after a small step (a run of nearby poses, as along a path or a
        // motion: at most a tenth of B's size) unless fronts did not pay lately; between unrelated poses (a
        // planner's samples) none is.
        front.valid = false;
        const bool write = small && front.wait == 0;
        if (small && front.wait > 0)
            --front.wait;
        if (!write)
        {
            ++front.incoherent;
            return bvhCollide(a, b, X_AB, hitA, hitB);
        }
        front.uses = 0;
        ++front.rebuilds;
        front.entries.clear();
        CollisionTraversal traversal(a, b, X, margin, *last, &front.entries, 0.0, stamp);
        if (traversal.run({0u, 0u}))
            return report(traversal);
        front.motion = 0.0;
        front.motions[stamp % BvhFront::POSES] = 0.0;
        front.freshSize = front.entries.size();
        front.valid = true;
        return false;
    }

    void bvhPointDistance(const TriangleBvh &tree, const Eigen::Vector3d &p, double upperBound, double stopBelow,
                          BvhPointResult &result)
    {
        result = BvhPointResult();
        result.distance = upperBound;
        if (tree.nodes().empty())
            return;
        const Mesh &m = tree.mesh();
        // Lower bound on the distance from p to anything in a node: the box distance, or the sphere's.
        auto bound = [&p](const TriangleBvh::Node &n)
        {
            const Eigen::Vector3d d = n.local(p);
            return std::max((d.cwiseAbs() - n.half).cwiseMax(0.0).norm(), d.norm() - n.radius);
        };
        struct Entry
        {
            std::uint32_t node;
            double bound;
        };
        // Depth first, the nearer child first (measured faster here than a best-first heap).
        std::vector<Entry> &stack = threadStack<Entry, 4>();
        stack.push_back({0u, bound(tree.nodes()[0])});
        Eigen::Vector3d on;
        while (!stack.empty())
        {
            const Entry e = stack.back();
            stack.pop_back();
            if (e.bound >= result.distance)
                continue;
            const TriangleBvh::Node &n = tree.nodes()[e.node];
            if (n.isLeaf())
            {
                for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
                {
                    const std::uint32_t t = tree.order()[k];
                    const Triangle &f = m.triangles[t];
                    ++result.triangleTests;
                    const double d = pointTriangleDistance(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]], on);
                    if (d < result.distance)
                    {
                        result.distance = d;
                        result.found = true;
                        result.triangle = t;
                        result.closest = on;
                        if (d <= stopBelow)
                            return;
                    }
                }
                continue;
            }
            Entry near{n.first, bound(tree.nodes()[n.first])}, far{n.first + 1, bound(tree.nodes()[n.first + 1])};
            if (far.bound < near.bound)
                std::swap(near, far);
            if (far.bound < result.distance)
                stack.push_back(far);
            if (near.bound < result.distance)
                stack.push_back(near);
        }
    }

    bool bvhRayWinding(const TriangleBvh &tree, const Eigen::Vector3d &p, const Eigen::Vector3d &direction,
                       int &winding)
    {
        winding = 0;
        if (tree.nodes().empty())
            return true;
        const Eigen::Vector3d d = direction.normalized();
        const Mesh &m = tree.mesh();
        // Signs closer to zero than this (relative to the magnitudes multiplied) are not trusted: roundoff in a
        // triple product is a few 1e-16 of them, so 1e-10 leaves a wide margin.
        constexpr double eps = 1e-10;
        std::vector<std::uint32_t> &stack = threadStack<std::uint32_t, 5>();
        stack.push_back(0u);
        while (!stack.empty())
        {
            const TriangleBvh::Node &n = tree.nodes()[stack.back()];
            stack.pop_back();
            // Slab test of the ray against the node's box (in the box's frame), padded against roundoff.
            const Eigen::Vector3d lo = -n.local(p);
            const Eigen::Vector3d dir = n.aligned ? d : Eigen::Vector3d(n.axes.transpose() * d);
            const Eigen::Vector3d half = n.half.array() + 1e-9 * (n.center.norm() + n.half.norm() + p.norm());
            double enter = 0.0, leave = std::numeric_limits<double>::infinity();
            bool hit = true;
            for (int k = 0; k < 3 && hit; ++k)
            {
                if (dir[k] == 0.0)
                {
                    hit = std::abs(lo[k]) <= half[k];
                    continue;
                }
                double t0 = (lo[k] - half[k]) / dir[k], t1 = (lo[k] + half[k]) / dir[k];
                if (t0 > t1)
                    std::swap(t0, t1);
                enter = std::max(enter, t0);
                leave = std::min(leave, t1);
                hit = enter <= leave;
            }
            if (!hit)
                continue;
            if (!n.isLeaf())
            {
                stack.push_back(n.first);
                stack.push_back(n.first + 1);
                continue;
            }
            for (std::uint32_t k = n.first; k < n.first + n.count; ++k)
            {
                const Triangle &f = m.triangles[tree.order()[k]];
                const Eigen::Vector3d a = m.vertices[f[0]] - p, b = m.vertices[f[1]] - p, c = m.vertices[f[2]] - p;
                // The line p + s d passes the triangle's inside iff these three signed volumes share a sign.
                const double la = a.norm(), lb = b.norm(), lc = c.norm();
                const double u = d.dot(b.cross(c)), v = d.dot(c.cross(a)), w = d.dot(a.cross(b));
                const double tu = eps * lb * lc, tv = eps * lc * la, tw = eps * la * lb;
                const bool allPositive = u > tu && v > tv && w > tw, allNegative = u < -tu && v < -tv && w < -tw;
                if (!allPositive && !allNegative)
                {
                    const bool missed = (u > tu || v > tv || w > tw) && (u < -tu || v < -tv || w < -tw);
                    const bool behind = a.dot(d) < 0.0 && b.dot(d) < 0.0 && c.dot(d) < 0.0;
                    if (missed || behind)
                        continue;
                    return false;  // the line grazes an edge or a corner in front of p: not robust
                }
                // It crosses the plane at s = det(a, b, c) / (u + v + w): in front of p when s > 0.
                const double det = a.dot(b.cross(c));
                if (std::abs(det) <= eps * la * lb * lc)
                    return false;  // p lies on the triangle (to roundoff)
                if ((det > 0.0) == allPositive)
                    winding += allPositive ? 1 : -1;  // d . normal = u + v + w: leaving through the front is +1
            }
        }
        return true;
    }
}  // namespace meshgap
