#ifndef MESHGAP_OMPL_NARROW_PASSAGE_SAMPLER_H
#define MESHGAP_OMPL_NARROW_PASSAGE_SAMPLER_H

#include <ompl/base/StateSampler.h>
#include <ompl/base/ValidStateSampler.h>
#include <ompl/util/RandomNumbers.h>

#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    /**
       @anchor mgNarrowPassageSampler
       @par Short description
       A valid-state sampler for narrow passages, driven by exact clearance. It draws a state uniformly (or near a
       given one); a state in collision is pushed out along its penetration direction (the deepest point's, reversed
       witness direction; ClearanceChecker::validStateAway(): a translation by the depth plus a margin, doubled up
       to four times). A free state closer than narrow_clearance to an obstacle (default 0: the robot's radius about
       its origin) is then moved up the exact clearance gradient (clearanceGradient(), backtracking steps, at most
       medial_steps of them, default 4) towards the middle of the free space around it. If it is still closer than
       narrow_clearance there, the free space is thin (a passage, seen from its middle): the state is kept; any
       other state is kept with probability free_probability (default 0.2), else drawn again, so open space is not
       over-sampled. Colliding samples are common exactly where the free space is thin, so the states it returns
       crowd into passages and sit in their middle: OMPL's obstacle-based sampler and its maximize-clearance
       sampler combined, with the push and the centring exact. sampleNear() (the local samples of tree planners
       such as EST, BiEST and BKPIECE) draws near the given state as the uniform sampler does, up to OMPL's
       attempts count, and returns the first free draw; only if every draw collides (where the uniform sampler
       gives up: the neighbourhood is nearly all obstacle, as inside a passage) is the last one pushed out along its
       penetration direction (not centred). So a tree grows as fast as with uniform sampling in open space and
       still gets states where uniform sampling returns none. Cost: an exact
       collision test per sample; a bounded clearance query (ClearanceChecker::clearanceBelow()) only for a free
       state not kept at random, and a full query only for a colliding one. sample() gives up (returns false)
       after OMPL's attempts count. Needs the space's validity checker to be a meshgap ClearanceChecker in CERTIFIED
       mode (looked up at construction): with another checker it samples uniformly and rejects invalid states, with a
       warning. Planners that use valid-state samplers (PRM, PRM*, EST, BiEST, BKPIECE, SBL, STRIDE, ...) use it; the
       RRT family and LazyPRM* sample the space directly and ignore it.
    */
    class NarrowPassageSampler : public ompl::base::ValidStateSampler
    {
    public:
        explicit NarrowPassageSampler(const ompl::base::SpaceInformation *si);
        ~NarrowPassageSampler() override;

        bool sample(ompl::base::State *state) override;
        bool sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance) override;

        void setFreeProbability(double p) { freeProbability_ = p; }
        double getFreeProbability() const { return freeProbability_; }
        void setNarrowClearance(double c) { narrowClearance_ = c; }
        double getNarrowClearance() const { return narrowClearance_; }
        void setMedialSteps(unsigned steps) { medialSteps_ = steps; }
        unsigned getMedialSteps() const { return medialSteps_; }

    private:
        /** \brief Turn a drawn state into a returned one (see the class description); false to draw again. A
            \e local sample (sampleNear()) in collision is only pushed out. */
        bool accept(ompl::base::State *state, bool local);
        /** \brief Gradient ascent of the clearance from the free \e state (of clearance \e clearance), at most
            medialSteps_ accepted steps; returns the clearance reached. */
        double centre(ompl::base::State *state, double clearance);

        ompl::base::StateSamplerPtr sampler_;
        std::shared_ptr<const ClearanceChecker> checker_;
        ompl::base::State *work_;
        ompl::RNG rng_;
        double freeProbability_{0.2};
        double narrowClearance_{0.0};
        unsigned medialSteps_{4};
        std::vector<double> gradient_, step_;
    };
}  // namespace meshgap

#endif
