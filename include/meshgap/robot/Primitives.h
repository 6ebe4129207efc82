#ifndef MESHGAP_ROBOT_PRIMITIVES_H
#define MESHGAP_ROBOT_PRIMITIVES_H

#include <Eigen/Core>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief A closed box of edge lengths \e size centred on the origin (URDF's box): 8 corners, 12 triangles
        wound outward. Throws meshgap::Exception for a size not positive and finite. */
    Mesh boxMesh(const Eigen::Vector3d &size);

    /** \brief A closed cylinder about the z axis, centred on the origin (URDF's cylinder, MoveIt's): a prism on a
        regular \e segments-gon CIRCUMSCRIBED about the circle of \e radius (its sides tangent to the circle),
        \e length long, wound outward. The prism contains the true cylinder, so a state the mesh finds free is free
        for the cylinder, and a distance to the mesh is a lower bound of the distance to the cylinder, below it by at
        most the excess radius(1 / cos(pi / segments) - 1) (0.48% of the radius at 32 segments). Throws
        meshgap::Exception for a radius or length not positive and finite, or fewer than 3 segments. */
    Mesh cylinderMesh(double radius, double length, unsigned int segments);

    /** \brief A closed sphere of \e radius about the origin (URDF's sphere, MoveIt's): a latitude-longitude mesh with
        \e segments meridians and segments / 2 bands, convex and scaled so that every face's plane is at least
        \e radius from the centre: it CIRCUMSCRIBES the sphere (contains the ball). Distances to it are lower bounds,
        below the sphere's by at most radius(1 / cos^2(pi / segments) - 1) (0.97% at 32 segments; sphereExcess()
        gives the exact figure). Throws meshgap::Exception for a radius not positive and finite, or fewer than 4
        segments. */
    Mesh sphereMesh(double radius, unsigned int segments);

    /** \brief How far sphereMesh(radius, segments) reaches beyond the sphere at most: its farthest vertex's distance
        from the centre less \e radius. */
    double sphereExcess(double radius, unsigned int segments);

    /** \brief A closed cone about the z axis (MoveIt's cone): its base, a regular \e segments-gon circumscribed
        about the circle of \e radius, at z = -length / 2, its apex at z = +length / 2, wound outward. It contains the
        true cone; distances are lower bounds, below the cone's by at most radius(1 / cos(pi / segments) - 1).
        Throws meshgap::Exception as cylinderMesh(). */
    Mesh coneMesh(double radius, double length, unsigned int segments);
}  // namespace meshgap

#endif
