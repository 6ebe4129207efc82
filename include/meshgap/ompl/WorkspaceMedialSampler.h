#ifndef MESHGAP_OMPL_WORKSPACE_MEDIAL_SAMPLER_H
#define MESHGAP_OMPL_WORKSPACE_MEDIAL_SAMPLER_H

#include <ompl/base/StateSampler.h>
#include <ompl/base/ValidStateSampler.h>
#include <ompl/util/RandomNumbers.h>

#include <limits>

#include "meshgap/ompl/RetractionSampler.h"

namespace meshgap
{
    /** \brief An elongated robot's shape in its own frame, from its surface's vertices: the principal axis (the
        direction of largest spread), the point on it the robot is centred about, and how far the robot reaches
        along it and away from it. */
    struct RobotAxis
    {
        Eigen::Vector3d centre{Eigen::Vector3d::Zero()};      ///< the vertices' mean, robot frame
        Eigen::Vector3d direction{Eigen::Vector3d::UnitX()};  ///< unit principal axis, robot frame
        double halfLength{0.0};                               ///< largest |(v - centre) . direction| over the vertices
        double radius{0.0};  ///< largest distance of a vertex from the axis line: the cross-section's radius

        static RobotAxis of(const Mesh &robot);
    };

    /**
       @anchor mgWorkspaceMedialSampler
       @par Short description
       A valid-state sampler for passages about as wide as the robot's cross-section, found in the workspace and
       followed by the robot's long axis. It draws a point p of the workspace (the space's translation bounds) and
       retracts it onto the workspace's medial axis: along the direction from p's nearest obstacle point to p, to
       where the nearest obstacle point changes side (bisection; exact point-to-obstacle distances from a scene of
       the same obstacles with a point-sized probe as robot). A medial point m whose radius rho (its distance to the
       obstacles) lies between the robot's cross-section radius (RobotAxis::radius) and max_radius_factor times it
       (default 2), and whose nearest obstacle points on either side lie across from each other (more than 120
       degrees apart seen from m: not the bisector of a concave edge), is a passage the robot fits through only
       just. The passage's direction there is the one, among
       directions_ (default 24) evenly spread in the plane normal to m's witness direction, along which the
       workspace stays open longest: the largest min(d(m + rho e), d(m - rho e)). (In a tube that is its axis; in a
       slot any direction of the slot's plane that stays in it.) The robot's long axis (RobotAxis::direction) is
       turned onto +-e, rolled by a random angle about it, and placed so that the point of its axis line at a random
       offset in [-2 halfLength, 2 halfLength] from its centre sits at m: the robot lies in the passage, enters it
       from one end, or waits lined up in front of it (the states that join the passage to the open space). A state
       that collides is retracted (RetractionSampler::retract(), the exact signed distance's gradient in the full
       pose) and kept if that succeeds. sample() returns, with probability uniform_probability (default 0.5), a
       uniformly drawn valid state (up to OMPL's attempts count), so open space is covered too (a roadmap needs
       both); otherwise the first passage state of up to 2,000 draws (most workspace points are in open space or
       in no passage of the robot's size, and are rejected after one bounded point query), or false. sampleNear() is
       RetractionSampler's: free draws near the state, the last one retracted if all collide. Nothing here depends
       on a particular problem: for a compact robot the long axis is an arbitrary one and the sampler still puts
       the robot in passages of its size. Every state returned is valid by the exact test and within the bounds.
       Needs a certified meshgap ClearanceChecker on an SE(3) space; otherwise it samples uniformly, with a warning.
    */
    class WorkspaceMedialSampler : public ompl::base::ValidStateSampler
    {
    public:
        explicit WorkspaceMedialSampler(const ompl::base::SpaceInformation *si);
        ~WorkspaceMedialSampler() override;

        bool sample(ompl::base::State *state) override;
        bool sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance) override;

        /** \brief One passage sample (no uniform alternative): false if this draw found no passage or the robot
            could not be placed in it. */
        bool samplePassage(ompl::base::State *state);

        /** \brief The workspace medial point reached from \e p (see the class description) and its radius; false
            if \e p is inside an obstacle or farther than the largest radius from every obstacle, the medial
            point lies out of the bounds, or its two sides are not across from each other. Public for tests. */
        bool medialPoint(const Eigen::Vector3d &p, Eigen::Vector3d &medial, double &radius,
                         Eigen::Vector3d &normal) const;
        /** \brief Distance from the point \e p to the obstacles (negative or 0 inside one; the probe is a
            tetrahedron of circumradius 1e-6 times the robot's cross-section radius, so the answer is within that of
            the point's), and the nearest obstacle point in \e nearest; \e bound (no witness) if the distance is at
            least \e bound. */
        double pointDistance(const Eigen::Vector3d &p, Eigen::Vector3d &nearest,
                             double bound = std::numeric_limits<double>::infinity()) const;

        const RobotAxis &axis() const { return axis_; }
        void setUniformProbability(double p) { uniformProbability_ = p; }
        double getUniformProbability() const { return uniformProbability_; }
        void setMaxRadiusFactor(double f) { maxRadiusFactor_ = f; }
        double getMaxRadiusFactor() const { return maxRadiusFactor_; }

    private:
        ompl::base::StateSamplerPtr sampler_;
        std::shared_ptr<const ClearanceChecker> checker_;
        ScenePtr probe_;  ///< the checker's obstacles with a point-sized robot
        RetractionSampler retraction_;
        RobotAxis axis_;
        Eigen::AlignedBox3d box_;  ///< the translation bounds
        ompl::RNG rng_;
        double uniformProbability_{0.5};
        double maxRadiusFactor_{2.0};
        unsigned directions_{24};
        unsigned passageAttempts_{2000};
    };
}  // namespace meshgap

#endif
