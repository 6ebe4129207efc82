#include "meshgap/distance/SolverFactory.h"

#include <functional>

#include "meshgap/Registry.h"
#include "meshgap/distance/CombGA.h"
#include "meshgap/distance/CombSA.h"
#include "meshgap/distance/Enumeration.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/HillClimb.h"
#include "meshgap/distance/WarmFast.h"

namespace meshgap
{
    namespace
    {
        const Registry<std::function<DistanceSolverPtr()>> &solverRegistry()
        {
            static const Registry<std::function<DistanceSolverPtr()>> solvers(
                "algorithm",
                {
                    {"comb-GA-nl", [] { return std::make_shared<CombGA>(false); }},
                    {"comb-GA-wl", [] { return std::make_shared<CombGA>(true); }},
                    {"comb-SA-nl", [] { return std::make_shared<CombSA>(false); }},
                    {"comb-SA-wl", [] { return std::make_shared<CombSA>(true); }},
                    {"enumeration", [] { return std::make_shared<Enumeration>(); }},
                    {"exact", [] { return std::make_shared<ExactSolver>(); }},
                    {"hill-climb", [] { return std::make_shared<HillClimb>(); }},
                    {"warm-fast", [] { return std::make_shared<WarmFast>(); }},
                });
            return solvers;
        }
    }  // namespace

    std::vector<std::string> solverNames()
    {
        return solverRegistry().names();
    }

    DistanceSolverPtr allocSolver(const std::string &name)
    {
        return solverRegistry().at(name, "algorithm")();
    }
}  // namespace meshgap
