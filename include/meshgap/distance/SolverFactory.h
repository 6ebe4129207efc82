#ifndef MESHGAP_DISTANCE_SOLVER_FACTORY_H
#define MESHGAP_DISTANCE_SOLVER_FACTORY_H

#include <string>
#include <vector>

#include "meshgap/distance/DistanceSolver.h"

namespace meshgap
{
    /** \brief The algorithm names allocSolver() knows, as in the paper ("enumeration", "hill-climb", ...). */
    std::vector<std::string> solverNames();

    /** \brief A new solver by name. Throws meshgap::Exception listing the valid names for an unknown one. */
    DistanceSolverPtr allocSolver(const std::string &name);
}  // namespace meshgap

#endif
