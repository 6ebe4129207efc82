#ifndef MESHGAP_ROBOT_MOTION_BOUND_H
#define MESHGAP_ROBOT_MOTION_BOUND_H

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

    private:
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
        /** \brief Per link, one move of a frame on its way up, nearest first: what it measures from which state
            number, its factor, and where the frame is on the link's way up (an index into chains_). */
        struct Term
        {
            Measure measure;
            std::size_t variable;
            double factor;
            std::size_t step;
        };
        /** \brief What \e t measures from \e a to \e b, times its factor. */
        static double termMove(const Term &t, const std::vector<double> &a, const std::vector<double> &b);
        /** \brief The terms of frame \e motion, at \e step on a link's way up, for points at most \e reach from
            its origin, appended to \e terms. */
        static void addTerms(const FrameMotion &motion, std::size_t step, double reach, std::vector<Term> &terms);
        std::vector<std::vector<Term>> terms_;
        /** \brief Per link, its frame and every frame above it, up to the root. */
        std::vector<std::vector<std::size_t>> chains_;
    };
}  // namespace meshgap

#endif
