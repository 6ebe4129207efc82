#ifndef MESHGAP_ROBOT_MOTION_BOUND_H
#define MESHGAP_ROBOT_MOTION_BOUND_H

#include <vector>

#include "meshgap/robot/UrdfRobot.h"

namespace meshgap
{
    /** \brief How far any point of a link can move along a straight joint-space motion of a fixed-base URDF
        robot (adaptive dynamic collision checking: Schwarzer, Saha and Latombe, IEEE T-RO 2005): at most
        sum_j |dq_j| r_jL over the movable joints j above link L, where r_jL bounds the distance of any point of L
        from joint j's axis (revolute, continuous: the lengths of the joint origins from j down to L, the largest
        reach of the prismatic joints between, and L's radius about its frame) and r_jL = 1 for a prismatic joint.
        A mimic joint moves |multiplier| times its source. Continuous joints move along the shorter arc, as OMPL's
        SO(2) interpolation does. The bound holds for every state between (the joint values change linearly). */
    class MotionBound
    {
    public:
        /** \brief Throws meshgap::Exception for a floating base (not bounded here). */
        explicit MotionBound(const UrdfRobot &robot);

        /** \brief The bound for every link of \e robot (as it was given, payloads included) from state \e a to
            state \e b (each robot.dimension() numbers), into \e out. */
        void linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                               std::vector<double> &out) const;

        /** \brief The bound for links \e first and \e second relative to each other from state \e a to state
            \e b: how far any point of either moves in the frame of their nearest common ancestor (the joints above
            that frame move both alike, which changes no distance between them), summed over the two. At most
            linkDisplacements()' two bounds added; far less for links close in the tree (a wrist and the link two
            joints up). */
        double pairDisplacement(std::size_t first, std::size_t second, const std::vector<double> &a,
                                const std::vector<double> &b) const;

    private:
        /** \brief Per link, the movable joints above it, nearest first: the state number driving it, its factor
            r * |m|, and where its child frame is on the link's way up (an index into chains_). */
        struct Term
        {
            std::size_t variable;
            double factor;
            bool angle;  ///< a continuous joint's value: the shorter arc
            std::size_t step;
        };
        /** \brief |b - a| of \e t (the shorter arc for an angle) times its factor. */
        static double termMove(const Term &t, const std::vector<double> &a, const std::vector<double> &b);
        std::vector<std::vector<Term>> terms_;
        /** \brief Per link, its frame and every frame above it, up to the root. */
        std::vector<std::vector<std::size_t>> chains_;
        std::vector<bool> continuous_;  ///< per state number
    };
}  // namespace meshgap

#endif
