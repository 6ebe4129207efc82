#ifndef MESHGAP_GEOMETRY_PRIMITIVE_H
#define MESHGAP_GEOMETRY_PRIMITIVE_H

#include <Eigen/Geometry>

namespace meshgap
{
    /** \brief A primitive solid as URDF and MoveIt name it (shape_msgs/SolidPrimitive): what a body's mesh was built
        from when it was built from primitives (Body::primitives()), whose mesh circumscribes the solid (boxMesh(),
        cylinderMesh(), sphereMesh(), coneMesh()). Exact distance and collision answer such a body as its solids
        (PrimitiveDistance.h, BvhSolid.h); the node solvers and penetration depth read its mesh. */
    struct Primitive
    {
        enum class Kind
        {
            BOX,       ///< edge lengths size.x(), size.y(), size.z(), centred on the origin
            SPHERE,    ///< radius size.x() about the origin
            CYLINDER,  ///< radius size.x(), length size.y(), about the z axis, centred on the origin
            CONE,      ///< base radius size.x() at z = -size.y() / 2, apex at z = +size.y() / 2
            CAPSULE    ///< the points within size.x() of the segment from z = -size.y() / 2 to +size.y() / 2 (FCL's)
        };
        Kind kind{Kind::BOX};
        /** \brief The dimensions, as \e kind reads them (unused entries 0). */
        Eigen::Vector3d size{Eigen::Vector3d::Zero()};
        /** \brief The solid's pose in the frame of the body's mesh. */
        Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
    };
}  // namespace meshgap

#endif
