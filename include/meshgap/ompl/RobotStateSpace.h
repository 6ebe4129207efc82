#ifndef MESHGAP_OMPL_ROBOT_STATE_SPACE_H
#define MESHGAP_OMPL_ROBOT_STATE_SPACE_H

#include <ompl/base/StateSpace.h>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief The OMPL state space of a robot model, its subspaces in the order of the model's state numbers:
        - UrdfRobot: an SE(3) space for a floating base (translation within \e bounds), then, per run of joints,
          one RealVectorStateSpace for consecutive revolute and prismatic joints (bounded by their limits) and one
          SO2StateSpace per continuous joint;
        - RigidBodyRobot: one SE(2) or SE(3) space (translation within \e bounds; SE(2) takes its x and y);
        - MultiBodyRobot: one such space per body.
        A compound space always (so that robotStateToVector() and its inverse walk one layout). Throws
        meshgap::Exception for another kind of model, or bounds that are not 3-dimensional when needed. */
    ompl::base::StateSpacePtr robotStateSpace(const RobotModel &robot, const ompl::base::RealVectorBounds &bounds);

    /** \brief The model's state numbers of \e state of a space made by robotStateSpace() (or any compound of SE(3)
        ("x y z qx qy qz qw"), SE(2) ("x y theta"), SO(2) and real-vector spaces), into \e out, resized to the
        space's count. No allocation once \e out has its size. */
    void robotStateToVector(const ompl::base::StateSpace &space, const ompl::base::State *state,
                            std::vector<double> &out);

    /** \brief The inverse: set \e state from the numbers \e values (as many as robotStateToVector() gives). Throws
        meshgap::Exception for a count that does not match. */
    void robotStateFromVector(const ompl::base::StateSpace &space, const std::vector<double> &values,
                              ompl::base::State *state);
}  // namespace meshgap

#endif
