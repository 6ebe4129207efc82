#ifndef MESHGAP_OMPL_ROBOT_CHECKER_H
#define MESHGAP_OMPL_ROBOT_CHECKER_H

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "meshgap/ThreadCounters.h"
#include "meshgap/ompl/ClearanceField.h"
#include "meshgap/robot/MotionBound.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(RobotChecker);

    /**
       @anchor mgRobotChecker
       @par Short description
       An OMPL state validity checker for a robot of many bodies (RobotScene) in a space made by robotStateSpace():
       isValid() is the exact whole-robot collision verdict (every link against the obstacles, every self pair the
       model checks; containment included), clearance() the minimum signed distance over those pairs, exact and
       certified (specs: EXACT), negative in collision. A warm start per thread and checker (the thread's last
       answer); thread-safe.

       As a ClearanceField (the clearance objectives, the path optimiser): clearanceOrContact() and clearanceBelow()
       are the whole-robot query stopped at the first collision and bounded (RobotRequest::stopBelow, upperBound);
       sweep() is the largest displacement bound over the pairs (MotionBound: a link's for a link against the
       obstacles, the pair's relative one for a self pair), the constant the certified RobotMotionValidator uses;
       the gradient is robotClearanceGradient()'s, the closest pair's, in the tangent coordinates of
       robotTangentDimension() (joint values; an SE(3) pose's translation and rotation vector), steps along it
       applyRobotStep(), the metric the levers of robotTangentLevers() (a step of metric length a moves no link
       point further than about a per coordinate).
    */
    class RobotChecker : public ompl::base::StateValidityChecker, public ClearanceField
    {
    public:
        RobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene);

        bool isValid(const ompl::base::State *state) const override;
        double clearance(const ompl::base::State *state) const override;
        /** \brief The whole answer (the pair, the witnesses, every link's clearance) at \e state. */
        void distance(const ompl::base::State *state, const RobotRequest &request, RobotResult &result) const;

        const RobotScene &scene() const { return *scene_; }
        const RobotSceneConstPtr &scenePtr() const { return scene_; }

        double clearanceOrContact(const ompl::base::State *state) const override;
        double clearanceBelow(const ompl::base::State *state, double bound) const override;
        bool certified() const override { return true; }
        std::uint64_t fieldId() const override { return id_; }
        double lengthScale() const override { return lengthScale_; }
        double sweep(const ompl::base::State *s1, const ompl::base::State *s2) const override;
        unsigned gradientDimension() const override { return static_cast<unsigned>(levers_.size()); }
        double gradient(const ompl::base::State *state, std::vector<double> &gradient,
                        const ClearanceGradientOptions &options = {},
                        ClearanceGradientInfo *info = nullptr) const override;
        double gradientNorm2(const std::vector<double> &gradient) const override;
        void ascentStep(const std::vector<double> &gradient, double alpha, std::vector<double> &step) const override;
        void applyStep(const ompl::base::State *state, const double *step, ompl::base::State *out) const override;

        /** \brief The isValid() calls so far, over every thread (for a progress line). */
        std::uint64_t validityCalls() const { return counts_.sum(0); }

    private:
        RobotSceneConstPtr scene_;
        std::uint64_t id_;
        /** \brief isValid() calls, counted per thread (nothing shared on the query's path). */
        mutable ThreadCounters<1> counts_;
        MotionBound bound_;
        /** \brief Per tangent coordinate, its lever (robotTangentLevers(); at least 1e-9 of the length scale). */
        std::vector<double> levers_;
        double lengthScale_{1.0};
    };
}  // namespace meshgap

#endif
