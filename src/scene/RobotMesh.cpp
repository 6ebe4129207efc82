#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    Mesh loadRobotMesh(const std::string &path, LoadReport *reportOut)
    {
        LoadReport report;
        Mesh mesh = loadMesh(path, &report);
        // Vertices are single-precision values widened to double, so float(v) is exact; the subtraction rounds to
        // float as OMPL.app's aiVector3D arithmetic does.
        const float cx = static_cast<float>(report.omplAppCenter.x()), cy = static_cast<float>(report.omplAppCenter.y()),
                    cz = static_cast<float>(report.omplAppCenter.z());
        for (Eigen::Vector3d &v : mesh.vertices)
            v = Eigen::Vector3d(static_cast<float>(v.x()) - cx, static_cast<float>(v.y()) - cy,
                                static_cast<float>(v.z()) - cz);
        if (reportOut)
            *reportOut = report;
        return mesh;
    }
}  // namespace meshgap
