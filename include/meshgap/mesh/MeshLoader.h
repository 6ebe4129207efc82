#ifndef MESHGAP_MESH_MESH_LOADER_H
#define MESHGAP_MESH_MESH_LOADER_H

#include <Eigen/Core>
#include <optional>
#include <string>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief What loading a file found and changed. */
    struct LoadReport
    {
        std::size_t rawVertices{0};   ///< vertices assimp returned, over all sub-meshes (before welding)
        std::size_t rawTriangles{0};  ///< three-index faces assimp returned
        std::size_t skippedPrimitives{0};  ///< points and lines (e.g. SketchUp edge lines), not surfaces
        CleanReport clean;                 ///< degenerate and duplicated triangles dropped
        std::size_t components{0};         ///< connected components of the welded surface
        /** \brief Boundary and non-manifold edges of the welded surface, all parts together (an open or
            non-manifold file is warned about once, with these counts). */
        EdgeReport edges;
        /** \brief OMPL.app's robot centre, when LoadOptions::omplAppCenter asked for it: the mean of every vertex
            assimp returned with OMPL.app's post-processing (duplicates and line-mesh vertices included) after node
            transforms, accumulated in single precision exactly as OMPL.app's scene::sceneCenter does. OMPL.app
            shifts a robot mesh by this point. Empty when not asked for. */
        std::optional<Eigen::Vector3d> omplAppCenter;
    };

    /** \brief What loadMesh() computes besides the mesh. */
    struct LoadOptions
    {
        /** \brief Import with OMPL.app's whole post-processing, its GenNormals and JoinIdenticalVertices steps
            included, and fill LoadReport::omplAppCenter from the vertices they leave. The two steps split each
            corner by its face's normal and join the copies again within a mesh; the centre counts what they leave
            (on a 250k-triangle file about 0.4 s of assimp's 0.5 s). Without this the file is imported without
            them: the weld that follows does their joining, and the mesh is the same (same vertices, same order,
            same triangles; checked on every mesh file of the test and benchmark data). */
        bool omplAppCenter{false};
    };

    /** \brief Load a triangle mesh (OBJ, STL ASCII/binary, PLY, COLLADA and anything else assimp reads).

        The file is imported with OMPL.app's post-processing (Triangulate, SortByPType, OptimizeGraph; and
        JoinIdenticalVertices and GenNormals when \e options ask for OMPL.app's centre) and default importer settings,
        so COLLADA's up-axis rotation applies and vertex positions are bit-for-bit those OMPL.app uses. Every node
        transform is applied (in assimp's single precision arithmetic, as OMPL.app does) and all sub-meshes are merged;
        only three-index faces are kept. Then vertices at identical positions are welded regardless of normals or
        texture coordinates (so flat-shaded files that repeat each vertex per face stay one connected surface), and
        degenerate and duplicated triangles are dropped (counted in the report, with a warning). A surface that is not
        closed (boundary edges, used by one triangle, or non-manifold edges, used by three or more) is loaded as it is,
        with one warning naming the file and both counts (LoadReport::edges; once per process, warnIfNotClosed()): it
        has no inside, so nothing is found to lie inside it (no containment, no penetration depth into it; README.md,
        "Open meshes").

        Throws meshgap::Exception naming \e path for: a missing or unreadable file, a file assimp cannot parse,
        no triangles, a NaN or infinite coordinate, an index out of range. */
    Mesh loadMesh(const std::string &path, LoadReport *report = nullptr, const LoadOptions &options = {});

    /** \brief The one warning (OMPL_WARN) loadMesh() gives for a surface that is not closed, naming \e name (a file,
        or what a mesh built in memory is) and both counts of \e edges; nothing when edges.closed(), nor when this
        process has warned about the same name with the same counts already (a file loaded again). Thread-safe. */
    void warnIfNotClosed(const std::string &name, const EdgeReport &edges);
}  // namespace meshgap

#endif
