// The control maps: OMPL.app control problems of meshgap's own (a "control" key), one per vehicle model that has no
// problem among OMPL.app's resources here: a kinematic car through a chicane of two walls (car_chicane), a blimp
// through a window in a wall (blimp_window) and a quadrotor through a window in a wall (quadrotor_window). Each is
// written as meshes and an OMPL.app .cfg, then read back and set up as meshgap_plan sets it up (start and goal free).

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "makemap/MapScene.h"
#include "meshgap/Exception.h"
#include <ompl/base/goals/GoalState.h>

#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/MeshWriter.h"
#include "support/Shapes.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace makemap
    {
        namespace
        {
            /** \brief A wall across the hall, x in [-0.15, 0.15], y in [-3, 3], z in [0, 4], with a window
                y in [-1, 1], z in [\e low, \e high]: drawn in (y, z), extruded along x. */
            Mesh wallWithWindow(double low, double high)
            {
                Polyhedron wall = prismPolyhedron({{-3.0, 0.0}, {3.0, 0.0}, {3.0, 4.0}, {-3.0, 4.0}},
                                                  {{{-1.0, low}, {1.0, low}, {1.0, high}, {-1.0, high}}}, 0.3);
                Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
                X.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
                X.translation() = Vector3d(-0.15, 0, 0);
                wall.transform(X);
                return wall.mesh(uniformSizing(1.0), "wall");
            }

            /** \brief Read the problem back and set it up as meshgap_plan does (start and goal in bounds and free);
                print their certified clearance. */
            void checkControlProblem(const fs::path &cfg)
            {
                const ProblemConfig config = readProblemConfig(cfg.string());
                const OmplControlProblem problem = setupControlProblem(config, ClearanceChecker::Mode::CERTIFIED);
                const ompl::base::ProblemDefinitionPtr &pdef = problem.setup->getProblemDefinition();
                const ompl::base::State *goal = pdef->getGoal()->as<ompl::base::GoalState>()->getState();
                std::printf("%s: control %s, start clearance %.6g, goal clearance %.6g, %zu obstacle triangles\n",
                            cfg.filename().c_str(), config.control.c_str(),
                            problem.checker->clearance(pdef->getStartState(0)), problem.checker->clearance(goal),
                            problem.scene->obstacles().front()->surface().triangles.size());
            }

            const char *const BENCHMARK = "\n[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n\n"
                                          "[planner]\nkpiece=\nrrt=\nest=\npdst=\nsst=\n";
        }  // namespace

        void writeCarChicane(const fs::path &directory)
        {
            fs::create_directories(directory);
            // Two walls across the yard, the first open at the top, the second at the bottom: the car drives an S.
            writeObj(mergeMeshes({boxBetween(Vector3d(-1.65, -4.0, -0.5), Vector3d(-1.35, 1.0, 0.5), 1.0),
                                  boxBetween(Vector3d(1.35, -1.0, -0.5), Vector3d(1.65, 4.0, 0.5), 1.0)},
                                 ""),
                     (directory / "car_chicane_world.obj").string());
            writeObj(makeBox(Vector3d(1.0, 0.5, 0.3), 0.5), (directory / "car_chicane_robot.obj").string());
            writeText(directory / "car_chicane.cfg",
                      std::string("[problem]\nname = car_chicane\nrobot = car_chicane_robot.obj\n"
                                  "world = car_chicane_world.obj\ncontrol = kinematic_car\n"
                                  "start.x = -4.5\nstart.y = 0\nstart.theta = 0\n"
                                  "goal.x = 4.5\ngoal.y = 0\ngoal.theta = 0\n"
                                  "volume.min.x = -6\nvolume.min.y = -4\nvolume.max.x = 6\nvolume.max.y = 4\n") +
                          BENCHMARK);
            checkControlProblem(directory / "car_chicane.cfg");
        }

        void writeBlimpWindow(const fs::path &directory)
        {
            fs::create_directories(directory);
            // The window is above the blimp's start and goal height: it climbs, passes, descends.
            writeObj(wallWithWindow(2.0, 3.2), (directory / "blimp_window_world.obj").string());
            writeObj(makeCapsule(Vector3d(-0.3, 0, 0), Vector3d(0.3, 0, 0), 0.18, 8, 2, 0.2),
                     (directory / "blimp_window_robot.obj").string());
            writeText(directory / "blimp_window.cfg",
                      std::string("[problem]\nname = blimp_window\nrobot = blimp_window_robot.obj\n"
                                  "world = blimp_window_world.obj\ncontrol = blimp\n"
                                  "start.x = -3\nstart.y = 0\nstart.z = 1\n"
                                  "start.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 1\nstart.theta = 0\n"
                                  "goal.x = 3\ngoal.y = 0\ngoal.z = 1\n"
                                  "goal.axis.x = 0\ngoal.axis.y = 0\ngoal.axis.z = 1\ngoal.theta = 0\n"
                                  "volume.min.x = -5\nvolume.min.y = -3\nvolume.min.z = 0\n"
                                  "volume.max.x = 5\nvolume.max.y = 3\nvolume.max.z = 4\n") +
                          BENCHMARK);
            checkControlProblem(directory / "blimp_window.cfg");
        }

        void writeQuadrotorWindow(const fs::path &directory)
        {
            fs::create_directories(directory);
            writeObj(wallWithWindow(1.5, 3.0), (directory / "quadrotor_window_world.obj").string());
            // A flat cross of two arms; OMPL.app's quadrotor thrusts along its body's -z, so it flies upside down
            // (turned by pi about x), which the symmetric cross does not show.
            writeObj(mergeMeshes({makeBox(Vector3d(0.6, 0.1, 0.06), 0.2), makeBox(Vector3d(0.1, 0.6, 0.06), 0.2)}, ""),
                     (directory / "quadrotor_window_robot.obj").string());
            writeText(directory / "quadrotor_window.cfg",
                      std::string("[problem]\nname = quadrotor_window\nrobot = quadrotor_window_robot.obj\n"
                                  "world = quadrotor_window_world.obj\ncontrol = quadrotor\n"
                                  "start.x = -3\nstart.y = 0\nstart.z = 2\n"
                                  "start.axis.x = 1\nstart.axis.y = 0\nstart.axis.z = 0\n"
                                  "start.theta = 3.14159265358979\n"
                                  "goal.x = 3\ngoal.y = 0\ngoal.z = 2\n"
                                  "goal.axis.x = 1\ngoal.axis.y = 0\ngoal.axis.z = 0\n"
                                  "goal.theta = 3.14159265358979\n"
                                  "volume.min.x = -5\nvolume.min.y = -3\nvolume.min.z = 0\n"
                                  "volume.max.x = 5\nvolume.max.y = 3\nvolume.max.z = 4\n") +
                          BENCHMARK);
            checkControlProblem(directory / "quadrotor_window.cfg");
        }
    }  // namespace makemap
}  // namespace meshgap
