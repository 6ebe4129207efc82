#ifndef MESHGAP_ROBOT_PRIMITIVES_H
#define MESHGAP_ROBOT_PRIMITIVES_H

#include <Eigen/Core>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief A closed box of edge lengths \e size centred on the origin (URDF's box): 8 corners, 12 triangles
        wound outward. Throws meshgap::Exception for a size not positive and finite. */
    Mesh boxMesh(const Eigen::Vector3d &size);

    /** \brief A closed cylinder about the z axis, centred on the origin (URDF's cylinder): a prism on a regular
        \e segments-gon inscribed in the circle of \e radius, \e length long, wound outward. Throws
        meshgap::Exception for a radius or length not positive and finite, or fewer than 3 segments. */
    Mesh cylinderMesh(double radius, double length, unsigned int segments);

    /** \brief A closed sphere of \e radius about the origin (URDF's sphere): a latitude-longitude mesh with
        \e segments meridians and segments / 2 bands (every vertex on the sphere), wound outward. Throws
        meshgap::Exception for a radius not positive and finite, or fewer than 4 segments. */
    Mesh sphereMesh(double radius, unsigned int segments);
}  // namespace meshgap

#endif
