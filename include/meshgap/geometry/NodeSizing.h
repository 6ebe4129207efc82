#ifndef MESHGAP_GEOMETRY_NODE_SIZING_H
#define MESHGAP_GEOMETRY_NODE_SIZING_H

#include <string>
#include <vector>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    /** \brief The adaptive grid-size rule (see refineMesh() with a size per vertex, Refine.h). All lengths are
        fractions of the body's size (Mesh::size(), the bounding-box diagonal) so one set of defaults fits bodies of
        any unit. */
    struct AdaptiveSizing
    {
        /** \brief h = featureFraction x local feature size (so about 1 / featureFraction edges across a part). */
        double featureFraction{0.5};
        /** \brief Smallest grid size, a fraction of the body's size: knife edges, thin walls and touching parts stop
            here. 0.03 (a little finer than the uniform default, 1/25 = 0.04) keeps node counts within about 2.5x of
            the uniform grid's on the OMPL.app worlds of thin walls; 1/200 gave 134,318 nodes for Abstract's world
            (uniform: 10,290) and 61,053 for the bowl (as generated: 3,957). */
        double minFraction{0.03};
        /** \brief Largest grid size, a fraction of the body's size: large thick parts stop here (2.5x the uniform
            default). */
        double maxFraction{0.1};
        /** \brief Grading g: the size grows by at most g per unit of mesh distance away from a small feature
            (h_v <= h_u + g |uv| along every input edge), so sizes vary smoothly and a feature's fine patch reaches
            past its border. */
        double grading{0.5};
    };

    /** \brief Local feature size at each vertex of \e mesh: the distance from the vertex to the nearest triangle
        that faces the opposite way, i.e. whose unit normal n_T has n_T . n_i < -1/2 (more than 120 degrees apart)
        for the unit normal n_i of some triangle incident to the vertex. That is the thickness of a plate, peg or
        finger across the vertex, the width of a hole or slot it lines, and 0 at a sharp convex or concave crease
        whose two sides face more than 120 degrees apart (a knife edge). Triangles incident to the vertex count (so
        a knife edge gives 0). +infinity when no triangle faces away (an open sheet). Degenerate triangles are
        ignored. Exact (a pruned search over a bounding-volume tree, no sampling). */
    std::vector<double> localFeatureSizes(const Mesh &mesh);

    /** \brief The target grid size at each vertex of \e mesh under \e rule: first
        h0_v = clamp(featureFraction * lfs_v, minFraction * size, maxFraction * size) with lfs from localFeatureSizes(),
        then graded along the input edges: h_v = min over vertices u of (h0_u + grading * meshDistance(u, v)), mesh
        distance along input edges (a multi-source Dijkstra), so no size exceeds h0 and neighbouring sizes differ by
        at most grading times their edge length. Throws meshgap::Exception for a non-positive or non-finite fraction
        or a negative grading. */
    std::vector<double> adaptiveNodeSizes(const Mesh &mesh, const AdaptiveSizing &rule = AdaptiveSizing());

    /** \brief Throws meshgap::Exception, naming \e source and the value, when \e rule has a non-positive or
        non-finite fraction, a negative or non-finite grading, or minFraction above maxFraction. */
    void checkAdaptiveSizing(const AdaptiveSizing &rule, const std::string &source);
}  // namespace meshgap

#endif
