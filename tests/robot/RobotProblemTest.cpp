// The robot problem file (.cfg with robot.urdf or robot.1, ...): what it yields (the robot, its payload, the states,
// the world, the bounds), checked against poses composed by hand, and one clear error naming file:line per bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/Scene.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        const std::string RESOURCES = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot";
        const std::string PROBLEM_ARM = RESOURCES + "/problems/arm2.urdf";
        const std::string PROBLEM_CUBE = RESOURCES + "/meshgap_test_description/meshes/cube.obj";

        /** \brief A folder of its own per test process, with a world of two unit cubes (x in [2, 3] and [-3, -2]). */
        class RobotProblemFiles : public ::testing::Test
        {
        protected:
            void SetUp() override
            {
                dir_ = fs::temp_directory_path() / ("meshgap_robot_problem_" + std::to_string(::getpid()));
                fs::create_directories(dir_);
                std::ofstream world(dir_ / "world.obj");
                int base = 0;
                for (double x0 : {2.0, -3.0})
                {
                    for (int k = 0; k < 8; ++k)
                        world << "v " << x0 + (k & 1) << " " << ((k >> 1) & 1) << " " << ((k >> 2) & 1) << "\n";
                    // corners k = x + 2y + 4z (1-based in the file), each face wound outward
                    const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
                    for (const auto &f : faces)
                        world << "f " << base + f[0] + 1 << " " << base + f[1] + 1 << " " << base + f[2] + 1 << "\n";
                    base += 8;
                }
            }
            void TearDown() override { fs::remove_all(dir_); }

            /** \brief Write \e lines as the cfg \e name; line k of the file is lines[k - 1]. */
            std::string cfg(const std::vector<std::string> &lines, const std::string &name = "problem.cfg")
            {
                const std::string path = (dir_ / name).string();
                std::ofstream out(path);
                for (const std::string &line : lines)
                    out << line << "\n";
                return path;
            }

            /** \brief The message readRobotProblem() throws for \e path ("" when it does not throw). */
            static std::string robotError(const std::string &path)
            {
                try
                {
                    readRobotProblem(path);
                }
                catch (const Exception &e)
                {
                    return e.what();
                }
                return "";
            }

            fs::path dir_;
        };

        Eigen::Isometry3d rotation(double angle, const Eigen::Vector3d &axis)
        {
            return Eigen::Isometry3d(Eigen::AngleAxisd(angle, axis.normalized()));
        }

        Eigen::Isometry3d shift(double x, double y, double z)
        {
            return Eigen::Isometry3d(Eigen::Translation3d(x, y, z));
        }

        std::vector<std::string> armLines(const std::string &start, const std::string &extra = "")
        {
            return {"[problem]",
                    "robot.urdf = " + PROBLEM_ARM,
                    "world = world.obj",
                    "start.joints = " + start,
                    "goal.joints = -0.5 0.25",
                    extra,
                    "volume.min.x = -4",
                    "volume.min.y = -1",
                    "volume.min.z = -2",
                    "volume.max.x = 4",
                    "volume.max.y = 1",
                    "volume.max.z = 3",
                    "[planner]",
                    "rrtconnect.range = 0.5"};
        }
    }  // namespace

    TEST_F(RobotProblemFiles, UrdfProblemYieldsTheArmItsPayloadStatesAndWorld)
    {
        auto lines = armLines("0.3 -0.7", "attach = " + PROBLEM_CUBE + " hand 0.01 0 0 0 0 0.6 0.8");
        lines.insert(lines.begin() + 2, "robot.srdf = " + RESOURCES + "/problems/arm2.srdf");
        const RobotProblem p = readRobotProblem(cfg(lines));
        ASSERT_TRUE(p.urdf);
        EXPECT_EQ(p.name, "problem");
        EXPECT_EQ(p.robot->dimension(), 2u);
        EXPECT_EQ(p.start, (std::vector<double>{0.3, -0.7}));
        ASSERT_TRUE(p.goal);
        EXPECT_EQ(*p.goal, (std::vector<double>{-0.5, 0.25}));
        ASSERT_EQ(p.obstacles.size(), 2u);  // the world's two cubes
        ASSERT_TRUE(p.volume);
        EXPECT_EQ(p.volume->min(), Eigen::Vector3d(-4, -1, -2));
        EXPECT_EQ(p.volume->max(), Eigen::Vector3d(4, 1, 3));
        ASSERT_EQ(p.planners.size(), 1u);
        EXPECT_EQ(p.planners[0].second, "0.5");

        // The payload sits at the hand: yaw about z at height 0.2, 0.5 along the upper arm, elbow about y, 0.4 along
        // the forearm, then the attach pose (a rotation about z with cos = 0.8, sin = 0.6, half-angle quaternion).
        const std::size_t payload = p.robot->findLink("payload");
        ASSERT_NE(payload, RobotModel::NONE);
        EXPECT_TRUE(p.robot->links()[payload].payload);
        const Eigen::Isometry3d attach = shift(0.01, 0, 0) * rotation(2 * std::atan2(0.6, 0.8), Eigen::Vector3d::UnitZ());
        const Eigen::Isometry3d expected = shift(0, 0, 0.2) * rotation(0.3, Eigen::Vector3d::UnitZ()) *
                                           shift(0.5, 0, 0) * rotation(-0.7, Eigen::Vector3d::UnitY()) *
                                           shift(0.4, 0, 0) * attach;
        const auto poses = p.robot->linkPoses(p.start);
        EXPECT_TRUE(poses[payload].isApprox(expected, 1e-12)) << poses[payload].matrix() << "\n" << expected.matrix();
        // The SRDF's pair and the payload's parent are allowed; the payload is checked against the upper arm.
        const std::size_t base = p.robot->findLink("base"), upper = p.robot->findLink("upper"),
                          fore = p.robot->findLink("fore");
        EXPECT_TRUE(p.robot->isAllowed(base, fore));
        EXPECT_TRUE(p.robot->isAllowed(fore, payload));
        EXPECT_FALSE(p.robot->isAllowed(upper, payload));
    }

    TEST_F(RobotProblemFiles, SevenMoreNumbersMakeTheBaseFloat)
    {
        auto lines = armLines("1 2 0.5 0 0 0.6 0.8 0.3 -0.7");
        lines[4] = "goal.joints = 0 0 0 0 0 0 1 0 0";
        const RobotProblem p = readRobotProblem(cfg(lines));
        const auto *robot = dynamic_cast<const UrdfRobot *>(p.robot.get());
        ASSERT_NE(robot, nullptr);
        EXPECT_TRUE(robot->floatingBase());
        EXPECT_EQ(robot->dimension(), 9u);
        const Eigen::Isometry3d X_base = shift(1, 2, 0.5) * rotation(2 * std::atan2(0.6, 0.8), Eigen::Vector3d::UnitZ());
        const Eigen::Isometry3d expected = X_base * shift(0, 0, 0.2) * rotation(0.3, Eigen::Vector3d::UnitZ());
        std::vector<Eigen::Isometry3d> frames;
        p.robot->framePoses(p.start.data(), p.start.size(), frames);
        const std::size_t upper = p.robot->findFrame("upper");
        EXPECT_TRUE(frames[upper].isApprox(expected, 1e-12)) << frames[upper].matrix() << "\n" << expected.matrix();
    }

    TEST_F(RobotProblemFiles, NumberedBodiesInSE3AreCentredAndPosedAsOmplAppDoes)
    {
        const std::string path = cfg({"[problem]",
                                      "name = swap",
                                      "robot.1 = " + PROBLEM_CUBE,
                                      "robot.2 = " + PROBLEM_CUBE,
                                      "world = world.obj",
                                      "start.1.x = -1",
                                      "start.1.y = 0",
                                      "start.1.z = 0.5",
                                      "start.1.theta = 1.5707963267948966",
                                      "start.1.axis.x = 0",
                                      "start.1.axis.z = 2",
                                      "start.2.x = 1",
                                      "start.2.y = 0",
                                      "start.2.z = 0.5",
                                      "goal.1.x = 1",
                                      "goal.1.y = 0",
                                      "goal.1.z = 0.5",
                                      "goal.2.x = -1",
                                      "goal.2.y = 0",
                                      "goal.2.z = 0.5"});
        const RobotProblem p = readRobotProblem(path);
        EXPECT_FALSE(p.urdf);
        EXPECT_FALSE(p.planar);
        EXPECT_EQ(p.name, "swap");
        ASSERT_EQ(p.robot->dimension(), 14u);
        const double h = std::sqrt(0.5);
        const std::vector<double> start = {-1, 0, 0.5, 0, 0, h, h, 1, 0, 0.5, 0, 0, 0, 1};
        ASSERT_EQ(p.start.size(), start.size());
        for (std::size_t k = 0; k < start.size(); ++k)
            EXPECT_NEAR(p.start[k], start[k], 1e-15) << k;
        ASSERT_TRUE(p.goal);
        EXPECT_EQ(*p.goal, (std::vector<double>{1, 0, 0.5, 0, 0, 0, 1, -1, 0, 0.5, 0, 0, 0, 1}));
        EXPECT_FALSE(p.volume);
        // OMPL.app centres a robot mesh on its vertices' mean: the unit cube [0, 1]^3 becomes [-0.5, 0.5]^3, so the
        // corner (1, 1, 1) of body 1, turned a quarter about z, lands at (-1, 0, 0.5) + (-0.5, 0.5, 0.5).
        const auto poses = p.robot->linkPoses(p.start);
        const Mesh &mesh = p.robot->links()[0].body->surface();
        Eigen::Vector3d corner = Eigen::Vector3d::Constant(-1);
        for (const Eigen::Vector3d &v : mesh.vertices)
            if (v.minCoeff() > 0.49)
                corner = poses[0] * v;
        EXPECT_TRUE(corner.isApprox(Eigen::Vector3d(-1.5, 0.5, 1.0), 1e-12)) << corner.transpose();
    }

    TEST_F(RobotProblemFiles, NumberedBodiesWithoutZAreSE2)
    {
        const RobotProblem p = readRobotProblem(
            cfg({"[problem]", "robot.1 = " + PROBLEM_CUBE, "robot.2 = " + PROBLEM_CUBE, "world = world.obj",
                 "start.1.x = -1", "start.1.y = 0.5", "start.1.theta = 0.25", "start.2.x = 1", "start.2.y = -0.5",
                 "volume.min.x = -4", "volume.min.y = -2", "volume.max.x = 4", "volume.max.y = 2"}));
        EXPECT_TRUE(p.planar);
        const auto *robot = dynamic_cast<const MultiBodyRobot *>(p.robot.get());
        ASSERT_NE(robot, nullptr);
        EXPECT_EQ(robot->space(0), RigidSpace::SE2);
        EXPECT_EQ(robot->space(1), RigidSpace::SE2);
        EXPECT_EQ(p.start, (std::vector<double>{-1, 0.5, 0.25, 1, -0.5, 0}));
        EXPECT_FALSE(p.goal);
        ASSERT_TRUE(p.volume);
        EXPECT_EQ(p.volume->min().head<2>(), Eigen::Vector2d(-4, -2));
    }

    TEST_F(RobotProblemFiles, BadInputNamesTheFileLineAndProblem)
    {
        auto has = [](const std::string &message, const std::string &what)
        { return message.find(what) != std::string::npos; };
        // start.joints is line 4 of armLines()
        std::string e = robotError(cfg(armLines("0.3 -0.7 0.1")));
        EXPECT_TRUE(has(e, "problem.cfg:4: start.joints has 3 numbers") && has(e, "yaw elbow")) << e;
        e = robotError(cfg(armLines("0.3 x")));
        EXPECT_TRUE(has(e, "problem.cfg:4:") && has(e, "'x' is not a finite number")) << e;
        e = robotError(cfg(armLines("0.3 2.5")));
        EXPECT_TRUE(has(e, "problem.cfg:4:") && has(e, "joint 'elbow'") && has(e, "outside its limits")) << e;
        e = robotError(cfg(armLines("0 0", "attach = " + PROBLEM_CUBE + " claw 0 0 0 0 0 0 1")));
        EXPECT_TRUE(has(e, "problem.cfg:6: attach: the robot has no link 'claw'")) << e;
        e = robotError(cfg(armLines("0 0", "attach = nothing.obj hand 0 0 0 0 0 0 1")));
        EXPECT_TRUE(has(e, "problem.cfg:6:") && has(e, "nothing.obj' does not exist")) << e;
        auto lines = armLines("0 0");
        lines[1] = "robot.urdf = " + RESOURCES + "/missing_mesh.urdf";
        e = robotError(cfg(lines));
        EXPECT_TRUE(has(e, "problem.cfg:2: robot.urdf:") && has(e, "missing_mesh.urdf")) << e;
        lines[1] = "robot.urdf = no_such.urdf";
        e = robotError(cfg(lines));
        EXPECT_TRUE(has(e, "problem.cfg:2:") && has(e, "no_such.urdf' does not exist")) << e;
        e = robotError(cfg({"[problem]", "robot.1 = " + PROBLEM_CUBE, "robot.3 = " + PROBLEM_CUBE, "world = world.obj",
                            "start.1.x = 0", "start.1.y = 0"}));
        EXPECT_TRUE(has(e, "robot.3 is given but robot.2 is not")) << e;
        e = robotError(
            cfg({"[problem]", "robot = " + PROBLEM_CUBE, "world = world.obj", "start.x = 0", "start.y = 0"}));
        EXPECT_TRUE(has(e, "problem.cfg:2:") && has(e, "single-body problem")) << e;
    }

    TEST_F(RobotProblemFiles, EachReaderSendsTheOtherKindOfFileAway)
    {
        const std::string robot = cfg(armLines("0 0"));
        const Problem asRobot = readProblem(robot);
        ASSERT_TRUE(asRobot.robot);
        EXPECT_FALSE(asRobot.rigidBody);
        EXPECT_EQ(asRobot.robot->start, (std::vector<double>{0.0, 0.0}));
        try
        {
            readProblemConfig(robot);
            ADD_FAILURE() << "a robot problem read as a single body";
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find("problem.cfg:2: 'robot.urdf' makes this a robot problem"),
                      std::string::npos)
                << e.what();
        }
        const std::string single = cfg(
            {"[problem]", "robot = " + PROBLEM_CUBE, "world = world.obj", "start.x = 0", "start.y = 0"}, "single.cfg");
        const Problem asSingle = readProblem(single);
        ASSERT_TRUE(asSingle.rigidBody);
        EXPECT_FALSE(asSingle.robot);
        EXPECT_NE(asSingle.rigidBody->robot.find("cube.obj"), std::string::npos);
        EXPECT_NO_THROW(readProblemConfig(single));
    }
}  // namespace meshgap

namespace meshgap
{
    namespace
    {
        /** \brief The one-link robot of \e config against the single-body scene of the same meshes (Scene::fromMeshes,
            the checker's): the same exact signed distance, collision verdict and witnesses at \e count poses between
            the start and the goal, nudged by \e seed's random steps. */
        void expectOneLinkRobotAnswersAsTheScene(const ProblemConfig &config, int count, unsigned seed)
        {
            const RobotProblem problem = rigidBodyProblem(config);
            ASSERT_EQ(problem.robot->links().size(), 1u);
            ASSERT_EQ(problem.robot->dimension(), config.planar ? 3u : 7u);
            EXPECT_EQ(problem.planar, config.planar);
            EXPECT_TRUE(problem.robot->selfPairs().empty());
            // The start and goal states place the body where the cfg's poses do.
            const RigidSpace space = config.planar ? RigidSpace::SE2 : RigidSpace::SE3;
            EXPECT_TRUE(rigidPose(space, problem.start.data()).isApprox(config.start, 1e-12));
            ASSERT_TRUE(problem.goal && config.goal);
            EXPECT_TRUE(rigidPose(space, problem.goal->data()).isApprox(*config.goal, 1e-12));
            const ScenePtr scene =
                Scene::fromMeshes(loadRobotMesh(config.robot, config.planar), loadMesh(config.world));
            const RobotScene robot(problem.robot, problem.obstacles);
            ASSERT_EQ(robot.obstacles().size(), scene->obstacles().size());
            std::mt19937 rng(seed);
            std::normal_distribution<double> noise(0.0, 0.3);
            const double size = scene->robot().bvh().nodes()[0].radius;
            RobotWarmStart warm;
            int colliding = 0;
            for (int i = 0; i < count; ++i)
            {
                std::vector<double> q(problem.start.size());
                for (std::size_t k = 0; k < q.size(); ++k)
                    q[k] = problem.start[k] + (double(i) / (count - 1)) * ((*problem.goal)[k] - problem.start[k]) +
                           noise(rng) * (k < (config.planar ? 2u : 3u) ? size : 1.0);
                if (!config.planar)
                    Eigen::Map<Eigen::Vector4d>(q.data() + 3).normalize();
                SceneResult s;
                scene->distance(rigidPose(space, q.data()), SceneRequest(), s);
                RobotResult r;
                robot.distance(q.data(), q.size(), RobotRequest(), warm, r);
                EXPECT_EQ(r.inCollision, s.inCollision) << "pose " << i;
                EXPECT_NEAR(r.distance, s.distance, 1e-9 * size) << "pose " << i;
                EXPECT_TRUE(r.certified) << "pose " << i;
                if (!s.inCollision)
                {
                    EXPECT_NEAR((r.onA - r.onB).norm(), s.distance, 1e-9 * size) << "pose " << i;
                }
                colliding += s.inCollision ? 1 : 0;
            }
            EXPECT_LT(colliding, count);
        }
    }  // namespace

    TEST(RigidBodyProblem, ASingleBodyIsARobotOfOneLinkWithTheScenesAnswers)
    {
        const ProblemConfig config =
            readProblemConfig(std::string(MESHGAP_SOURCE_DIR) + "/maps/slotted_wall/slotted_wall.cfg");
        expectOneLinkRobotAnswersAsTheScene(config, 60, 1);
        const RobotProblem problem = readAnyRobotProblem(config.file);
        EXPECT_EQ(problem.robot->description(), "one body in SE(3)");
        EXPECT_EQ(problem.name, "slotted_wall");
        ASSERT_TRUE(problem.volume);
        EXPECT_TRUE(problem.volume->isApprox(*config.volume));
        EXPECT_EQ(problem.benchmark, config.benchmark);
    }

    TEST_F(RobotProblemFiles, APlanarSingleBodyIsARobotOfOneLinkInSE2)
    {
        const std::string path =
            cfg({"[problem]", "robot = " + PROBLEM_CUBE, "world = world.obj", "start.x = -0.5", "start.y = 0.5",
                 "start.theta = 0.3", "goal.x = 0.5", "goal.y = 0.5", "goal.theta = 2.5", "volume.min.x = -5",
                 "volume.min.y = -5", "volume.max.x = 5", "volume.max.y = 5"},
                "planar.cfg");
        const ProblemConfig config = readProblemConfig(path);
        ASSERT_TRUE(config.planar);
        expectOneLinkRobotAnswersAsTheScene(config, 80, 2);
        EXPECT_EQ(readAnyRobotProblem(path).robot->description(), "one body in SE(2)");
        // A control problem's body is a robot of one link too: its pose, the geometric part of the car's state.
        const std::string car = cfg({"[problem]", "robot = " + PROBLEM_CUBE, "world = world.obj", "start.x = 0",
                                     "start.y = 0.5", "start.theta = 0.1", "control = kinematic_car"},
                                    "car.cfg");
        const RobotProblem asCar = readAnyRobotProblem(car);
        EXPECT_EQ(asCar.robot->description(), "one body in SE(2)");
        ASSERT_EQ(asCar.start.size(), 3u);
        EXPECT_NEAR(asCar.start[1], 0.5, 1e-15);
        EXPECT_NEAR(asCar.start[2], 0.1, 1e-15);
    }
}  // namespace meshgap
