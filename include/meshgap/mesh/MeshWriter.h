#ifndef MESHGAP_MESH_MESH_WRITER_H
#define MESHGAP_MESH_MESH_WRITER_H

#include <string>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief Write \e mesh as a plain Wavefront OBJ file: one `v x y z` line per vertex (printed with %.17g, so
        reading the file back gives the same doubles) and one `f i j k` line per triangle (1-based). The file is
        written beside \e path under a temporary name and renamed over \e path once complete, so a reader never
        sees half a file. Throws meshgap::Exception naming the file if it cannot be written. */
    void writeObj(const Mesh &mesh, const std::string &path);
}  // namespace meshgap

#endif
