#include "meshgap/geometry/BvhCollide.h"

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
    using bvh::BoxPair;
    using bvh::lowerBound;
    using bvh::PairEntry;
    using bvh::RelativePose;
    using bvh::Separation;
    using bvh::splitA;
    using bvh::StepMotion;
    using bvh::threadStack;
    using bvh::triangleSeparation;

    namespace
    {
        /** \brief Full separating-axis test of the two oriented boxes (15 axes): true if they are disjoint. \e absR is
            |X.R| + 1e-12, entry by entry, worked out once per test: the C of two axis-aligned boxes is X.R itself. No
            bounding-sphere test first: along OMPL.app's Easy and Twistycool paths it pruned 0.1 and 1.2 % of the
            pairs, which the 15 axes then prune (boxes in disjoint spheres are disjoint), and cost more than it
            spared. Boxes the face axes leave overlapping that surely do (a ball within one reaches the other) skip
            the nine cross axes. */
        bool separated(const TriangleBvh::Node &a, const TriangleBvh::Node &b, const RelativePose &X,
                       const Eigen::Matrix3d &absR)
        {
            const bvh::PlacedNode &placed = X.place(b);
            const Eigen::Vector3d offset = placed.center - a.center;
            const BoxPair P(a, placed, offset);
            const Eigen::Vector3d &T = *P.T;
            const Eigen::Matrix3d &C = *P.C;
            Eigen::Matrix3d ownAbsC;
            const bool bothAligned = a.aligned && b.aligned;
            if (!bothAligned)
                ownAbsC = C.cwiseAbs().array() + 1e-12;
            const Eigen::Matrix3d &absC = bothAligned ? absR : ownAbsC;
            const Eigen::Vector3d absT = T.cwiseAbs();
            if (((absT - a.half - absC * b.half).array() > 0.0).any())
                return true;
            const Eigen::Vector3d absU = (C.transpose() * T).cwiseAbs();
            if (((absU - absC.transpose() * a.half - b.half).array() > 0.0).any())
                return true;
            // The ball of one box's least half extent about its centre (within that box) reaching the other box: they
            // overlap, no cross axis can separate them.
            const double ballA = a.half.minCoeff(), ballB = b.half.minCoeff();
            if ((absT - a.half).cwiseMax(0.0).squaredNorm() <= ballB * ballB ||
                (absU - b.half).cwiseMax(0.0).squaredNorm() <= ballA * ballA)
                return false;
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

        /** \brief Whether triangle \e p (three corners, A's frame) lies apart from the box of centre \e c, axes \e axes
            (columns, A's frame) and half extents \e half by more than \e beyond along one of the 13 separating axes
            of a triangle and a box (the box's 3 face normals, the triangle's normal, the 9 crosses of a box axis and
            an edge), plus a pad of 1e-11 of the coordinates' scale against roundoff: far beyond
            trianglesIntersect()'s contact tolerance, so no triangle within the box can be reported touching it. The
            gap along an axis is measured against the axis's 1-norm, not its length (no square root; the gap
            proven is the smaller). Exact for a triangle and a box: some axis separates them whenever they are apart
            by more than that. */
        bool triangleApartFromBox(const Eigen::Vector3d *p, const Eigen::Vector3d &c, const Eigen::Matrix3d &axes,
                                  const Eigen::Vector3d &half, double beyond)
        {
            const Eigen::Vector3d q0 = axes.transpose() * (p[0] - c), q1 = axes.transpose() * (p[1] - c),
                                  q2 = axes.transpose() * (p[2] - c);
            const double pad = beyond + 1e-11 * (c.cwiseAbs().sum() + half.sum() +
                                                 (p[0].cwiseAbs() + p[1].cwiseAbs() + p[2].cwiseAbs()).sum());
            // The box's face normals (its frame's unit vectors).
            const Eigen::Vector3d lo = q0.cwiseMin(q1).cwiseMin(q2), hi = q0.cwiseMax(q1).cwiseMax(q2);
            if (((lo - half).array() > pad).any() || ((-hi - half).array() > pad).any())
                return true;
            // A corner within the box: the triangle meets it, no axis can separate them.
            if (((q0.cwiseAbs() - half).array() <= 0.0).all() || ((q1.cwiseAbs() - half).array() <= 0.0).all() ||
                ((q2.cwiseAbs() - half).array() <= 0.0).all())
                return false;
            // Along m, corners projecting to u (twice) and v lie apart from the box (radius r) by more than the pad
            // (against m's 1-norm, at least its length).
            auto apart = [pad](double u, double v, double r, double norm1) {
                const double reach = r + pad * norm1;
                return std::min(u, v) > reach || std::max(u, v) < -reach;
            };
            const double hx = half.x(), hy = half.y(), hz = half.z();
            // Box axis x, y, z crossed with each edge E (corners S and S + E on it, T the third corner):
            // x × E = (0, -E.z, E.y), y × E = (E.z, 0, -E.x), z × E = (-E.y, E.x, 0).
            const Eigen::Vector3d *edge[3][2] = {{&q0, &q2}, {&q1, &q0}, {&q2, &q1}};
            const Eigen::Vector3d e[3] = {q1 - q0, q2 - q1, q0 - q2};
            for (int k = 0; k < 3; ++k)
            {
                const Eigen::Vector3d &S = *edge[k][0], &T = *edge[k][1], &E = e[k];
                const double ax = std::abs(E.x()), ay = std::abs(E.y()), az = std::abs(E.z());
                if (apart(E.y() * S.z() - E.z() * S.y(), E.y() * T.z() - E.z() * T.y(), hy * az + hz * ay, ay + az) ||
                    apart(E.z() * S.x() - E.x() * S.z(), E.z() * T.x() - E.x() * T.z(), hx * az + hz * ax, ax + az) ||
                    apart(E.x() * S.y() - E.y() * S.x(), E.x() * T.y() - E.y() * T.x(), hx * ay + hy * ax, ax + ay))
                    return true;
            }
            // The triangle's normal: every corner projects to about the same value (the extremes of the three
            // taken).
            const Eigen::Vector3d n = e[0].cross(e[1]);
            const double a = n.dot(q0), b = n.dot(q1), d = n.dot(q2);
            const double reach = half.dot(n.cwiseAbs()) + pad * n.cwiseAbs().sum();
            return std::min({a, b, d}) > reach || std::max({a, b, d}) < -reach;
        }

        /** \brief Whether a leaf's triangle lies apart from the other node's box by more than \e beyond (see
            triangleApartFromBox()): \e na's (A's) triangle against \e nb's box placed by \e X, then \e nb's
            triangle placed by \e X against \e na's box. A leaf's box, even the tightest, reaches past its
            triangle's corners, and a node near a triangle's slanted side but not touching it (as a robot's passing
            through a hole in a wall of large triangles) meets the box, not the triangle. */
        bool leafApart(const TriangleBvh &a, const TriangleBvh &b, const RelativePose &X, const TriangleBvh::Node &na,
                       const TriangleBvh::Node &nb, double beyond = 0.0)
        {
            if (na.isLeaf() && na.count == 1)
            {
                const Mesh &m = a.mesh();
                const Triangle &f = m.triangles[a.order()[na.first]];
                const Eigen::Vector3d p[3] = {m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]};
                const bvh::PlacedNode &placed = X.place(nb);
                if (triangleApartFromBox(p, placed.center, placed.axes, nb.half, beyond))
                    return true;
            }
            if (nb.isLeaf() && nb.count == 1)
            {
                const Mesh &m = b.mesh();
                const Triangle &f = m.triangles[b.order()[nb.first]];
                const Eigen::Vector3d p[3] = {X.R * m.vertices[f[0]] + X.t, X.R * m.vertices[f[1]] + X.t,
                                              X.R * m.vertices[f[2]] + X.t};
                if (triangleApartFromBox(p, na.center, na.axes, na.half, beyond))
                    return true;
            }
            return false;
        }

        /** \brief Push the two children of pair \e e (nodes \e na of \e a, \e nb of \e b) split as splitA() says,
            the child whose box centre lies nearer the other node's on top (tested first): at a colliding pose the
            first intersecting pair is what ends the test, and it lies where the surfaces cross, nearer the middle of
            the overlap than its edges. The verdict does not depend on the order. Always inlined: as a call it cost
            OMPL.app's Easy path 3 % more instructions. */
        inline __attribute__((always_inline)) void pushChildren(std::vector<PairEntry> &stack, const PairEntry &e,
                                                                const TriangleBvh &a, const TriangleBvh &b,
                                                                const TriangleBvh::Node &na,
                                                                const TriangleBvh::Node &nb, const RelativePose &X)
        {
            if (splitA(na, nb))
            {
                const Eigen::Vector3d &other = X.place(nb).center;
                const bool leftFirst = (a.nodes()[na.first].center - other).squaredNorm() <=
                                       (a.nodes()[na.first + 1].center - other).squaredNorm();
                stack.push_back({na.first + (leftFirst ? 1u : 0u), e.b});
                stack.push_back({na.first + (leftFirst ? 0u : 1u), e.b});
            }
            else
            {
                const Eigen::Vector3d left = X.place(b.nodes()[nb.first]).center;
                const bool leftFirst = (left - na.center).squaredNorm() <=
                                       (X.place(b.nodes()[nb.first + 1]).center - na.center).squaredNorm();
                stack.push_back({e.a, nb.first + (leftFirst ? 1u : 0u)});
                stack.push_back({e.a, nb.first + (leftFirst ? 0u : 1u)});
            }
        }

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

    namespace
    {
        /** \brief The stateless test, counting the node pairs it visits into \e pairs. */
        bool collideCounted(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                            std::uint32_t *hitA, std::uint32_t *hitB, std::size_t &pairs)
        {
            if (a.nodes().empty() || b.nodes().empty())
                return false;
            const RelativePose X(X_AB, b);
            const Eigen::Matrix3d absR = X.R.cwiseAbs().array() + 1e-12;
            std::vector<PairEntry> &stack = threadStack<PairEntry, 3>();
            stack.push_back({0u, 0u});
            std::size_t visited = 0;
            while (!stack.empty())
            {
                const PairEntry e = stack.back();
                stack.pop_back();
                ++visited;
                const TriangleBvh::Node &na = a.nodes()[e.a], &nb = b.nodes()[e.b];
                if (separated(na, nb, X, absR) || (na.isLeaf() != nb.isLeaf() && leafApart(a, b, X, na, nb)))
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
                        pairs += visited;
                        return true;
                    }
                    continue;
                }
                pushChildren(stack, e, a, b, na, nb, X);
            }
            pairs += visited;
            return false;
        }
    }  // namespace

    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, std::uint32_t *hitA,
                    std::uint32_t *hitB)
    {
        std::size_t pairs = 0;
        return collideCounted(a, b, X_AB, hitA, hitB, pairs);
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
                               std::uint32_t stamp, std::size_t budget)
                : a_(a),
                  b_(b),
                  X_(X),
                  margin_(margin),
                  lookahead_(lookahead),
                  record_(record),
                  motion_(motion),
                  stamp_(stamp),
                  budget_(budget),
                  stack_(threadStack<PairEntry, 6>())
            {
            }

            /** \brief True at the first intersecting pair of triangles below \e start (hitA / hitB name it). False
                also when the node pairs visited by this traversal's runs together exceed its budget (over is then
                set, and what was recorded is incomplete). */
            bool run(const PairEntry &start)
            {
                stack_.clear();
                stack_.push_back(start);
                while (!stack_.empty())
                {
                    if (++visited_ > budget_)
                    {
                        over = true;
                        return false;
                    }
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
                    // proven at the next pose or two; a leaf's triangle apart by that much from the other box is kept
                    // with that much as its gap.
                    const double enough = margin_ + 2.0 * lookahead_.displacement(nb);
                    if (bound > enough)
                    {
                        keep(e, bound);
                        continue;
                    }
                    if (leafApart(a_, b_, X_, na, nb, enough))
                    {
                        keep(e, enough);
                        continue;
                    }
                    pushChildren(stack_, e, a_, b_, na, nb, X_);
                }
                return false;
            }

            std::uint32_t hitA{0}, hitB{0};
            bool over{false};  ///< the budget ran out

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
            const std::size_t budget_;
            std::size_t visited_{0};
            std::vector<PairEntry> &stack_;
        };

    }  // namespace

    namespace
    {
        /** \brief Re-test the entries of a valid collision front at the pose \e X_AB, \e motion (B's displacement
            summed since the front was written) later: an entry is kept while key - motion stays above the margin,
            else while its gap lowered by its own node's displacement since then does (re-based on this pose); else
            the traversal runs below it and its sub-front (in traversal's record) replaces it. True at the first
            intersecting pair (the front is then left as it is); false with traversal.over set when the traversal's
            budget ran out (the front is then no longer a cut). \e retested counts the entries re-tested. */
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
                if (traversal.over)
                    return false;
                front.entries[i] = front.next.back();  // its sub-front replaces it (at least one entry)
                front.next.pop_back();
            }
            return false;
        }
        /** \brief A collision the test with \e front found: no front is kept, the hit is reported. */
        bool reportHit(BvhFront &front, const CollisionTraversal &t, std::uint32_t *hitA, std::uint32_t *hitB)
        {
            front.valid = false;
            front.collided = true;
            if (hitA)
                *hitA = t.hitA;
            if (hitB)
                *hitB = t.hitB;
            return true;
        }

        /** \brief The stateless test, its cost the yardstick of the next tests' budget. */
        bool statelessTest(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                           BvhFront &front, std::uint32_t *hitA, std::uint32_t *hitB)
        {
            std::size_t pairs = 0;
            front.collided = collideCounted(a, b, X_AB, hitA, hitB, pairs);
            front.statelessPairs = pairs;
            return front.collided;
        }

        /** \brief A test with the front that visits more node pairs than its budget stops there and answers as the
            stateless test does; the front is dropped, and none is written for a while (as when fronts do not last). */
        bool overBudgetTest(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                            BvhFront &front, std::uint32_t *hitA, std::uint32_t *hitB)
        {
            ++front.overBudget;
            front.valid = false;
            front.wait = front.backoff = std::min(2 * front.backoff + 1, 64u);
            return statelessTest(a, b, X_AB, front, hitA, hitB);
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
        const RelativePose X(X_AB, b);
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
        const std::size_t budget =
            BvhFront::BUDGET * std::max<std::size_t>(front.statelessPairs, BvhFront::MIN_BUDGET);
        // The last step's motion, node by node: the lookahead of the pairs written now.
        const bool small = step <= 0.1 * rootB.radius;
        std::optional<StepMotion> last;
        if (small)
            last.emplace(front.poses[(stamp - 1) % BvhFront::POSES], X_AB, rootB);
        if (front.valid && small)
        {
            const double motion = front.motion + step;
            front.next.clear();
            CollisionTraversal traversal(a, b, X, margin, *last, &front.next, motion, stamp, budget);
            std::size_t retested = 0;
            if (retestCollisionFront(front, traversal, b, X_AB, margin, motion, stamp, retested))
                return reportHit(front, traversal, hitA, hitB);
            if (traversal.over)
                return overBudgetTest(a, b, X_AB, front, hitA, hitB);
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
        // Nor while the bodies collide: a front written then ends at the first hit, and the next colliding test
        // would pay for writing it again. The first free test after a collision runs stateless too.
        const bool write = small && front.wait == 0 && !front.collided;
        if (small && front.wait > 0)
            --front.wait;
        if (!write)
        {
            ++front.incoherent;
            return statelessTest(a, b, X_AB, front, hitA, hitB);
        }
        front.uses = 0;
        ++front.rebuilds;
        front.entries.clear();
        CollisionTraversal traversal(a, b, X, margin, *last, &front.entries, 0.0, stamp, budget);
        if (traversal.run({0u, 0u}))
            return reportHit(front, traversal, hitA, hitB);
        if (traversal.over)
            return overBudgetTest(a, b, X_AB, front, hitA, hitB);
        front.motion = 0.0;
        front.motions[stamp % BvhFront::POSES] = 0.0;
        front.freshSize = front.entries.size();
        front.valid = true;
        return false;
    }
}  // namespace meshgap
