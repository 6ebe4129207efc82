#ifndef MESHGAP_GEOMETRY_TRIANGLE_BVH_H
#define MESHGAP_GEOMETRY_TRIANGLE_BVH_H

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief A bounding-volume hierarchy over a mesh's triangles: a binary tree of boxes in the body frame, each the
        tighter (smaller volume) of the axis-aligned box and the box along the principal axes of its triangles'
        corners, with a bounding sphere about the box centre; built top-down, each node's triangles cut in two along
        one of its box axes where the surface area heuristic (the children's box areas times their triangle counts)
        is least, leaves of at most LEAF_SIZE triangles (a leaf's principal box is flat: a triangle's own plane).
        Between two trees at a relative pose, a box pair is bounded from below by the gap of the spheres, then by the
        gaps along each box's three face axes (their norm). Immutable; the mesh must outlive the tree. */
    class TriangleBvh
    {
    public:
        static constexpr std::uint32_t LEAF_SIZE = 1;

        struct Node
        {
            Eigen::Vector3d center{Eigen::Vector3d::Zero()};  ///< box centre, body frame
            Eigen::Vector3d half{Eigen::Vector3d::Zero()};    ///< box half extents along its axes
            /** \brief The box's axes (columns, body frame; a rotation); the identity when aligned. */
            Eigen::Matrix3d axes{Eigen::Matrix3d::Identity()};
            double radius{0.0};      ///< every triangle corner of the node lies within radius of center
            std::uint32_t first{0};  ///< leaf: first index in order(); inner: index of the left child
            std::uint32_t count{0};  ///< leaf: number of triangles (> 0); inner: 0 (right child is first + 1)
            bool aligned{true};      ///< axes is the identity (the cheaper tests apply)
            bool isLeaf() const { return count > 0; }
            /** \brief \e p (body frame) in the box's frame: relative to its centre, along its axes. */
            Eigen::Vector3d local(const Eigen::Vector3d &p) const
            {
                return aligned ? Eigen::Vector3d(p - center) : Eigen::Vector3d(axes.transpose() * (p - center));
            }
            /** \brief Whether \e p (body frame) lies outside the box. */
            bool outside(const Eigen::Vector3d &p) const { return (local(p).cwiseAbs() - half).maxCoeff() > 0.0; }
        };

        explicit TriangleBvh(const Mesh &mesh);

        const Mesh &mesh() const { return *mesh_; }
        const std::vector<Node> &nodes() const { return nodes_; }
        /** \brief Triangle indices in leaf order. */
        const std::vector<std::uint32_t> &order() const { return order_; }
        /** \brief Unit normal of each triangle (body frame), for the plane-separation bound at the leaves. */
        const std::vector<Eigen::Vector3d> &normals() const { return normals_; }

    private:
        const Mesh *mesh_;
        std::vector<Node> nodes_;
        std::vector<std::uint32_t> order_;
        std::vector<Eigen::Vector3d> normals_;
    };

    /** \brief What a distance traversal found and what it cost. */
    struct BvhDistanceResult
    {
        /** \brief The smallest triangle-pair distance below the upper bound given, or the upper bound itself when no
            pair beats it (then found is false and the pair fields are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangleA{0}, triangleB{0};
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};  ///< A's frame
        std::size_t boxTests{0}, triangleTests{0};
    };

    /** \brief The certificate of the last distance traversal between two trees, kept by a caller (a warm start) for
        the next, nearby pose: the front of that traversal, a cut through the tree of node pairs (every pair of
        triangles lies under exactly one entry), each entry with a lower bound on its distance.

        A bound computed at one pose stays a lower bound at a later one once the largest displacement of B's points
        between the two poses is subtracted. Two such displacements are used:
        - for all entries at once, the whole of B (motionBound()), summed over the steps since the front was rebuilt
          (motion): each entry stores key = bound + motion at the time, and key - motion is its bound now; a scan of
          the keys keeps most entries without any work;
        - for an entry that fails that test and was computed within the last POSES traversals, the displacement of
          its own node of B between that traversal's pose and this one (nodeMotionBound()), much smaller for a part
          near the centre of a rotation; an entry kept that way is re-based on this pose.
        An entry that fails both is re-tested: a pair of leaves first along the axis that separated it last time
        (a sliding motion leaves that gap unchanged), then in full; any other pair by its box bound, descended where
        it could beat the best, its sub-front replacing it. The answer is the cold traversal's: same prune rule,
        same tie rule. The front is
        rebuilt from the roots when it has grown past FRONT_GROWTH times the size of a fresh one, or when a
        traversal had to re-test more entries than half a fresh front (a motion too large to pay); and a query whose
        pose lies further from the last one than the distance it seeks (B's displacement above the upper bound, as
        between a planner's unrelated samples) runs from the roots and writes no front at all. When fronts keep
        failing within two queries, writing backs off (uses, backoff, wait).
        Belongs to one caller; not thread-safe. */
    struct BvhFront
    {
        static constexpr std::size_t FRONT_GROWTH = 2;
        static constexpr std::uint32_t POSES = 8;

        struct Entry
        {
            std::uint32_t a, b;   ///< node of tree A, node of tree B
            std::uint32_t stamp;  ///< the traversal that computed the bound
            /** \brief A pair of leaves: the axis that separated its triangles (unit, from A's towards B's; zero if
                none), re-tested first: the gap along it is a fresh lower bound for about a tenth of a full test. */
            float axis[3];
            double key;  ///< that lower bound on the pair's distance + motion at the time
        };

        std::vector<Entry> entries;  ///< the front (valid when valid is set)
        std::vector<Entry> next;     ///< sub-fronts of the entries being re-tested (kept for its capacity)
        std::array<Eigen::Isometry3d, POSES> poses;  ///< X_AB of the last POSES traversals, by stamp % POSES
        std::array<double, POSES> motions{};         ///< motion at each of them
        double motion{0.0};                          ///< displacement bounds summed since the front was rebuilt
        std::uint32_t stamp{0};                      ///< the last traversal's number
        std::size_t freshSize{0};                    ///< size of the front the last traversal from the roots wrote
        bool valid{false};          ///< entries cover the whole pair tree (false: start from the roots)
        bool started{false};        ///< a traversal has run (poses holds its pose)
        std::size_t reused{0};      ///< statistics: entries kept without a test, over the front's lifetime
        std::size_t retested{0};    ///< entries re-tested in full
        std::size_t axisKept{0};    ///< entries kept by their separating axis
        std::size_t rebuilds{0};    ///< traversals from the roots that wrote a front
        std::size_t incoherent{0};  ///< traversals from the roots for a pose too far from the last one
        /** \brief Queries the current front has answered; and, when fronts keep failing within two queries
            (motions as large as the gaps), how many queries run from the roots without writing one (doubled at each
            such failure, up to 64; back to 0 once a front lasts). */
        std::uint32_t uses{0}, backoff{0}, wait{0};

        /** \brief Heap bytes held (both buffers' capacity). */
        std::size_t memoryBytes() const { return (entries.capacity() + next.capacity()) * sizeof(Entry); }
        /** \brief Forget the history (the next traversal starts as a first one would), keeping the memory. */
        void clear()
        {
            valid = false;
            started = false;
            uses = backoff = wait = 0;
        }
    };

    /** \brief Upper bound on how far any point within \e radius of \e center (B's frame) moves between B's poses
        \e from and \e to (both in A's frame): |to c - from c| + radius |R_to - R_from|_2, the spectral norm of the
        rotation difference being 2 sin(theta / 2) for the relative angle theta. Padded against roundoff. */
    double nodeMotionBound(const Eigen::Vector3d &center, double radius, const Eigen::Isometry3d &from,
                           const Eigen::Isometry3d &to);

    /** \brief Upper bound on how far any point of \e b (its root sphere) moves between B's poses \e from and \e to
        (both in A's frame): |to c - from c| + r |R_to - R_from|_2 for the root sphere (c, r), the spectral norm of
        the rotation difference being 2 sin(theta / 2) for the relative angle theta. Padded against roundoff. */
    double motionBound(const TriangleBvh &b, const Eigen::Isometry3d &from, const Eigen::Isometry3d &to);

    /** \brief Exact minimum distance between the triangles of \e a (frame A) and of \e b placed by \e X_AB, searching
        only for pairs closer than \e upperBound (pass a distance some real pair achieves to prune with it, or
        infinity; \e seedA / \e seedB name that pair, if any). Completes the whole traversal unless \e stopBelow is
        reached (a pair at or below it ends the search early; pass a negative value to never stop). A completed
        traversal with found == false proves no pair is closer than \e upperBound. Intersecting triangles have
        distance 0.

        Ties are canonical: pairs whose distances agree within a rounding slack (1e-12 of the scene's scale) count
        as equally close, and the one with the smallest (triangle of A, triangle of B) wins. So the answer, pair and
        witness points do not depend on the seed or the visiting order: a warm-started query gives the cold query's
        answer bit for bit.

        With \e front, the traversal starts from that certificate of an earlier query between the same trees (if it
        is valid) instead of the roots, and leaves its own front there (BvhFront); the answer is the same.

        With \e seedAxis, the seed pair's distance is exactly \e upperBound (computed by triangleDistance() with B's
        corners placed as R v + t, as here) and \e seedAxis its witness direction (unit, from A's point towards
        B's): the traversal does not test that pair again. */
    void bvhDistance(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, double upperBound,
                     double stopBelow, BvhDistanceResult &result, std::uint32_t seedA = UINT32_MAX,
                     std::uint32_t seedB = UINT32_MAX, BvhFront *front = nullptr,
                     const Eigen::Vector3d *seedAxis = nullptr);

    /** \brief True when some triangle of \e a intersects (or touches) some triangle of \e b placed by \e X_AB;
        stops at the first such pair, which is reported through \e hitA / \e hitB when given. */
    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB,
                    std::uint32_t *hitA = nullptr, std::uint32_t *hitB = nullptr);

    /** \brief bvhCollide() carried along a run of nearby poses: \e front keeps the node pairs the last test proved
        apart, each with a lower bound on its gap (the sphere and face-axis bound of a box pair, the separating-axis
        gap of a triangle pair), and the next test re-tests only the entries whose gap B's motion since then could
        have closed, descending below those that no longer separate. The verdict and the reported pair are those of
        the stateless bvhCollide(): a pair is kept only while its gap exceeds ten times the contact tolerance of
        trianglesIntersect(), and every pair that might touch is decided by trianglesIntersect() itself.

        An entry whose gap B's whole motion since then could have closed is kept if its own node's displacement
        could not have (as in bvhDistance()), else re-tested and descended. A front is written (from the roots) only
        after a small step, at most a tenth of B's bounding radius (a run of nearby poses, as along a path or a
        motion, not a planner's unrelated samples), its box pairs kept apart by twice their node's motion in that
        step, so that they outlast the next one; it is rebuilt when it has grown past FRONT_GROWTH times a fresh
        one or a test re-tested more than half of it; when fronts keep failing within two tests (motions as large
        as the gaps), writing backs off (BvhFront::backoff). A collision leaves no front. Belongs to one caller. */
    bool bvhCollide(const TriangleBvh &a, const TriangleBvh &b, const Eigen::Isometry3d &X_AB, BvhFront &front,
                    std::uint32_t *hitA = nullptr, std::uint32_t *hitB = nullptr);

    /** \brief What a point query (bvhPointDistance()) found and what it cost. */
    struct BvhPointResult
    {
        /** \brief Distance from the point to the nearest triangle below the upper bound given, or the upper bound
            itself when none is closer (then found is false and triangle / closest are untouched). */
        double distance{std::numeric_limits<double>::infinity()};
        bool found{false};
        std::uint32_t triangle{0};                         ///< the nearest triangle (mesh index)
        Eigen::Vector3d closest{Eigen::Vector3d::Zero()};  ///< the nearest point on it, body frame
        std::size_t triangleTests{0};
    };

    /** \brief Exact distance from \e p (in the tree's body frame) to the nearest triangle of \e tree, searching only
        for triangles closer than \e upperBound; nearer boxes first. A triangle at or below \e stopBelow ends the
        search early (the answer is then only an upper bound; negative: never stop). Deterministic: the same point
        gives the same triangle and closest point. */
    void bvhPointDistance(const TriangleBvh &tree, const Eigen::Vector3d &p, double upperBound, double stopBelow,
                          BvhPointResult &result);

    /** \brief Winding number of \e tree's surface about \e p (body frame) by ray casting: the signed number of
        triangles the ray p + s \e direction (s > 0) crosses, +1 where it leaves through a triangle's front
        (counter-clockwise) side and -1 where it enters. For a closed surface that is the generalised winding number
        (an integer: 0 outside, +-1 inside, more inside overlapping shells), found in O(log n) triangle tests
        instead of O(n). Returns false, leaving \e winding undefined, when the answer is not robust: the ray passes
        within roundoff of a triangle's edge or corner (then try another direction), or \e p lies on the surface. */
    bool bvhRayWinding(const TriangleBvh &tree, const Eigen::Vector3d &p, const Eigen::Vector3d &direction,
                       int &winding);
}  // namespace meshgap

#endif
