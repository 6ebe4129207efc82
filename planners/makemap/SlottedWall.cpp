#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "makemap/MapScene.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshOperations.h"
#include "support/Shapes.h"

namespace meshgap
{
    namespace makemap
    {
        // Slotted wall, in its own units: a wall with a narrow slot (short route, little play) and a wide slot off to
        // one side (long route, four times the play), and a C-shaped payload that fits through either slot only lying
        // nearly flat. Not from the paper: a planning problem that forces a trade-off between length and clearance.
        constexpr double WALL_THICKNESS = 10.0;                // x in [-5, 5]
        constexpr double WALL_WIDTH = 200.0;                   // y in [-100, 100]
        constexpr double WALL_HEIGHT = 150.0;                  // z in [0, 150]
        constexpr double SLOT_LENGTH = 40.0;                   // both slots, along y
        constexpr double SLOT_Z = 75.0;                        // both slots' mid-height
        constexpr double PAYLOAD_THICKNESS = 8.0;              // the C part's extrusion
        constexpr double NARROW_SLOT = PAYLOAD_THICKNESS + 5.0; // 5 of play in total, centred at y = 0
        constexpr double WIDE_SLOT = PAYLOAD_THICKNESS + 20.0;  // 20 of play (4x), centred at y = 55
        constexpr double WIDE_SLOT_Y = 55.0;
        constexpr double WALL_GRID = 9.0;
        constexpr double PAYLOAD_GRID = 2.5;

        /** \brief Wall (world frame): x in [-5, 5], y in [-100, 100], z in [0, 150], with two horizontal rectangular
            through slots of length 40 (along y) at z = 75: 13 high at y = 0 and 28 high at y = 55. */
        Mesh slottedWall()
        {
            auto slot = [](double y, double height) {
                return Polygon2d{{y - 0.5 * SLOT_LENGTH, SLOT_Z - 0.5 * height},
                                 {y + 0.5 * SLOT_LENGTH, SLOT_Z - 0.5 * height},
                                 {y + 0.5 * SLOT_LENGTH, SLOT_Z + 0.5 * height},
                                 {y - 0.5 * SLOT_LENGTH, SLOT_Z + 0.5 * height}};
            };
            // Profile drawn in (y, z), extruded along x: (X, Y, Z) -> (Z - 5, X, Y).
            Polyhedron p = meshgap::prismPolyhedron({{-0.5 * WALL_WIDTH, 0.0},
                                                     {0.5 * WALL_WIDTH, 0.0},
                                                     {0.5 * WALL_WIDTH, WALL_HEIGHT},
                                                     {-0.5 * WALL_WIDTH, WALL_HEIGHT}},
                                                    {slot(0.0, NARROW_SLOT), slot(WIDE_SLOT_Y, WIDE_SLOT)}, WALL_THICKNESS);
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
            X.translation() = Vector3d(-0.5 * WALL_THICKNESS, 0.0, 0.0);
            p.transform(X);
            return p.mesh(meshgap::uniformSizing(WALL_GRID), "slotted wall");
        }

        /** \brief Payload (body frame): a C, x in [0, 20], y in [0, 30], arms 6 thick opening towards +x, extruded
            8 along z. */
        Mesh payload()
        {
            return meshgap::prismPolyhedron({{0.0, 0.0},
                                             {20.0, 0.0},
                                             {20.0, 6.0},
                                             {6.0, 6.0},
                                             {6.0, 24.0},
                                             {20.0, 24.0},
                                             {20.0, 30.0},
                                             {0.0, 30.0}},
                                            {}, PAYLOAD_THICKNESS)
                .mesh(meshgap::uniformSizing(PAYLOAD_GRID), "payload");
        }

        Scene slottedWallScene()
        {
            Scene s;
            s.name = "slotted_wall";
            s.units = "units";
            s.a = slottedWall();
            s.b = payload();
            const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
            // Start: in front of the wall (-x), standing on edge (rolled 90 degrees about x: 20 along x, 8 along y, 30
            // along z), which fits neither slot; slid towards the wall until 5 from it. Goal: the same on the far
            // side, 6 from the wall.
            const Eigen::Matrix3d R = rotation(Vector3d::UnitX(), 90.0);
            const Vector3d centre(10.0, 15.0, 0.5 * PAYLOAD_THICKNESS);  // the C's bounding-box centre (body frame)
            s.poses.push_back(placeAtGap(*bodyA, *bodyB, pose(Vector3d(-40.0, -10.0, 70.0) - R * centre, R),
                                         Vector3d::UnitX(), 5.0, "slotted_wall start"));
            s.goal = placeAtGap(*bodyA, *bodyB, pose(Vector3d(40.0, -10.0, 70.0) - R * centre, R), -Vector3d::UnitX(), 6.0,
                                "slotted_wall goal");
            // The state volume keeps B's origin (its vertex mean, near the C's middle; no point of the C is more than 20
            // from it) at least 25 inside the wall's sides, top and bottom, so the only ways across are the slots.
            s.volume = Eigen::AlignedBox3d(Vector3d(-45.0, -75.0, 25.0), Vector3d(45.0, 75.0, 125.0));
            s.partsA = partsByPlace(s.a, {"narrow slot", "wide slot", "wall"}, [](const Vector3d &c) {
                const bool inFace = std::abs(c.x()) < 0.5 * WALL_THICKNESS - 1e-9;
                if (inFace && std::abs(c.y()) <= 0.5 * SLOT_LENGTH + 1e-9 &&
                    std::abs(c.z() - SLOT_Z) <= 0.5 * NARROW_SLOT + 1e-9)
                    return std::size_t(0);
                if (inFace && std::abs(c.y() - WIDE_SLOT_Y) <= 0.5 * SLOT_LENGTH + 1e-9 &&
                    std::abs(c.z() - SLOT_Z) <= 0.5 * WIDE_SLOT + 1e-9)
                    return std::size_t(1);
                return std::size_t(2);
            });
            s.partsB = partsByRuns({{"payload", 0}}, s.b.triangles.size());
            return s;
        }

    }  // namespace makemap
}  // namespace meshgap
