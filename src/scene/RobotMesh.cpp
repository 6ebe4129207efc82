#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    namespace
    {
        /** \brief Shift by the centre (its z only when \e shiftZ), in single precision. Vertices are single-precision
            values widened to double, so float(v) is exact; the subtraction rounds to float as OMPL.app's aiVector3D
            arithmetic does. */
        Mesh centred(const std::string &path, LoadReport *reportOut, bool shiftZ)
        {
            LoadReport report;
            LoadOptions options;
            options.omplAppCenter = true;
            Mesh mesh = loadMesh(path, &report, options);
            const Eigen::Vector3d &c = report.omplAppCenter.value();
            const float cx = static_cast<float>(c.x()), cy = static_cast<float>(c.y()),
                        cz = shiftZ ? static_cast<float>(c.z()) : 0.0f;
            for (Eigen::Vector3d &v : mesh.vertices)
                v = Eigen::Vector3d(static_cast<float>(v.x()) - cx, static_cast<float>(v.y()) - cy,
                                    shiftZ ? static_cast<double>(static_cast<float>(v.z()) - cz) : v.z());
            if (reportOut)
                *reportOut = report;
            return mesh;
        }
    }  // namespace

    Mesh loadRobotMesh(const std::string &path, LoadReport *report)
    {
        return centred(path, report, true);
    }

    Mesh loadPlanarRobotMesh(const std::string &path, LoadReport *report)
    {
        return centred(path, report, false);
    }
}  // namespace meshgap
