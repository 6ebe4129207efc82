#ifndef MESHGAP_ROBOT_ROBOT_BATCH_H
#define MESHGAP_ROBOT_ROBOT_BATCH_H

#include <vector>

#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/SceneBatch.h"

namespace meshgap
{
    /** \brief RobotScene::distance() at every state of \e states (\e count rows of robot().dimension() numbers,
        one after the other), in order, into \e results (resized to \e count). States are taken in blocks of
        SCENE_BATCH_BLOCK consecutive rows by up to \e threads threads (at least 1; the caller's thread is one),
        each block answered with a RobotWarmStart started afresh at its first state and carried along it (nearby
        states pay less), so every answer depends on its block alone and is the same for any number of threads.
        An exception thrown by a query (a state with a non-finite number or outside a joint's limits, say) is
        rethrown here once every thread has stopped, a meshgap::Exception naming the row ("states[700]: ..."). */
    void robotDistanceBatch(const RobotScene &scene, const double *states, std::size_t count,
                            const RobotRequest &request, unsigned threads, std::vector<RobotResult> &results);

    /** \brief RobotScene::inCollision() at every state into \e results (resized; 1 = collides), in blocks as
        robotDistanceBatch() does. */
    void robotInCollisionBatch(const RobotScene &scene, const double *states, std::size_t count, bool selfCollision,
                               unsigned threads, std::vector<char> &results);
}  // namespace meshgap

#endif
