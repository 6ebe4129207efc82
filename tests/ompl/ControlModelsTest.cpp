// OMPL.app's control models (ControlModels.h) against their motions in closed form: the kinematic car along a circle
// of radius L / tan(phi), the dynamic car straight ahead under a constant acceleration; the pose of a compound state
// is its component 0; setupControlProblem() on a small planar problem.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <unistd.h>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/ControlModels.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/MeshWriter.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace oc = ompl::control;

namespace
{
    ob::RealVectorBounds square(double half)
    {
        ob::RealVectorBounds bounds(2);
        bounds.setLow(-half);
        bounds.setHigh(half);
        return bounds;
    }

    /** \brief Propagate \e from under the control (u0, u1) for \e duration; the result's reals. */
    std::vector<double> propagate(const oc::SpaceInformationPtr &si, const std::vector<double> &from, double u0,
                                  double u1, double duration)
    {
        ob::ScopedState<> start(si->getStateSpace()), result(si->getStateSpace());
        start = from;
        oc::Control *control = si->allocControl();
        control->as<oc::RealVectorControlSpace::ControlType>()->values[0] = u0;
        control->as<oc::RealVectorControlSpace::ControlType>()->values[1] = u1;
        si->getStatePropagator()->propagate(start.get(), control, duration, result.get());
        si->freeControl(control);
        return result.reals();
    }

    double angleBetween(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }
}  // namespace

TEST(ControlModels, KinematicCarFollowsItsCircle)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("kinematic_car", square(100));
    EXPECT_EQ(si->getStateSpace()->getType(), ob::STATE_SPACE_SE2);
    const auto &bounds = si->getControlSpace()->as<oc::RealVectorControlSpace>()->getBounds();
    EXPECT_EQ(bounds.low, (std::vector<double>{-5.0, -M_PI / 6}));
    EXPECT_EQ(bounds.high, (std::vector<double>{5.0, M_PI / 6}));
    // (speed, steering, duration): forward, backward, and far enough round the circle for the yaw to wrap.
    for (const auto &[v, phi, t] : {std::make_tuple(2.0, 0.3, 1.5), std::make_tuple(-1.5, -0.45, 2.0),
                                    std::make_tuple(5.0, 0.5, 3.0)})
    {
        const double x0 = 1.0, y0 = -2.0, theta0 = 0.7;
        const std::vector<double> q = propagate(si, {x0, y0, theta0}, v, phi, t);
        const double radius = 1.0 / std::tan(phi), turn = v * t / radius;  // L = 1
        // The circle's centre lies at radius to the car's left (negative radius: to its right).
        const double cx = x0 - radius * std::sin(theta0), cy = y0 + radius * std::cos(theta0);
        const double theta = theta0 + turn;
        EXPECT_NEAR(q[0], cx + radius * std::sin(theta), 1e-6) << v << " " << phi;
        EXPECT_NEAR(q[1], cy - radius * std::cos(theta), 1e-6) << v << " " << phi;
        EXPECT_LT(angleBetween(q[2], theta), 1e-6) << v << " " << phi;
        EXPECT_GT(q[2], -M_PI - 1e-12);  // wrapped
        EXPECT_LE(q[2], M_PI + 1e-12);
    }
}

TEST(ControlModels, DynamicCarGoesStraightWithoutSteering)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("dynamic_car", square(100));
    const auto *space = si->getStateSpace()->as<ob::CompoundStateSpace>();
    ASSERT_EQ(space->getSubspaceCount(), 2u);
    EXPECT_EQ(space->getSubspace(0)->getType(), ob::STATE_SPACE_SE2);
    EXPECT_EQ(space->getSubspace(1)->getDimension(), 2u);
    EXPECT_TRUE(si->getStateSpace()->hasDefaultProjection());
    const auto &bounds = si->getControlSpace()->as<oc::RealVectorControlSpace>()->getBounds();
    EXPECT_EQ(bounds.high, (std::vector<double>{0.5, M_PI / 90}));
    // (initial speed, acceleration, duration): coasting, then speeding up; zero steering angle and rate.
    for (const auto &[v0, a, t] : {std::make_tuple(0.7, 0.0, 4.0), std::make_tuple(-0.2, 0.3, 3.0)})
    {
        const double x0 = 1.0, y0 = 2.0, theta0 = 0.4;
        const std::vector<double> q = propagate(si, {x0, y0, theta0, v0, 0.0}, a, 0.0, t);
        const double s = v0 * t + 0.5 * a * t * t;
        EXPECT_NEAR(q[0], x0 + s * std::cos(theta0), 1e-9);
        EXPECT_NEAR(q[1], y0 + s * std::sin(theta0), 1e-9);
        EXPECT_NEAR(q[2], theta0, 1e-12);
        EXPECT_NEAR(q[3], v0 + a * t, 1e-9);
        EXPECT_NEAR(q[4], 0.0, 1e-12);
    }
}

TEST(ControlModels, PoseOfACompoundStateIsItsComponentZero)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("dynamic_car", square(10));
    ob::ScopedState<> s(si->getStateSpace());
    s = std::vector<double>{1.5, -2.0, 0.3, 0.9, -0.1};
    const Eigen::Isometry3d X = poseFromState(*si->getStateSpace(), s.get());
    EXPECT_NEAR((X.translation() - Eigen::Vector3d(1.5, -2.0, 0.0)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(Eigen::AngleAxisd(X.linear()).angle(), 0.3, 1e-12);
    ob::ScopedState<> back(si->getStateSpace());
    back = std::vector<double>{0.0, 0.0, 0.0, 0.9, -0.1};
    stateFromPose(*si->getStateSpace(), X, back.get());
    EXPECT_EQ(back.reals().size(), 5u);
    for (std::size_t k = 0; k < 5; ++k)
        EXPECT_NEAR(back.reals()[k], s.reals()[k], 1e-12) << k;
}

TEST(ControlModels, UnmodelledNameIsRefused)
{
    try
    {
        controlSpaceInformation("hovercraft", square(10));
        FAIL();
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("hovercraft"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("dynamic_car"), std::string::npos) << e.what();
    }
}

TEST(ControlModels, SetupControlProblemStartsAtRestAndRefusesMismatches)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_control_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeObj(test::transformed(test::box(0.5, 0.5, 0.5, 1), test::translation(0, 0, 0.5)), (dir / "w.obj").string());
    writeObj(test::box(0.3, 0.15, 0.2, 1), (dir / "r.obj").string());
    const std::string head = "[problem]\nrobot = r.obj\nworld = w.obj\ncontrol = dynamic_car\n";
    const std::string tail = "goal.x = 3\ngoal.y = 0\ngoal.theta = 0\n"
                             "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n";
    std::ofstream((dir / "ok.cfg").string()) << head << "start.x = -3\nstart.y = 0\nstart.theta = 0.5\n" << tail;
    const OmplControlProblem problem =
        setupControlProblem(readProblemConfig((dir / "ok.cfg").string()), ClearanceChecker::Mode::CERTIFIED);
    const ob::State *start = problem.setup->getProblemDefinition()->getStartState(0);
    const std::vector<double> reals = ob::ScopedState<>(problem.setup->getStateSpace(), start).reals();
    EXPECT_EQ(reals, (std::vector<double>{-3.0, 0.0, 0.5, 0.0, 0.0}));
    EXPECT_THROW(setupProblem(readProblemConfig((dir / "ok.cfg").string()), ClearanceChecker::Mode::CERTIFIED),
                 Exception);
    // A start in the box: the message names the file and says which.
    std::ofstream((dir / "hit.cfg").string()) << head << "start.x = 0\nstart.y = 0\nstart.theta = 0\n" << tail;
    try
    {
        setupControlProblem(readProblemConfig((dir / "hit.cfg").string()), ClearanceChecker::Mode::CERTIFIED);
        ADD_FAILURE();
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("hit.cfg: start is in collision"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}
