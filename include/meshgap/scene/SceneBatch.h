#ifndef MESHGAP_SCENE_SCENE_BATCH_H
#define MESHGAP_SCENE_SCENE_BATCH_H

#include <Eigen/Geometry>
#include <vector>

#include "meshgap/scene/Scene.h"

namespace meshgap
{
    /** \brief The unit of work that threads share in distanceBatch() and inCollisionBatch(). Fixed, so the blocks
        (and so every answer) are the same whatever the number of threads. */
    constexpr std::size_t SCENE_BATCH_BLOCK = 256;

    /** \brief Scene::distance() at every pose of \e poses, in order, into \e results (resized to poses.size()).

        With \e warm, a SceneWarmStart is carried from pose to pose (a path's states are nearby, so it pays): for
        complete exact answers (request.exact, no stopBelow, computeDepth), which are bit for bit the cold ones, each thread
        carries its own across the blocks it takes; otherwise one starts afresh at each block of SCENE_BATCH_BLOCK
        consecutive poses. Without \e warm every query starts cold. Up to \e threads threads
        (at least 1; the caller's thread is one) each take the next block not yet taken until none is left, so they
        finish together however the cost varies along the batch. The blocks do not depend on \e threads, so the
        answers are identical for any number of threads. An exception thrown by a query is rethrown here once every
        thread has stopped. Allocates only \e results and the threads. */
    void distanceBatch(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, const SceneRequest &request,
                       bool warm, unsigned threads, std::vector<SceneResult> &results);

    /** \brief Scene::inCollision() at every pose of \e poses into \e results (resized; 1 = collides), its blocks
        shared among up to \e threads (at least 1) threads as distanceBatch() does; each thread carries a warm start
        (collision fronts: the same verdicts, cheaper along a trajectory). */
    void inCollisionBatch(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, unsigned threads,
                          std::vector<char> &results);
}  // namespace meshgap

#endif
