// Example: RRT* maximising the smallest clearance along the path, on an OMPL.app-format problem.
//
//   meshgap_example_rrtstar_max_min_clearance problem.cfg [seconds] [give-up seconds]
//
// It optimises for `seconds` (default 5), longer if it has no solution by then (until `give-up seconds`, by default
// ten times as long).
//
// meshgap builds the OMPL problem from the .cfg (space, bounds, robot and world meshes, start and goal) with a
// ClearanceChecker whose clearance() is the exact distance to the nearest obstacle. The objective "max_min_clearance"
// is meshgap's MaxMinClearanceObjective: OMPL's MaximizeMinClearanceObjective (the smallest clearance over the
// states OMPL samples along each motion), computed from far fewer, cheaper queries. The clearance motion validator certifies each motion by conservative advancement
// on the same exact clearance (no motion is sampled, so none can slip through a thin obstacle).

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <limits>
#include <cstdlib>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ProblemSetup.h"

int main(int argc, char **argv)
{
    if (argc < 2)
    {
        std::fprintf(stderr, "usage: %s problem.cfg [seconds] [give-up seconds]\n", argv[0]);
        return 1;
    }
    const double seconds = argc > 2 ? std::atof(argv[2]) : 5.0;
    const double giveUp = argc > 3 ? std::atof(argv[3]) : 10.0 * seconds;
    try
    {
        // 1. The problem: exact (certified) clearance, objective by name.
        meshgap::OmplProblem problem = meshgap::setupProblem(meshgap::readProblemConfig(argv[1]),
                                                             meshgap::ClearanceChecker::Mode::CERTIFIED,
                                                             "max_min_clearance");
        ompl::base::SpaceInformationPtr si = problem.setup->getSpaceInformation();

        // 2. Motions certified by conservative advancement on the exact clearance.
        si->setMotionValidator(std::make_shared<meshgap::ClearanceMotionValidator>(si, problem.checker));

        // 3. RRT*, which keeps improving the path until the time is up.
        // Every clearance-objective iteration is costly (OMPL's max-min objective asks clearance() along each
        // candidate motion), so a larger goal bias than the default 0.05 finds the first solution sooner.
        auto rrtstar = std::make_shared<ompl::geometric::RRTstar>(si);
        rrtstar->setGoalBias(0.2);
        problem.setup->setPlanner(rrtstar);
        // Optimise for `seconds`, but do not give up before a first solution (up to `giveUp` seconds). RRT* hands
        // its problem definition a solution only when it returns, but reports each better one as it finds it.
        namespace ob = ompl::base;
        std::atomic<bool> found{false};
        problem.setup->getProblemDefinition()->setIntermediateSolutionCallback(
            [&found](const ob::Planner *, const std::vector<const ob::State *> &, const ob::Cost &) { found = true; });
        const ob::PlannerTerminationCondition stop = ob::plannerOrTerminationCondition(
            ob::plannerAndTerminationCondition(ob::timedPlannerTerminationCondition(seconds),
                                               ob::PlannerTerminationCondition([&found] { return found.load(); })),
            ob::timedPlannerTerminationCondition(giveUp));
        const ompl::base::PlannerStatus status = problem.setup->solve(stop);
        if (status != ompl::base::PlannerStatus::EXACT_SOLUTION)
        {
            std::printf("not solved within %g s (%s)\n", giveUp, status.asString().c_str());
            return 2;
        }

        // 4. What it found. The objective's cost is the smallest clearance OMPL sampled along the motions (it
        //    leaves out the start state); the smallest clearance at the path's states is asked of the checker.
        ompl::geometric::PathGeometric &path = problem.setup->getSolutionPath();
        double smallest = std::numeric_limits<double>::infinity();
        for (const ompl::base::State *s : path.getStates())
            smallest = std::min(smallest, problem.checker->clearance(s));
        const meshgap::CheckerStats stats = problem.checker->stats();
        std::printf("solved: %zu states, length %.4g, objective cost %.4g, smallest clearance at the states %.4g\n",
                    path.getStateCount(), path.length(),
                    path.cost(problem.setup->getOptimizationObjective()).value(), smallest);
        std::printf("checker: %llu validity and %llu clearance queries in %.3f s\n",
                    static_cast<unsigned long long>(stats.validityCalls),
                    static_cast<unsigned long long>(stats.clearanceCalls), stats.seconds);
        return 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
