// Example: PRM* with a weighted objective, path length plus w times the integral of 1/clearance.
//
//   meshgap_example_prmstar_weighted_clearance problem.cfg [seconds] [weight] [give-up seconds]
//
// It optimises for `seconds` (default 5), longer if it has no solution by then (until `give-up seconds`, by default
// ten times as long).
//
// The clearance term (OMPL's integral of 1/clearance along the path) makes paths that pass close to obstacles
// expensive; the weight w, a length, sets the trade: at clearance w a piece of path costs twice its length. With no
// weight given, meshgap uses a tenth of the robot's radius. The two terms are also printed apart, so you can see the
// trade PRM* made.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/planners/prm/PRMstar.h>

#include "meshgap/ompl/Objectives.h"
#include "meshgap/ompl/ProblemSetup.h"

int main(int argc, char **argv)
{
    if (argc < 2)
    {
        std::fprintf(stderr, "usage: %s problem.cfg [seconds] [weight (0: the default)] [give-up seconds]\n", argv[0]);
        return 1;
    }
    const double seconds = argc > 2 ? std::atof(argv[2]) : 5.0;
    const double giveUp = argc > 4 ? std::atof(argv[4]) : 10.0 * seconds;
    try
    {
        meshgap::ObjectiveOptions objective;
        if (argc > 3)
            objective.weight = std::atof(argv[3]);
        meshgap::OmplProblem problem = meshgap::setupProblem(meshgap::readProblemConfig(argv[1]),
                                                             meshgap::ClearanceChecker::Mode::CERTIFIED, "weighted",
                                                             meshgap::BodyOptions(), objective);
        ompl::base::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        auto prmstar = std::make_shared<ompl::geometric::PRMstar>(si);
        problem.setup->setPlanner(prmstar);
        // Optimise for `seconds`, but do not give up before a first solution (up to `giveUp` seconds). PRM* hands its
        // problem definition a solution only when it returns, but reports its best cost as it runs (NaN before the
        // first solution; read as OMPL's Benchmark reads it).
        namespace ob = ompl::base;
        const auto bestCost = prmstar->getPlannerProgressProperties().at("best cost REAL");
        const ob::PlannerTerminationCondition stop = ob::plannerOrTerminationCondition(
            ob::plannerAndTerminationCondition(
                ob::timedPlannerTerminationCondition(seconds),
                ob::PlannerTerminationCondition([bestCost] { return std::isfinite(std::atof(bestCost().c_str())); })),
            ob::timedPlannerTerminationCondition(giveUp));
        const ompl::base::PlannerStatus status = problem.setup->solve(stop);
        if (status != ompl::base::PlannerStatus::EXACT_SOLUTION)
        {
            std::printf("not solved within %g s (%s)\n", giveUp, status.asString().c_str());
            return 2;
        }

        ompl::geometric::PathGeometric &path = problem.setup->getSolutionPath();
        // Each term on its own, with the same objectives the weighted one adds up.
        const double length = path.cost(meshgap::allocObjective("length", si)).value();
        const double inverseClearance = path.cost(meshgap::allocObjective("clearance", si)).value();
        const double total = path.cost(problem.setup->getOptimizationObjective()).value();
        std::printf("solved: %zu states, length %.4g, integral of 1/clearance %.4g, weighted cost %.4g\n",
                    path.getStateCount(), length, inverseClearance, total);
        return 0;
    }
    catch (const std::exception &e)
    {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
