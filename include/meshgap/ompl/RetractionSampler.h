#ifndef MESHGAP_OMPL_RETRACTION_SAMPLER_H
#define MESHGAP_OMPL_RETRACTION_SAMPLER_H

#include <ompl/base/StateSampler.h>
#include <ompl/base/ValidStateSampler.h>
#include <ompl/util/RandomNumbers.h>

#include "meshgap/ompl/ClearanceChecker.h"

namespace meshgap
{
    /**
       @anchor mgRetractionSampler
       @par Short description
       A valid-state sampler that retracts colliding draws onto the free space by the exact signed distance's
       gradient in the full pose, rotation included. A drawn state in collision climbs the signed distance (minus
       the penetration depth, ClearanceChecker::clearance()) along clearanceGradient()'s ascent step, which turns
       the robot about its origin as well as moving it: a robot whose far end sticks into an obstacle turns away
       from it about the contact, so an elongated robot drawn across the mouth of a tube or a slot turns into line
       with it, where a pure push-out (NarrowPassageSampler, OMPL's obstacle-based sampler) only translates it.
       Each step asks the signed distance to rise by the depth plus a margin (2% of the robot's radius about its
       origin) to first order, halved until it rises (at most 4 halvings), at most retract_steps steps (default
       12); a state that ends free (the exact test) is then moved up the clearance gradient for up to medial_steps
       steps (default 2, as NarrowPassageSampler's centring) and returned. sample() keeps a draw that is free as
       drawn with probability free_probability (default 0.1), so most of its states are retractions: states on
       the boundary of the free space, turned into the passages that touch it. sampleNear() (the local samples
       of tree planners: EST, BiEST, SBL, BKPIECE, ...) draws near the given state as the uniform sampler does, up
       to OMPL's attempts count, and returns the first free draw; only if every draw collides (the neighbourhood
       is nearly all obstacle: the inside or the mouth of a passage) is the last one retracted. Every state
       returned is valid by the exact test and within the bounds. Cost: a collision test per free draw, an exact
       signed distance with its gradient (a penetration query) per retraction step. Needs the space's validity
       checker to be a meshgap ClearanceChecker in CERTIFIED mode (looked up at construction): with another
       checker it samples uniformly and rejects invalid states, with a warning.
    */
    class RetractionSampler : public ompl::base::ValidStateSampler
    {
    public:
        explicit RetractionSampler(const ompl::base::SpaceInformation *si);
        ~RetractionSampler() override;

        bool sample(ompl::base::State *state) override;
        bool sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance) override;

        /** \brief Retract the colliding \e state to a valid one in place (see the class description); false, with
            \e state unspecified, if the steps run out or the ascent stalls. A valid \e state is returned as it is. */
        bool retract(ompl::base::State *state);

        void setFreeProbability(double p) { freeProbability_ = p; }
        double getFreeProbability() const { return freeProbability_; }
        void setRetractSteps(unsigned steps) { retractSteps_ = steps; }
        unsigned getRetractSteps() const { return retractSteps_; }
        void setMedialSteps(unsigned steps) { medialSteps_ = steps; }
        unsigned getMedialSteps() const { return medialSteps_; }

    private:
        /** \brief One backtracking step up the signed distance from \e state (signed distance \e value, gradient
            gradient_) aiming for a rise of \e target; true (and \e state, \e value updated) if it rose. */
        bool climb(ompl::base::State *state, double &value, double target);

        ompl::base::StateSamplerPtr sampler_;
        std::shared_ptr<const ClearanceChecker> checker_;
        ompl::base::State *work_;
        ompl::RNG rng_;
        double freeProbability_{0.1};
        unsigned retractSteps_{12};
        unsigned medialSteps_{2};
        std::vector<double> gradient_, step_;
    };
}  // namespace meshgap

#endif
