#ifndef MESHGAP_DISTANCE_ENUMERATION_H
#define MESHGAP_DISTANCE_ENUMERATION_H

#include "meshgap/distance/DistanceSolver.h"

namespace meshgap
{
    /**
       @anchor mgEnumeration
       @par Short description
       The exact minimum over all node pairs: the paper's reference ("enumeration", Tables III, V, VI) and the
       oracle for every other node-level solver. Exact, but not brute force: nodes are grouped into clusters with
       bounding spheres (Body::clusters()), cluster pairs are visited in order of their distance lower bound, and
       the search stops once the next lower bound exceeds the best distance found, so the result is the same as
       trying all pairs. evaluations counts the d^2 computed.
    */
    class Enumeration : public DistanceSolver
    {
    public:
        Enumeration() : DistanceSolver("enumeration") {}
        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;
    };
}  // namespace meshgap

#endif
