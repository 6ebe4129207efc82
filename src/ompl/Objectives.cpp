#include "meshgap/ompl/Objectives.h"

#include <algorithm>
#include <cmath>
#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/OptimizationObjective.h>

#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    ClearanceObjective::ClearanceObjective(const ompl::base::SpaceInformationPtr &si, double minClearance)
      : ompl::base::StateCostIntegralObjective(si, true), minClearance_(minClearance)
    {
        if (!(minClearance_ > 0.0))
            throw Exception("ClearanceObjective", "minClearance must be positive");
        description_ = "Integral of 1/clearance";
    }

    ompl::base::Cost ClearanceObjective::stateCost(const ompl::base::State *s) const
    {
        return ompl::base::Cost(1.0 / std::max(si_->getStateValidityChecker()->clearance(s), minClearance_));
    }

    std::vector<std::string> objectiveNames()
    {
        return {"length", "clearance", "max_min_clearance", "weighted"};
    }

    ompl::base::OptimizationObjectivePtr allocObjective(const std::string &name,
                                                        const ompl::base::SpaceInformationPtr &si,
                                                        const ObjectiveOptions &options)
    {
        namespace ob = ompl::base;
        if (name == "length")
            return std::make_shared<ob::PathLengthOptimizationObjective>(si);
        if (name == "clearance")
            return std::make_shared<ClearanceObjective>(si, options.minClearance);
        if (name == "max_min_clearance")
            return std::make_shared<ob::MaximizeMinClearanceObjective>(si);
        if (name == "weighted")
        {
            double weight = options.weight;
            if (weight == 0.0)
            {
                const auto *checker = dynamic_cast<const ClearanceChecker *>(si->getStateValidityChecker().get());
                weight = checker != nullptr ? 0.1 * checker->scene().robot().radiusAboutOrigin() : 1.0;
            }
            if (!(weight > 0.0) || !std::isfinite(weight))
                throw Exception("objective", "the weight of 'weighted' must be positive and finite");
            auto multi = std::make_shared<ob::MultiOptimizationObjective>(si);
            multi->addObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si), 1.0);
            multi->addObjective(std::make_shared<ClearanceObjective>(si, options.minClearance), weight);
            multi->lock();
            return multi;
        }
        std::string valid;
        for (const std::string &n : objectiveNames())
            valid += (valid.empty() ? "" : ", ") + n;
        throw Exception("objective", "unknown objective '" + name + "'; valid names: " + valid);
    }
}  // namespace meshgap
