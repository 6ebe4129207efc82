#include "meshgap/ompl/PathCertifier.h"

#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <chrono>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace ob = ompl::base;
    namespace og = ompl::geometric;

    namespace
    {
        /** \brief Samples for a detour around the motion from \e a to \e b: every other one near the motion (a state
            within \e radius, by the space's own sampleUniformNear(), of a point of the straight motion at a uniform
            fraction), the others uniform over the space as the space's sampler draws them. */
        class NearMotionSampler : public ob::StateSampler
        {
        public:
            NearMotionSampler(const ob::StateSpace *space, const ob::State *a, const ob::State *b, double radius)
              : ob::StateSampler(space), inner_(space->allocDefaultStateSampler()), a_(a), b_(b), radius_(radius),
                on_(space->allocState())
            {
            }
            ~NearMotionSampler() override { space_->freeState(on_); }
            NearMotionSampler(const NearMotionSampler &) = delete;
            NearMotionSampler &operator=(const NearMotionSampler &) = delete;

            void sampleUniform(ob::State *state) override
            {
                if ((near_ = !near_))
                {
                    space_->interpolate(a_, b_, rng_.uniform01(), on_);
                    inner_->sampleUniformNear(state, on_, radius_);
                }
                else
                    inner_->sampleUniform(state);
            }
            void sampleUniformNear(ob::State *state, const ob::State *near, double distance) override
            {
                inner_->sampleUniformNear(state, near, distance);
            }
            void sampleGaussian(ob::State *state, const ob::State *mean, double stdDev) override
            {
                inner_->sampleGaussian(state, mean, stdDev);
            }

        private:
            ob::StateSamplerPtr inner_;
            const ob::State *a_, *b_;
            double radius_;
            ob::State *on_;
            bool near_{false};
        };

        /** \brief RRTConnect drawing its samples from a sampler given (OMPL's draws from the space's). */
        class DetourRRTConnect : public og::RRTConnect
        {
        public:
            using og::RRTConnect::RRTConnect;
            void useSampler(ob::StateSamplerPtr sampler) { sampler_ = std::move(sampler); }
        };
    }  // namespace

    PathCertifier::PathCertifier(ob::SpaceInformationPtr si) : si_(std::move(si))
    {
        if (!si_)
            throw Exception("PathCertifier", "no space information");
    }

    void PathCertifier::setRepairRange(double fraction)
    {
        if (!(fraction > 0.0 && fraction <= 1.0))
            throw Exception("PathCertifier", "the repair range must be in (0, 1] (a fraction of the motion's length)");
        repairRange_ = fraction;
    }

    void PathCertifier::setSampledSpaceInformation(ob::SpaceInformationPtr sampled)
    {
        if (sampled && sampled->getStateSpace() != si_->getStateSpace())
            throw Exception("PathCertifier", "the sampled SpaceInformation is on another state space");
        sampled_ = std::move(sampled);
    }

    bool PathCertifier::search(const ob::SpaceInformationPtr &si, const ob::State *a, const ob::State *b,
                               std::vector<ob::State *> &out, const ob::PlannerTerminationCondition &ptc) const
    {
        if (repairIterations_ == 0 || ptc())
            return false;
        auto pdef = std::make_shared<ob::ProblemDefinition>(si);
        pdef->setStartAndGoalStates(a, b);
        auto planner = std::make_shared<DetourRRTConnect>(si);
        // Short steps: the detour stays near the motion it replaces, and each certified step is cheap to prove.
        const double length = si->distance(a, b);
        planner->setRange(repairRange_ * length);
        planner->setProblemDefinition(pdef);
        planner->setup();
        planner->useSampler(std::make_shared<NearMotionSampler>(si->getStateSpace().get(), a, b, length));
        unsigned calls = 0;
        const unsigned budget = repairIterations_;
        const ob::PlannerTerminationCondition local([&ptc, &calls, budget] { return ++calls > budget || ptc(); });
        if (planner->solve(local) != ob::PlannerStatus::EXACT_SOLUTION)
            return false;
        const auto &path = *pdef->getSolutionPath()->as<og::PathGeometric>();
        const std::size_t n = path.getStateCount();
        // The planner's path runs from copies of a and b (its goal region's tolerance is 0 for a single state, but
        // the ends are checked rather than assumed).
        if (n < 2 || si->distance(path.getState(0), a) != 0.0 || si->distance(path.getState(n - 1), b) != 0.0)
            return false;
        for (std::size_t k = 1; k + 1 < n; ++k)
            out.push_back(si_->cloneState(path.getState(k)));
        return true;
    }

    bool PathCertifier::proveDetour(const ob::State *a, const ob::State *b, const std::vector<ob::State *> &rough,
                                    unsigned depth, std::vector<ob::State *> &out,
                                    const ob::PlannerTerminationCondition &ptc)
    {
        // Every state of rough ends in out (in order, with the states of nested detours) or is freed.
        std::vector<ob::State *> local;
        std::size_t k = 0;
        bool free = true;
        for (const ob::State *from = a; free && k <= rough.size(); ++k)
        {
            const ob::State *to = k < rough.size() ? rough[k] : b;
            if (!si_->checkMotion(from, to))
            {
                ++stats_.detourRefused;
                free = detour(from, to, depth + 1, local, ptc);
            }
            if (free && k < rough.size())
                local.push_back(rough[k]);
            from = to;
        }
        if (free)
        {
            out.insert(out.end(), local.begin(), local.end());
            return true;
        }
        for (ob::State *s : local)
            si_->freeState(s);
        for (--k; k < rough.size(); ++k)
            si_->freeState(rough[k]);
        return false;
    }

    bool PathCertifier::detour(const ob::State *a, const ob::State *b, unsigned depth, std::vector<ob::State *> &out,
                               const ob::PlannerTerminationCondition &ptc)
    {
        std::vector<ob::State *> rough;
        // A sampled search first (rough stays empty when it fails), its motions proven in turn.
        if (sampled_ && depth < SAMPLED_DEPTH && search(sampled_, a, b, rough, ptc) &&
            proveDetour(a, b, rough, depth, out, ptc))
        {
            ++stats_.sampled;
            return true;
        }
        // The certified search: every motion of its path was accepted by the certified validator.
        return search(si_, a, b, out, ptc);
    }

    bool PathCertifier::certify(og::PathGeometric &path, const ob::PlannerTerminationCondition &ptc)
    {
        const auto start = std::chrono::steady_clock::now();
        stats_ = Stats();
        std::vector<ob::State *> &states = path.getStates();
        std::vector<ob::State *> certified, between;
        certified.reserve(states.size());
        bool free = true;
        for (std::size_t i = 0; free && i + 1 < states.size(); ++i)
        {
            certified.push_back(states[i]);
            ++stats_.motions;
            if (si_->checkMotion(states[i], states[i + 1]))
                continue;
            ++stats_.refused;
            between.clear();
            const auto repairStart = std::chrono::steady_clock::now();
            free = detour(states[i], states[i + 1], 0, between, ptc);
            stats_.repairSeconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - repairStart).count();
            if (free)
            {
                ++stats_.repaired;
                stats_.inserted += static_cast<unsigned>(between.size());
                certified.insert(certified.end(), between.begin(), between.end());
            }
        }
        if (free)
        {
            if (!states.empty())
                certified.push_back(states.back());
            states.swap(certified);
        }
        else  // the path keeps its own states; what was inserted is freed
        {
            std::size_t own = 0;
            for (ob::State *s : certified)
                if (own < states.size() && s == states[own])
                    ++own;
                else
                    si_->freeState(s);
        }
        stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return free;
    }
}  // namespace meshgap
