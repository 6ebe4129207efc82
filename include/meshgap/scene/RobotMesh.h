#ifndef MESHGAP_SCENE_ROBOT_MESH_H
#define MESHGAP_SCENE_ROBOT_MESH_H

#include <string>

#include "meshgap/mesh/MeshLoader.h"

namespace meshgap
{
    /** \brief Load a robot mesh in OMPL.app's robot frame: every vertex shifted by the robot's centre
        (LoadReport::omplAppCenter), subtracting in single precision as OMPL.app does, so that a state
        (x y z qx qy qz qw) places it exactly where OMPL.app places it: p_world = R(q) (v - c) + (x, y, z).
        The world mesh is loaded as it is (loadMesh()), at the identity pose. */
    Mesh loadRobotMesh(const std::string &path, LoadReport *report = nullptr);

    /** \brief The same for OMPL.app's 2D (SE(2)) problems: shifted by the centre's x and y only (OMPL.app's
        RigidBodyGeometry zeroes the centre's z for Motion_2D), so the robot keeps its height over the plane. */
    Mesh loadPlanarRobotMesh(const std::string &path, LoadReport *report = nullptr);

    /** \brief loadPlanarRobotMesh() for a planar problem, loadRobotMesh() otherwise. */
    inline Mesh loadRobotMesh(const std::string &path, bool planar, LoadReport *report = nullptr)
    {
        return planar ? loadPlanarRobotMesh(path, report) : loadRobotMesh(path, report);
    }
}  // namespace meshgap

#endif
