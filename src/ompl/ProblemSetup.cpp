#include "meshgap/ompl/ProblemSetup.h"

#include <ompl/base/objectives/MaximizeMinClearanceObjective.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    namespace
    {
        void setState(ompl::base::ScopedState<ompl::base::SE3StateSpace> &s, const Eigen::Isometry3d &X)
        {
            const Eigen::Quaterniond q(X.linear());
            s->setXYZ(X.translation().x(), X.translation().y(), X.translation().z());
            s->rotation().x = q.x();
            s->rotation().y = q.y();
            s->rotation().z = q.z();
            s->rotation().w = q.w();
        }
    }  // namespace

    OmplProblem setupProblem(const ProblemConfig &config, ClearanceChecker::Mode mode, const std::string &objective,
                             const BodyOptions &bodies)
    {
        if (!config.volume)
            throw Exception(config.file, "no volume (volume.min.* and volume.max.*): the planner needs bounds");
        if (!config.goal)
            throw Exception(config.file, "no goal (goal.x, goal.y, goal.z)");
        OmplProblem problem;
        problem.scene = Scene::fromMeshes(loadRobotMesh(config.robot), loadMesh(config.world), bodies);

        auto space = std::make_shared<ompl::base::SE3StateSpace>();
        ompl::base::RealVectorBounds bounds(3);
        for (int k = 0; k < 3; ++k)
        {
            bounds.setLow(k, config.volume->min()[k]);
            bounds.setHigh(k, config.volume->max()[k]);
        }
        space->setBounds(bounds);
        problem.setup = std::make_shared<ompl::geometric::SimpleSetup>(space);
        const ompl::base::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        problem.checker = std::make_shared<ClearanceChecker>(si, problem.scene, mode);
        problem.setup->setStateValidityChecker(problem.checker);

        ompl::base::ScopedState<ompl::base::SE3StateSpace> start(space), goal(space);
        setState(start, config.start);
        setState(goal, *config.goal);
        for (const auto &[label, state] : {std::make_pair("start", &start), std::make_pair("goal", &goal)})
        {
            if (!si->satisfiesBounds(state->get()))
                throw Exception(config.file, std::string(label) + " lies outside the volume");
            if (!problem.checker->isValid(state->get()))
                throw Exception(config.file, std::string(label) + " is in collision");
        }
        problem.setup->setStartAndGoalStates(start, goal);

        problem.objective = !objective.empty() ? objective : (config.objective.empty() ? "length" : config.objective);
        if (problem.objective == "length")
            problem.setup->setOptimizationObjective(std::make_shared<ompl::base::PathLengthOptimizationObjective>(si));
        else if (problem.objective == "max_min_clearance")
            problem.setup->setOptimizationObjective(std::make_shared<ompl::base::MaximizeMinClearanceObjective>(si));
        else
            throw Exception(config.file, "unknown objective '" + problem.objective +
                                             "' (valid: length, max_min_clearance)");
        if (config.objectiveThreshold)
            problem.setup->getOptimizationObjective()->setCostThreshold(ompl::base::Cost(*config.objectiveThreshold));
        return problem;
    }
}  // namespace meshgap
