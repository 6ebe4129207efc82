// The URDF kinematic tree: forward kinematics against transforms composed by hand, the links' geometry, the pairs
// checked, package:// resolution, the SRDF, and one clear error for each kind of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/PackagePath.h"
#include "meshgap/robot/Primitives.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "TestMeshes.h"

namespace fs = std::filesystem;

namespace meshgap
{
    namespace
    {
        const std::string URDF_RESOURCES = std::string(MESHGAP_TEST_RESOURCES_DIR) + "/robot";
        const std::string TREE = URDF_RESOURCES + "/meshgap_test_description/urdf/tree.urdf";

        // Rotations written out element by element, and the Rodrigues formula, independent of Eigen's geometry.
        Eigen::Matrix3d rotX(double a)
        {
            Eigen::Matrix3d R;
            R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
            return R;
        }
        Eigen::Matrix3d rotY(double a)
        {
            Eigen::Matrix3d R;
            R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
            return R;
        }
        Eigen::Matrix3d rotZ(double a)
        {
            Eigen::Matrix3d R;
            R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
            return R;
        }
        /** \brief URDF's rpy: roll about x, then pitch about y, then yaw about z, all fixed axes. */
        Eigen::Matrix3d rpyMatrix(double r, double p, double y)
        {
            return rotZ(y) * rotY(p) * rotX(r);
        }
        Eigen::Matrix3d rotAxis(Eigen::Vector3d u, double a)
        {
            u /= std::sqrt(u.dot(u));
            Eigen::Matrix3d K;
            K << 0, -u.z(), u.y(), u.z(), 0, -u.x(), -u.y(), u.x(), 0;
            return Eigen::Matrix3d::Identity() + std::sin(a) * K + (1 - std::cos(a)) * K * K;
        }
        /** \brief The homogeneous matrix of rotation R then translation p. */
        Eigen::Matrix4d homogeneous(const Eigen::Matrix3d &R, double x, double y, double z)
        {
            Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
            M.block<3, 3>(0, 0) = R;
            M(0, 3) = x;
            M(1, 3) = y;
            M(2, 3) = z;
            return M;
        }
        Eigen::Matrix4d homogeneous(double x, double y, double z)
        {
            return homogeneous(Eigen::Matrix3d::Identity(), x, y, z);
        }
        Eigen::Matrix4d rotationOnly(const Eigen::Matrix3d &rotation)
        {
            return homogeneous(rotation, 0, 0, 0);
        }

        /** \brief tree.urdf's frames at q = (wrist_roll, shoulder, extend, spin, tilt), composed by hand from the
            file's numbers: origin (translation, then rpy), then the joint's motion. */
        std::map<std::string, Eigen::Matrix4d> handFrames(const std::vector<double> &q)
        {
            const double wr = q[0], sh = q[1], ex = q[2], sp = q[3], ti = q[4];
            std::map<std::string, Eigen::Matrix4d> X;
            X["base"] = Eigen::Matrix4d::Identity();
            X["arm"] = homogeneous(rotZ(0.5), 0, 0, 0.1) * rotationOnly(rotZ(sh));
            X["slider"] = X["arm"] * homogeneous(rotX(0.3), 0.05, 0, 0.45) * homogeneous(ex, 0, 0);
            X["wrist"] = X["slider"] * homogeneous(rotY(0.4), 0.2, 0, 0.05) *
                         rotationOnly(rotAxis(Eigen::Vector3d(1, 0, 1), wr));
            X["tool"] = X["wrist"] * homogeneous(rpyMatrix(0.1, 0.2, 0.3), 0, 0, 0.06);
            X["flange"] = X["tool"] * homogeneous(0.02, 0, 0);
            X["finger"] =
                X["flange"] * homogeneous(0, 0.05, 0.02) * rotationOnly(rotX(-0.5 * sh + 0.2));  // mimics shoulder
            X["follower"] =
                X["arm"] * homogeneous(0, -0.1, 0) * homogeneous(0, 0, 2 * ex + 0.01);  // mimics extend; unit axis
            X["camera"] = homogeneous(rotZ(1.0), 0.15, 0.1, 0.1);
            X["spinner"] = X["camera"] * homogeneous(0, 0, 0.03) * rotationOnly(rotZ(sp));
            X["tip"] = X["spinner"] * homogeneous(rotY(-0.2), 0.03, 0, 0) * rotationOnly(rotY(ti));
            return X;
        }

        std::string writeFile(const std::string &name, const std::string &text)
        {
            const fs::path folder = fs::temp_directory_path() / "meshgap_robot_test";
            fs::create_directories(folder);
            const std::string path = (folder / name).string();
            std::ofstream(path) << text;
            return path;
        }

        /** \brief The message of what \e f throws (empty when it throws nothing or something else). */
        template <typename F>
        std::string errorOf(F f)
        {
            try
            {
                f();
            }
            catch (const Exception &e)
            {
                return e.what();
            }
            return "";
        }
    }  // namespace

    TEST(UrdfRobot, ForwardKinematicsMatchesTransformsComposedByHand)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE);
        ASSERT_EQ(robot->dimension(), 5u);
        // The state follows the file's order of the movable joints that mimic none.
        std::vector<std::string> names;
        for (std::size_t k : robot->variables())
            names.push_back(robot->joints()[k].name);
        EXPECT_EQ(names, (std::vector<std::string>{"wrist_roll", "shoulder", "extend", "spin", "tilt"}));
        EXPECT_EQ(robot->frames().size(), 11u);

        std::mt19937 rng(7);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        double worst = 0.0;
        for (int trial = 0; trial < 200; ++trial)
        {
            // Anywhere within each joint's limits (framePoses() refuses a state beyond them), [-3, 3] when unbounded.
            std::vector<double> q;
            for (std::size_t i = 0; i < robot->dimension(); ++i)
            {
                const double lo = std::isfinite(robot->stateLower(i)) ? robot->stateLower(i) : -3.0;
                const double hi = std::isfinite(robot->stateUpper(i)) ? robot->stateUpper(i) : 3.0;
                q.push_back(lo + (hi - lo) * unit(rng));
            }
            std::vector<Eigen::Isometry3d> frames;
            robot->framePoses(q.data(), q.size(), frames);
            const auto hand = handFrames(q);
            ASSERT_EQ(hand.size(), frames.size());
            for (std::size_t f = 0; f < frames.size(); ++f)
            {
                const std::string &name = robot->frames()[f].name;
                ASSERT_EQ(hand.count(name), 1u) << name;
                worst = std::max(worst, (frames[f].matrix() - hand.at(name)).cwiseAbs().maxCoeff());
            }
            const std::vector<Eigen::Isometry3d> links = robot->linkPoses(q);
            for (std::size_t i = 0; i < links.size(); ++i)
                EXPECT_LT((links[i].matrix() - hand.at(robot->links()[i].name)).cwiseAbs().maxCoeff(), 1e-12);
        }
        EXPECT_LT(worst, 1e-12);
    }

    TEST(UrdfRobot, FloatingBasePutsTheRootAtTheStatesPose)
    {
        UrdfOptions options;
        options.floatingBase = true;
        const UrdfRobotPtr robot = UrdfRobot::load(TREE, options);
        ASSERT_EQ(robot->dimension(), 12u);
        EXPECT_EQ(robot->jointOffset(), 7u);
        // A half turn about z (quaternion (0, 0, 1, 0) scaled: the state's quaternion is normalised).
        const std::vector<double> q = {1, 2, 3, 0, 0, 2, 0, 0.1, 0.2, 0.05, 0.3, 0.4};
        std::vector<Eigen::Isometry3d> frames;
        robot->framePoses(q.data(), q.size(), frames);
        const Eigen::Matrix4d base = homogeneous(rotZ(M_PI), 1, 2, 3);
        const auto hand = handFrames({0.1, 0.2, 0.05, 0.3, 0.4});
        for (std::size_t f = 0; f < frames.size(); ++f)
            EXPECT_LT((frames[f].matrix() - base * hand.at(robot->frames()[f].name)).cwiseAbs().maxCoeff(), 1e-12)
                << robot->frames()[f].name;
    }

    TEST(UrdfRobot, LinksCarryTheirCollisionGeometryElseTheirVisualOne)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE);
        // Ten links with geometry; "tool" is a frame only.
        EXPECT_EQ(robot->links().size(), 10u);
        EXPECT_EQ(robot->findLink("tool"), RobotModel::NONE);
        EXPECT_NE(robot->findFrame("tool"), RobotModel::NONE);
        auto bounds = [&](const std::string &name) { return robot->links()[robot->findLink(name)].body->surface().bounds(); };
        // arm: a cylinder (z from 0 to 0.5) and a box on top (to 0.525); its visual unit sphere is not used.
        EXPECT_NEAR(bounds("arm").min().z(), 0.0, 1e-12);
        EXPECT_NEAR(bounds("arm").max().z(), 0.525, 1e-12);
        // x: the box's corner, turned by 0.3 about z, reaches past the cylinder (radius 0.05).
        EXPECT_NEAR(bounds("arm").max().x(), 0.05 * (std::cos(0.3) + std::sin(0.3)), 1e-12);
        EXPECT_NEAR(bounds("arm").min().y(), -0.05 * (std::cos(0.3) + std::sin(0.3)), 1e-12);
        // base: the box raised by its origin.
        EXPECT_TRUE(bounds("base").min().isApprox(Eigen::Vector3d(-0.2, -0.15, 0.0), 1e-12));
        EXPECT_TRUE(bounds("base").max().isApprox(Eigen::Vector3d(0.2, 0.15, 0.1), 1e-12));
        // flange: the unit cube from package://, scaled by 0.1, then moved by the origin.
        EXPECT_TRUE(bounds("flange").min().isApprox(Eigen::Vector3d::Constant(-0.5), 1e-12));
        EXPECT_TRUE(bounds("flange").max().isApprox(Eigen::Vector3d::Constant(-0.4), 1e-12));
        // camera: visual only, a sphere of radius 0.02 raised by 0.01 (circumscribed: its poles a little beyond).
        EXPECT_NEAR(bounds("camera").min().z(), -0.01 - sphereExcess(0.02, 32), 1e-12);
        EXPECT_NEAR(bounds("camera").max().z(), 0.03 + sphereExcess(0.02, 32), 1e-12);
        for (const RobotLink &link : robot->links())
            EXPECT_TRUE(link.body->isClosed()) << link.name;
    }

    TEST(UrdfRobot, AdjacentLinksAreAllowedAndTheSrdfAllowsMore)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE);
        auto allowed = [&](const std::string &a, const std::string &b)
        { return robot->isAllowed(robot->findLink(a), robot->findLink(b)); };
        // Joined by a joint; flange-wrist through the frame "tool", which has no geometry.
        for (const auto &[a, b] : std::vector<std::pair<std::string, std::string>>{
                 {"base", "arm"}, {"arm", "slider"}, {"slider", "wrist"}, {"wrist", "flange"}, {"flange", "finger"},
                 {"arm", "follower"}, {"base", "camera"}, {"camera", "spinner"}, {"spinner", "tip"}})
            EXPECT_TRUE(allowed(a, b)) << a << " " << b;
        EXPECT_FALSE(allowed("base", "slider"));
        EXPECT_FALSE(allowed("wrist", "finger"));
        const std::size_t links = robot->links().size();
        EXPECT_EQ(robot->selfPairs().size(), links * (links - 1) / 2 - 9);

        const std::string srdf = writeFile("tree.srdf", "<robot name=\"tree\">\n"
                                                        "  <disable_collisions link1=\"base\" link2=\"slider\" "
                                                        "reason=\"Never\"/>\n"
                                                        "  <disable_collisions link1=\"tool\" link2=\"finger\"/>\n"
                                                        "</robot>\n");
        readSrdf(*robot, srdf);
        EXPECT_TRUE(allowed("base", "slider"));
        EXPECT_FALSE(allowed("wrist", "finger"));  // "tool" has no geometry: naming it allows nothing
        EXPECT_EQ(robot->selfPairs().size(), links * (links - 1) / 2 - 10);
    }

    TEST(UrdfRobot, PayloadFollowsItsLinkAndMayTouchOnlyItsParent)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE);
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = rotY(0.7);
        X.translation() = Eigen::Vector3d(0.01, 0.02, 0.03);
        // On "tool" (no geometry): its parent link is "wrist", the nearest ancestor with geometry.
        const std::size_t payload = robot->attach("part", test::box(0.02, 0.01, 0.03), "tool", X);
        EXPECT_TRUE(robot->links()[payload].payload);
        EXPECT_TRUE(robot->isAllowed(payload, robot->findLink("wrist")));
        EXPECT_FALSE(robot->isAllowed(payload, robot->findLink("flange")));
        EXPECT_FALSE(robot->isAllowed(payload, robot->findLink("arm")));
        const std::vector<double> q = {0.3, -0.2, 0.1, 0.5, 0.6};
        const std::vector<Eigen::Isometry3d> links = robot->linkPoses(q);
        const Eigen::Matrix4d hand = handFrames(q).at("tool") * homogeneous(rotY(0.7), 0.01, 0.02, 0.03);
        EXPECT_LT((links[payload].matrix() - hand).cwiseAbs().maxCoeff(), 1e-12);
        // On a link with geometry: that link.
        const std::size_t second = robot->attach("part2", test::box(0.01, 0.01, 0.01), "arm", X);
        EXPECT_TRUE(robot->isAllowed(second, robot->findLink("arm")));
        EXPECT_FALSE(robot->isAllowed(second, robot->findLink("base")));
        EXPECT_FALSE(robot->isAllowed(second, payload));
    }

    TEST(UrdfRobot, PackageUrisResolveThroughTheSearchPathThenTheDescriptionsFolders)
    {
        const std::string package = URDF_RESOURCES + "/meshgap_test_description";
        const std::string folder = package + "/urdf";
        const std::string cube = "package://meshgap_test_description/meshes/cube.obj";
        // From the URDF's folder and its parents, with no search path.
        EXPECT_EQ(fs::canonical(resolveRobotUri(cube, {}, folder)), fs::canonical(package + "/meshes/cube.obj"));
        // A search path entry holding the package, or being it, comes first.
        const fs::path copy = fs::temp_directory_path() / "meshgap_robot_test" / "share" / "meshgap_test_description";
        fs::create_directories(copy / "meshes");
        fs::copy_file(package + "/meshes/cube.obj", copy / "meshes" / "cube.obj",
                      fs::copy_options::overwrite_existing);
        const std::string install = (fs::temp_directory_path() / "meshgap_robot_test").string();
        EXPECT_EQ(fs::canonical(resolveRobotUri(cube, {install}, folder)), fs::canonical(copy / "meshes" / "cube.obj"));
        EXPECT_EQ(fs::canonical(resolveRobotUri(cube, {copy.string()}, folder)),
                  fs::canonical(copy / "meshes" / "cube.obj"));
        // Relative paths are relative to the description's folder; file:// and absolute paths are themselves.
        EXPECT_EQ(fs::canonical(resolveRobotUri("../meshes/cube.obj", {}, folder)),
                  fs::canonical(package + "/meshes/cube.obj"));
        EXPECT_EQ(resolveRobotUri("file://" + package + "/meshes/cube.obj", {}, "/"), package + "/meshes/cube.obj");
        // An unknown package names itself and the folders searched.
        const std::string message = errorOf([&] { resolveRobotUri("package://no_such_package/a.stl", {}, folder); });
        EXPECT_NE(message.find("no package 'no_such_package'"), std::string::npos) << message;
        EXPECT_NE(message.find(folder), std::string::npos) << message;
    }

    TEST(UrdfRobot, BadInputGetsOneClearErrorEach)
    {
        const std::string head = "<robot name=\"bad\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>";
        auto joint = [](const std::string &name, const std::string &type, const std::string &parent,
                        const std::string &child)
        {
            return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
                   "\"/><child link=\"" + child + "\"/><axis xyz=\"0 0 1\"/>" +
                   "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>";
        };
        auto expectError = [&](const std::string &file, const std::string &text, const std::string &expected)
        {
            const std::string path = writeFile(file, text);
            const std::string message = errorOf([&] { UrdfRobot::load(path); });
            EXPECT_NE(message.find(path), std::string::npos) << message;
            EXPECT_NE(message.find(expected), std::string::npos) << message;
        };
        expectError("cycle.urdf",
                    head + joint("j1", "fixed", "a", "b") + joint("j2", "fixed", "b", "c") +
                        joint("j3", "revolute", "c", "a") + "</robot>",
                    "the joints form a cycle");
        expectError("two_parents.urdf",
                    head + joint("j1", "fixed", "a", "b") + joint("j2", "fixed", "b", "c") +
                        joint("j3", "revolute", "c", "b") + "</robot>",
                    "link 'b' is the child of two joints, 'j1' and 'j3'");
        expectError("screw.urdf", head + joint("j1", "screw", "a", "b") + joint("j2", "fixed", "b", "c") + "</robot>",
                    "joint 'j1' has an unknown type 'screw'");
        expectError("mimic_planar.urdf",
                    head + joint("j1", "planar", "a", "b") +
                        "<joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>"
                        "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j1\"/></joint>"
                        "</robot>",
                    "joint 'j2' mimics 'j1', a planar joint (only a joint of one value is mimicked)");
        expectError("zero_axis.urdf",
                    head + "<joint name=\"j1\" type=\"planar\"><parent link=\"a\"/><child link=\"b\"/>"
                           "<axis xyz=\"0 0 0\"/></joint>" +
                        joint("j2", "fixed", "b", "c") + "</robot>",
                    "joint 'j1': its axis: zero or not finite");
        expectError("two_roots.urdf", head + joint("j1", "fixed", "a", "b") + "</robot>", "several root links");
        expectError("unknown_link.urdf",
                    head + joint("j1", "fixed", "a", "b") + joint("j2", "fixed", "b", "d") + "</robot>",
                    "joint 'j2' names link 'd', which is not defined");
        expectError("mimic.urdf",
                    head + joint("j1", "revolute", "a", "b") +
                        "<joint name=\"j2\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>"
                        "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/><mimic joint=\"j9\"/></joint>"
                        "</robot>",
                    "joint 'j2' mimics 'j9', which is not defined");
        expectError("not_xml.urdf", "<robot name=\"x\"><link name=\"a\">", "cannot read the URDF");

        // A missing mesh names the link and the file it looked for (the package is found beside the resources).
        const std::string missing = URDF_RESOURCES + "/missing_mesh.urdf";
        const std::string message = errorOf([&] { UrdfRobot::load(missing); });
        EXPECT_NE(message.find(missing), std::string::npos) << message;
        EXPECT_NE(message.find("link 'body'"), std::string::npos) << message;
        EXPECT_NE(message.find("no such file"), std::string::npos) << message;
        EXPECT_NE(message.find("no_such_mesh.stl"), std::string::npos) << message;
        EXPECT_NE(errorOf([] { UrdfRobot::load("/no/such/robot.urdf"); }).find("no such file"), std::string::npos);
    }

    TEST(UrdfRobot, BadSrdfStateAndPayloadGetOneClearErrorEach)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(TREE);
        const std::string srdf = writeFile("unknown_link.srdf", "<robot name=\"tree\">\n"
                                                                "  <disable_collisions link1=\"base\" link2=\"arm\"/>\n"
                                                                "  <disable_collisions link1=\"base\" link2=\"elbow\"/>\n"
                                                                "</robot>\n");
        std::string message = errorOf([&] { readSrdf(*robot, srdf); });
        EXPECT_NE(message.find(srdf + ":3"), std::string::npos) << message;
        EXPECT_NE(message.find("link 'elbow', which the robot does not have"), std::string::npos) << message;

        const std::vector<double> state(4, 0.0);
        message = errorOf([&] { robot->linkPoses(state); });
        EXPECT_NE(message.find("a state of 4 numbers, where this robot has 5"), std::string::npos) << message;
        const std::vector<double> nan = {0, 0, std::nan(""), 0, 0};
        message = errorOf([&] { robot->linkPoses(nan); });
        EXPECT_NE(message.find("state number 2 is not finite"), std::string::npos) << message;

        message = errorOf([&] { robot->attach("part", test::box(0.1, 0.1, 0.1), "gripper", Eigen::Isometry3d::Identity()); });
        EXPECT_NE(message.find("payload 'part' attached to 'gripper', which is no link of this robot"),
                  std::string::npos)
            << message;
        message = errorOf([&] { robot->attach("arm", test::box(0.1, 0.1, 0.1), "tool", Eigen::Isometry3d::Identity()); });
        EXPECT_NE(message.find("a link of that name exists already"), std::string::npos) << message;
    }

    // Numbers so large that the frames of valid states are not finite (or far beyond any robot) are refused, naming the
    // joint; the bound itself is accepted. The fuzz inputs in tests/resources/fuzz/urdf/ gave infinite frames before.
    TEST(UrdfRobot, JointNumbersAboveABillionAreRefused)
    {
        const std::string head = "<robot name=\"big\"><link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link><link name=\"b\"/><link name=\"c\"/>"
                                 "<link name=\"d\"/>";
        auto joint = [](const std::string &name, const std::string &parent, const std::string &child,
                        const std::string &xyz, const std::string &limit, const std::string &extra)
        {
            return "<joint name=\"" + name + "\" type=\"prismatic\"><origin xyz=\"" + xyz + "\"/><parent link=\"" +
                   parent + "\"/><child link=\"" + child + "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-" + limit +
                   "\" upper=\"" + limit + "\" effort=\"1\" velocity=\"1\"/>" + extra + "</joint>";
        };
        auto mimic = [](const std::string &of, const std::string &multiplier)
        { return "<mimic joint=\"" + of + "\" multiplier=\"" + multiplier + "\"/>"; };
        auto load = [&](const std::string &xyz, const std::string &limit, const std::string &multiplier)
        {
            const std::string text = head + joint("j1", "a", "b", xyz, limit, "") +
                                     joint("j2", "b", "c", xyz, "1", mimic("j1", multiplier)) +
                                     joint("j3", "c", "d", "0 0 0", "1", mimic("j2", multiplier)) + "</robot>";
            const std::string path = writeFile("big.urdf", text);
            return errorOf([&] { UrdfRobot::load(path); });
        };
        // At the bound: accepted, and the frames at the limits are finite.
        EXPECT_EQ(load("1e9 0 -1e9", "1e9", "3e4"), "");
        const std::string atBound = head + joint("j1", "a", "b", "1e9 0 0", "1e9", "") +
                                    joint("j2", "b", "c", "1e9 0 0", "1e9", "") +
                                    joint("j3", "c", "d", "0 0 0", "1", "") + "</robot>";
        const std::vector<double> state = {1e9, 1e9, 1};
        std::vector<Eigen::Isometry3d> frames;
        UrdfRobot::load(writeFile("big.urdf", atBound))->framePoses(state.data(), state.size(), frames);
        ASSERT_EQ(frames.size(), 4u);
        EXPECT_EQ(frames[3].translation(), Eigen::Vector3d(2e9, 0, 2e9 + 1));  // origins along x, motion along z
        for (const Eigen::Isometry3d &X : frames)
            EXPECT_TRUE(X.matrix().allFinite());
        // Beyond 1e12 the XML check refuses the number as written; between 1e9 and 1e12 the joint check does.
        const std::string beyond = load("1e308 0 0", "1", "1");
        EXPECT_NE(beyond.find("joint 'j1': <origin xyz=\"1e308 0 0\">: xyz has 1e308, beyond 1e12"), std::string::npos)
            << beyond;
        EXPECT_NE(load("0 -2e9 0", "1", "1").find("joint 'j1': the origin's coordinate -2e+09"), std::string::npos);
        const std::string limit = load("0 0 0", "1e300", "1");
        EXPECT_NE(limit.find("joint 'j1'"), std::string::npos) << limit;
        EXPECT_NE(limit.find("1e300, beyond 1e12"), std::string::npos) << limit;
        EXPECT_NE(load("0 0 0", "2e9", "1").find("joint 'j1': the limit -2e+09"), std::string::npos);
        // j2 = 1e5 j1, j3 = 1e5 j2 = 1e10 j1: the composed multiplier is refused.
        EXPECT_NE(load("0 0 0", "1", "1e5").find("joint 'j3': the mimic multiplier (along its chain of mimic joints) "
                                                 "1e+10"),
                  std::string::npos);
    }

    // tinyxml2 keeps an unknown entity in a name ("&nt") where urdfdom changes it, so the two readers saw different
    // joints (a null joint dereferenced; tests/resources/fuzz/urdf/unknown_entity_in_joint_name.urdf): refused.
    TEST(UrdfRobot, NamesTheXmlReadersReadDifferentlyAreRefused)
    {
        const std::string tail = "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"
                                 "</joint></robot>";
        const std::string path = writeFile("entity.urdf", "<robot name=\"e\"><link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link><link name=\"b\"/>"
                                                          "<joint name=\"j&nt\" type=\"revolute\"><parent link=\"a\"/>"
                                                          "<child link=\"b\"/>" + tail);
        const std::string message = errorOf([&] { UrdfRobot::load(path); });
        EXPECT_NE(message.find(path + ": urdfdom reads joint 'j&nt' differently"), std::string::npos) << message;
        // A known entity is read alike by both.
        const std::string known =
            writeFile("entity.urdf", "<robot name=\"e\"><link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link><link name=\"b&amp;c\"/><joint "
                                     "name=\"j&amp;k\" type=\"revolute\"><parent link=\"a\"/>"
                                     "<child link=\"b&amp;c\"/>" + tail);
        const UrdfRobotPtr robot = UrdfRobot::load(known);
        ASSERT_EQ(robot->joints().size(), 1u);
        EXPECT_EQ(robot->joints()[0].name, "j&k");
        EXPECT_NE(robot->findFrame("b&c"), RobotModel::NONE);
    }

    // An axis whose norm overflows ("1 0 1e300") or underflows ("1e-200 0 0") still has a direction; the plain
    // normalisation made the first the zero vector (tests/resources/fuzz/urdf/axis_norm_overflow.urdf).
    TEST(UrdfRobot, AxesOfHugeOrTinyLengthKeepTheirDirection)
    {
        for (const auto &[xyz, unit] : {std::make_pair(std::string("1 0 1e300"), Eigen::Vector3d(0, 0, 1)),
                                        std::make_pair(std::string("1e-200 0 0"), Eigen::Vector3d(1, 0, 0)),
                                        std::make_pair(std::string("3e-170 0 4e-170"), Eigen::Vector3d(0.6, 0, 0.8))})
        {
            const std::string path = writeFile("axis.urdf", "<robot name=\"x\"><link name=\"a\"><collision><geometry><box size=\"1 1 1\"/></geometry></collision></link><link name=\"b\"/>"
                                                            "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/>"
                                                            "<child link=\"b\"/><axis xyz=\"" +
                                                                xyz + "\"/></joint></robot>");
            const UrdfRobotPtr robot = UrdfRobot::load(path);
            EXPECT_LT((robot->joints()[0].axis - unit).norm(), 1e-15) << xyz;
        }
    }
}  // namespace meshgap
