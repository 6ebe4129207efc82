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
}  // namespace meshgap

#endif
