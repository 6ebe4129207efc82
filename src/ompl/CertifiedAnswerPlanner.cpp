#include "meshgap/ompl/CertifiedAnswerPlanner.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

#include <chrono>
#include <cmath>
#include <deque>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace ob = ompl::base;
    namespace og = ompl::geometric;

    namespace
    {
        /** \brief OMPL's sampled motion check (DiscreteMotionValidator: the end state, then the states between in
            halves of halves), its step a fraction of the space's extent of its own rather than the state space's
            (which the certified validator's space shares). */
        class SampledMotionValidator : public ob::MotionValidator
        {
        public:
            explicit SampledMotionValidator(const ob::SpaceInformationPtr &si) : ob::MotionValidator(si)
            {
            }

            void setFraction(double fraction) { fraction_ = fraction; }
            /** \brief Check \e factor times as many states as the fraction says. */
            void setRefinement(unsigned factor) { refinement_ = factor; }

            bool checkMotion(const ob::State *s1, const ob::State *s2) const override
            {
                const bool free = check(s1, s2);
                free ? ++valid_ : ++invalid_;
                return free;
            }

            bool checkMotion(const ob::State *s1, const ob::State *s2,
                             std::pair<ob::State *, double> &lastValid) const override
            {
                // In order from s1, the last free state kept (the planners that ask this want it).
                const ob::StateSpace &space = *si_->getStateSpace();
                const unsigned n = segments(s1, s2);
                ob::State *s = si_->allocState();
                bool free = true;
                for (unsigned k = 1; free && k <= n; ++k)
                {
                    space.interpolate(s1, s2, double(k) / n, s);
                    free = si_->isValid(s);
                    if (!free)
                    {
                        if (lastValid.first)
                            space.interpolate(s1, s2, double(k - 1) / n, lastValid.first);
                        lastValid.second = double(k - 1) / n;
                    }
                }
                si_->freeState(s);
                free ? ++valid_ : ++invalid_;
                return free;
            }

        private:
            unsigned segments(const ob::State *s1, const ob::State *s2) const
            {
                const ob::StateSpace &space = *si_->getStateSpace();
                const unsigned own = space.validSegmentCount(s1, s2);
                if (!(fraction_ > 0.0))
                    return std::max(1u, own) * refinement_;
                const double scaled = std::ceil(own * space.getLongestValidSegmentFraction() / fraction_);
                return static_cast<unsigned>(std::max(1.0, scaled)) * refinement_;
            }

            bool check(const ob::State *s1, const ob::State *s2) const
            {
                if (!si_->isValid(s2))
                    return false;
                const unsigned n = segments(s1, s2);
                if (n < 2)
                    return true;
                const ob::StateSpace &space = *si_->getStateSpace();
                thread_local std::deque<std::pair<unsigned, unsigned>> ranges;
                ranges.assign(1, {1u, n - 1});
                ob::State *s = si_->allocState();
                bool free = true;
                while (free && !ranges.empty())
                {
                    const auto [lo, hi] = ranges.front();
                    ranges.pop_front();
                    const unsigned mid = (lo + hi) / 2;
                    space.interpolate(s1, s2, double(mid) / n, s);
                    free = si_->isValid(s);
                    if (lo < mid)
                        ranges.emplace_back(lo, mid - 1);
                    if (hi > mid)
                        ranges.emplace_back(mid + 1, hi);
                }
                si_->freeState(s);
                return free;
            }

            double fraction_{0.0};  ///< 0: the state space's own
            unsigned refinement_{1};
        };
    }  // namespace

    CertifiedAnswerPlanner::CertifiedAnswerPlanner(const ob::SpaceInformationPtr &si, const Allocator &allocate)
      : ob::Planner(si, "CertifiedAnswer"), certifier_(si)
    {
        searchSi_ = std::make_shared<ob::SpaceInformation>(si->getStateSpace());
        if (si->getStateValidityChecker())
            searchSi_->setStateValidityChecker(si->getStateValidityChecker());
        searchSi_->setMotionValidator(std::make_shared<SampledMotionValidator>(searchSi_));
        repairSi_ = std::make_shared<ob::SpaceInformation>(si->getStateSpace());
        if (si->getStateValidityChecker())
            repairSi_->setStateValidityChecker(si->getStateValidityChecker());
        auto repairCheck = std::make_shared<SampledMotionValidator>(repairSi_);
        repairCheck->setRefinement(REPAIR_REFINEMENT);
        repairSi_->setMotionValidator(repairCheck);
        certifier_.setSampledSpaceInformation(repairSi_);
        search_ = allocate ? allocate(searchSi_) : nullptr;
        if (!search_)
            throw Exception("CertifiedAnswerPlanner", "the allocator gave no planner");
        if (search_->getSpaceInformation() != searchSi_)
            throw Exception("CertifiedAnswerPlanner", "the allocator's planner is not on the SpaceInformation given");
        setName(search_->getName());
        specs_ = search_->getSpecs();
        params_.include(search_->params());
    }

    void CertifiedAnswerPlanner::setSearchResolution(double fraction)
    {
        if (!(fraction >= 0.0 && fraction <= 1.0))
            throw Exception("CertifiedAnswerPlanner", "the search resolution must be in [0, 1] (0: the space's)");
        searchResolution_ = fraction;
        std::static_pointer_cast<SampledMotionValidator>(searchSi_->getMotionValidator())->setFraction(fraction);
        std::static_pointer_cast<SampledMotionValidator>(repairSi_->getMotionValidator())->setFraction(fraction);
    }

    void CertifiedAnswerPlanner::setProblemDefinition(const ob::ProblemDefinitionPtr &pdef)
    {
        ob::Planner::setProblemDefinition(pdef);
        searchPdef_.reset();
    }

    void CertifiedAnswerPlanner::syncSearchProblem()
    {
        for (const ob::SpaceInformationPtr &twin : {searchSi_, repairSi_})
            if (twin->getStateValidityChecker() != si_->getStateValidityChecker())
                twin->setStateValidityChecker(si_->getStateValidityChecker());
        if (!searchSi_->isSetup())
            searchSi_->setup();
        if (searchPdef_ && searchPdef_->getStartStateCount() == pdef_->getStartStateCount() &&
            searchPdef_->getGoal() == pdef_->getGoal())
            return;
        searchPdef_ = std::make_shared<ob::ProblemDefinition>(searchSi_);
        for (unsigned i = 0; i < pdef_->getStartStateCount(); ++i)
            searchPdef_->addStartState(pdef_->getStartState(i));
        searchPdef_->setGoal(pdef_->getGoal());
        if (pdef_->hasOptimizationObjective())
            searchPdef_->setOptimizationObjective(pdef_->getOptimizationObjective());
        search_->clear();
        search_->setProblemDefinition(searchPdef_);
    }

    void CertifiedAnswerPlanner::setup()
    {
        ob::Planner::setup();
        if (!pdef_)
            return;
        syncSearchProblem();
        if (!search_->isSetup())
            search_->setup();
    }

    void CertifiedAnswerPlanner::clear()
    {
        ob::Planner::clear();
        search_->clear();
        if (searchPdef_)
            searchPdef_->clearSolutionPaths();
        stats_ = Stats();
    }

    ob::PlannerStatus CertifiedAnswerPlanner::solve(const ob::PlannerTerminationCondition &ptc)
    {
        checkValidity();
        syncSearchProblem();
        if (!search_->isSetup())
            search_->setup();
        stats_ = Stats();
        ob::PlannerStatus status = ob::PlannerStatus::TIMEOUT;
        do
        {
            ++stats_.searches;
            searchPdef_->clearSolutionPaths();
            status = search_->solve(ptc);
            const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
            if ((!exact && status != ob::PlannerStatus::APPROXIMATE_SOLUTION) || !searchPdef_->getSolutionPath())
                return status;
            const double difference = searchPdef_->getSolutionDifference();
            // The answer lives in the problem's SpaceInformation (its checks, its simplification: certified).
            auto path = std::make_shared<og::PathGeometric>(si_);
            og::PathGeometric rough(*searchPdef_->getSolutionPath()->as<og::PathGeometric>());
            og::PathSimplifier(searchSi_).reduceVertices(rough);
            for (const ob::State *s : rough.getStates())
                path->append(s);
            const auto start = std::chrono::steady_clock::now();
            if (!repairSi_->isSetup())
                repairSi_->setup();
            const bool certified = certifier_.certify(*path, ptc);
            const PathCertifier::Stats &c = certifier_.lastStats();
            stats_.motions += c.motions;
            stats_.refused += c.refused;
            stats_.repaired += c.repaired;
            stats_.inserted += c.inserted;
            stats_.sampledDetours += c.sampled;
            stats_.repairSeconds += c.repairSeconds;
            stats_.certifySeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (certified)
            {
                pdef_->addSolutionPath(path, !exact, exact ? 0.0 : difference, getName());
                return status;
            }
            // A motion the certified validator refuses and no detour found: the search starts again.
            ++stats_.rejectedPaths;
            search_->clear();
        } while (!ptc());
        return ob::PlannerStatus::TIMEOUT;
    }

    void CertifiedAnswerPlanner::getPlannerData(ob::PlannerData &data) const
    {
        search_->getPlannerData(data);
        data.properties["certified answer searches INTEGER"] = std::to_string(stats_.searches);
        data.properties["certified answer motions INTEGER"] = std::to_string(stats_.motions);
        data.properties["certified answer motions refused INTEGER"] = std::to_string(stats_.refused);
        data.properties["certified answer motions repaired INTEGER"] = std::to_string(stats_.repaired);
        data.properties["certified answer states inserted INTEGER"] = std::to_string(stats_.inserted);
        data.properties["certified answer sampled detours INTEGER"] = std::to_string(stats_.sampledDetours);
        data.properties["certified answer paths rejected INTEGER"] = std::to_string(stats_.rejectedPaths);
        data.properties["certified answer time REAL"] = std::to_string(stats_.certifySeconds);
        data.properties["certified answer repair time REAL"] = std::to_string(stats_.repairSeconds);
    }
}  // namespace meshgap
