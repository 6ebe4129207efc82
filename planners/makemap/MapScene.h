#ifndef MESHGAP_PLANNERS_MAKEMAP_MAP_SCENE_H
#define MESHGAP_PLANNERS_MAKEMAP_MAP_SCENE_H

// What meshgap_makemap's scene recipes make and its writer writes: a scene (bodies A and B, B's poses, a planning
// problem, named parts), and the helpers the recipes share: poses, parts and the exact gap solver.

#include <Eigen/Geometry>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/Mesh.h"
#include "support/Shapes.h"

namespace meshgap
{
    namespace makemap
    {
        using Eigen::Vector2d;
        using Eigen::Vector3d;

        constexpr double PI = 3.14159265358979323846;

        inline double radians(double degrees)
        {
            return degrees * PI / 180.0;
        }

        /** \brief Largest edge of the battery and fixture meshes in cm (--battery-grid). */
        extern double batteryGrid;

        // ---------------------------------------------------------------------------------------------------------
        // Scenes
        // ---------------------------------------------------------------------------------------------------------

        struct Parts
        {
            std::vector<std::string> names;
            std::vector<std::size_t> label;  // per triangle, an index into names
        };

        struct Scene
        {
            std::string name, units, description;
            Mesh a, b;                               // A in the world frame; B in its body frame (not yet centred)
            std::vector<Eigen::Isometry3d> poses;    // B's body frame in A's frame
            std::optional<Eigen::Isometry3d> start;  // the planning problem's start; unset: the first pose
            Eigen::Isometry3d goal;                  // a pose clear of A (for the planning problem)
            Parts partsA, partsB;                    // named groups of triangles (for the report)
            std::optional<Eigen::AlignedBox3d> volume;  // the cfg's state volume; unset: a box around everything
        };

        /** \brief The pose with this translation and rotation. */
        Eigen::Isometry3d pose(const Vector3d &translation, const Eigen::Matrix3d &rotation = Eigen::Matrix3d::Identity());

        /** \brief Rotation by \e degrees about \e axis. */
        Eigen::Matrix3d rotation(const Vector3d &axis, double degrees);

        /** \brief The triangles of one part (all vertices kept). */
        Mesh partMesh(const Mesh &m, const Parts &parts, std::size_t i);

        /** \brief Parts of a body whose triangles come in consecutive runs (name, first triangle). */
        Parts partsByRuns(const std::vector<std::pair<std::string, std::size_t>> &runs, std::size_t triangles);

        /** \brief Parts of a body told apart by where each triangle's centroid is. */
        Parts partsByPlace(const Mesh &m, std::vector<std::string> names,
                           const std::function<std::size_t(const Vector3d &)> &classify);

        /** \brief \e body moved by \e X. */
        Mesh posed(const Mesh &body, const Eigen::Isometry3d &X);

        /** \brief A box between corners \e lo and \e hi, one grid cell per \e h. */
        Mesh boxBetween(const Vector3d &lo, const Vector3d &hi, double h);

        /** \brief \e text written to \e path (a .cfg, a URDF) whole or not at all (writeStreamAtomically()). */
        void writeText(const std::filesystem::path &path, const std::string &text);

        /** \brief A mesh as a body for exact queries: its surface kept as it is (no refinement), so triangle indices
            in a DistanceResult are the mesh's own. */
        BodyPtr exactBody(const Mesh &mesh);

        /** \brief Exact distance between A and B placed at X (B's pose in A's frame): closest triangles and witness
            points (in A's frame), distance 0 when they intersect or one lies inside the other. */
        DistanceResult distanceAt(const Body &a, const Body &b, const Eigen::Isometry3d &X);

        /** \brief Slide B from pose X along the unit direction w until its exact distance to A is \e gap. */
        Eigen::Isometry3d placeAtGap(const Body &a, const Body &b, Eigen::Isometry3d X, const Vector3d &w, double gap,
                                     const std::string &what);

        /** \brief The recipes: the paper's scenes (PaperScenes.cpp) and two of meshgap's own. */
        Scene batteryFixture();
        Scene handBowl();
        Scene handshake();
        Scene slottedWallScene();
        Scene twistedScene();

        /** \brief The robot maps (RobotMaps.cpp), each written into \e directory with its robot problem file, then
            read back and checked (start and goal free). */
        void writeArmFixture(const std::filesystem::path &directory);
        void writeSwapSE3(const std::filesystem::path &directory);
        void writeSwapSE2(const std::filesystem::path &directory);

        /** \brief The control maps (ControlMaps.cpp): OMPL.app control problems, each written into \e directory with
            its meshes, then read back and set up as meshgap_plan sets it up (start and goal free). */
        void writeCarChicane(const std::filesystem::path &directory);
        void writeBlimpWindow(const std::filesystem::path &directory);
        void writeQuadrotorWindow(const std::filesystem::path &directory);

        /** \brief Write \e s into \e directory (meshes, poses, the OMPL.app problem), then report and check it. */
        void writeScene(Scene s, const std::filesystem::path &directory);
    }  // namespace makemap
}  // namespace meshgap

#endif
