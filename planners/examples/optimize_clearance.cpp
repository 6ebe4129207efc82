// Example: plan with any OMPL planner, then push the path away from the obstacles with meshgap's
// ClearancePathOptimizer (exact clearance gradient, every motion certified collision-free).
//
//   meshgap_example_optimize_clearance problem.cfg [plan seconds] [optimise seconds]
//
// Copy steps 3-5 into your own SimpleSetup: the optimiser needs only the space information and a meshgap
// ClearanceChecker in CERTIFIED mode (the default), and works on the PathGeometric any planner returns.

#include <cstdio>
#include <cstdlib>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include "meshgap/ompl/ClearanceGradient.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ClearancePathOptimizer.h"
#include "meshgap/ompl/ProblemSetup.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

int main(int argc, char **argv)
{
    if (argc < 2)
    {
        std::fprintf(stderr, "usage: %s problem.cfg [plan seconds] [optimise seconds]\n", argv[0]);
        return 1;
    }
    const double planSeconds = argc > 2 ? std::atof(argv[2]) : 5.0;
    const double optimizeSeconds = argc > 3 ? std::atof(argv[3]) : 5.0;
    try
    {
        // 1. An OMPL.app problem: SE(3) (or SE(2)) space, meshgap's certified clearance checker, start and goal.
        meshgap::OmplProblem problem =
            meshgap::setupProblem(meshgap::readProblemConfig(argv[1]), meshgap::ClearanceChecker::Mode::CERTIFIED);
        og::SimpleSetup &setup = *problem.setup;
        const ob::SpaceInformationPtr si = setup.getSpaceInformation();

        // 2. Any planner. With the certified motion validator every motion of the path is proven free, which the
        //    optimiser requires of its input (OMPL's discrete validator samples motions and may graze).
        si->setMotionValidator(std::make_shared<meshgap::ClearanceMotionValidator>(si, problem.checker));
        setup.setPlanner(std::make_shared<og::RRTConnect>(si));
        if (setup.solve(planSeconds) != ob::PlannerStatus::EXACT_SOLUTION)
        {
            std::printf("not solved within %g s\n", planSeconds);
            return 2;
        }
        og::PathGeometric &path = setup.getSolutionPath();

        // 3. The gradient at a state: which way (translation, then rotation as a world-frame rotation vector) the
        //    clearance rises fastest. The optimiser follows it; here it is only printed.
        std::vector<double> gradient;
        const double c = meshgap::clearanceGradient(*problem.checker, path.getState(path.getStateCount() / 2), gradient);
        std::printf("middle state: clearance %.4g, gradient", c);
        for (double g : gradient)
            std::printf(" %.3g", g);
        std::printf("\n");

        // 4. The optimiser, with its OMPL parameters (also settable by name: optimizer.params().setParam(...)).
        meshgap::ClearancePathOptimizer optimizer(si, problem.checker);
        optimizer.setTimeLimit(optimizeSeconds);
        optimizer.setMaxLengthFactor(3.0);
        optimizer.setSeed(1);
        optimizer.optimize(path);

        // 5. Before and after, measured the same way (exact clearance, minimised along every motion).
        const meshgap::ClearancePathOptimizer::Stats &s = optimizer.lastStats();
        std::printf("solved: min clearance %.4g -> %.4g, length %.4g -> %.4g, %u -> %u states, %.2f s\n",
                    s.minClearanceBefore, s.minClearanceAfter, s.lengthBefore, s.lengthAfter, s.statesBefore,
                    s.statesAfter, s.seconds);
        return 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
