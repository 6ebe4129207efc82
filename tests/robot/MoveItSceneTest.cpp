// MoveIt's planning scene and motion plan request (YAML) as a robot problem: the obstacles where poses composed by
// hand put them, the states the request gives, the allowed collision matrix honoured, one clear error per bad input;
// and MotionBenchMaker's UR5 problems (../shared/data/mbm, skipped when absent) read with a valid start and goal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "meshgap/Exception.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/UrdfRobot.h"
#include "TestScale.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        const std::string ARM = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/problems/arm2.urdf";
        const std::string ARM_SRDF = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot/problems/arm2.srdf";

        /** \brief The scene of the tests: a box (object pose turned a quarter about z, then the primitive's pose), a
            cylinder, a sphere and a cone, and a tetrahedron given inline. */
        const char *const SCENE = R"(name: test
robot_state:
  joint_state:
    name: [yaw, elbow, wrist]
    position: [0.5, 0.1, 0]
world:
  collision_objects:
    - id: Box1
      pose:
        position: [1, 0, 0]
        orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]
      primitives:
        - type: box
          dimensions: [0.1, 0.2, 0.3]
      primitive_poses:
        - position: [0, 0.5, 0]
          orientation: [0, 0, 0, 1]
    - id: Round
      primitives:
        - type: cylinder
          dimensions: [0.4, 0.1]
        - type: sphere
          dimensions: [0.2]
        - type: 4
          dimensions: [0.3, 0.05]
      primitive_poses:
        - position: {x: 0, y: -2, z: 0}
          orientation: {x: 0, y: 0, z: 0, w: 1}
        - position: [0, 3, 1]
          orientation: [0, 0, 0, 0]
        - position: [3, 3, 0]
          orientation: [0, 0, 0, 1]
    - id: Tet
      meshes:
        - vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
          triangles: [{vertex_indices: [0, 2, 1]}, [0, 1, 3], [0, 3, 2], [1, 2, 3]]
      mesh_poses:
        - position: [-5, 0, 0]
          orientation: [0, 0, 0, 1]
allowed_collision_matrix:
  entry_names: [base, Box1, box_link, upper]
  entry_values:
    - [false, true, false, false]
    - [true, false, false, false]
    - [false, false, false, true]
    - [false, false, true, false]
)";

        const char *const REQUEST = R"(group_name: arm
start_state:
  joint_state:
    name: [elbow]
    position: [0.2]
goal_constraints:
  - joint_constraints:
      - joint_name: yaw
        position: 1.0
)";

        /** \brief The URDF, SRDF, scene and request. */
        MoveItFiles moveItFiles(const std::vector<std::string> &paths)
        {
            MoveItFiles f;
            f.urdf = paths.at(0);
            f.srdf = paths.at(1);
            f.scene = paths.at(2);
            f.request = paths.at(3);
            return f;
        }

        /** \brief A folder of its own per test process. */
        class MoveItFilesTest : public ::testing::Test
        {
        protected:
            void SetUp() override
            {
                dir_ = fs::temp_directory_path() / ("meshgap_moveit_" + std::to_string(::getpid()));
                fs::create_directories(dir_);
            }
            void TearDown() override { fs::remove_all(dir_); }

            std::string write(const std::string &name, const std::string &text)
            {
                const std::string path = (dir_ / name).string();
                std::ofstream(path) << text;
                return path;
            }

            /** \brief \e text with its first \e from replaced by \e to. */
            static std::string edit(std::string text, const std::string &from, const std::string &to)
            {
                const std::size_t at = text.find(from);
                EXPECT_NE(at, std::string::npos) << from;
                return at == std::string::npos ? text : text.replace(at, from.size(), to);
            }

            /** \brief The problem of the arm, \e srdf, and this scene and request ("": none). */
            RobotProblem read(const std::string &srdf, const std::string &scene, const std::string &request)
            {
                return readMoveItProblem(moveItFiles({ARM, srdf, scene.empty() ? "" : write("s.yaml", scene),
                                                      request.empty() ? "" : write("r.yaml", request)}));
            }

            /** \brief The message readMoveItProblem() throws for this scene and request ("" when it does not). */
            std::string error(const std::string &scene, const std::string &request = REQUEST)
            {
                try
                {
                    read(ARM_SRDF, scene, request);
                }
                catch (const Exception &e)
                {
                    return e.what();
                }
                return "";
            }

            fs::path dir_;
        };

        bool near(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double tol = 1e-12)
        {
            return (a - b).cwiseAbs().maxCoeff() < tol;
        }
    }  // namespace

    TEST_F(MoveItFilesTest, ObstaclesSitWhereTheComposedPosesPutThem)
    {
        const RobotProblem p = read(ARM_SRDF, SCENE, REQUEST);
        ASSERT_EQ(p.obstacles.size(), 5u);
        EXPECT_EQ(p.obstacleNames, (std::vector<std::string>{"Box1", "Round", "Round", "Round", "Tet"}));
        // Box: centre (1, 0, 0) + Rz(90)(0, 0.5, 0) = (0.5, 0, 0); its x and y sizes swapped by the turn.
        const Eigen::AlignedBox3d box = p.obstacles[0]->surface().bounds();
        EXPECT_TRUE(near(box.min(), Eigen::Vector3d(0.4, -0.05, -0.15))) << box.min().transpose();
        EXPECT_TRUE(near(box.max(), Eigen::Vector3d(0.6, 0.05, 0.15))) << box.max().transpose();
        // Cylinder: height 0.4 along z, radius 0.1 (circumscribed: the polygon's corners a little beyond).
        const Eigen::AlignedBox3d cylinder = p.obstacles[1]->surface().bounds();
        EXPECT_NEAR(cylinder.min().z(), -0.2, 1e-12);
        EXPECT_NEAR(cylinder.max().z(), 0.2, 1e-12);
        EXPECT_NEAR(cylinder.center().y(), -2.0, 1e-12);
        EXPECT_GE(cylinder.max().x(), 0.1);
        EXPECT_LE(cylinder.max().x(), 0.1 / std::cos(M_PI / 32) + 1e-12);
        // Sphere: the all-zero quaternion is the identity, as MoveIt takes it.
        EXPECT_TRUE(near(p.obstacles[2]->surface().bounds().center(), Eigen::Vector3d(0, 3, 1), 1e-9));
        EXPECT_GE(p.obstacles[2]->surface().bounds().max().z(), 1.2);
        // Cone: base at z = -0.15, apex at z = +0.15.
        EXPECT_NEAR(p.obstacles[3]->surface().bounds().min().z(), -0.15, 1e-12);
        EXPECT_NEAR(p.obstacles[3]->surface().bounds().max().z(), 0.15, 1e-12);
        EXPECT_TRUE(near(p.obstacles[4]->surface().bounds().min(), Eigen::Vector3d(-5, 0, 0)));
        EXPECT_TRUE(p.obstacles[4]->isClosed());
    }

    TEST_F(MoveItFilesTest, EachPrimitiveKeepsItsSolidWhereItsMeshIs)
    {
        const RobotProblem p = read(ARM_SRDF, SCENE, REQUEST);
        ASSERT_EQ(p.obstacles.size(), 5u);
        using Kind = Primitive::Kind;
        const std::vector<Kind> kinds = {Kind::BOX, Kind::CYLINDER, Kind::SPHERE, Kind::CONE};
        const std::vector<Eigen::Vector3d> sizes = {{0.1, 0.2, 0.3}, {0.1, 0.4, 0}, {0.2, 0, 0}, {0.05, 0.3, 0}};
        const std::vector<Eigen::Vector3d> centres = {{0.5, 0, 0}, {0, -2, 0}, {0, 3, 1}, {3, 3, 0}};
        for (std::size_t o = 0; o < 4; ++o)
        {
            ASSERT_EQ(p.obstacles[o]->primitives().size(), 1u) << o;
            const Primitive &solid = p.obstacles[o]->primitives()[0];
            EXPECT_EQ(solid.kind, kinds[o]) << o;
            EXPECT_TRUE(near(solid.size, sizes[o])) << o << ": " << solid.size.transpose();
            EXPECT_TRUE(near(solid.pose.translation(), centres[o], 1e-12)) << o;
            // The mesh in the solid's frame: within its circumscribed extent, and reaching it.
            double reach = 0.0;
            for (const Eigen::Vector3d &v : p.obstacles[o]->surface().vertices)
            {
                const Eigen::Vector3d u = solid.pose.inverse() * v;
                const double radial = kinds[o] == Kind::SPHERE ? u.norm() : u.head<2>().norm();
                const double extent = kinds[o] == Kind::BOX ? (2.0 * u.cwiseAbs().cwiseQuotient(solid.size)).maxCoeff()
                                      : kinds[o] == Kind::SPHERE ? radial / solid.size.x()
                                                                 : std::max(radial / solid.size.x(),
                                                                            2.0 * std::abs(u.z()) / solid.size.y());
                reach = std::max(reach, extent);
            }
            EXPECT_GE(reach, 1.0 - 1e-12) << o;
            EXPECT_LE(reach, 1.0 / std::pow(std::cos(M_PI / 32), 2) + 1e-12) << o;
        }
        // The box turned a quarter about z by the object's pose: its x and y edges along the world's y and x.
        EXPECT_TRUE(near(p.obstacles[0]->primitives()[0].pose.linear() * Eigen::Vector3d::UnitX(),
                         Eigen::Vector3d::UnitY(), 1e-12));
        EXPECT_TRUE(p.obstacles[4]->primitives().empty());  // a mesh
        // The URDF's links are boxes: each keeps its box, in the link's frame.
        for (const RobotLink &link : p.robot->links())
        {
            ASSERT_EQ(link.body->primitives().size(), 1u) << link.name;
            EXPECT_EQ(link.body->primitives()[0].kind, Kind::BOX) << link.name;
            const Eigen::AlignedBox3d bounds = link.body->surface().bounds();
            EXPECT_TRUE(near(bounds.sizes(), link.body->primitives()[0].size, 1e-12)) << link.name;
            EXPECT_TRUE(near(bounds.center(), link.body->primitives()[0].pose.translation(), 1e-12)) << link.name;
        }
    }

    TEST_F(MoveItFilesTest, StartIsTheSceneStateUnderTheRequestsAndGoalTheStartUnderTheConstraints)
    {
        const RobotProblem p = read("", SCENE, REQUEST);
        EXPECT_EQ(p.start, (std::vector<double>{0.5, 0.2}));
        ASSERT_TRUE(p.goal);
        EXPECT_EQ(*p.goal, (std::vector<double>{1.0, 0.2}));
        // No request: the scene's state, no goal.
        const RobotProblem s = read("", SCENE, "");
        EXPECT_EQ(s.start, (std::vector<double>{0.5, 0.1}));
        EXPECT_FALSE(s.goal);
    }

    TEST_F(MoveItFilesTest, TheAllowedCollisionMatrixIsHonouredWithTheSrdf)
    {
        const RobotProblem p = read(ARM_SRDF, SCENE, REQUEST);
        const RobotModel &robot = *p.robot;
        const std::size_t base = robot.findLink("base"), fore = robot.findLink("fore");
        ASSERT_NE(base, RobotModel::NONE);
        EXPECT_TRUE(robot.isAllowed(base, fore));  // the SRDF's
        // base and Box1: that link against that object's one body, nothing else; box_link (no such link) ignored.
        EXPECT_EQ(p.allowedObstacles, (std::vector<LinkPair>{{base, 0}}));
        // A box overlapping the base: in collision unless the pair is allowed.
        const std::string overlapping = edit(SCENE, "position: [1, 0, 0]", "position: [0.5, 0, -0.05]");
        const RobotProblem q = read(ARM_SRDF, overlapping, "");
        RobotWarmStart warm;
        const RobotScene allowed(q.robot, q.obstacles, q.allowedObstacles), checked(q.robot, q.obstacles);
        EXPECT_FALSE(allowed.inCollision(q.start.data(), q.start.size(), warm));
        EXPECT_TRUE(checked.inCollision(q.start.data(), q.start.size(), warm));
        EXPECT_EQ(allowed.linkObstacles(base), (std::vector<std::size_t>{1, 2, 3, 4}));
    }

    TEST_F(MoveItFilesTest, BadInputGetsOneErrorNamingTheFileAndTheEntry)
    {
        const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
            {"world:\n  collision_objects: [\n", "s.yaml:", "cannot read the YAML"},
            {"world: 5\n", "s.yaml:1", "world: is not a map"},
            {edit(SCENE, "name: [yaw, elbow, wrist]", "name: [yaw, knee, wrist]"), "s.yaml:5", "no joint 'knee'"},
            {edit(SCENE, "position: [0.5, 0.1, 0]", "position: [0.5, 9, 0]"), "s.yaml:5", "outside its limits"},
            {edit(SCENE, "position: [0.5, 0.1, 0]", "position: [0.5, 0.1, 0.3]"), "s.yaml:5", "fixed in the URDF"},
            {edit(SCENE, "dimensions: [0.1, 0.2, 0.3]", "dimensions: [0.1, abc, 0.3]"), "s.yaml:14",
             "world.collision_objects[0] ('Box1').primitives[0].dimensions[1]: 'abc' is not a number"},
            {edit(SCENE, "dimensions: [0.1, 0.2, 0.3]", "dimensions: [0.1, 0.2]"), "s.yaml:14",
             "a box takes 3 (x y z)"},
            {edit(SCENE, "type: box", "type: capsule"), "s.yaml:13", "unknown primitive type 'capsule'"},
            {edit(SCENE, "dimensions: [0.2]", "dimensions: [-0.2]"), "s.yaml:", "radius"},
            {edit(SCENE, "orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]", "orientation: [0, 0, 1, 1]"),
             "s.yaml:11", "Box1').pose.orientation: the quaternion is not of unit length"},
            {edit(SCENE, "- vertices: [[0, 0, 0],", "- resource: package://nowhere/none.stl\n          x: [[0, 0, 0],"),
             "s.yaml:", "('Tet').meshes[0].resource"},
            {edit(SCENE, "[0, 1, 3]", "[0, 1, 7]"), "s.yaml:", "vertex index 7"},
            {edit(SCENE, "    - [false, true, false, false]\n", ""), "s.yaml:", "4 entry_names but 3 rows"},
            {edit(SCENE, "- id: Tet\n", "- id: Tet\n      header: {frame_id: nowhere}\n"), "s.yaml:",
             "unknown frame 'nowhere'"},
        };
        for (const auto &[scene, where, what] : cases)
        {
            const std::string message = error(scene);
            EXPECT_NE(message.find(where), std::string::npos) << message;
            EXPECT_NE(message.find(what), std::string::npos) << message;
        }
        const std::string request = error(SCENE, edit(REQUEST, "joint_name: yaw", "joint_name: hip"));
        EXPECT_NE(request.find("r.yaml:8: goal_constraints[0].joint_constraints[0]"), std::string::npos) << request;
        EXPECT_NE(request.find("no joint 'hip'"), std::string::npos) << request;
        const std::string missing = error(SCENE, "- 1\n");
        EXPECT_NE(missing.find("r.yaml: not a YAML map"), std::string::npos) << missing;
    }

    TEST_F(MoveItFilesTest, AFrameIdOfALinkPlacesTheObjectAtThatLinksPoseInTheScenesState)
    {
        // Link 'fore' at yaw 0.5, elbow 0.1: its frame's pose from the robot, the object at its origin.
        const std::string scene = edit(SCENE, "- id: Tet\n", "- id: Tet\n      header: {frame_id: fore}\n");
        const RobotProblem p = read("", scene, "");
        std::vector<Eigen::Isometry3d> frames;
        p.robot->framePoses(p.start.data(), p.start.size(), frames);
        const Eigen::Vector3d origin = frames[p.robot->findFrame("fore")] * Eigen::Vector3d(-5, 0, 0);
        EXPECT_TRUE(near(p.obstacles[4]->surface().vertices[0], origin, 1e-12));
    }

    TEST_F(MoveItFilesTest, ARobotCfgTakesTheSceneAndRequestKeys)
    {
        write("s.yaml", SCENE);
        write("r.yaml", REQUEST);
        const std::string lines = "[problem]\nrobot.urdf = " + ARM + "\nrobot.srdf = " + ARM_SRDF +
                                  "\nscene = s.yaml\nrequest = r.yaml\n";
        const RobotProblem p = readRobotProblem(write("p.cfg", lines));
        EXPECT_EQ(p.obstacles.size(), 5u);
        EXPECT_EQ(p.start, (std::vector<double>{0.5, 0.2}));
        ASSERT_TRUE(p.goal);
        EXPECT_EQ(*p.goal, (std::vector<double>{1.0, 0.2}));
        EXPECT_EQ(p.allowedObstacles.size(), 1u);
        const Problem any = readProblem((dir_ / "p.cfg").string());
        EXPECT_TRUE(any.robot && !any.rigidBody);
        EXPECT_EQ(any.robot->obstacles.size(), 5u);
        // start.joints replaces the request's start; a missing scene is named by its key.
        const RobotProblem q = readRobotProblem(write("q.cfg", lines + "start.joints = 0.1 0.3\n"));
        EXPECT_EQ(q.start, (std::vector<double>{0.1, 0.3}));
        try
        {
            readRobotProblem(write("m.cfg", "[problem]\nrobot.urdf = " + ARM + "\nscene = none.yaml\n"));
            ADD_FAILURE() << "no error";
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find("m.cfg:3: scene file"), std::string::npos) << e.what();
        }
    }

    TEST(MoveItBenchMaker, Ur5ProblemsReadWithAValidStartAndGoal)
    {
        const fs::path folder = fs::path(MESHGAP_SHARED_DATA_DIR) / "mbm" / "ur5";
        if (!fs::exists(folder / "problems.tar.bz2") || !fs::exists(folder / "ur5.urdf"))
            GTEST_SKIP() << "MotionBenchMaker's UR5 problems are not in " << folder.string();
        const fs::path dir = fs::temp_directory_path() / ("meshgap_mbm_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        const std::string command =
            "tar -xjf '" + (folder / "problems.tar.bz2").string() + "' -C '" + dir.string() + "'";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::size_t read = 0;
        // Two problems of each scenario; the first only under a reduced test::scale(). Every problem shares one robot,
        // its URDF and SRDF read once (MoveItFiles::robot, as the suite runner reads them).
        const std::vector<std::string> numbers =
            test::scale() < 1.0 ? std::vector<std::string>{"0001"} : std::vector<std::string>{"0001", "0100"};
        const UrdfRobotConstPtr robot =
            readMoveItRobot(moveItFiles({(folder / "ur5.urdf").string(), (folder / "ur5.srdf").string(), "", ""}));
        for (const char *scenario : {"bookshelf_small", "bookshelf_tall", "bookshelf_thin", "box", "cage",
                                     "table_pick", "table_under_pick"})
            for (const std::string &n : numbers)
            {
                const fs::path problems = dir / "problems" / (std::string(scenario) + "_ur5");
                MoveItFiles files = moveItFiles({(folder / "ur5.urdf").string(), (folder / "ur5.srdf").string(),
                                                 (problems / ("scene" + n + ".yaml")).string(),
                                                 (problems / ("request" + n + ".yaml")).string()});
                files.robot = robot;
                const RobotProblem p = readMoveItProblem(files);
                ASSERT_TRUE(p.goal) << files.request;
                EXPECT_EQ(p.start.size(), 6u);
                EXPECT_GT(p.obstacles.size(), 0u) << files.scene;
                const RobotScene scene(p.robot, p.obstacles, p.allowedObstacles);
                RobotWarmStart warm;
                EXPECT_FALSE(scene.inCollision(p.start.data(), p.start.size(), warm)) << files.scene << " start";
                EXPECT_FALSE(scene.inCollision(p.goal->data(), p.goal->size(), warm)) << files.scene << " goal";
                ++read;
            }
        fs::remove_all(dir);
        EXPECT_EQ(read, 7 * numbers.size());
    }
}  // namespace meshgap
