// OMPL.app's control models (ControlModels.h) against their motions in closed form: the kinematic car along a circle
// of radius L / tan(phi), the dynamic car straight ahead under a constant acceleration, the blimp under a constant
// thrust at a constant yaw rate, the quadrotor at a fixed attitude (its velocity relaxing exponentially) and turning
// at a constant angular velocity; the blimp and the quadrotor also against a fine Runge-Kutta integration of their
// equations written in other coordinates (the heading as an angle; the attitude as a rotation matrix); the pose of a
// compound state is its component 0; setupControlProblem() on small problems.

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

    /** \brief Propagate \e from under the controls \e u for \e duration; the result's reals. */
    std::vector<double> propagate(const oc::SpaceInformationPtr &si, const std::vector<double> &from,
                                  const std::vector<double> &u, double duration)
    {
        ob::ScopedState<> start(si->getStateSpace()), result(si->getStateSpace());
        start = from;
        oc::Control *control = si->allocControl();
        for (std::size_t k = 0; k < u.size(); ++k)
            control->as<oc::RealVectorControlSpace::ControlType>()->values[k] = u[k];
        si->getStatePropagator()->propagate(start.get(), control, duration, result.get());
        si->freeControl(control);
        return result.reals();
    }

    ob::RealVectorBounds box(double half)
    {
        ob::RealVectorBounds bounds(3);
        bounds.setLow(-half);
        bounds.setHigh(half);
        return bounds;
    }

    /** \brief The reals of an SE(3) pose (x y z, quaternion x y z w), then \e rates. */
    std::vector<double> poseReals(const Eigen::Vector3d &p, const Eigen::Quaterniond &q, std::vector<double> rates)
    {
        std::vector<double> reals{p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
        reals.insert(reals.end(), rates.begin(), rates.end());
        return reals;
    }

    /** \brief The rotation of reals 3 to 6 (quaternion x y z w). */
    Eigen::Matrix3d rotationOf(const std::vector<double> &q)
    {
        return Eigen::Quaterniond(q[6], q[3], q[4], q[5]).normalized().toRotationMatrix();
    }

    /** \brief The classical Runge-Kutta 4 of \e f from \e y over \e duration in \e steps. */
    template <typename Vector, typename F>
    Vector rungeKutta(F f, Vector y, double duration, int steps)
    {
        const double h = duration / steps;
        for (int i = 0; i < steps; ++i)
        {
            const Vector k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
            y = y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        }
        return y;
    }

    Eigen::Matrix3d hat(const Eigen::Vector3d &w)
    {
        Eigen::Matrix3d W;
        W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
        return W;
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

TEST(ControlModels, BlimpSpacesAndBoundsAreOMPLApps)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("blimp", box(10));
    const auto *space = si->getStateSpace()->as<ob::CompoundStateSpace>();
    ASSERT_EQ(space->getSubspaceCount(), 3u);
    EXPECT_EQ(space->getSubspace(0)->getType(), ob::STATE_SPACE_SE3);
    EXPECT_EQ(space->getSubspace(1)->as<ob::RealVectorStateSpace>()->getBounds().high, std::vector<double>(3, 1.0));
    EXPECT_EQ(space->getSubspace(2)->as<ob::RealVectorStateSpace>()->getBounds().low, std::vector<double>{-0.2});
    EXPECT_EQ(space->getSubspaceWeight(1), 0.3);
    EXPECT_EQ(space->getSubspaceWeight(2), 0.3);
    const auto &bounds = si->getControlSpace()->as<oc::RealVectorControlSpace>()->getBounds();
    EXPECT_EQ(bounds.low, (std::vector<double>{-1.0, -1.0, -0.3}));
    EXPECT_EQ(bounds.high, (std::vector<double>{1.0, 1.0, 0.3}));
    EXPECT_TRUE(si->getStateSpace()->hasDefaultProjection());
    EXPECT_EQ(si->getStateSpace()->getDefaultProjection()->getDimension(), 3u);
    EXPECT_NEAR(si->getPropagationStepSize(), 0.01 * si->getStateSpace()->getMaximumExtent(), 1e-15);
}

TEST(ControlModels, BlimpFollowsItsClosedFormAtAConstantYawRate)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("blimp", box(100));
    // (thrust, climb, yaw rate, duration); no yaw acceleration, so the heading grows linearly.
    for (const auto &[uf, uz, omega, t] : {std::make_tuple(0.3, 0.25, 0.15, 2.0),
                                            std::make_tuple(-0.2, -0.3, -0.2, 2.5),
                                            std::make_tuple(0.3, 0.0, 0.0, 1.5)})
    {
        const Eigen::Vector3d p0(1.0, -2.0, 3.0), v0(0.2, -0.1, 0.2);
        const double theta0 = 0.7;
        const Eigen::Quaterniond q0(Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitZ()));
        const std::vector<double> q =
            propagate(si, poseReals(p0, q0, {v0.x(), v0.y(), v0.z(), omega}), {uf, uz, 0.0}, t);
        const double theta = theta0 + omega * t;
        Eigen::Vector2d dv, dp;  // the thrust's contribution to the velocity and the position in x, y
        if (omega == 0.0)
        {
            dv = uf * t * Eigen::Vector2d(std::cos(theta0), std::sin(theta0));
            dp = 0.5 * t * dv;
        }
        else
        {
            dv = uf / omega * Eigen::Vector2d(std::sin(theta) - std::sin(theta0), std::cos(theta0) - std::cos(theta));
            dp = uf / omega *
                 Eigen::Vector2d((std::cos(theta0) - std::cos(theta)) / omega - t * std::sin(theta0),
                                 (std::sin(theta0) - std::sin(theta)) / omega + t * std::cos(theta0));
        }
        EXPECT_NEAR(q[0], p0.x() + v0.x() * t + dp.x(), 1e-8) << uf << " " << omega;
        EXPECT_NEAR(q[1], p0.y() + v0.y() * t + dp.y(), 1e-8) << uf << " " << omega;
        EXPECT_NEAR(q[2], p0.z() + v0.z() * t + 0.5 * uz * t * t, 1e-9);
        EXPECT_NEAR(q[7], v0.x() + dv.x(), 1e-8);
        EXPECT_NEAR(q[8], v0.y() + dv.y(), 1e-8);
        EXPECT_NEAR(q[9], v0.z() + uz * t, 1e-9);
        EXPECT_NEAR(q[10], omega, 1e-12);
        // Still a rotation about z, by the heading.
        const Eigen::Matrix3d expected = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        EXPECT_LT((rotationOf(q) - expected).norm(), 1e-9) << uf << " " << omega;
        EXPECT_EQ(q[3], 0.0);
        EXPECT_EQ(q[4], 0.0);
    }
}

TEST(ControlModels, BlimpAgreesWithAFineIntegrationOfItsHeading)
{
    // Yaw acceleration too: the heading is quadratic in time and the position has no elementary closed form. The
    // reference integrates x'' = u0 cos(theta), y'' = u0 sin(theta), z'' = u1, theta'' = u2 with the heading as an
    // angle, 10^5 steps.
    const oc::SpaceInformationPtr si = controlSpaceInformation("blimp", box(100));
    const double uf = 0.2, uz = -0.2, ut = 0.1, t = 3.0, theta0 = -2.5, omega0 = -0.15;
    const Eigen::Vector3d p0(0.5, 0.5, 2.0), v0(-0.3, 0.4, 0.1);
    const std::vector<double> q =
        propagate(si, poseReals(p0, Eigen::Quaterniond(Eigen::AngleAxisd(theta0, Eigen::Vector3d::UnitZ())),
                                {v0.x(), v0.y(), v0.z(), omega0}),
                  {uf, uz, ut}, t);
    using Vector8 = Eigen::Matrix<double, 8, 1>;  // x y z theta, their rates
    Vector8 y0;
    y0 << p0, theta0, v0, omega0;
    const Vector8 y = rungeKutta(
        [&](const Vector8 &s)
        {
            Vector8 d;
            d << s.tail<4>(), uf * std::cos(s[3]), uf * std::sin(s[3]), uz, ut;
            return d;
        },
        y0, t, 100000);
    ASSERT_LT(y.segment<3>(4).cwiseAbs().maxCoeff(), 1.0);  // within the velocity bounds: nothing clamped
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(q[k], y[k], 1e-8) << k;
        EXPECT_NEAR(q[7 + k], y[4 + k], 1e-8) << k;
    }
    EXPECT_NEAR(q[10], y[7], 1e-12);
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(y[3], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    EXPECT_LT((rotationOf(q) - expected).norm(), 1e-9);
    // Past its bounds the velocity is clamped, as OMPL.app clamps it: full thrust ahead for 4 s from 0.5.
    const std::vector<double> fast =
        propagate(si, poseReals(p0, Eigen::Quaterniond::Identity(), {0.5, 0.0, 0.0, 0.0}), {1.0, 0.0, 0.3}, 4.0);
    EXPECT_EQ(fast[7], 1.0);
    EXPECT_EQ(fast[10], 0.2);
}

TEST(ControlModels, QuadrotorSpacesAndBoundsAreOMPLApps)
{
    const oc::SpaceInformationPtr si = controlSpaceInformation("quadrotor", box(10));
    const auto *space = si->getStateSpace()->as<ob::CompoundStateSpace>();
    ASSERT_EQ(space->getSubspaceCount(), 2u);
    EXPECT_EQ(space->getSubspace(0)->getType(), ob::STATE_SPACE_SE3);
    EXPECT_EQ(space->getSubspace(1)->as<ob::RealVectorStateSpace>()->getBounds().low, std::vector<double>(6, -1.0));
    EXPECT_EQ(space->getSubspaceWeight(1), 0.3);
    const auto &bounds = si->getControlSpace()->as<oc::RealVectorControlSpace>()->getBounds();
    EXPECT_EQ(bounds.low, (std::vector<double>{5.0, -1.0, -1.0, -1.0}));
    EXPECT_EQ(bounds.high, (std::vector<double>{15.0, 1.0, 1.0, 1.0}));
    EXPECT_EQ(si->getStateSpace()->getDefaultProjection()->getDimension(), 3u);
    // Pose bounds of the wrong dimension: refused, naming the model.
    EXPECT_THROW(controlSpaceInformation("quadrotor", square(10)), Exception);
    EXPECT_THROW(controlSpaceInformation("kinematic_car", box(10)), Exception);
}

TEST(ControlModels, QuadrotorAtAFixedAttitudeRelaxesToItsTerminalVelocity)
{
    // No angular velocity nor acceleration: n fixed, v' = -u0 n - v - g ez, so v(t) = vt + (v0 - vt) e^-t with
    // vt = -u0 n - g ez. Upside down (n pointing down), tilted 0.05 rad, thrust 10: vt = (0, -0.5, 0.18).
    const oc::SpaceInformationPtr si = controlSpaceInformation("quadrotor", box(100));
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(M_PI + 0.05, Eigen::Vector3d::UnitX()));
    const Eigen::Vector3d p0(1.0, 2.0, 3.0), v0(0.1, 0.2, -0.3), n = q0 * Eigen::Vector3d::UnitZ();
    const double u0 = 10.0, t = 2.5;
    const std::vector<double> q = propagate(si, poseReals(p0, q0, {v0.x(), v0.y(), v0.z(), 0, 0, 0}), {u0, 0, 0, 0}, t);
    const Eigen::Vector3d vt = -u0 * n - Eigen::Vector3d(0, 0, 9.81);
    const Eigen::Vector3d v = vt + (v0 - vt) * std::exp(-t), p = p0 + vt * t + (v0 - vt) * (1.0 - std::exp(-t));
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(q[k], p[k], 1e-9) << k;
        EXPECT_NEAR(q[7 + k], v[k], 1e-9) << k;
        EXPECT_EQ(q[10 + k], 0.0);
    }
    EXPECT_LT((rotationOf(q) - q0.toRotationMatrix()).norm(), 1e-12);
    // Upright, the thrust pushes down with gravity: the fall is clamped at OMPL.app's velocity bound.
    const std::vector<double> upright =
        propagate(si, poseReals(p0, Eigen::Quaterniond::Identity(), {0, 0, 0, 0, 0, 0}), {5.0, 0, 0, 0}, 1.0);
    EXPECT_EQ(upright[9], -1.0);
}

TEST(ControlModels, QuadrotorTurnsAtItsAngularVelocity)
{
    // Constant angular velocity w (world frame): R(t) = exp(t [w]x) R0.
    const oc::SpaceInformationPtr si = controlSpaceInformation("quadrotor", box(100));
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 0.5).normalized()));
    for (const Eigen::Vector3d &w : {Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(-0.9, 0.8, 1.0)})
    {
        const double t = 1.5;
        const std::vector<double> q =
            propagate(si, poseReals(Eigen::Vector3d(0, 0, 0), q0, {0, 0, 0, w.x(), w.y(), w.z()}), {10, 0, 0, 0}, t);
        const Eigen::Matrix3d expected = Eigen::AngleAxisd(w.norm() * t, w.normalized()) * q0.toRotationMatrix();
        EXPECT_LT((rotationOf(q) - expected).norm(), 1e-9) << w.transpose();
        EXPECT_NEAR(Eigen::Vector4d(q[3], q[4], q[5], q[6]).norm(), 1.0, 1e-14);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(q[10 + k], w[k], 1e-12);
    }
}

TEST(ControlModels, QuadrotorAgreesWithAFineIntegrationInRotationMatrices)
{
    // Every control at once; the reference integrates R' = [w]x R, p'' = -u0 R ez - p' - g ez, w' = (u1, u2, u3)
    // with the attitude as a rotation matrix, 10^5 steps.
    const oc::SpaceInformationPtr si = controlSpaceInformation("quadrotor", box(100));
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(M_PI - 0.05, Eigen::Vector3d(1, 0.3, 0).normalized()));
    const Eigen::Vector3d p0(-1.0, 0.5, 2.0), v0(0.2, -0.1, 0.3), w0(0.05, 0.0, -0.1), u(0.2, -0.1, 0.1);
    const double u0 = 10.5, t = 1.0;
    const std::vector<double> q = propagate(
        si, poseReals(p0, q0, {v0.x(), v0.y(), v0.z(), w0.x(), w0.y(), w0.z()}), {u0, u.x(), u.y(), u.z()}, t);
    using Vector18 = Eigen::Matrix<double, 18, 1>;  // p, v, w, R (column-major)
    Vector18 y0;
    const Eigen::Matrix3d R0 = q0.toRotationMatrix();
    y0 << p0, v0, w0, Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R0.data());
    const Vector18 y = rungeKutta(
        [&](const Vector18 &s)
        {
            const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix3d>(s.data() + 9);
            const Eigen::Matrix3d dR = hat(s.segment<3>(6)) * R;
            Vector18 d;
            d << s.segment<3>(3), -u0 * R.col(2) - s.segment<3>(3) - Eigen::Vector3d(0, 0, 9.81), u,
                Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dR.data());
            return d;
        },
        y0, t, 100000);
    ASSERT_LT(y.segment<3>(3).cwiseAbs().maxCoeff(), 1.0);  // within the velocity bounds: nothing clamped
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_NEAR(q[k], y[k], 1e-8) << k;
        EXPECT_NEAR(q[7 + k], y[3 + k], 1e-8) << k;
        EXPECT_NEAR(q[10 + k], y[6 + k], 1e-12) << k;
    }
    EXPECT_LT((rotationOf(q) - Eigen::Map<const Eigen::Matrix3d>(y.data() + 9)).norm(), 1e-8);
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
        EXPECT_NE(std::string(e.what()).find("dynamic_car, blimp, quadrotor"), std::string::npos) << e.what();
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

TEST(ControlModels, SetupControlProblemRefusesBadBlimpAndQuadrotorProblems)
{
    const fs::path dir = fs::temp_directory_path() / ("meshgap_control3d_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    writeObj(test::transformed(test::box(0.5, 0.5, 0.5, 1), test::translation(0, 0, 2)), (dir / "w.obj").string());
    writeObj(test::box(0.3, 0.15, 0.2, 1), (dir / "r.obj").string());
    const std::string volume = "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n";
    const std::string space = volume + "volume.min.z = 0\nvolume.max.z = 4\ngoal.x = 3\ngoal.y = 0\ngoal.z = 1\n";
    const std::string plane = volume + "goal.x = 3\ngoal.y = 0\ngoal.theta = 0\n";
    const auto write = [&](const std::string &name, const std::string &model, const std::string &lines)
    {
        std::ofstream((dir / name).string()) << "[problem]\nrobot = r.obj\nworld = w.obj\ncontrol = " << model << "\n"
                                             << lines;
        return (dir / name).string();
    };
    const std::string at = "start.x = -3\nstart.y = 0\nstart.z = 1\n";
    // Good: a blimp turned about z, a quadrotor turned any way; both start at rest.
    const std::string turned = "start.axis.x = 0\nstart.axis.y = 0\nstart.axis.z = 1\nstart.theta = 0.5\n";
    const std::string blimp = write("blimp.cfg", "blimp", at + turned + space);
    const OmplControlProblem b = setupControlProblem(readProblemConfig(blimp), ClearanceChecker::Mode::CERTIFIED);
    const std::vector<double> reals =
        ob::ScopedState<>(b.setup->getStateSpace(), b.setup->getProblemDefinition()->getStartState(0)).reals();
    ASSERT_EQ(reals.size(), 11u);
    EXPECT_NEAR(reals[5], std::sin(0.25), 1e-15);
    EXPECT_EQ(std::vector<double>(reals.begin() + 7, reals.end()), std::vector<double>(4, 0.0));
    const std::string flipped = "start.axis.x = 1\nstart.axis.y = 0\nstart.axis.z = 0\nstart.theta = 3\n";
    const std::string quad = write("quad.cfg", "quadrotor", at + flipped + space);
    EXPECT_NO_THROW(setupControlProblem(readProblemConfig(quad), ClearanceChecker::Mode::CERTIFIED));
    // Bad: a blimp tilted at its start; a blimp in a planar problem; a car in a 3D problem. One error naming the
    // file and what is wrong.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {write("tilted.cfg", "blimp",
               at + "start.axis.x = 1\nstart.axis.y = 0\nstart.axis.z = 0\nstart.theta = 0.2\n" + space),
         "tilted.cfg: start: control = blimp turns about z only, but its rotation is about the axis (1, 0, 0)"},
        {write("flat.cfg", "blimp", "start.x = -3\nstart.y = 0\nstart.theta = 0\n" + plane),
         "flat.cfg: control = blimp moves in space (SE(3))"},
        {write("car3d.cfg", "kinematic_car", at + space), "car3d.cfg: control = kinematic_car is a planar model"},
    };
    for (const auto &[cfg, message] : cases)
    {
        try
        {
            setupControlProblem(readProblemConfig(cfg), ClearanceChecker::Mode::CERTIFIED);
            ADD_FAILURE() << cfg;
        }
        catch (const Exception &e)
        {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    }
    fs::remove_all(dir);
}
