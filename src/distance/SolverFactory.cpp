#include "meshgap/distance/SolverFactory.h"

#include <functional>
#include <map>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
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
        const std::map<std::string, std::function<DistanceSolverPtr()>> &registry()
        {
            static const std::map<std::string, std::function<DistanceSolverPtr()>> solvers = {
                {"comb-GA-nl", [] { return std::make_shared<CombGA>(false); }},
                {"comb-GA-wl", [] { return std::make_shared<CombGA>(true); }},
                {"comb-SA-nl", [] { return std::make_shared<CombSA>(false); }},
                {"comb-SA-wl", [] { return std::make_shared<CombSA>(true); }},
                {"enumeration", [] { return std::make_shared<Enumeration>(); }},
                {"exact", [] { return std::make_shared<ExactSolver>(); }},
                {"hill-climb", [] { return std::make_shared<HillClimb>(); }},
                {"warm-fast", [] { return std::make_shared<WarmFast>(); }},
            };
            return solvers;
        }
    }  // namespace

    std::vector<std::string> solverNames()
    {
        std::vector<std::string> names;
        for (const auto &entry : registry())
            names.push_back(entry.first);
        return names;
    }

    DistanceSolverPtr allocSolver(const std::string &name)
    {
        const auto it = registry().find(name);
        if (it != registry().end())
            return it->second();
        throw Exception("algorithm", "unknown algorithm '" + name + "'; valid names: " + joinNames(solverNames()));
    }
}  // namespace meshgap
