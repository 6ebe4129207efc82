#ifndef MESHGAP_ROBOT_MOTION_BOUND_H
#define MESHGAP_ROBOT_MOTION_BOUND_H

#include <array>
#include <utility>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief How far any point of a link can move along a straight motion between two states of a robot of any
        kind (adaptive dynamic collision checking: Schwarzer, Saha and Latombe, IEEE T-RO 2005), from each frame's
        RobotModel::frameMotion(): at most the sum, over the moving frames f from the link's frame up to its root,
        of f's own move times r_fL, r_fL bounding the distance of any point of the link from f's origin (the link's
        radius about its frame, plus the reaches of the frames between):
        - a rotation about an axis through f's origin (revolute, continuous joint): |dq| scale r_fL;
        - a translation (prismatic joint): |dq| scale;
        - a frame free in SE(2) or SE(3) (a rigid body, one of several, a floating base, a planar or floating
          joint): |dp| + theta r_fL, dp its position's change and theta the angle between its two rotations (the
          shorter arc, as OMPL interpolates: yaw along the shorter arc, slerp along the shorter great arc).
        Every term moves at a constant rate along OMPL's interpolation, so the bound over a fraction of the motion
        is that fraction of it. A mimic joint moves |multiplier| times its source; continuous joints move along the
        shorter arc, as OMPL's SO(2) interpolation does. */
    class MotionBound
    {
    public:
        /** \brief What one motion moves (its frames' steps), computed once by motion() and read by every piece of it
            (pieceBounds()). Reused between motions without allocation. */
        struct Motion
        {
            std::vector<double> move;   ///< per term (all links' terms in a row): the frame's step, angle or length
            std::vector<double> crude;  ///< per term: its whole-motion displacement bound (move times its lever)
        };

        /** \brief Throws meshgap::Exception for a frame that moves free below a moving frame (no finite reach). */
        explicit MotionBound(const RobotModel &robot);

        /** \brief The bound for every link of \e robot (as it was given, payloads included) from state \e a to
            state \e b (each robot.dimension() numbers), into \e out. */
        void linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                               std::vector<double> &out) const;

        /** \brief The bound for links \e first and \e second relative to each other from state \e a to state
            \e b: how far any point of either moves in the frame of their nearest common ancestor (the frames above
            it move both alike, which changes no distance between them), summed over the two. At most
            linkDisplacements()' two bounds added; far less for links close in a tree (a wrist and the link two
            joints up), and exactly that sum for two bodies with no common frame (two bodies of several: their
            signed distance changes by at most both bodies' displacements). */
        double pairDisplacement(std::size_t first, std::size_t second, const std::vector<double> &a,
                                const std::vector<double> &b) const;

        /** \brief The steps of the straight motion from \e a to \e b, into \e out (for pieceBounds()). */
        void motion(const std::vector<double> &a, const std::vector<double> &b, Motion &out) const;

        /** \brief A tighter bound over a piece of \e motion: the states within \e half (a fraction of the motion)
            of a middle state whose frames' and links' world poses are \e frames and \e links. A frame f turning by
            an angle moves a point x at the rate |dq_f| dist(x, f's axis) (the distance to its origin for a free
            body's turn), not |dq_f| r_fL: the distance of the link's box (its BVH root box, 8 corners) from f's axis
            is measured at the middle state, rho_f, and grows over the piece by at most the link's own displacement
            relative to f (the crude bound of the frames below f, C_f). Integrating, f adds |dq_f| (half rho_f +
            half^2 C_f / 2); a translation adds half |dq_f|. \e out gets, per link, the running sums of its terms
            nearest first (pairBound() reads them). With \e only, just the links it marks (non-zero, one entry per
            link): the others' sums are left as they were. */
        void pieceBounds(const Motion &motion, const std::vector<Eigen::Isometry3d> &frames,
                         const std::vector<Eigen::Isometry3d> &links, double half, std::vector<double> &out,
                         const std::vector<unsigned char> *only = nullptr) const;
        /** \brief From pieceBounds()' \e sums: the bound for link \e link against the world. */
        double linkBound(std::size_t link, const std::vector<double> &sums) const
        {
            return sums[offsets_[link + 1] + link];
        }
        /** \brief How far a point of link \e link may stray from the straight line between its places at the two
            ends of a piece of \e motion h long (a fraction of it): at most h^2 / 8 times the bend returned, a bound
            of the second derivative of the point's path in t (the motion's fraction). Over the link's first \e terms
            terms (nearest first): all of them for its path in the world, pairTerms()' for its path in the frame
            of a pair's nearest common ancestor. With each frame's step m_j (an angle, or a length for a
            translation), its lever r_j and S_j the sum of the rotation steps of the frames above it (between it
            and the frame the path is seen in): a rotation adds m_j r_j (3 S_j + m_j) (its axis is turned by those
            above, the point turns about it, and about every axis below), a translation 2 m_j S_j (its direction
            turned by those above). Every frame moves at a constant rate along OMPL's interpolation, which is what
            the bound needs; a free body's turn is one about an axis fixed in its parent (slerp). */
        double bend(std::size_t link, std::size_t terms, const Motion &motion) const;
        /** \brief True when none of link \e link's first \e terms terms moves along \e motion (each step exactly 0):
            the link then stays where it is in the world (all its terms) or in a pair's nearest common frame
            (pairTerms()'), at every state of the motion. */
        bool stays(std::size_t link, std::size_t terms, const Motion &motion) const
        {
            for (std::size_t t = offsets_[link]; t < offsets_[link] + terms; ++t)
                if (motion.move[t] != 0.0)
                    return false;
            return true;
        }
        /** \brief The number of link \e link's terms (for bend(): its whole path in the world). */
        std::size_t numTerms(std::size_t link) const { return offsets_[link + 1] - offsets_[link]; }
        /** \brief For links \e first and \e second: how many of each one's terms lie below their nearest common
            ancestor (all of them for two bodies with no common frame). */
        std::pair<std::size_t, std::size_t> pairTerms(std::size_t first, std::size_t second) const;
        /** \brief From pieceBounds()' \e sums: the bound for links \e first and \e second relative to each other
            (as pairDisplacement(): each link's terms below their nearest common ancestor, \e terms from
            pairTerms()). */
        double pairBound(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                         const std::vector<double> &sums) const
        {
            return sums[offsets_[first] + first + terms.first] + sums[offsets_[second] + second + terms.second];
        }

        /** \brief How many ways pairSplitBound() splits the path of joints between links \e first and \e second
            (\e terms from pairTerms()): one more than the terms on it; 1 for two bodies with no common frame. */
        std::size_t pairSplits(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms) const;
        /** \brief A bound over a piece of \e motion (\e half a fraction of it, \e sums from pieceBounds()) for
            links \e first and \e second relative to each other, split at \e split (< pairSplits()): the path of
            joints from the first link up to their nearest common ancestor and down to the second, its first
            \e split joints charged to the first link, the rest to the second. Their distance d(A, M B), M the
            product of the path's joints, is d(M1^-1 A, M2 B) with M = M1 M2, so it changes by at most what the
            first link moves under M1^-1 plus what the second moves under M2, both in the frame between. A link's own
            joints add what pieceBounds() summed; a joint of the other link's way charged to it adds its step times
            the link's distance from the joint's axis: at any state at most its reach from the common ancestor's
            origin plus how far that origin is from the joint's (the frames' reaches between); over the piece at
            most its root sphere's at the middle state (\e frames and \e links, as pieceBounds() takes them),
            grown by how fast the link moves about that axis (its own terms' and the frames' between). Split at
            terms.first, it is pairBound(); a link far from the other's joints (a base against the upper arm two
            joints away) moves far less about them than the other does. +infinity for a split between two terms of
            one frame (a free frame's move and turn), which is no split between frames. */
        double pairSplitBound(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                              std::size_t split, const std::vector<double> &sums, const Motion &motion, double half,
                              const std::vector<Eigen::Isometry3d> &frames,
                              const std::vector<Eigen::Isometry3d> &links) const;
        /** \brief The frame between the two parts of \e split (pairSplitBound()): the first link's displacement
            in it plus the second's bound how far their distance changes. RobotModel::NONE for two separate roots. */
        std::size_t splitFrame(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                               std::size_t split) const;
        /** \brief The state numbers that move links \e first and \e second relative to each other (those of their
            terms below their nearest common ancestor, pairTerms()), each once, in increasing order, into
            \e numbers; per number, whether it is an angle moved along the shorter arc (a continuous joint), into
            \e arcs. False (no claim) when a free frame (SE(2), SE(3)) moves either below that ancestor, or the two
            have no common frame: their relative pose is then no function of a few numbers. */
        bool pairNumbers(std::size_t first, std::size_t second, std::vector<std::size_t> &numbers,
                         std::vector<unsigned char> &arcs) const;
        /** \brief The least pairSplitBound() over every split. */
        double pairPieceBound(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                              const std::vector<double> &sums, const Motion &motion, double half,
                              const std::vector<Eigen::Isometry3d> &frames,
                              const std::vector<Eigen::Isometry3d> &links) const;

    private:
        /** \brief For charged(): every split on one side, the least. */
        static constexpr std::size_t ALL_SPLITS = ~std::size_t(0);
        /** \brief Link \e own keeping its \e kept nearest terms of the \e counts.first below the common ancestor
            with link \e other (which has \e counts.second there), the rest charged to \e other: own's piece sum
            plus the charged terms' bounds (pairSplitBound()); with ALL_SPLITS, the least over every \e kept below
            counts.first. */
        double charged(std::size_t own, std::size_t other, std::pair<std::size_t, std::size_t> counts,
                       std::size_t kept, const std::vector<double> &sums, const Motion &motion, double half,
                       const std::vector<Eigen::Isometry3d> &frames,
                       const std::vector<Eigen::Isometry3d> &links) const;
        /** \brief Where links \e first and \e second's nearest common ancestor is on each one's way up (an index
            into chains_; past the end for two separate roots). */
        std::pair<std::size_t, std::size_t> commonSteps(std::size_t first, std::size_t second) const
        {
            return common_[first * chains_.size() + second];
        }
        /** \brief What a term measures between the two states. */
        enum class Measure
        {
            SCALAR,      ///< |b - a| of one state number
            ARC,         ///< the same along the shorter arc (an angle)
            PLANE_MOVE,  ///< |dx, dy| of an SE(2) pose
            PLANE_TURN,  ///< its yaw's change along the shorter arc
            SPACE_MOVE,  ///< |dx, dy, dz| of an SE(3) pose
            SPACE_TURN   ///< the angle between its two rotations
        };
        /** \brief How a term's lever is measured at a piece's middle state. */
        enum class Lever
        {
            NONE,    ///< a translation: no lever
            AXIS,    ///< a joint's rotation: the distance from its axis
            ORIGIN   ///< a free body's turn: the distance from its origin
        };
        /** \brief Per link, one move of a frame on its way up, nearest first: what it measures from which state
            number, its scale (a mimic joint's |multiplier|), the link's crude reach about it (1 for a translation),
            where the frame is on the link's way up (an index into chains_), which frame and about which axis. */
        struct Term
        {
            Measure measure;
            std::size_t variable;
            double scale;
            double reach;
            std::size_t step;
            std::size_t frame;
            Lever lever;
            Eigen::Vector3d axis;
        };
        /** \brief What \e t measures from \e a to \e b, times its scale: the frame's step. */
        static double termMove(const Term &t, const std::vector<double> &a, const std::vector<double> &b);
        /** \brief The terms of frame \e frame moving as \e motion, at \e step on a link's way up, for points at
            most \e reach from its origin, appended to \e terms. */
        static void addTerms(const FrameMotion &motion, std::size_t frame, std::size_t step, double reach,
                             std::vector<Term> &terms);
        /** \brief Every link's terms in a row: link i's are terms_[offsets_[i], offsets_[i + 1]). */
        std::vector<Term> terms_;
        std::vector<std::size_t> offsets_;
        /** \brief Per link, the 8 corners of its BVH's root box, in its body frame. */
        std::vector<std::array<Eigen::Vector3d, 8>> corners_;
        /** \brief Per link, its BVH's root sphere in its body frame: centre, radius. */
        std::vector<Eigen::Vector3d> centres_;
        std::vector<double> radii_;
        /** \brief Per link, its frame and every frame above it, up to the root. */
        std::vector<std::vector<std::size_t>> chains_;
        /** \brief Per link, per frame on its way up (as chains_): how far any point of the link is from that
            frame's origin at any state (the link's own reach, plus the reaches of the frames between). */
        std::vector<std::vector<double>> chainReach_;
        /** \brief commonSteps() of every pair of links, row by the first. */
        std::vector<std::pair<std::size_t, std::size_t>> common_;
    };
}  // namespace meshgap

#endif
