#ifndef MESHGAP_PLANNERS_BENCHMARK_MEASURED_PLANNER_H
#define MESHGAP_PLANNERS_BENCHMARK_MEASURED_PLANNER_H

#include <functional>
#include <ompl/base/Planner.h>
#include <ompl/base/PlannerData.h>
#include <string>

namespace meshgap
{
    namespace cli
    {
        /** \brief A planner run through another, so the checker's counters are read the moment solve() returns,
            before the Benchmark simplifies and checks the path with the same checker. Forwards what the Benchmark
            calls; carries the inner planner's parameters, specs and progress properties. */
        class MeasuredPlanner : public ompl::base::Planner
        {
        public:
            MeasuredPlanner(ompl::base::PlannerPtr inner, const std::string &name, std::function<void()> solved)
              : ompl::base::Planner(inner->getSpaceInformation(), name), inner_(std::move(inner)), solved_(std::move(solved))
            {
                specs_ = inner_->getSpecs();
                params_.include(inner_->params());
                for (const auto &[key, property] : inner_->getPlannerProgressProperties())
                    addPlannerProgressProperty(key, property);
            }

            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override
            {
                const ompl::base::PlannerStatus status = inner_->solve(ptc);
                solved_();
                return status;
            }
            void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override
            {
                ompl::base::Planner::setProblemDefinition(pdef);
                inner_->setProblemDefinition(pdef);
            }
            void clear() override
            {
                ompl::base::Planner::clear();
                inner_->clear();
            }
            void setup() override
            {
                ompl::base::Planner::setup();
                if (!inner_->isSetup())
                    inner_->setup();
            }
            void getPlannerData(ompl::base::PlannerData &data) const override { inner_->getPlannerData(data); }
            void printProperties(std::ostream &out) const override { inner_->printProperties(out); }

        private:
            ompl::base::PlannerPtr inner_;
            std::function<void()> solved_;
        };
    }  // namespace cli
}  // namespace meshgap

#endif
