#ifndef MESHGAP_OMPL_ROBOT_CHECKER_H
#define MESHGAP_OMPL_ROBOT_CHECKER_H

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

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
    */
    class RobotChecker : public ompl::base::StateValidityChecker
    {
    public:
        RobotChecker(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene);

        bool isValid(const ompl::base::State *state) const override;
        double clearance(const ompl::base::State *state) const override;
        /** \brief The whole answer (the pair, the witnesses, every link's clearance) at \e state. */
        void distance(const ompl::base::State *state, const RobotRequest &request, RobotResult &result) const;

        const RobotScene &scene() const { return *scene_; }

    private:
        RobotSceneConstPtr scene_;
        std::uint64_t id_;
    };
}  // namespace meshgap

#endif
