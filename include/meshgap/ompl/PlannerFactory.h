#ifndef MESHGAP_OMPL_PLANNER_FACTORY_H
#define MESHGAP_OMPL_PLANNER_FACTORY_H

#include <ompl/base/Planner.h>
#include <string>
#include <vector>

namespace meshgap
{
    /** \brief Planner names as OMPL.app's .cfg [planner] section spells them (rrtconnect, rrtstar, prmstar, ...). */
    std::vector<std::string> plannerNames();

    /** \brief A new OMPL geometric planner by name. Throws meshgap::Exception listing the valid names for an unknown
        one. */
    ompl::base::PlannerPtr allocPlanner(const std::string &name, const ompl::base::SpaceInformationPtr &si);

    /** \brief Sets one of the planner's OMPL parameters (its ParamSet, e.g. RRT*'s "range" or "use_k_nearest").
        Throws meshgap::Exception naming \e where and the planner's parameters for an unknown name, and the value
        for one the parameter refuses. */
    void setPlannerParam(ompl::base::Planner &planner, const std::string &key, const std::string &value,
                         const std::string &where);
}  // namespace meshgap

#endif
