#ifndef MESHGAP_OMPL_CLEARANCE_OPTIMIZING_PLANNER_H
#define MESHGAP_OMPL_CLEARANCE_OPTIMIZING_PLANNER_H

#include <ompl/base/Planner.h>

#include "meshgap/ompl/ClearancePathOptimizer.h"

namespace meshgap
{
    /**
       @anchor mgClearanceOptimizingPlanner
       @par Short description
       A planner followed by the ClearancePathOptimizer, as one OMPL planner (so a benchmark times and records both):
       solve() runs the inner planner until it finds a path (or \e ptc), then optimises the solution path in place for
       the rest of the time \e ptc leaves, or at most optimize_time seconds when that parameter is positive. The
       optimiser needs the space's validity checker to be a certified meshgap ClearanceField (a ClearanceChecker in
       CERTIFIED mode, a RobotChecker), looked up at each solve() (a benchmark may swap checkers); with another checker,
       or when the certified validator refuses the inner planner's path (a motion grazing an obstacle closer than it can
       prove free), the inner planner's path is returned as it is and a warning says why. Parameters: the inner
       planner's, and the optimiser's max_length_factor and optimize_time (default 0: all the time left).
    */
    class ClearanceOptimizingPlanner : public ompl::base::Planner
    {
    public:
        ClearanceOptimizingPlanner(ompl::base::PlannerPtr inner, const std::string &name);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override;
        void clear() override;
        void setup() override;
        void getPlannerData(ompl::base::PlannerData &data) const override;

        void setOptimizeTime(double seconds) { optimizeTime_ = seconds; }
        double getOptimizeTime() const { return optimizeTime_; }
        void setMaxLengthFactor(double f) { maxLengthFactor_ = f; }
        double getMaxLengthFactor() const { return maxLengthFactor_; }

        /** \brief The optimiser's statistics from the last solve() (all zero if it did not run). */
        const ClearancePathOptimizer::Stats &lastStats() const { return stats_; }

    private:
        ompl::base::PlannerPtr inner_;
        double optimizeTime_{0.0};
        double maxLengthFactor_{3.0};
        ClearancePathOptimizer::Stats stats_;
    };
}  // namespace meshgap

#endif
