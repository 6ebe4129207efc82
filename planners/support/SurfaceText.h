#ifndef MESHGAP_PLANNERS_SUPPORT_SURFACE_TEXT_H
#define MESHGAP_PLANNERS_SUPPORT_SURFACE_TEXT_H

#include <string>

#include "meshgap/mesh/Mesh.h"
#include "meshgap/scene/Scene.h"

namespace meshgap
{
    /** \brief "closed surface", or "open surface (B boundary edges, M non-manifold edges)": what the tools print
        about a body they loaded. */
    std::string surfaceText(const EdgeReport &edges);

    /** \brief The robot's and the world's parts' surfaces in one line: "robot closed surface; world all N parts
        closed", or "...; world K of N parts open (B boundary edges, M non-manifold edges)" (edges summed over the
        parts). */
    std::string sceneSurfacesText(const Scene &scene);
}  // namespace meshgap

#endif
