#ifndef MESHGAP_MESH_MESH_OPERATIONS_H
#define MESHGAP_MESH_MESH_OPERATIONS_H

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief Signed enclosed volume of a closed triangle mesh (positive when wound outward). */
    double signedVolume(const Mesh &mesh);

    /** \brief Several meshes as one (a body of several components); \e name becomes Mesh::source. */
    Mesh mergeMeshes(const std::vector<Mesh> &parts, const std::string &name);

    /** \brief Move every vertex by \e X. */
    void transformMesh(Mesh &mesh, const Eigen::Isometry3d &X);

    /** \brief Mean of the vertices (what OMPL.app takes as a robot mesh's centre). */
    Eigen::Vector3d vertexMean(const Mesh &mesh);

    /** \brief Split a mesh into its connected parts (by shared vertices), each a mesh of its own with only the
        vertices it uses, in order of first triangle. A world file becomes one obstacle per part. Throws
        meshgap::Exception naming Mesh::source for a triangle index out of range. */
    std::vector<Mesh> splitComponents(const Mesh &mesh);
}  // namespace meshgap

#endif
