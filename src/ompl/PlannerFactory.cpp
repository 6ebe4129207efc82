#include "meshgap/ompl/PlannerFactory.h"

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include <functional>

#include "meshgap/Exception.h"
#include "meshgap/Registry.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ClearanceOptimizingPlanner.h"

namespace meshgap
{
    namespace
    {
        using Allocator = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)>;

        template <typename P>
        Allocator allocatorOf()
        {
            return [](const ompl::base::SpaceInformationPtr &si) { return std::make_shared<P>(si); };
        }

        const Registry<Allocator> &plannerRegistry()
        {
            namespace og = ompl::geometric;
            static const Registry<Allocator> planners(
                "planner",
                {
                    {"biest", allocatorOf<og::BiEST>()},
                    {"bitstar", allocatorOf<og::BITstar>()},
                    {"bkpiece", allocatorOf<og::BKPIECE1>()},
                    {"est", allocatorOf<og::EST>()},
                    {"fmt", allocatorOf<og::FMT>()},
                    {"informedrrtstar", allocatorOf<og::InformedRRTstar>()},
                    {"kpiece", allocatorOf<og::KPIECE1>()},
                    {"lazyprmstar", allocatorOf<og::LazyPRMstar>()},
                    {"lbkpiece", allocatorOf<og::LBKPIECE1>()},
                    {"lbtrrt", allocatorOf<og::LBTRRT>()},
                    {"pdst", allocatorOf<og::PDST>()},
                    {"prm", allocatorOf<og::PRM>()},
                    {"prmstar", allocatorOf<og::PRMstar>()},
                    {"rrt", allocatorOf<og::RRT>()},
                    {"rrtconnect", allocatorOf<og::RRTConnect>()},
                    // RRTConnect, then the clearance path optimiser for the time left (ClearanceOptimizingPlanner).
                    {"rrtconnect+opt",
                     [](const ompl::base::SpaceInformationPtr &si) -> ompl::base::PlannerPtr {
                         return std::make_shared<ClearanceOptimizingPlanner>(std::make_shared<og::RRTConnect>(si),
                                                                             "RRTConnect+opt");
                     }},
                    {"rrtstar", allocatorOf<og::RRTstar>()},
                    {"sbl", allocatorOf<og::SBL>()},
                    {"stride", allocatorOf<og::STRIDE>()},
                    {"trrt", allocatorOf<og::TRRT>()},
                });
            return planners;
        }
    }  // namespace

    std::vector<std::string> plannerNames()
    {
        return plannerRegistry().names();
    }

    ompl::base::PlannerPtr allocPlanner(const std::string &name, const ompl::base::SpaceInformationPtr &si)
    {
        return plannerRegistry().at(name, "planner")(si);
    }

    void setPlannerParam(ompl::base::Planner &planner, const std::string &key, const std::string &value,
                         const std::string &where)
    {
        if (!planner.params().hasParam(key))
        {
            std::vector<std::string> names;
            planner.params().getParamNames(names);
            throw Exception(where, quote(key) + " is no parameter of " + planner.getName() +
                                       "; its parameters: " + (names.empty() ? "none" : joinNames(names)));
        }
        bool set = false;
        try
        {
            set = planner.params().setParam(key, value);
        }
        catch (const std::exception &)  // OMPL's conversion of the text to the parameter's type
        {
        }
        if (!set)
            throw Exception(where, planner.getName() + "'s " + key + " refuses the value " + quote(value));
    }
}  // namespace meshgap
