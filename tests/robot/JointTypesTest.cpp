// Joint types, one class each (src/robot/joints/): every type's motion against transforms composed by hand, a URDF
// with planar and floating joints against its link poses composed by hand, the Jacobian of every kind of robot
// against central finite differences of its frame poses, the clearance gradient of the planar and floating robot
// against finite differences of its distance, and RRTConnect with certified motions planning it densely free.
#include <gtest/gtest.h>

#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <map>
#include <random>

#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/JointGradient.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "robot/TestTree.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace meshgap
{
    namespace
    {
        Eigen::Matrix4d T(double x, double y, double z)
        {
            Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
            m.block<3, 1>(0, 3) = Eigen::Vector3d(x, y, z);
            return m;
        }

        Eigen::Matrix4d R(const Eigen::Matrix3d &r)
        {
            Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
            m.block<3, 3>(0, 0) = r;
            return m;
        }

        Eigen::Matrix4d R(const Eigen::Vector3d &axis, double angle)
        {
            return R(Eigen::AngleAxisd(angle, axis).toRotationMatrix());
        }

        /** \brief URDF's rpy: about x, then y, then z, all fixed axes. */
        Eigen::Matrix4d rpy(double r, double p, double y)
        {
            return R(Eigen::Vector3d::UnitZ(), y) * R(Eigen::Vector3d::UnitY(), p) * R(Eigen::Vector3d::UnitX(), r);
        }

        /** \brief The rotation of the quaternion (qx, qy, qz, qw), normalised. */
        Eigen::Matrix4d Q(double qx, double qy, double qz, double qw)
        {
            return R(Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix());
        }

        double gap(const Eigen::Isometry3d &X, const Eigen::Matrix4d &hand)
        {
            return (X.matrix() - hand).cwiseAbs().maxCoeff();
        }

        /** \brief A random state of mobile.urdf: positions within 1.5, yaws and the shoulder within their range, a
            quaternion of any length from 0.5 to 2. */
        std::vector<double> mobileState(std::mt19937 &rng)
        {
            std::uniform_real_distribution<double> u(-1.0, 1.0);
            std::normal_distribution<double> n;
            const Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
            const double length = 1.25 + 0.75 * u(rng), s = length / q.norm();
            return {1.5 * u(rng), 1.5 * u(rng), M_PI * u(rng), u(rng),  // drive, shoulder
                    1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng), s * q.x(), s * q.y(), s * q.z(), s * q.w(),  // fly
                    1.5 * u(rng), 1.5 * u(rng), M_PI * u(rng)};  // wall
        }
    }  // namespace

    TEST(JointTypes, EveryTypeMovesAsComposedByHand)
    {
        EXPECT_EQ(jointTypeNames(), "continuous, fixed, floating, planar, prismatic, revolute");
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(-2.0, 2.0);
        const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), z = Eigen::Vector3d::UnitZ();
        for (int trial = 0; trial < 50; ++trial)
        {
            const Eigen::Vector3d a = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
            JointSpec spec;
            spec.axis = 3.0 * a;  // normalised by the types that need an axis
            spec.hasLimits = true;
            spec.lower = -2.0;
            spec.upper = 2.0;
            const double q = u(rng), v[3] = {u(rng), u(rng), u(rng)};
            const double f[7] = {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng), 0.5 + u(rng)};
            EXPECT_LT(gap(makeJoint("revolute", spec)->pose(&q), R(a, q)), 1e-14);
            EXPECT_LT(gap(makeJoint("continuous", spec)->pose(&q), R(a, q)), 1e-14);
            EXPECT_LT(gap(makeJoint("prismatic", spec)->pose(&q), T(q * a.x(), q * a.y(), q * a.z())), 1e-14);
            EXPECT_EQ(gap(makeJoint("fixed", spec)->pose(nullptr), Eigen::Matrix4d::Identity()), 0.0);
            EXPECT_LT(gap(makeJoint("floating", spec)->pose(f), T(f[0], f[1], f[2]) * Q(f[3], f[4], f[5], f[6])),
                      1e-14);
            // Planar: about z, the plane is the xy plane (an SE(2) pose); about x, u = y and v = z; about -z,
            // u = x and v = -y.
            spec.axis = z;
            EXPECT_LT(gap(makeJoint("planar", spec)->pose(v), T(v[0], v[1], 0) * R(z, v[2])), 1e-14);
            EXPECT_LT(gap(makeJoint("planar", spec)->pose(v), poseFromSE2(v).matrix()), 1e-14);
            spec.axis = x;
            EXPECT_LT(gap(makeJoint("planar", spec)->pose(v), T(0, v[0], v[1]) * R(x, v[2])), 1e-14);
            spec.axis = -z;
            EXPECT_LT(gap(makeJoint("planar", spec)->pose(v), T(v[0], -v[1], 0) * R(-z, v[2])), 1e-14);
            // Any axis: the origin moves in the plane normal to it, as far as (x, y), and turns about it.
            spec.axis = a;
            const Eigen::Isometry3d X = makeJoint("planar", spec)->pose(v);
            EXPECT_NEAR(X.translation().dot(a), 0.0, 1e-14);
            EXPECT_NEAR(X.translation().norm(), std::hypot(v[0], v[1]), 1e-14);
            EXPECT_LT((X.linear() - R(a, v[2]).block<3, 3>(0, 0)).cwiseAbs().maxCoeff(), 1e-14);
        }
        // Sizes, spaces, limits; a type needing an axis refuses a zero one; an unknown type names the known ones.
        EXPECT_EQ(makeJoint("planar")->size(), 3u);
        EXPECT_EQ(makeJoint("floating")->size(), 7u);
        EXPECT_EQ(makeJoint("floating")->space(), JointSpace::SE3);
        EXPECT_EQ(makeJoint("floating")->neutral(6), 1.0);
        EXPECT_EQ(makeJoint("planar")->valueName(2), "theta");
        EXPECT_TRUE(std::isinf(makeJoint("planar")->lower(0)));
        JointSpec zero;
        zero.axis = Eigen::Vector3d::Zero();
        EXPECT_THROW(makeJoint("planar", zero), Exception);
        EXPECT_NO_THROW(makeJoint("floating", zero));
        try
        {
            makeJoint("screw");
            ADD_FAILURE() << "a screw joint was made";
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find("unknown type 'screw' (continuous, fixed, floating, planar"),
                      std::string::npos)
                << e.what();
        }
    }

    TEST(JointTypes, PlanarAndFloatingUrdfJointsPlaceTheirLinksAsComposedByHand)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(test::MOBILE_URDF);
        ASSERT_EQ(robot->dimension(), 14u);
        std::vector<std::string> names;
        for (std::size_t i = 0; i < robot->dimension(); ++i)
            names.push_back(robot->stateName(i));
        EXPECT_EQ(names, (std::vector<std::string>{"drive.x", "drive.y", "drive.theta", "shoulder", "fly.x", "fly.y",
                                                    "fly.z", "fly.qx", "fly.qy", "fly.qz", "fly.qw", "wall.x",
                                                    "wall.y", "wall.theta"}));
        EXPECT_EQ(robot->variables(), (std::vector<std::size_t>{0, 0, 0, 1, 2, 2, 2, 2, 2, 2, 2, 3, 3, 3}));
        EXPECT_TRUE(robot->movesFree());
        EXPECT_EQ(robot->stateLower(3), -1.0);
        EXPECT_TRUE(std::isinf(robot->stateUpper(0)));

        std::mt19937 rng(11);
        double worst = 0.0;
        for (int trial = 0; trial < 100; ++trial)
        {
            const std::vector<double> q = mobileState(rng);
            std::vector<Eigen::Isometry3d> frames, links;
            robot->linkPoses(q.data(), q.size(), frames, links);
            const Eigen::Matrix4d base = T(0, 0, 0.05) * R(Eigen::Vector3d::UnitZ(), 0.3) * T(q[0], q[1], 0) *
                                         R(Eigen::Vector3d::UnitZ(), q[2]);
            const Eigen::Matrix4d arm = base * T(0.1, 0, 0.1) * R(Eigen::Vector3d::UnitY(), q[3]);
            const Eigen::Matrix4d drone =
                T(0, 0, 1) * rpy(0.1, 0.2, 0.3) * T(q[4], q[5], q[6]) * Q(q[7], q[8], q[9], q[10]);
            const Eigen::Matrix4d slider = T(1.5, 0, 0.5) * T(0, q[11], q[12]) * R(Eigen::Vector3d::UnitX(), q[13]);
            const std::map<std::string, Eigen::Matrix4d> hand = {
                {"base", base}, {"arm", arm}, {"drone", drone}, {"slider", slider}};
            ASSERT_EQ(links.size(), 4u);
            for (std::size_t i = 0; i < links.size(); ++i)
                worst = std::max(worst, gap(links[i], hand.at(robot->links()[i].name)));
        }
        EXPECT_LT(worst, 1e-12);

        // The OMPL space: SE(2), the shoulder, SE(3), SE(2), positions within the problem's bounds.
        ob::RealVectorBounds bounds(3);
        bounds.setLow(-2.0);
        bounds.setHigh(2.0);
        const ob::StateSpacePtr space = robotStateSpace(*robot, bounds);
        const auto *compound = space->as<ob::CompoundStateSpace>();
        ASSERT_EQ(compound->getSubspaceCount(), 4u);
        EXPECT_EQ(compound->getSubspace(0)->getType(), ob::STATE_SPACE_SE2);
        EXPECT_EQ(compound->getSubspace(1)->getType(), ob::STATE_SPACE_REAL_VECTOR);
        EXPECT_EQ(compound->getSubspace(2)->getType(), ob::STATE_SPACE_SE3);
        EXPECT_EQ(compound->getSubspace(3)->getType(), ob::STATE_SPACE_SE2);
        const std::vector<double> values = {0.5, -0.5, 1.0, 0.2, 0.1, 0.2, 0.3, 0, 0, 0.6, 0.8, -1.0, 1.0, -0.5};
        ob::State *state = space->allocState();
        robotStateFromVector(*space, values, state);
        std::vector<double> back;
        robotStateToVector(*space, state, back);
        EXPECT_EQ(back, values);
        space->freeState(state);
    }

    TEST(JointTypes, JacobiansMatchFiniteDifferencesOfTheFramePoses)
    {
        UrdfOptions floating;
        floating.floatingBase = true;
        const std::vector<RobotModelConstPtr> robots = {
            UrdfRobot::load(test::MOBILE_URDF), UrdfRobot::load(test::TREE_URDF, floating),
            std::make_shared<MultiBodyRobot>(std::vector<MultiBodyRobot::Part>{
                {"flat", Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE2},
                {"free", Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE3}})};
        std::mt19937 rng(4);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (const RobotModelConstPtr &robot : robots)
        {
            double worst = 0.0;
            for (int trial = 0; trial < 30; ++trial)
            {
                // Within every limit; quaternions of length 0.5 to 2 (the Jacobian sees through the normalisation).
                std::vector<double> q(robot->dimension());
                for (std::size_t i = 0; i < q.size(); ++i)
                {
                    const double lo = std::max(robot->stateLower(i), -1.5), hi = std::min(robot->stateUpper(i), 1.5);
                    q[i] = 0.5 * (lo + hi) + 0.45 * (hi - lo) * u(rng);
                }
                std::vector<Eigen::Isometry3d> frames;
                robot->framePoses(q.data(), q.size(), frames);
                for (std::size_t f = 0; f < robot->frames().size(); ++f)
                {
                    const Eigen::Vector3d local(u(rng), u(rng), u(rng));
                    const Eigen::Matrix3Xd J = pointJacobian(*robot, q, frames, f, frames[f] * local);
                    const double h = 1e-6;
                    for (std::size_t k = 0; k < q.size(); ++k)
                    {
                        std::vector<double> plus = q, minus = q;
                        plus[k] += h;
                        minus[k] -= h;
                        std::vector<Eigen::Isometry3d> fp, fm;
                        robot->framePoses(plus.data(), plus.size(), fp);
                        robot->framePoses(minus.data(), minus.size(), fm);
                        const Eigen::Vector3d fd = (fp[f] * local - fm[f] * local) / (2 * h);
                        worst = std::max(worst, (fd - J.col(static_cast<Eigen::Index>(k))).norm());
                    }
                }
            }
            EXPECT_LT(worst, 1e-6) << robot->frames().back().name;
        }
    }

    TEST(JointTypes, ClearanceGradientOfPlanarAndFloatingJointsMatchesFiniteDifferences)
    {
        const UrdfRobotPtr robot = UrdfRobot::load(test::MOBILE_URDF);
        const std::vector<BodyConstPtr> obstacles = {
            Body::build(test::transformed(test::box(0.2, 0.2, 1.0), test::translation(0.0, 0.0, 1.0))),
            Body::build(test::transformed(test::icosphere(0.3, 2), test::translation(1.5, 0.5, 0.5)))};
        const RobotScene scene(robot, obstacles);
        std::mt19937 rng(8);
        RobotRequest every;
        every.everyPair = true;
        std::size_t free = 0, matching = 0;
        const int trials = test::scaled(200, 50);  // fewer under the sanitizers, the threshold below in proportion
        for (int trial = 0; trial < trials; ++trial)
        {
            const std::vector<double> q = mobileState(rng);
            RobotResult r;
            scene.distance(q, RobotRequest(), r);
            std::vector<Eigen::Isometry3d> frames;
            robot->framePoses(q.data(), q.size(), frames);
            Eigen::VectorXd g;
            if (!clearanceGradient(*robot, scene, q, frames, r, g) || r.distance < 1e-4)
                continue;
            ++free;
            const std::size_t pair = r.selfPair ? [&] {
                for (std::size_t p = 0; p < scene.selfPairs().size(); ++p)
                    if (scene.selfPairs()[p] == LinkPair(r.link, r.other))
                        return scene.links().size() + p;
                return std::size_t(0);
            }() : r.link;
            const double h = 1e-6;
            Eigen::VectorXd fd(g.size());
            for (Eigen::Index k = 0; k < g.size(); ++k)
            {
                std::vector<double> plus = q, minus = q;
                plus[static_cast<std::size_t>(k)] += h;
                minus[static_cast<std::size_t>(k)] -= h;
                RobotResult rp, rm;
                scene.distance(plus, every, rp);
                scene.distance(minus, every, rm);
                fd[k] = (rp.pairs[pair].distance - rm.pairs[pair].distance) / (2 * h);
            }
            matching += (fd - g).norm() <= 1e-4 * std::max(1.0, g.norm()) ? 1 : 0;
        }
        test::Note() << matching << " of " << free << " free states match finite differences";
        EXPECT_GT(free, static_cast<std::size_t>(trials) / 5);
        // A few states sit where the closest features switch (the distance has a kink there).
        EXPECT_GE(matching, free * 9 / 10);
    }

    TEST(JointTypes, RrtConnectPlansPlanarAndFloatingJointsDenselyFree)
    {
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        const UrdfRobotPtr robot = UrdfRobot::load(test::MOBILE_URDF);
        // A wall across the floor at x = 0 with a gap at y > 0.6: the base and its arm drive around it, the drone
        // flies over or around it, the slider keeps out of it.
        const auto scene = std::make_shared<RobotScene>(
            robot, std::vector<BodyConstPtr>{Body::build(
                       test::transformed(test::box(0.05, 1.1, 0.4), test::translation(0.0, -0.5, 0.4)))});
        ob::RealVectorBounds bounds(3);
        bounds.setLow(-1.5);
        bounds.setHigh(1.5);
        og::SimpleSetup setup(robotStateSpace(*robot, bounds));
        setup.setStateValidityChecker(std::make_shared<RobotChecker>(setup.getSpaceInformation(), scene));
        setup.getSpaceInformation()->setMotionValidator(
            std::make_shared<RobotMotionValidator>(setup.getSpaceInformation(), scene, *robot));
        // The base from one side of the wall to the other, the drone across it at its height.
        const std::vector<double> a = {-0.8, -0.5, 0, 0, -0.8, -0.5, -0.6, 0, 0, 0, 1, 0, 0, 0};
        const double h = std::sqrt(0.5);
        const std::vector<double> b = {0.8, -0.5, M_PI / 2, 0.5, 0.8, -0.5, -0.6, 0, 0, h, h, 0.5, 0.3, 1};
        ob::ScopedState<> start(setup.getStateSpace()), goal(setup.getStateSpace());
        robotStateFromVector(*setup.getStateSpace(), a, start.get());
        robotStateFromVector(*setup.getStateSpace(), b, goal.get());
        setup.setStartAndGoalStates(start, goal);
        setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
        ompl::RNG::setSeed(3);
        setup.setup();
        for (const std::vector<double> *q : {&a, &b})
        {
            RobotResult r;
            scene->distance(*q, RobotRequest(), r);
            ASSERT_GT(r.distance, 0.0) << robot->links()[r.link].name << " against "
                                       << (r.selfPair ? robot->links()[r.other].name : "the wall");
        }
        EXPECT_FALSE(setup.getSpaceInformation()->checkMotion(start.get(), goal.get()));  // straight through
        // RRTConnect stops at its first solution: the limit only bounds a run that could not find one.
        ASSERT_EQ(setup.solve(300.0), ob::PlannerStatus::EXACT_SOLUTION);
        og::PathGeometric path = setup.getSolutionPath();
        EXPECT_TRUE(path.check());
        path.interpolate(static_cast<unsigned int>(std::ceil(path.length() / 2e-3)) + 1);
        std::vector<double> q;
        double least = std::numeric_limits<double>::infinity();
        // Every state (every test::stride()-th under the sanitizers).
        const std::vector<ob::State *> &states = path.getStates();
        for (std::size_t i = 0; i < states.size(); i += static_cast<std::size_t>(test::stride()))
        {
            robotStateToVector(*setup.getStateSpace(), states[i], q);
            RobotResult r;
            scene->distance(q, RobotRequest(), r);
            least = std::min(least, r.distance);
        }
        test::Note() << path.getStateCount() << " states, least clearance " << least;
        EXPECT_GE(least, 0.0);
    }
}  // namespace meshgap
