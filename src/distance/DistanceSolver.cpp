#include "meshgap/distance/DistanceSolver.h"

#include "meshgap/Exception.h"

namespace meshgap
{
    void DistanceSolver::checkRequest(const Body &a, const Body &b, const DistanceRequest &request) const
    {
        if (a.numNodes() == 0 || b.numNodes() == 0)
            throw Exception(name_, "a body has no nodes");
        if (request.start && (request.start->a >= a.numNodes() || request.start->b >= b.numNodes()))
            throw Exception(name_, "start node pair out of range");
    }
}  // namespace meshgap
