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

    private:
        /** \brief Per link, the movable joints above it: the state number driving it and its factor r * |m|. */
        struct Term
        {
            std::size_t variable;
            double factor;
            bool angle;  ///< a continuous joint's value: the shorter arc
        };
        std::vector<std::vector<Term>> terms_;
        std::vector<bool> continuous_;  ///< per state number
    };
}  // namespace meshgap

#endif
