// Example: meshgap's clearance checker in your own OMPL SimpleSetup.
//
//   meshgap_example_own_simple_setup world.obj robot.obj "start x y z qx qy qz qw" "goal x y z qx qy qz qw" [seconds]
//
// No .cfg here: you build the SE(3) space, its bounds, start and goal yourself, as in any OMPL program; meshgap
// only loads the meshes and answers the validity and clearance queries. The robot's states are poses of the robot
// mesh's own frame (x y z, quaternion scalar-last, as OMPL prints SE(3) states); the world mesh stays where it is.

#include <algorithm>
#include <cstdio>
#include <limits>
#include <cstdlib>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/Scene.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

int main(int argc, char **argv)
{
    if (argc < 5)
    {
        std::fprintf(stderr, "usage: %s world.obj robot.obj \"x y z qx qy qz qw\" \"x y z qx qy qz qw\" [seconds]\n",
                     argv[0]);
        return 1;
    }
    const double seconds = argc > 5 ? std::atof(argv[5]) : 5.0;
    try
    {
        // 1. Geometry: the world split into its connected parts (one obstacle each), the robot in its own frame.
        const meshgap::Mesh world = meshgap::loadMesh(argv[1]), robot = meshgap::loadMesh(argv[2]);
        meshgap::ScenePtr scene = meshgap::Scene::fromMeshes(robot, world);

        // 2. Your own state space: SE(3), bounded by the world's box grown by the robot's radius.
        auto space = std::make_shared<ob::SE3StateSpace>();
        Eigen::AlignedBox3d box;
        for (const Eigen::Vector3d &v : world.vertices)
            box.extend(v);
        const double margin = scene->robot().radiusAboutOrigin();
        ob::RealVectorBounds bounds(3);
        for (int k = 0; k < 3; ++k)
        {
            bounds.setLow(k, box.min()[k] - margin);
            bounds.setHigh(k, box.max()[k] + margin);
        }
        space->setBounds(bounds);
        og::SimpleSetup setup(space);

        // 3. meshgap's checker: exact collision test, exact clearance.
        auto checker = std::make_shared<meshgap::ClearanceChecker>(setup.getSpaceInformation(), scene);
        setup.setStateValidityChecker(checker);

        // 4. Start and goal from poses; stateFromPose() fills an SE(3) (or SE(2)) state.
        ob::ScopedState<> start(space), goal(space);
        meshgap::stateFromPose(*space, meshgap::parsePose(argv[3], "start"), start.get());
        meshgap::stateFromPose(*space, meshgap::parsePose(argv[4], "goal"), goal.get());
        std::printf("start clearance %.4g, goal clearance %.4g\n", checker->clearance(start.get()),
                    checker->clearance(goal.get()));
        setup.setStartAndGoalStates(start, goal);

        // 5. Any OMPL planner.
        setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
        if (setup.solve(seconds) != ob::PlannerStatus::EXACT_SOLUTION)
        {
            std::printf("not solved within %g s\n", seconds);
            return 2;
        }
        og::PathGeometric &path = setup.getSolutionPath();
        double smallest = std::numeric_limits<double>::infinity();
        for (const ob::State *s : path.getStates())
            smallest = std::min(smallest, checker->clearance(s));
        std::printf("solved: %zu states, length %.4g, smallest clearance at the states %.4g\n", path.getStateCount(),
                    path.length(), smallest);
        return 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
