#include "meshgap/ompl/ProblemSetup.h"

#include <sstream>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "meshgap/Exception.h"
#include "meshgap/ompl/ControlModels.h"
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
            if (r.onB != Eigen::Vector3d::Zero() || r.onA != Eigen::Vector3d::Zero())
                text << " near " << point(r.onB);
            if (r.distance < 0.0)
                text << ": signed distance " << r.distance << " (penetration depth " << -r.distance << ")";
            else
                text << ": the surfaces touch or cross (signed distance 0; no penetration depth computed)";
            return text.str();
        }

        /** \brief The cfg's volume as pose bounds: x, y (and z unless planar). */
        ompl::base::RealVectorBounds poseBounds(const ProblemConfig &config)
        {
            const int dimensions = config.planar ? 2 : 3;
            ompl::base::RealVectorBounds bounds(dimensions);
            for (int k = 0; k < dimensions; ++k)
            {
                bounds.setLow(k, config.volume->min()[k]);
                bounds.setHigh(k, config.volume->max()[k]);
            }
            return bounds;
        }

        /** \brief The cfg's start and goal poses in \e space (its other components zero), each checked in bounds
            and free. */
        std::pair<ompl::base::ScopedState<>, ompl::base::ScopedState<>>
        startAndGoal(const ProblemConfig &config, const ompl::base::SpaceInformation &si, const Scene &scene,
                     const ClearanceChecker &checker)
        {
            const ompl::base::StateSpacePtr &space = si.getStateSpace();
            ompl::base::ScopedState<> start(space), goal(space);
            start = 0.0;
            goal = 0.0;
            stateFromPose(*space, config.start, start.get());
            stateFromPose(*space, *config.goal, goal.get());
            for (const auto &[label, state] : {std::make_pair("start", &start), std::make_pair("goal", &goal)})
            {
                if (!si.satisfiesBounds(state->get()))
                    throw Exception(config.file, std::string(label) + " lies outside the volume");
                if (!checker.isValid(state->get()))
                {
                    // Exact answer for the message, whatever the checker's mode.
                    SceneRequest request;
                    SceneResult r;
                    scene.distance(poseFromState(*space, state->get()), request, r);
                    throw Exception(config.file, std::string(label) + " " + collisionReport(scene, r));
                }
            }
            return {start, goal};
        }

        /** \brief The blimp turns about z only: its start and goal rotations must be rotations about z. */
        void checkTurnsAboutZ(const ProblemConfig &config)
        {
            for (const bool start : {true, false})
            {
                const Eigen::Matrix3d R = start ? config.start.linear() : config.goal->linear();
                if ((R.col(2) - Eigen::Vector3d::UnitZ()).norm() <= 1e-9)
                    continue;
                const Eigen::AngleAxisd turn(R);
                std::ostringstream angle;
                angle << turn.angle();
                throw Exception(config.file, std::string(start ? "start" : "goal") +
                                                 ": control = blimp turns about z only, but its rotation is about the "
                                                 "axis " + point(turn.axis()) + " (angle " + angle.str() + ")");
            }
        }

        void checkVolumeAndGoal(const ProblemConfig &config)
        {
            if (!config.volume)
                throw Exception(config.file, "no volume (volume.min.* and volume.max.*): the planner needs bounds");
            if (!config.goal)
                throw Exception(config.file,
                                "no goal (goal.x, goal.y" + std::string(config.planar ? ")" : ", goal.z)"));
        }
    }  // namespace

    OmplControlProblem setupControlProblem(const ProblemConfig &config, ClearanceChecker::Mode mode,
                                           const BodyOptions &bodies)
    {
        checkVolumeAndGoal(config);
        if (config.control.empty())
            throw Exception(config.file, "no control key: a geometric problem (setupProblem())");
        if (config.planar != controlModelIsPlanar(config.control))
            throw Exception(config.file, "control = " + config.control +
                                             (config.planar ? " moves in space (SE(3)): the problem must give start.z "
                                                              "and goal.z (and the volume's z)" :
                                                              " is a planar model (x, y, theta): the problem must be "
                                                              "planar (no start.z)"));
        if (config.control == "blimp")
            checkTurnsAboutZ(config);
        ompl::control::SpaceInformationPtr si;
        try
        {
            si = controlSpaceInformation(config.control, poseBounds(config));
        }
        catch (const Exception &e)
        {
            throw Exception(config.file, e.what());
        }
        OmplControlProblem problem;
        problem.scene = Scene::fromMeshes(loadRobotMesh(config.robot, config.planar), loadMesh(config.world), bodies);
        problem.setup = std::make_shared<ompl::control::SimpleSetup>(si);
        problem.checker = std::make_shared<ClearanceChecker>(si, problem.scene, mode);
        problem.setup->setStateValidityChecker(problem.checker);
        const auto [start, goal] = startAndGoal(config, *si, *problem.scene, *problem.checker);
        problem.setup->setStartAndGoalStates(start, goal);
        return problem;
    }

    OmplProblem setupProblem(const ProblemConfig &config, ClearanceChecker::Mode mode, const std::string &objective,
                             const BodyOptions &bodies, const ObjectiveOptions &objectiveOptions)
    {
        namespace ob = ompl::base;
        checkVolumeAndGoal(config);
        if (!config.control.empty())
            throw Exception(config.file, "control = " + config.control + ": a control problem (OMPL.app's " +
                                             config.control + " model), set up by setupControlProblem()");
        OmplProblem problem;
        problem.scene = Scene::fromMeshes(loadRobotMesh(config.robot, config.planar),
                                          loadMesh(config.world), bodies);

        const ob::RealVectorBounds bounds = poseBounds(config);
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

        const auto [start, goal] = startAndGoal(config, *si, *problem.scene, *problem.checker);
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
