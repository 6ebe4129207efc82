#include "support/SceneExport.h"

#include <cmath>

#include "meshgap/Exception.h"

namespace meshgap
{
    Mesh segmentBox(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double width)
    {
        if (!(width > 0.0) || !std::isfinite(width) || !a.allFinite() || !b.allFinite())
            throw Exception("segmentBox", "needs finite end points and a positive, finite width");
        const double length = (b - a).norm();
        const Eigen::Vector3d axis = length > 0.0 ? Eigen::Vector3d((b - a) / length) : Eigen::Vector3d::UnitX();
        // Two unit vectors across the axis.
        const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
        const double h = 0.5 * width;
        const Eigen::Vector3d from = a - h * axis, to = b + h * axis;
        Mesh box;
        box.source = "segment";
        for (const Eigen::Vector3d &end : {from, to})
            for (const auto &corner :
                 {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)})
                box.vertices.push_back(end + h * (corner.x() * u + corner.y() * v));
        // Corners 0-3 at the start, 4-7 at the end, counter-clockwise about the axis; faces wound outward.
        box.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}};
        for (std::uint32_t i = 0; i < 4; ++i)
        {
            const std::uint32_t j = (i + 1) % 4;
            box.triangles.push_back({i, j, j + 4});
            box.triangles.push_back({i, j + 4, i + 4});
        }
        return box;
    }

    std::vector<ColoredMesh> sceneExportParts(const Scene &scene, const std::vector<Eigen::Isometry3d> &robotPoses,
                                              const SceneExportOptions &options, std::vector<SceneResult> *results)
    {
        std::vector<ColoredMesh> parts;
        for (std::size_t i = 0; i < scene.obstacles().size(); ++i)
            parts.push_back({"obstacle " + std::to_string(i), scene.obstacles()[i]->surface(), options.worldColor});
        const Mesh &robot = scene.robot().surface();
        const double width = options.segmentWidth > 0.0 ? options.segmentWidth : robot.size() / 200.0;
        if (results)
            results->clear();
        SceneWarmStart warm;
        for (std::size_t k = 0; k < robotPoses.size(); ++k)
        {
            const Eigen::Isometry3d &X = robotPoses[k];
            SceneResult r;
            scene.distance(X, SceneRequest(), warm, r);
            ColoredMesh placed{"robot " + std::to_string(k), robot,
                               r.inCollision ? options.collisionColor : options.robotColor};
            for (Eigen::Vector3d &p : placed.mesh.vertices)
                p = X * p;
            parts.push_back(std::move(placed));
            parts.push_back({"clearance " + std::to_string(k), segmentBox(r.onA, r.onB, width),
                             r.inCollision ? options.collisionColor : options.segmentColor});
            if (results)
                results->push_back(r);
        }
        return parts;
    }

    std::vector<ColoredMesh> robotExportParts(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                              const SceneExportOptions &options)
    {
        std::vector<ColoredMesh> parts;
        for (std::size_t i = 0; i < scene.obstacles().size(); ++i)
            parts.push_back({"obstacle " + std::to_string(i), scene.obstacles()[i]->surface(), options.worldColor});
        const std::size_t links = scene.links().size();
        double size = 0.0;
        for (const RobotLink &link : scene.links())
            size = std::max(size, link.body->surface().size());
        const double width = options.segmentWidth > 0.0 ? options.segmentWidth : size / 200.0;
        RobotWarmStart warm;
        RobotResult r;
        std::vector<Eigen::Isometry3d> frames, poses;
        for (std::size_t k = 0; k < states.size(); ++k)
        {
            scene.distance(states[k].data(), states[k].size(), RobotRequest(), warm, r);
            scene.robot().linkPoses(states[k].data(), states[k].size(), frames, poses);
            const Eigen::Vector4d &color = r.inCollision ? options.collisionColor : options.robotColor;
            for (std::size_t i = 0; i < links; ++i)
            {
                ColoredMesh placed{"robot " + std::to_string(k) + (links == 1 ? "" : " " + scene.links()[i].name),
                                   scene.links()[i].body->surface(), color};
                for (Eigen::Vector3d &p : placed.mesh.vertices)
                    p = poses[i] * p;
                parts.push_back(std::move(placed));
            }
            parts.push_back({"clearance " + std::to_string(k), segmentBox(r.onA, r.onB, width),
                             r.inCollision ? options.collisionColor : options.segmentColor});
        }
        return parts;
    }
}  // namespace meshgap
