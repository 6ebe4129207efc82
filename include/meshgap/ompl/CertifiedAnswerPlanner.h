#ifndef MESHGAP_OMPL_CERTIFIED_ANSWER_PLANNER_H
#define MESHGAP_OMPL_CERTIFIED_ANSWER_PLANNER_H

#include <ompl/base/Planner.h>

#include <functional>

#include "meshgap/ompl/PathCertifier.h"

namespace meshgap
{
    /**
       @anchor mgCertifiedAnswerPlanner
       @par Short description
       A planner whose every returned motion is certified, at the price of a sampled search: another planner
       (allocated by the function it is given) searches in a twin of the SpaceInformation, with the same state
       space and validity checker but a sampled motion check (states at searchResolution() of the space's extent
       apart, OMPL's order: the end state, then halves of halves); the path it finds, its vertices first reduced
       under that sampled check (OMPL's PathSimplifier::reduceVertices(): fewer and shorter motions to prove, the
       proof's cost growing with each motion's length), is then put, motion by motion,
       to the SpaceInformation's own motion validator, the certified one (RobotMotionValidator,
       ClearanceMotionValidator), and a motion it refuses is replanned between its two states (PathCertifier): first
       by RRTConnect in a second twin whose sampled check is REPAIR_REFINEMENT times as fine as the search's, that
       detour's motions then proven in turn, and by RRTConnect with the certified validator only where that fails.
       Only the answer pays for the proof: the search's thousands of motion checks are sampled, the answer's few
       are proven. When a refused motion cannot be repaired, the search starts again (cleared) and
       its next path is certified in turn, until the termination condition. So what solve() adds to the problem
       definition is certified whatever the sampled check let through; an approximate solution of the search is
       certified the same way and reported approximate. A planner that searches until the termination condition
       (RRT* and the other optimizing planners) leaves no time to repair: its answer is proven after the condition,
       and one refused motion then means no solution. The planner takes the inner planner's name, parameters and
       specs; getPlannerData() gives the search's graph and, as properties, what the certification did (the last
       solve()'s searches, motions certified, refused, repaired and states inserted, and its time).
    */
    class CertifiedAnswerPlanner : public ompl::base::Planner
    {
    public:
        /** \brief Makes the search planner on the SpaceInformation it is given. */
        using Allocator = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr &)>;

        /** \brief What the last solve() did. */
        struct Stats
        {
            unsigned searches{0};  ///< runs of the search planner (1 unless a path could not be certified)
            unsigned motions{0};   ///< motions put to the certified validator, over every path certified
            unsigned refused{0};   ///< of those, refused
            unsigned repaired{0};  ///< of those, replaced by a certified detour
            unsigned inserted{0};  ///< states the repairs inserted
            unsigned sampledDetours{0};    ///< detours found by a sampled search and proven (PathCertifier)
            unsigned rejectedPaths{0};     ///< paths of the search that could not be certified
            double certifySeconds{0.0};    ///< time certifying and repairing
            double repairSeconds{0.0};     ///< of which repairing
        };

        /** \brief \e si: the problem's; its motion validator must be the certified one. Throws meshgap::Exception
            when \e allocate returns no planner. */
        CertifiedAnswerPlanner(const ompl::base::SpaceInformationPtr &si, const Allocator &allocate);

        ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
        void setProblemDefinition(const ompl::base::ProblemDefinitionPtr &pdef) override;
        void clear() override;
        void setup() override;
        void getPlannerData(ompl::base::PlannerData &data) const override;

        const Stats &lastStats() const { return stats_; }
        /** \brief The search planner, and the twin SpaceInformation it searches in (its motion validator the
            sampled one). */
        const ompl::base::PlannerPtr &searchPlanner() const { return search_; }
        const ompl::base::SpaceInformationPtr &searchSpaceInformation() const { return searchSi_; }
        PathCertifier &certifier() { return certifier_; }

        /** \brief The search's motion check resolution, a fraction of the space's maximum extent; 0 (the default):
            the space's own (SpaceInformation::getStateValidityCheckingResolution(), OMPL's 1 % unless set). */
        void setSearchResolution(double fraction);
        double getSearchResolution() const { return searchResolution_; }

    private:
        /** \brief The search's problem definition: the problem's start states, goal and objective. */
        void syncSearchProblem();

        ompl::base::SpaceInformationPtr searchSi_;
        /** \brief The repairs' twin: the search's sampled check, REPAIR_REFINEMENT times as fine. */
        ompl::base::SpaceInformationPtr repairSi_;
        static constexpr unsigned REPAIR_REFINEMENT = 4;
        ompl::base::PlannerPtr search_;
        ompl::base::ProblemDefinitionPtr searchPdef_;
        PathCertifier certifier_;
        Stats stats_;
        double searchResolution_{0.0};
    };
}  // namespace meshgap

#endif
