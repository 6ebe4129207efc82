#include "meshgap/ompl/ControlModels.h"

#include <cmath>
#include <ompl/base/ProjectionEvaluator.h>
#include <ompl/base/spaces/SE2StateSpace.h>
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

        oc::SpaceInformationPtr dynamicCar(const ob::RealVectorBounds &poseBounds)
        {
            auto se2 = std::make_shared<ob::SE2StateSpace>();
            se2->setBounds(poseBounds);
            auto velocity = std::make_shared<ob::RealVectorStateSpace>(2);
            velocity->setBounds(carBounds(1.0, 30.0 * DEGREE));
            auto space = std::make_shared<ob::CompoundStateSpace>();
            space->addSubspace(se2, 1.0);
            space->addSubspace(velocity, 0.3);
            space->lock();
            se2->setup();  // its default projection, which the compound space's wraps
            space->registerDefaultProjection(
                std::make_shared<PoseProjection>(space.get(), se2->getDefaultProjection()));
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
    }  // namespace

    const std::vector<std::string> &modelledControlNames()
    {
        static const std::vector<std::string> names{"kinematic_car", "dynamic_car"};
        return names;
    }

    oc::SpaceInformationPtr controlSpaceInformation(const std::string &model, const ob::RealVectorBounds &poseBounds)
    {
        oc::SpaceInformationPtr si;
        if (model == "kinematic_car")
            si = kinematicCar(poseBounds);
        else if (model == "dynamic_car")
            si = dynamicCar(poseBounds);
        else
            throw Exception("control = " + model, "not a modelled control problem (modelled: kinematic_car, "
                                                  "dynamic_car)");
        si->getStateSpace()->setup();  // the ODE solver reads a state's reals through the locations setup() finds
        si->setMinMaxControlDuration(1, 10);
        si->setPropagationStepSize(si->getStateValidityCheckingResolution() * si->getStateSpace()->getMaximumExtent());
        return si;
    }
}  // namespace meshgap
