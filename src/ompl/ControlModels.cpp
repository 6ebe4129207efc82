#include "meshgap/ompl/ControlModels.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/control/ODESolver.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "meshgap/Exception.h"

namespace ob = ompl::base;
namespace oc = ompl::control;

namespace meshgap
{
    namespace
    {
        /** \brief \e si without ownership, for the ODE solver its own propagator holds: a solver owning its space
            information would make a cycle (si -> propagator -> solver -> si) that is never freed. */
        oc::SpaceInformationPtr unowned(const oc::SpaceInformationPtr &si)
        {
            return oc::SpaceInformationPtr(oc::SpaceInformationPtr(), si.get());
        }

        constexpr double DEGREE = M_PI / 180.0;
        constexpr double AXLE_DISTANCE = 1.0;  ///< L, front to rear axle
        constexpr double CAR_MASS = 1.0;       ///< m of the dynamic car
        constexpr double INTEGRATION_STEP = 1e-2;
        constexpr double QUADROTOR_MASS = 1.0;     ///< m of the quadrotor
        constexpr double QUADROTOR_DAMPING = 1.0;  ///< beta of the quadrotor
        constexpr double GRAVITY = 9.81;

        /** \brief The pose subspace's own projection, applied to component 0 of a compound state. */
        class PoseProjection : public ob::ProjectionEvaluator
        {
        public:
            PoseProjection(const ob::StateSpace *space, ob::ProjectionEvaluatorPtr pose)
              : ob::ProjectionEvaluator(space), pose_(std::move(pose))
            {
            }
            unsigned int getDimension() const override { return pose_->getDimension(); }
            void defaultCellSizes() override { cellSizes_ = pose_->getCellSizes(); }
            void project(const ob::State *state, Eigen::Ref<Eigen::VectorXd> projection) const override
            {
                pose_->project(state->as<ob::CompoundState>()->components[0], projection);
            }

        private:
            ob::ProjectionEvaluatorPtr pose_;
        };

        /** \brief Speed and steering angle: the controls of the kinematic car, the state of the dynamic car. */
        ob::RealVectorBounds carBounds(double speed, double steering)
        {
            ob::RealVectorBounds bounds(2);
            bounds.setLow(0, -speed);
            bounds.setHigh(0, speed);
            bounds.setLow(1, -steering);
            bounds.setHigh(1, steering);
            return bounds;
        }

        /** \brief Wrap the yaw of the SE(2) state \e pose into (-pi, pi]. */
        void wrapYaw(ob::State *pose)
        {
            auto *se2 = pose->as<ob::SE2StateSpace::StateType>();
            se2->setYaw(std::remainder(se2->getYaw(), 2.0 * M_PI));
        }

        oc::SpaceInformationPtr kinematicCar(const ob::RealVectorBounds &poseBounds)
        {
            auto se2 = std::make_shared<ob::SE2StateSpace>();
            se2->setBounds(poseBounds);
            auto controls = std::make_shared<oc::RealVectorControlSpace>(se2, 2);
            controls->setBounds(carBounds(5.0, 30.0 * DEGREE));
            auto si = std::make_shared<oc::SpaceInformation>(se2, controls);
            auto ode = [](const oc::ODESolver::StateType &q, const oc::Control *c, oc::ODESolver::StateType &qdot)
            {
                const double *u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
                qdot.assign(q.size(), 0.0);
                qdot[0] = u[0] * std::cos(q[2]);
                qdot[1] = u[0] * std::sin(q[2]);
                qdot[2] = u[0] * std::tan(u[1]) / AXLE_DISTANCE;
            };
            auto solver = std::make_shared<oc::ODEBasicSolver<>>(unowned(si), ode, INTEGRATION_STEP);
            si->setStatePropagator(oc::ODESolver::getStatePropagator(
                solver, [](const ob::State *, const oc::Control *, double, ob::State *result) { wrapYaw(result); }));
            return si;
        }

        /** \brief A bounded real vector space of \e dimension, every coordinate in [-limit, limit]. */
        std::shared_ptr<ob::RealVectorStateSpace> velocities(unsigned int dimension, double limit)
        {
            auto space = std::make_shared<ob::RealVectorStateSpace>(dimension);
            ob::RealVectorBounds bounds(dimension);
            bounds.setLow(-limit);
            bounds.setHigh(limit);
            space->setBounds(bounds);
            return space;
        }

        /** \brief The compound space of \e pose (weight 1) and \e rates (weight 0.3 each), locked, with the pose's
            own default projection as its default projection. */
        std::shared_ptr<ob::CompoundStateSpace> withRates(const ob::StateSpacePtr &pose,
                                                          const std::vector<ob::StateSpacePtr> &rates)
        {
            auto space = std::make_shared<ob::CompoundStateSpace>();
            space->addSubspace(pose, 1.0);
            for (const ob::StateSpacePtr &rate : rates)
                space->addSubspace(rate, 0.3);
            space->lock();
            pose->setup();  // its default projection, which the compound space's wraps
            space->registerDefaultProjection(
                std::make_shared<PoseProjection>(space.get(), pose->getDefaultProjection()));
            return space;
        }

        /** \brief Clamp the rate subspaces (1 and on) of a compound state into their bounds, as OMPL.app does after
            each propagation. */
        void clampRates(const ob::CompoundStateSpace &space, ob::State *state)
        {
            for (unsigned int k = 1; k < space.getSubspaceCount(); ++k)
                space.getSubspace(k)->enforceBounds(state->as<ob::CompoundState>()->components[k]);
        }

        /** \brief The SE(3) pose of a compound state (its component 0). */
        ob::SE3StateSpace::StateType &pose3(ob::State *state)
        {
            return *state->as<ob::CompoundState>()->components[0]->as<ob::SE3StateSpace::StateType>();
        }

        oc::SpaceInformationPtr dynamicCar(const ob::RealVectorBounds &poseBounds)
        {
            auto se2 = std::make_shared<ob::SE2StateSpace>();
            se2->setBounds(poseBounds);
            auto velocity = std::make_shared<ob::RealVectorStateSpace>(2);
            velocity->setBounds(carBounds(1.0, 30.0 * DEGREE));
            auto space = withRates(se2, {velocity});
            auto controls = std::make_shared<oc::RealVectorControlSpace>(space, 2);
            controls->setBounds(carBounds(0.5, 2.0 * DEGREE));
            auto si = std::make_shared<oc::SpaceInformation>(space, controls);
            auto ode = [](const oc::ODESolver::StateType &q, const oc::Control *c, oc::ODESolver::StateType &qdot)
            {
                const double *u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
                qdot.assign(q.size(), 0.0);
                qdot[0] = q[3] * std::cos(q[2]);
                qdot[1] = q[3] * std::sin(q[2]);
                qdot[2] = q[3] * CAR_MASS * std::tan(q[4]) / AXLE_DISTANCE;
                qdot[3] = u[0];
                qdot[4] = u[1];
            };
            auto solver = std::make_shared<oc::ODEBasicSolver<>>(unowned(si), ode, INTEGRATION_STEP);
            si->setStatePropagator(oc::ODESolver::getStatePropagator(
                solver, [](const ob::State *, const oc::Control *, double, ob::State *result)
                { wrapYaw(result->as<ob::CompoundState>()->components[0]); }));
            return si;
        }

        /** \brief The blimp's heading: the yaw of its rotation about z (reals 3 to 6: the quaternion x, y, z, w). */
        double blimpHeading(const oc::ODESolver::StateType &q)
        {
            return 2.0 * std::atan2(q[5], q[6]);
        }

        oc::SpaceInformationPtr blimp(const ob::RealVectorBounds &poseBounds)
        {
            auto se3 = std::make_shared<ob::SE3StateSpace>();
            se3->setBounds(poseBounds);
            auto space = withRates(se3, {velocities(3, 1.0), velocities(1, 0.2)});
            auto controls = std::make_shared<oc::RealVectorControlSpace>(space, 3);
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-1.0);
            bounds.setHigh(1.0);
            bounds.setLow(2, -0.3);
            bounds.setHigh(2, 0.3);
            controls->setBounds(bounds);
            auto si = std::make_shared<oc::SpaceInformation>(space, controls);
            // Reals: x y z, the quaternion (x y z w) of a rotation about z, the velocity, the yaw rate.
            auto ode = [](const oc::ODESolver::StateType &q, const oc::Control *c, oc::ODESolver::StateType &qdot)
            {
                const double *u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
                const double heading = blimpHeading(q), omega = q[10];
                qdot.assign(q.size(), 0.0);
                qdot[0] = q[7];
                qdot[1] = q[8];
                qdot[2] = q[9];
                qdot[5] = 0.5 * omega * q[6];  // the quaternion (0, 0, sin, cos) of half the heading
                qdot[6] = -0.5 * omega * q[5];
                qdot[7] = u[0] * std::cos(heading);
                qdot[8] = u[0] * std::sin(heading);
                qdot[9] = u[1];
                qdot[10] = u[2];
            };
            auto solver = std::make_shared<oc::ODEBasicSolver<>>(unowned(si), ode, INTEGRATION_STEP);
            const ob::CompoundStateSpace *compound = space.get();
            si->setStatePropagator(oc::ODESolver::getStatePropagator(
                solver, [compound](const ob::State *, const oc::Control *, double, ob::State *result)
                {
                    ob::SO3StateSpace::StateType &r = pose3(result).rotation();
                    r.setAxisAngle(0.0, 0.0, 1.0, 2.0 * std::atan2(r.z, r.w));
                    clampRates(*compound, result);
                }));
            return si;
        }

        /** \brief The quadrotor's equations of motion over its reals: x y z, the quaternion (x y z w), the velocity,
            the angular velocity (in the world frame). */
        void quadrotorODE(const oc::ODESolver::StateType &q, const oc::Control *c, oc::ODESolver::StateType &qdot)
        {
            const double *u = c->as<oc::RealVectorControlSpace::ControlType>()->values;
            const Eigen::Vector3d v(q[7], q[8], q[9]), omega(q[10], q[11], q[12]);
            const Eigen::Vector3d axis(q[3], q[4], q[5]);  // the quaternion's vector part
            const double w = q[6];
            // d/dt (w, axis) = (0, omega) * (w, axis) / 2
            const Eigen::Vector3d axisRate = 0.5 * (w * omega + omega.cross(axis));
            const double wRate = -0.5 * omega.dot(axis);
            // The body's z axis in the world frame; the thrust u0 acts along its negative.
            const Eigen::Vector3d n(2.0 * (q[3] * q[5] + w * q[4]), 2.0 * (q[4] * q[5] - w * q[3]),
                                    w * w - q[3] * q[3] - q[4] * q[4] + q[5] * q[5]);
            const Eigen::Vector3d a =
                (-u[0] * n - QUADROTOR_DAMPING * v) / QUADROTOR_MASS - Eigen::Vector3d(0.0, 0.0, GRAVITY);
            qdot.assign(q.size(), 0.0);
            for (int k = 0; k < 3; ++k)
            {
                qdot[k] = v[k];
                qdot[3 + k] = axisRate[k];
                qdot[7 + k] = a[k];
                qdot[10 + k] = u[1 + k];
            }
            qdot[6] = wRate;
        }

        oc::SpaceInformationPtr quadrotor(const ob::RealVectorBounds &poseBounds)
        {
            auto se3 = std::make_shared<ob::SE3StateSpace>();
            se3->setBounds(poseBounds);
            auto space = withRates(se3, {velocities(6, 1.0)});
            auto controls = std::make_shared<oc::RealVectorControlSpace>(space, 4);
            ob::RealVectorBounds bounds(4);
            bounds.setLow(-1.0);
            bounds.setHigh(1.0);
            bounds.setLow(0, 5.0);
            bounds.setHigh(0, 15.0);
            controls->setBounds(bounds);
            auto si = std::make_shared<oc::SpaceInformation>(space, controls);
            auto solver = std::make_shared<oc::ODEBasicSolver<>>(unowned(si), quadrotorODE, INTEGRATION_STEP);
            const ob::CompoundStateSpace *compound = space.get();
            si->setStatePropagator(oc::ODESolver::getStatePropagator(
                solver, [compound](const ob::State *, const oc::Control *, double, ob::State *result)
                {
                    compound->getSubspace(0)->as<ob::SE3StateSpace>()->getSubspace(1)->enforceBounds(
                        &pose3(result).rotation());  // normalises the quaternion
                    clampRates(*compound, result);
                }));
            return si;
        }
    }  // namespace

    const std::vector<std::string> &modelledControlNames()
    {
        static const std::vector<std::string> names{"kinematic_car", "dynamic_car", "blimp", "quadrotor"};
        return names;
    }

    bool controlModelIsPlanar(const std::string &model)
    {
        return model == "kinematic_car" || model == "dynamic_car";
    }

    oc::SpaceInformationPtr controlSpaceInformation(const std::string &model, const ob::RealVectorBounds &poseBounds)
    {
        const std::vector<std::string> &names = modelledControlNames();
        if (std::find(names.begin(), names.end(), model) == names.end())
            throw Exception("control = " + model, "not a modelled control problem (modelled: kinematic_car, "
                                                  "dynamic_car, blimp, quadrotor)");
        if (poseBounds.low.size() != (controlModelIsPlanar(model) ? 2u : 3u))
            throw Exception("control = " + model, std::string("the pose bounds must be ") +
                                                      (controlModelIsPlanar(model) ? "planar (x, y)" : "3D (x, y, z)"));
        oc::SpaceInformationPtr si;
        if (model == "kinematic_car")
            si = kinematicCar(poseBounds);
        else if (model == "dynamic_car")
            si = dynamicCar(poseBounds);
        else if (model == "blimp")
            si = blimp(poseBounds);
        else
            si = quadrotor(poseBounds);
        si->getStateSpace()->setup();  // the ODE solver reads a state's reals through the locations setup() finds
        si->setMinMaxControlDuration(1, 10);
        si->setPropagationStepSize(si->getStateValidityCheckingResolution() * si->getStateSpace()->getMaximumExtent());
        return si;
    }
}  // namespace meshgap
