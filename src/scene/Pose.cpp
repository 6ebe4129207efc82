#include "meshgap/scene/Pose.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Limits.h"
#include "meshgap/Text.h"

namespace meshgap
{
    Eigen::Isometry3d parsePose(const std::string &text, const std::string &where)
    {
        std::istringstream in(text);
        std::vector<double> v;
        std::string token;
        while (in >> token)
        {
            double x = 0.0;
            if (!parseNumber(token, x))
                throw Exception(where, quote(token) + " is not a number (expected x y z qx qy qz qw)");
            v.push_back(x);
        }
        if (v.size() != 7)
            throw Exception(where, "expected 7 numbers (x y z qx qy qz qw), found " + std::to_string(v.size()));
        for (double x : v)
            if (!std::isfinite(x))
                throw Exception(where, "pose has a NaN or infinite number");
        for (int k = 0; k < 3; ++k)
            if (std::abs(v[k]) > MAX_MAGNITUDE)
            {
                std::ostringstream problem;
                problem << "position " << "xyz"[k] << " = " << v[k] << " is beyond 1e12 in magnitude, the largest "
                        << "meshgap's geometry answers reliably";
                throw Exception(where, problem.str());
            }
        Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // Eigen takes w first
        const double norm = q.norm();
        if (std::abs(norm - 1.0) > 1e-3)
            throw Exception(where, "quaternion (qx qy qz qw) is not of unit length (norm " + std::to_string(norm) + ")");
        q.normalize();
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = q.toRotationMatrix();
        pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        return pose;
    }

    std::vector<Eigen::Isometry3d> readPoses(const std::string &path)
    {
        checkInputFile(path);
        std::ifstream in(path);
        if (!in)
            throw Exception(excerpt(path), "cannot open the pose file");
        std::vector<Eigen::Isometry3d> poses;
        std::string line;
        for (std::size_t number = 1; std::getline(in, line); ++number)
        {
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#')
                continue;
            poses.push_back(parsePose(line, excerpt(path) + ":" + std::to_string(number)));
        }
        if (poses.empty())
            throw Exception(excerpt(path), "no poses in the file");
        return poses;
    }

    std::string formatPose(const Eigen::Isometry3d &pose)
    {
        const Eigen::Quaterniond q(pose.linear());
        char buffer[256];
        std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g", pose.translation().x(),
                      pose.translation().y(), pose.translation().z(), q.x(), q.y(), q.z(), q.w());
        return buffer;
    }

    Eigen::Isometry3d poseFromAxisAngle(const Eigen::Vector3d &position, double theta, const Eigen::Vector3d &axis)
    {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        if (theta != 0.0)
        {
            // Scale by the largest component first: axis.normalized() alone overflows for components above about
            // 1e154 (giving a zero axis, so a matrix that is no rotation) and underflows below about 1e-154.
            const double largest = axis.cwiseAbs().maxCoeff();
            if (!(largest > 0.0) || !std::isfinite(largest) || !std::isfinite(theta))
                throw Exception("rotation", "the axis must be finite and non-zero and the angle finite");
            pose.linear() = Eigen::AngleAxisd(theta, (axis / largest).normalized()).toRotationMatrix();
        }
        pose.translation() = position;
        return pose;
    }
}  // namespace meshgap
