// Control paths planned on the control maps of maps/ (car_chicane, blimp_window, quadrotor_window) and on OMPL.app's
// BugTrap_dcar are free under a dense check: every control of the path is propagated again from its state, one
// integration step (0.01) at a time, and the exact distance from the scene at each of those poses is positive. The
// planner checks a state one propagation step apart (OMPL's default, as OMPL.app plans); the dense check looks
// between them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ompl/base/ScopedState.h>
#include <ompl/control/planners/kpiece/KPIECE1.h>
#include <ompl/control/planners/rrt/RRT.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>
#include <ompl/util/RandomNumbers.h>

#include "meshgap/ompl/ProblemSetup.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace oc = ompl::control;

namespace
{
    /** \brief What the dense check found over a control path. */
    struct DenseCheck
    {
        std::size_t poses{0}, colliding{0};
        double least{std::numeric_limits<double>::infinity()};
    };

    /** \brief The exact distance at \e state, recorded in \e check. */
    void checkState(const OmplControlProblem &problem, const ob::State *state, DenseCheck &check)
    {
        SceneRequest request;
        SceneResult r;
        problem.scene->distance(poseFromState(*problem.setup->getStateSpace(), state), request, r);
        ++check.poses;
        check.least = std::min(check.least, r.distance);
        check.colliding += r.distance > 0.0 ? 0 : 1;
    }

    /** \brief Each control of \e path propagated from the state one propagation step at a time (as the planner
        propagated it), and within each step every 0.01 (the integration step) from the step's first state. */
    DenseCheck denseCheck(const OmplControlProblem &problem, const oc::PathControl &path)
    {
        const oc::SpaceInformationPtr &si = problem.setup->getSpaceInformation();
        const double step = si->getPropagationStepSize();
        const auto substeps = static_cast<int>(std::floor(step / 0.01 + 1e-9));
        ob::ScopedState<> state(si->getStateSpace(), path.getState(0)), next(si->getStateSpace()),
            inner(si->getStateSpace());
        DenseCheck check;
        checkState(problem, state.get(), check);
        for (std::size_t c = 0; c < path.getControlCount(); ++c)
        {
            const auto steps = static_cast<unsigned int>(std::lround(path.getControlDuration(c) / step));
            for (unsigned int s = 0; s < steps; ++s)
            {
                for (int k = 1; k < substeps; ++k)
                {
                    si->getStatePropagator()->propagate(state.get(), path.getControl(c), 0.01 * k, inner.get());
                    checkState(problem, inner.get(), check);
                }
                si->getStatePropagator()->propagate(state.get(), path.getControl(c), step, next.get());
                checkState(problem, next.get(), check);
                state = next;
            }
        }
        return check;
    }

    /** \brief Plan \e cfg with \e planner for \e seconds (seed 5), then check the path densely. */
    void planAndCheck(const std::string &cfg, const std::string &planner, double seconds)
    {
        ompl::RNG::setSeed(5);
        const OmplControlProblem problem =
            setupControlProblem(readProblemConfig(cfg), ClearanceChecker::Mode::CERTIFIED);
        const oc::SpaceInformationPtr &si = problem.setup->getSpaceInformation();
        if (planner == "rrt")
            problem.setup->setPlanner(std::make_shared<oc::RRT>(si));
        else
            problem.setup->setPlanner(std::make_shared<oc::KPIECE1>(si));
        const ob::PlannerStatus status = problem.setup->solve(seconds);
        ASSERT_TRUE(status == ob::PlannerStatus::EXACT_SOLUTION || status == ob::PlannerStatus::APPROXIMATE_SOLUTION)
            << cfg << ": " << status.asString();
        const oc::PathControl &path = problem.setup->getSolutionPath();
        ASSERT_GT(path.getControlCount(), 0u) << cfg;
        const DenseCheck check = denseCheck(problem, path);
        EXPECT_EQ(check.colliding, 0u) << cfg << " " << planner << ": " << check.colliding << " of " << check.poses
                                       << " poses collide, least distance " << check.least;
        EXPECT_GT(check.poses, 10 * path.getControlCount()) << cfg;
        // The path's end is where the planner says: the distance to the goal it reports.
        const double gap = problem.setup->getProblemDefinition()->getSolutionDifference();
        EXPECT_TRUE(status == ob::PlannerStatus::EXACT_SOLUTION || gap > 0.0) << gap;
    }

    std::string mapsDir()
    {
        return std::string(MESHGAP_SOURCE_DIR) + "/maps";
    }
}  // namespace

TEST(ControlPathDense, KinematicCarThroughTheChicane)
{
    planAndCheck(mapsDir() + "/car_chicane/car_chicane.cfg", "kpiece", 3.0);
    planAndCheck(mapsDir() + "/car_chicane/car_chicane.cfg", "rrt", 3.0);
}

TEST(ControlPathDense, FindsACarDrivenThroughAWall)
{
    // The oracle can fail: full speed ahead from the start runs into the first wall (x in [-1.65, -1.35]).
    const OmplControlProblem problem = setupControlProblem(
        readProblemConfig(mapsDir() + "/car_chicane/car_chicane.cfg"), ClearanceChecker::Mode::CERTIFIED);
    const oc::SpaceInformationPtr &si = problem.setup->getSpaceInformation();
    oc::PathControl path(si);
    oc::Control *ahead = si->allocControl();
    ahead->as<oc::RealVectorControlSpace::ControlType>()->values[0] = 5.0;
    ahead->as<oc::RealVectorControlSpace::ControlType>()->values[1] = 0.0;
    const ob::State *start = problem.setup->getProblemDefinition()->getStartState(0);
    path.append(start, ahead, 5 * si->getPropagationStepSize());  // 4 units ahead, from x = -4.5
    ob::ScopedState<> end(si->getStateSpace());
    si->propagate(start, ahead, 5, end.get());
    path.append(end.get());
    const DenseCheck check = denseCheck(problem, path);
    EXPECT_GT(check.colliding, 0u);
    EXPECT_LT(check.least, 0.0 + 1e-12);
    si->freeControl(ahead);
}

TEST(ControlPathDense, BlimpThroughTheWindow)
{
    planAndCheck(mapsDir() + "/blimp_window/blimp_window.cfg", "kpiece", 3.0);
}

TEST(ControlPathDense, QuadrotorThroughTheWindow)
{
    planAndCheck(mapsDir() + "/quadrotor_window/quadrotor_window.cfg", "kpiece", 3.0);
}

TEST(ControlPathDense, BugTrapDynamicCar)
{
    const std::string data = std::string(MESHGAP_SHARED_DATA_DIR) + "/omplapp";
    if (!fs::exists(data + "/BugTrap_dcar.cfg"))
        GTEST_SKIP() << data << " is absent (OMPL.app's problems)";
    planAndCheck(data + "/BugTrap_dcar.cfg", "kpiece", 3.0);
}
