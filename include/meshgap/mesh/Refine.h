#ifndef MESHGAP_MESH_REFINE_H
#define MESHGAP_MESH_REFINE_H

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief What refinement did. */
    struct RefineReport
    {
        std::size_t nodesBefore{0}, nodesAfter{0};
        std::size_t trianglesBefore{0}, trianglesAfter{0};
        double longestEdge{0.0};  ///< longest edge after refinement (<= h unless h was not positive)
    };

    /** \brief Refine \e mesh so no edge is longer than \e h: longest-edge bisection (Rivara). The globally longest
        edge above h is split at its midpoint in every triangle that shares it, so the result is conforming (a shared
        edge is split the same way on both sides and the surface graph stays connected), the surface is the same
        point set (new nodes lie on the original edges), and triangle shapes stay bounded (each triangle is always cut
        across its own longest edge). Non-manifold edges are split in all their triangles. With \e h <= 0 or
        infinite, the mesh is returned unchanged. If \e parent is given, it receives for every output triangle the
        index of the input triangle it lies in. */
    Mesh refineMesh(const Mesh &mesh, double h, RefineReport *report = nullptr,
                    std::vector<std::uint32_t> *parent = nullptr);

    /** \brief Adaptive refinement: the grid size varies over the surface. \e vertexSize gives a target size h_v > 0
        at each vertex of \e mesh; the size field is its linear (barycentric) interpolation over each input triangle,
        so a vertex made at an edge's midpoint gets (h_a + h_b) / 2. The rule: an edge ab is split while
        |ab| > (h_a + h_b) / 2, the size at its midpoint. The splits are the same conforming longest-edge bisection
        as above (Rivara): edges over their size are taken longest first, and before an edge is split, any longer
        edge of a triangle that shares it is split first, so every triangle is still cut across its own longest edge
        (bounded shapes), no node hangs (an edge is split in all its triangles), and new nodes lie on the input
        surface. Where the field is constant this is exactly refineMesh(mesh, h). Body builds the field with
        adaptiveNodeSizes() (NodeSizing.h: a fraction of the local feature size, clamped and graded). Throws
        meshgap::Exception when \e vertexSize has the wrong length or a value that is not positive and finite. */
    Mesh refineMesh(const Mesh &mesh, const std::vector<double> &vertexSize, RefineReport *report = nullptr,
                    std::vector<std::uint32_t> *parent = nullptr);
}  // namespace meshgap

#endif
