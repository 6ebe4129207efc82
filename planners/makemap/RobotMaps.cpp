// The robot maps: an arm carrying a C-shaped payload through a window in a fixture wall (arm_fixture), and two
// L-shaped bodies swapping rooms through one door, in SE(3) (swap_se3) and in SE(2) (swap_se2). Each is written as
// meshes, a URDF (the arm, URDF primitives only) and a robot problem file, then read back and checked: start and goal
// free (exact whole-robot distance, self pairs included).

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "makemap/MapScene.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "support/MeshWriter.h"
#include "support/Shapes.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace makemap
    {
        namespace
        {
            /** \brief Read the problem back: its start and goal must be free; print their exact clearance. */
            void checkProblem(const fs::path &cfg)
            {
                const RobotProblem p = readRobotProblem(cfg.string());
                const RobotScene scene(p.robot, p.obstacles, p.allowedObstacles);
                RobotRequest request;
                for (const auto *state : {&p.start, &*p.goal})
                {
                    RobotResult r;
                    scene.distance(*state, request, r);
                    if (r.inCollision || r.distance <= 0.0)
                        throw Exception(cfg.string(), std::string(state == &p.start ? "start" : "goal") +
                                                          " collides: the recipe is wrong");
                    std::printf("%s: %s clearance %.6g (%s %s %s)\n", cfg.filename().c_str(),
                                state == &p.start ? "start" : "goal", r.distance, scene.links()[r.link].name.c_str(),
                                r.selfPair ? "and link" : "and obstacle",
                                r.selfPair ? scene.links()[r.other].name.c_str() : std::to_string(r.other).c_str());
                }
                std::printf("%s: %zu links, %zu obstacles, %zu state numbers\n", cfg.filename().c_str(),
                            p.robot->links().size(), p.obstacles.size(), p.robot->dimension());
            }

            /** \brief The arm: a base, a column turning about z, then three links pitching about y (upper arm 0.5,
                forearm 0.4, hand 0.15), a tool frame at the hand's tip; boxes and cylinders only. */
            const char *const ARM_URDF = R"(<?xml version="1.0"?>
<!-- Written by meshgap_makemap: a small four-joint arm of URDF primitives (metres). -->
<robot name="arm4">
  <link name="base">
    <collision><origin xyz="0 0 0.05" rpy="0 0 0"/><geometry><cylinder radius="0.1" length="0.1"/></geometry></collision>
  </link>
  <link name="column">
    <collision><origin xyz="0 0 0.15" rpy="0 0 0"/><geometry><cylinder radius="0.05" length="0.3"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0.25 0 0" rpy="0 0 0"/><geometry><box size="0.5 0.06 0.06"/></geometry></collision>
  </link>
  <link name="fore">
    <collision><origin xyz="0.2 0 0" rpy="0 0 0"/><geometry><box size="0.4 0.05 0.05"/></geometry></collision>
  </link>
  <link name="hand">
    <collision><origin xyz="0.075 0 0" rpy="0 0 0"/><geometry><box size="0.15 0.08 0.04"/></geometry></collision>
  </link>
  <link name="tool"/>
  <joint name="yaw" type="revolute">
    <origin xyz="0 0 0.1" rpy="0 0 0"/><parent link="base"/><child link="column"/><axis xyz="0 0 1"/>
    <limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/>
  </joint>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.3" rpy="0 0 0"/><parent link="column"/><child link="upper"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="revolute">
    <origin xyz="0.5 0 0" rpy="0 0 0"/><parent link="upper"/><child link="fore"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" effort="1" velocity="1"/>
  </joint>
  <joint name="wrist" type="revolute">
    <origin xyz="0.4 0 0" rpy="0 0 0"/><parent link="fore"/><child link="hand"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="1" velocity="1"/>
  </joint>
  <joint name="tool_mount" type="fixed">
    <origin xyz="0.15 0 0" rpy="0 0 0"/><parent link="hand"/><child link="tool"/>
  </joint>
</robot>
)";

            /** \brief An L (two arms \e arm thick, \e size long) in the x-y plane, \e height thick, centred on z = 0. */
            Mesh lShape(double size, double arm, double height, double h)
            {
                return posed(makeExtrusion({{0, 0}, {size, 0}, {size, arm}, {arm, arm}, {arm, size}, {0, size}}, {},
                                           height, h),
                             pose(Vector3d(0, 0, -0.5 * height)));
            }
        }  // namespace

        void writeArmFixture(const fs::path &directory)
        {
            fs::create_directories(directory);
            writeText(directory / "arm4.urdf", ARM_URDF);
            // The payload: a C in the tool frame's x-y plane, x in [0, 0.12], y in [-0.09, 0.09], arms 0.03 thick,
            // opening towards +x, 0.04 thick along z (centred).
            const Mesh c = posed(makeExtrusion({{0, -0.09}, {0.12, -0.09}, {0.12, -0.06}, {0.03, -0.06}, {0.03, 0.06},
                                                {0.12, 0.06}, {0.12, 0.09}, {0, 0.09}},
                                               {}, 0.04, 0.03),
                                 pose(Vector3d(0, 0, -0.02)));
            writeObj(c, (directory / "arm_fixture_payload.obj").string());
            // The fixture: a wall x in [0.62, 0.67], y in [-1.3, 1.3], z in [-0.8, 1.6] (beyond the arm's reach on
            // every side) with a window y in [-0.25, 0.25], z in [0.2, 0.6]: drawn in (y, z), extruded along x.
            Polyhedron wall = prismPolyhedron({{-1.3, -0.8}, {1.3, -0.8}, {1.3, 1.6}, {-1.3, 1.6}},
                                              {{{-0.25, 0.2}, {0.25, 0.2}, {0.25, 0.6}, {-0.25, 0.6}}}, 0.05);
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
            X.translation() = Vector3d(0.62, 0, 0);
            wall.transform(X);
            writeObj(wall.mesh(uniformSizing(0.4), "fixture"), (directory / "arm_fixture_world.obj").string());
            // Start: the payload hangs below the window in front of the wall; goal: the arm straight out through the
            // window, the payload beyond the wall.
            writeText(directory / "arm_fixture.cfg",
                      "[problem]\nname = arm_fixture\nrobot.urdf = arm4.urdf\nworld = arm_fixture_world.obj\n"
                      "attach = arm_fixture_payload.obj tool 0 0 0 0 0 0 1\n"
                      "start.joints = 0 -0.5 2 0.07\ngoal.joints = 0 0 0 0\n\n"
                      "[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n");
            checkProblem(directory / "arm_fixture.cfg");
            // The same arm on a floating base (seven numbers first: x y z qx qy qz qw), free within a box 0.6 by 0.6
            // by 0.4 around the origin; the goal shifts the base 0.1 along x.
            writeText(directory / "arm_fixture_floating.cfg",
                      "[problem]\nname = arm_fixture_floating\nrobot.urdf = arm4.urdf\nworld = arm_fixture_world.obj\n"
                      "attach = arm_fixture_payload.obj tool 0 0 0 0 0 0 1\n"
                      "start.joints = 0 0 0 0 0 0 1 0 -0.5 2 0.07\ngoal.joints = 0.1 0 0 0 0 0 1 0 0 0 0\n"
                      "volume.min.x = -0.3\nvolume.min.y = -0.3\nvolume.min.z = -0.2\n"
                      "volume.max.x = 0.3\nvolume.max.y = 0.3\nvolume.max.z = 0.2\n\n"
                      "[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n");
            checkProblem(directory / "arm_fixture_floating.cfg");
        }

        namespace
        {
            /** \brief "start.N.x = ..." lines of one body (z only in 3D). */
            std::string bodyLines(const std::string &prefix, const Vector3d &p, bool planar)
            {
                std::ostringstream out;
                out << prefix << ".x = " << p.x() << "\n" << prefix << ".y = " << p.y() << "\n";
                if (!planar)
                    out << prefix << ".z = " << p.z() << "\n";
                return out.str();
            }

            /** \brief Two L-shaped bodies in two rooms divided by a wall with one door (y in [-0.5, 0.5]), each body
                behind a partition of its room; start and goal swap them (as OMPL.app's multi-body demos do). */
            void writeSwap(const fs::path &directory, const std::string &name, bool planar)
            {
                fs::create_directories(directory);
                const double lo = planar ? -0.5 : -0.5, hi = planar ? 0.5 : 3.0, h = 1.0;
                std::vector<Mesh> parts = {boxBetween(Vector3d(-2.6, -2.5, lo), Vector3d(-2.4, 0.5, hi), h),
                                           boxBetween(Vector3d(2.4, -0.5, lo), Vector3d(2.6, 2.5, hi), h)};
                if (planar)
                {
                    parts.push_back(boxBetween(Vector3d(-0.1, -2.5, lo), Vector3d(0.1, -0.5, hi), h));
                    parts.push_back(boxBetween(Vector3d(-0.1, 0.5, lo), Vector3d(0.1, 2.5, hi), h));
                }
                else
                {
                    // The dividing wall drawn in (y, z), the door 1 wide and 1.5 high, extruded along x.
                    Polyhedron wall = prismPolyhedron({{-2.5, lo}, {2.5, lo}, {2.5, hi}, {-2.5, hi}},
                                                      {{{-0.5, 0.0}, {0.5, 0.0}, {0.5, 1.5}, {-0.5, 1.5}}}, 0.2);
                    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                    X.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
                    X.translation() = Vector3d(-0.1, 0, 0);
                    wall.transform(X);
                    parts.push_back(wall.mesh(uniformSizing(h), "wall"));
                }
                writeObj(mergeMeshes(parts, ""), (directory / (name + "_world.obj")).string());
                writeObj(lShape(0.6, 0.2, planar ? 0.2 : 0.3, 0.2), (directory / (name + "_robot.obj")).string());
                const Vector3d a(-3.3, -1.2, 1.0), b(3.3, 1.2, 1.0);
                std::ostringstream cfg;
                cfg << "[problem]\nname = " << name << "\nrobot.1 = " << name << "_robot.obj\nrobot.2 = " << name
                    << "_robot.obj\nworld = " << name << "_world.obj\n"
                    << bodyLines("start.1", a, planar) << bodyLines("start.2", b, planar)
                    << bodyLines("goal.1", b, planar) << bodyLines("goal.2", a, planar)
                    << "volume.min.x = -4\nvolume.min.y = -2\n" << (planar ? "" : "volume.min.z = 0\n")
                    << "volume.max.x = 4\nvolume.max.y = 2\n" << (planar ? "" : "volume.max.z = 2.5\n")
                    << "\n[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n";
                writeText(directory / (name + ".cfg"), cfg.str());
                checkProblem(directory / (name + ".cfg"));
            }
        }  // namespace

        void writeSwapSE3(const fs::path &directory)
        {
            writeSwap(directory, "swap_se3", false);
        }

        void writeSwapSE2(const fs::path &directory)
        {
            writeSwap(directory, "swap_se2", true);
        }
    }  // namespace makemap
}  // namespace meshgap
