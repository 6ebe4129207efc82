#include "meshgap/ompl/ClearanceOptimizingPlanner.h"

#include <ompl/geometric/PathGeometric.h>

#include "meshgap/Exception.h"

namespace meshgap
{
    ClearanceOptimizingPlanner::ClearanceOptimizingPlanner(ompl::base::PlannerPtr inner, const std::string &name)
        : ompl::base::Planner(inner->getSpaceInformation(), name), inner_(std::move(inner))
    {
        specs_ = inner_->getSpecs();
        params_.include(inner_->params());
        params_.declareParam<double>(
            "optimize_time", [this](double v) { setOptimizeTime(v); }, [this] { return getOptimizeTime(); });
        params_.declareParam<double>(
            "max_length_factor", [this](double v) { setMaxLengthFactor(v); }, [this] { return getMaxLengthFactor(); });
        for (const auto &[key, property] : inner_->getPlannerProgressProperties())
            addPlannerProgressProperty(key, property);
    }

    void ClearanceOptimizingPlanner::setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef)
    {
        ompl::base::Planner::setProblemDefinition(pdef);
        inner_->setProblemDefinition(pdef);
    }

    void ClearanceOptimizingPlanner::clear()
    {
        ompl::base::Planner::clear();
        inner_->clear();
    }

    void ClearanceOptimizingPlanner::setup()
    {
        ompl::base::Planner::setup();
        if (!inner_->isSetup())
            inner_->setup();
    }

    void ClearanceOptimizingPlanner::getPlannerData(ompl::base::PlannerData &data) const
    {
        inner_->getPlannerData(data);
    }

    ompl::base::PlannerStatus ClearanceOptimizingPlanner::solve(const ompl::base::PlannerTerminationCondition &ptc)
    {
        stats_ = ClearancePathOptimizer::Stats();
        const ompl::base::PlannerStatus status = inner_->solve(ptc);
        if ((status != ompl::base::PlannerStatus::EXACT_SOLUTION &&
             status != ompl::base::PlannerStatus::APPROXIMATE_SOLUTION) ||
            !pdef_->hasSolution())
            return status;
        auto checker = std::dynamic_pointer_cast<ClearanceField>(si_->getStateValidityChecker());
        if (!checker || !checker->certified())
        {
            OMPL_WARN("%s: the validity checker is not a certified meshgap ClearanceField: path not optimised",
                      getName().c_str());
            return status;
        }
        auto path = std::dynamic_pointer_cast<ompl::geometric::PathGeometric>(pdef_->getSolutionPath());
        if (!path)
            return status;
        ClearancePathOptimizer optimizer(si_, checker);
        optimizer.setMaxLengthFactor(maxLengthFactor_);
        try
        {
            if (optimizeTime_ > 0.0)
                optimizer.optimize(*path, ompl::base::plannerOrTerminationCondition(
                                              ptc, ompl::base::timedPlannerTerminationCondition(optimizeTime_)));
            else
                optimizer.optimize(*path, ptc);
            stats_ = optimizer.lastStats();
            OMPL_INFORM("%s: min clearance %g -> %g, length %g -> %g, %u -> %u states in %.3f s", getName().c_str(),
                        stats_.minClearanceBefore, stats_.minClearanceAfter, stats_.lengthBefore, stats_.lengthAfter,
                        stats_.statesBefore, stats_.statesAfter, stats_.seconds);
        }
        catch (const Exception &e)
        {
            OMPL_WARN("%s: path not optimised: %s", getName().c_str(), e.what());
        }
        return status;
    }
}  // namespace meshgap
