#ifndef MESHGAP_OMPL_ROBOT_STATE_SPACE_H
#define MESHGAP_OMPL_ROBOT_STATE_SPACE_H

#include <ompl/base/StateSpace.h>
#include <vector>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief The OMPL state space of a robot model: one subspace per block of RobotModel::stateBlocks(), in the
        order of the model's state numbers: a RealVectorStateSpace for a run of joints of one bounded value
        (revolute, prismatic; bounded by their limits), an SO2StateSpace per continuous joint, an SE2StateSpace
        per planar joint or SE(2) body (x and y within the first two of \e bounds), an SE3StateSpace per floating
        joint, floating base or SE(3) body (the position within \e bounds). A compound space always (so that
        robotStateToVector() and its inverse walk one layout). Throws meshgap::Exception for a robot without a
        movable joint, or bounds that are not 3-dimensional (2 for SE(2)) when needed. */
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
