#ifndef MESHGAP_PLANNERS_SUPPORT_MESH_WRITER_H
#define MESHGAP_PLANNERS_SUPPORT_MESH_WRITER_H

#include <Eigen/Core>
#include <string>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief Write \e mesh as a plain Wavefront OBJ file: one `v x y z` line per vertex (printed with %.17g, so
        reading the file back gives the same doubles) and one `f i j k` line per triangle (1-based). The file is
        written beside \e path under a temporary name and renamed over \e path once complete, so a reader never
        sees half a file. Throws meshgap::Exception naming the file if it cannot be written. */
    void writeObj(const Mesh &mesh, const std::string &path);

    /** \brief One mesh of a file written by writeGlb(): its triangles (already in the file's frame), a name and a
        colour. */
    struct ColoredMesh
    {
        std::string name;
        Mesh mesh;
        /** \brief RGBA in [0, 1]; an alpha below 1 is written as a blended (see-through) material. */
        Eigen::Vector4d color{0.7, 0.7, 0.7, 1.0};
    };

    /** \brief Write \e parts as one glTF 2.0 binary file (.glb), through assimp's exporter (format id "glb2"): one
        mesh, one material (base colour and diffuse colour) and one node (identity transform, named after the part)
        per part, in order, vertices in single precision (glTF's), no normals (glTF viewers then shade flat, as the
        specification requires). A part without triangles is skipped. Written under a temporary name and renamed
        over \e path once complete, as writeObj() does. Throws meshgap::Exception naming the file for a triangle
        index out of range, a non-finite coordinate or a failed export (with assimp's message). */
    void writeGlb(const std::vector<ColoredMesh> &parts, const std::string &path);
}  // namespace meshgap

#endif
