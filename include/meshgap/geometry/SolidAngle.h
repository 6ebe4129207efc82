#ifndef MESHGAP_GEOMETRY_SOLID_ANGLE_H
#define MESHGAP_GEOMETRY_SOLID_ANGLE_H

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace meshgap
{
    /** \brief Solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee, 1983), signed by the
        triangle's orientation: the terms of a closed surface's winding number about the origin (their sum over 4 pi). */
    inline double solidAngle(const Eigen::Vector3d &a, const Eigen::Vector3d &b, const Eigen::Vector3d &c)
    {
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double numerator = a.dot(b.cross(c));
        const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        return 2.0 * std::atan2(numerator, denominator);
    }
}  // namespace meshgap

#endif
