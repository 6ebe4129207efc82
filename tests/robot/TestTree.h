#ifndef MESHGAP_TESTS_ROBOT_TEST_TREE_H
#define MESHGAP_TESTS_ROBOT_TEST_TREE_H

// The robot tests' small arm: tests/resources' tree.urdf (five joints of every kind), a box payload on its tool, and
// six boxes around its base within its reach.

#include <cmath>
#include <string>
#include <vector>

#include "TestMeshes.h"
#include "meshgap/robot/UrdfRobot.h"

namespace meshgap::test
{
    inline const std::string TREE_URDF =
        std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/meshgap_test_description/urdf/tree.urdf";

    /** \brief mobile.urdf: a planar base (normal z) with a revolute arm, a floating drone and a planar slider (normal
        x); state "drive.x y theta, shoulder, fly.x y z qx qy qz qw, wall.x y theta" (14 numbers). */
    inline const std::string MOBILE_URDF =
        std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/meshgap_test_description/urdf/mobile.urdf";

    /** \brief tree.urdf with a box payload (half-extents 3, 2 and 1 cm) 4 cm out along its tool's z. */
    inline UrdfRobotPtr treeWithPayload()
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE_URDF);
        robot->attach("payload", box(0.03, 0.02, 0.01), "tool", translation(0.0, 0.0, 0.04));
        return robot;
    }

    /** \brief Six posts 10 cm square and \e top high, standing on z = 0 at radius 0.35 around the tree's base, every 60 deg:
        its sweep passes near and through them. */
    inline std::vector<BodyConstPtr> postsAroundTree(double top = 0.6)
    {
        std::vector<BodyConstPtr> bodies;
        for (int k = 0; k < 6; ++k)
        {
            const double a = k * M_PI / 3;
            bodies.push_back(Body::build(
                transformed(box(0.05, 0.05, top / 2), translation(0.35 * std::cos(a), 0.35 * std::sin(a), top / 2))));
        }
        return bodies;
    }

    /** \brief The nearest frame above both \e f1 and \e f2 (themselves included), or NONE (two roots): found by
        walking the parents, apart from the library's own search. */
    inline std::size_t commonFrame(const RobotModel &robot, std::size_t f1, std::size_t f2)
    {
        for (std::size_t f = f1; f != RobotModel::NONE; f = robot.frames()[f].parent)
            for (std::size_t g = f2; g != RobotModel::NONE; g = robot.frames()[g].parent)
                if (f == g)
                    return f;
        return RobotModel::NONE;
    }
}  // namespace meshgap::test

#endif
