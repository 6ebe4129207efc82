#include "support/SurfaceText.h"

namespace meshgap
{
    namespace
    {
        std::string edgesText(const EdgeReport &edges)
        {
            return "(" + std::to_string(edges.boundaryEdges) + " boundary edges, " +
                   std::to_string(edges.nonManifoldEdges) + " non-manifold edges)";
        }
    }  // namespace

    std::string surfaceText(const EdgeReport &edges)
    {
        return edges.closed() ? std::string("closed surface") : "open surface " + edgesText(edges);
    }

    std::string sceneSurfacesText(const Scene &scene)
    {
        std::size_t open = 0;
        EdgeReport total;
        for (const BodyConstPtr &part : scene.obstacles())
        {
            open += !part->isClosed();
            total.boundaryEdges += part->edges().boundaryEdges;
            total.nonManifoldEdges += part->edges().nonManifoldEdges;
        }
        const std::string parts = std::to_string(scene.obstacles().size()) + " parts";
        return "robot " + surfaceText(scene.robot().edges()) + "; world " +
               (open == 0 ? "all " + parts + " closed"
                          : std::to_string(open) + " of " + parts + " open " + edgesText(total));
    }
}  // namespace meshgap
