#ifndef MESHGAP_GEOMETRY_BVH_FRONT_H
#define MESHGAP_GEOMETRY_BVH_FRONT_H

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshgap
{
    class TriangleBvh;

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
        /** \brief Collision fronts: a test with the front visits at most BUDGET times as many node pairs as the last
            stateless test did (at least MIN_BUDGET), else it answers as the stateless test does (bvhCollide()). */
        static constexpr std::size_t BUDGET = 2;
        static constexpr std::size_t MIN_BUDGET = 64;

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
        bool collided{false};       ///< collision fronts: the last test found a collision (no front is written)
        std::size_t statelessPairs{0};  ///< collision fronts: node pairs the last stateless test visited
        std::size_t overBudget{0};      ///< collision fronts: tests that ran out of budget (statistics)
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
            collided = false;
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
}  // namespace meshgap

#endif
