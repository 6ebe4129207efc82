#include "meshgap/ompl/ProblemSetup.h"

#include <sstream>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "meshgap/Exception.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    namespace
    {
        std::string point(const Eigen::Vector3d &p)
        {
            std::ostringstream out;
            out.precision(6);
            out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
            return out.str();
        }

        /** \brief Why a start or goal pose is not free: the obstacle hit, where, and the signed distance. */
        std::string collisionReport(const Scene &scene, const SceneResult &r)
        {
            const Mesh &part = scene.obstacles()[r.obstacle]->surface();
            Eigen::AlignedBox3d box;
            for (const Eigen::Vector3d &v : part.vertices)
                box.extend(v);
            std::ostringstream text;
            text.precision(6);
            text << "is in collision with obstacle " << r.obstacle << " of " << scene.obstacles().size()
                 << " (the world part whose bounding box is centred at " << point(box.center()) << ")";
            if (r.onObstacle != Eigen::Vector3d::Zero() || r.onRobot != Eigen::Vector3d::Zero())
                text << " near " << point(r.onObstacle);
            if (r.distance < 0.0)
                text << ": signed distance " << r.distance << " (penetration depth " << -r.distance << ")";
            else
                text << ": the surfaces touch or cross (signed distance 0; no penetration depth computed)";
            return text.str();
        }
    }  // namespace

    OmplProblem setupProblem(const ProblemConfig &config, ClearanceChecker::Mode mode, const std::string &objective,
                             const BodyOptions &bodies, const ObjectiveOptions &objectiveOptions)
    {
        namespace ob = ompl::base;
        if (!config.volume)
            throw Exception(config.file, "no volume (volume.min.* and volume.max.*): the planner needs bounds");
        if (!config.goal)
            throw Exception(config.file, "no goal (goal.x, goal.y" + std::string(config.planar ? ")" : ", goal.z)"));
        if (!config.control.empty())
            throw Exception(config.file, "control = " + config.control + ": a control problem (OMPL.app's " +
                                             config.control + " model) is not planned by meshgap; its geometry "
                                             "answers distance queries (meshgap_distance, Python's Scene)");
        OmplProblem problem;
        problem.scene = Scene::fromMeshes(loadRobotMesh(config.robot, config.planar),
                                          loadMesh(config.world), bodies);

        const int dimensions = config.planar ? 2 : 3;
        ob::RealVectorBounds bounds(dimensions);
        for (int k = 0; k < dimensions; ++k)
        {
            bounds.setLow(k, config.volume->min()[k]);
            bounds.setHigh(k, config.volume->max()[k]);
        }
        ob::StateSpacePtr space;
        if (config.planar)
        {
            auto se2 = std::make_shared<ob::SE2StateSpace>();
            se2->setBounds(bounds);
            space = se2;
        }
        else
        {
            auto se3 = std::make_shared<ob::SE3StateSpace>();
            se3->setBounds(bounds);
            space = se3;
        }
        problem.setup = std::make_shared<ompl::geometric::SimpleSetup>(space);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        problem.checker = std::make_shared<ClearanceChecker>(si, problem.scene, mode);
        problem.setup->setStateValidityChecker(problem.checker);

        ob::ScopedState<> start(space), goal(space);
        stateFromPose(*space, config.start, start.get());
        stateFromPose(*space, *config.goal, goal.get());
        for (const auto &[label, state] : {std::make_pair("start", &start), std::make_pair("goal", &goal)})
        {
            if (!si->satisfiesBounds(state->get()))
                throw Exception(config.file, std::string(label) + " lies outside the volume");
            if (!problem.checker->isValid(state->get()))
            {
                // Exact answer for the message, whatever the checker's mode.
                SceneRequest request;
                SceneResult r;
                problem.scene->distance(poseFromState(*space, state->get()), request, r);
                throw Exception(config.file, std::string(label) + " " + collisionReport(*problem.scene, r));
            }
        }
        problem.setup->setStartAndGoalStates(start, goal);

        problem.objective = !objective.empty() ? objective : (config.objective.empty() ? "length" : config.objective);
        try
        {
            problem.setup->setOptimizationObjective(allocObjective(problem.objective, si, objectiveOptions));
        }
        catch (const Exception &e)
        {
            throw Exception(config.file, e.what());
        }
        if (config.objectiveThreshold)
            problem.setup->getOptimizationObjective()->setCostThreshold(ob::Cost(*config.objectiveThreshold));
        if (!config.sampler.empty())
            setValidStateSampler(*si, config.sampler, config.file + ": [problem] sampler");  // as OMPL.app reads it
        return problem;
    }
}  // namespace meshgap
