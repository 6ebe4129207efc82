#ifndef MESHGAP_PLANNERS_SUPPORT_SCENE_EXPORT_H
#define MESHGAP_PLANNERS_SUPPORT_SCENE_EXPORT_H

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/Scene.h"
#include "support/MeshWriter.h"

namespace meshgap
{
    /** \brief What sceneExportParts() draws. */
    struct SceneExportOptions
    {
        /** \brief Side of the closest-point segments' square cross-section; negative: 1/200 of the robot's size
            (its surface's bounding-box diagonal). */
        double segmentWidth{-1.0};
        Eigen::Vector4d worldColor{0.62, 0.64, 0.68, 0.6};      ///< obstacles (see-through)
        Eigen::Vector4d robotColor{0.20, 0.45, 0.85, 1.0};      ///< the robot at each pose
        Eigen::Vector4d segmentColor{0.10, 0.75, 0.25, 1.0};    ///< a free pose's closest-point segment
        Eigen::Vector4d collisionColor{0.90, 0.10, 0.10, 1.0};  ///< a colliding pose's robot and segment
    };

    /** \brief A thin box (8 corners, 12 triangles, closed) of square cross-section \e width along the segment from
        \e a to \e b, extended by width / 2 beyond each end, so a zero-length segment still gives a small cube. */
    Mesh segmentBox(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double width);

    /** \brief The scene as meshes in the world frame, for writeGlb(): each obstacle's surface ("obstacle i"), then
        for each pose k of \e robotPoses the robot's surface there ("robot k") and the closest-point segment
        ("clearance k", from the robot's witness point to the obstacle's) of the exact query Scene::distance() (one
        warm start carried along the poses, which changes no answer). A colliding pose's robot and segment get
        options.collisionColor (its witness points are then those of the penetration depth, see Scene::distance()).
        If \e results is given it receives the query result at each pose. */
    std::vector<ColoredMesh> sceneExportParts(const Scene &scene, const std::vector<Eigen::Isometry3d> &robotPoses,
                                              const SceneExportOptions &options = SceneExportOptions(),
                                              std::vector<SceneResult> *results = nullptr);

    /** \brief The same scene for any kind of problem (a single body is a robot of one link): each obstacle's surface
        ("obstacle i"), then at each robot state k of \e states every link's surface there ("robot k" for a robot of
        one link, "robot k LINK" for several) and the closest-point segment of the pair that attains the whole
        robot's clearance ("clearance k", the exact RobotScene::distance(), one warm start carried along), a
        colliding state's links and segment in options.collisionColor. The segment's width (when not given) is 1/200
        of the largest link's size. */
    std::vector<ColoredMesh> robotExportParts(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                              const SceneExportOptions &options = SceneExportOptions());
}  // namespace meshgap

#endif
