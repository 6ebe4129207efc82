#include "meshgap/robot/RobotProblem.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/MultiBodyRobot.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/scene/ConfigFile.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/RobotMesh.h"

namespace meshgap
{
    namespace
    {
        namespace fs = std::filesystem;

        const char *const POSE_FIELDS[] = {"x", "y", "z", "theta", "axis.x", "axis.y", "axis.z"};

        /** \brief The N of "robot.N", or 0 when \e key is no such key. */
        std::size_t bodyNumber(const std::string &key, const std::string &prefix, std::string *rest = nullptr)
        {
            if (key.compare(0, prefix.size(), prefix) != 0)
                return 0;
            std::size_t end = prefix.size();
            while (end < key.size() && std::isdigit(static_cast<unsigned char>(key[end])))
                ++end;
            if (end == prefix.size() || end - prefix.size() > 6 || key[prefix.size()] == '0')
                return 0;
            if (rest)
                *rest = key.substr(end);
            else if (end != key.size())
                return 0;
            return std::stoul(key.substr(prefix.size(), end - prefix.size()));
        }

        bool robotKey(const std::string &key)
        {
            static const std::set<std::string> known = {
                "name",         "world",        "objective",    "objective.threshold", "sampler", "scene", "request",
                "robot.urdf",   "robot.srdf",   "robot.package_path", "attach", "start.joints",
                "goal.joints",  "volume.min.x", "volume.min.y", "volume.min.z", "volume.max.x",
                "volume.max.y", "volume.max.z"};
            if (known.count(key) || bodyNumber(key, "robot.") > 0)
                return true;
            for (const char *prefix : {"start.", "goal."})
            {
                std::string rest;
                if (bodyNumber(key, prefix, &rest) > 0 && !rest.empty())
                    for (const char *field : POSE_FIELDS)
                        if (rest == std::string(".") + field)
                            return true;
            }
            return false;
        }

        /** \brief The file \e key names, relative to \e folder; it must exist. */
        std::string existingFile(const ConfigKeys &keys, const std::string &key, const std::string &text,
                                 const fs::path &folder)
        {
            fs::path p(text);
            if (p.is_relative())
                p = folder / p;
            std::error_code error;  // a name too long or a folder that cannot be searched: checkInputFile() says so
            if (!fs::exists(p, error) && !error)
                throw Exception(keys.where(key), key + " file " + quote(p.string()) + " does not exist");
            try
            {
                checkInputFile(p.string());
            }
            catch (const Exception &e)
            {
                throw Exception(keys.where(key), key + " file " + e.what());
            }
            return p.lexically_normal().string();
        }

        /** \brief Run \e f; a meshgap::Exception it throws is rethrown prefixed by where \e key is given. */
        template <typename F>
        auto naming(const ConfigKeys &keys, const std::string &key, F &&f) -> decltype(f())
        {
            try
            {
                return f();
            }
            catch (const Exception &e)
            {
                throw Exception(keys.where(key), key + ": " + e.what());
            }
        }

        /** \brief The folders of robot.package_path (split at ':'), or empty. */
        std::vector<std::string> packagePath(const ConfigKeys &keys, const fs::path &folder)
        {
            std::vector<std::string> dirs;
            if (!keys.has("robot.package_path"))
                return dirs;
            std::stringstream list(keys.value("robot.package_path"));
            std::string dir;
            while (std::getline(list, dir, ':'))
                if (!dir.empty())
                    dirs.push_back(fs::path(dir).is_relative() ? (folder / dir).lexically_normal().string() : dir);
            return dirs;
        }

        /** \brief The obstacles: the world mesh's connected parts. */
        void readWorld(const ConfigKeys &keys, const fs::path &folder, const BodyOptions &options,
                       RobotProblem &problem)
        {
            if (!keys.has("world") && !problem.scene.empty())
                return;  // the scene's obstacles alone
            keys.require("world");
            problem.world = existingFile(keys, "world", keys.value("world"), folder);
            naming(keys, "world",
                   [&]
                   {
                       for (Mesh &part : splitComponents(loadMesh(problem.world)))
                           problem.obstacles.push_back(Body::build(std::move(part), options));
                       return 0;
                   });
        }

        /** \brief The names of the movable joints' values, in state order. */
        std::string jointNames(const UrdfRobot &robot)
        {
            std::string names;
            for (std::size_t i = robot.jointOffset(); i < robot.dimension(); ++i)
                names += (names.empty() ? "" : " ") + robot.stateName(i);
            return names;
        }

        /** \brief Check the joint values \e key gives: their count, the floating base's quaternion and the joints'
            limits. */
        void checkJoints(const ConfigKeys &keys, const std::string &key, const std::vector<double> &q,
                         const UrdfRobot &robot)
        {
            const std::size_t joints = robot.variables().size(), offset = robot.jointOffset();
            if (q.size() != robot.dimension())
                throw Exception(keys.where(key),
                                key + " has " + std::to_string(q.size()) + " numbers; robot " + quote(robot.name()) +
                                    " takes " + (offset ? "7 (the floating base's x y z qx qy qz qw) + " : "") +
                                    std::to_string(joints) + " (its movable joints: " + jointNames(robot) + ")" +
                                    (offset ? "" : ", or 7 more first for a floating base (x y z qx qy qz qw)"));
            if (offset && std::abs(Eigen::Vector4d(q[3], q[4], q[5], q[6]).norm() - 1.0) > 1e-6)
                throw Exception(keys.where(key), key + ": the floating base's quaternion (numbers 4 to 7) is not of "
                                                       "unit length");
            for (std::size_t i = offset; i < q.size(); ++i)
            {
                const double value = q[i], lower = robot.stateLower(i), upper = robot.stateUpper(i);
                if (value < lower || value > upper)
                {
                    std::ostringstream text;
                    text << key << ": joint " << quote(robot.stateName(i)) << " (number " << i + 1 << ") = " << value
                         << " is outside its limits [" << lower << ", " << upper << "]";
                    throw Exception(keys.where(key), text.str());
                }
            }
        }

        /** \brief The attach line: the payload mesh fixed to its link. */
        void attachPayload(const ConfigKeys &keys, const fs::path &folder, const BodyOptions &options,
                           RobotModel &robot)
        {
            std::istringstream fields(keys.value("attach"));
            std::string mesh, link, rest;
            fields >> mesh >> link;
            std::getline(fields, rest);
            if (mesh.empty() || link.empty())
                throw Exception(keys.where("attach"),
                                "attach = MESH LINK x y z qx qy qz qw: found " + quote(keys.value("attach")));
            const Eigen::Isometry3d X = naming(keys, "attach", [&] { return parsePose(rest, "the pose"); });
            if (robot.findFrame(link) == RobotModel::NONE)
            {
                std::string links;
                for (const RobotFrame &f : robot.frames())
                    links += (links.empty() ? "" : ", ") + f.name;
                throw Exception(keys.where("attach"),
                                "attach: the robot has no link " + quote(link) + " (its links: " + links + ")");
            }
            const std::string path = existingFile(keys, "attach", mesh, folder);
            naming(keys, "attach", [&] { return robot.attach("payload", loadMesh(path), link, X, options); });
        }

        /** \brief robot.urdf, robot.srdf, start.joints and goal.joints. */
        void readUrdfKeys(const ConfigKeys &keys, const fs::path &folder, RobotProblem &problem,
                          const BodyOptions &options)
        {
            UrdfOptions urdfOptions;
            urdfOptions.packagePath = packagePath(keys, folder);
            urdfOptions.body = options;
            const std::string urdf = existingFile(keys, "robot.urdf", keys.value("robot.urdf"), folder);
            const std::vector<double> start = keys.numbers("start.joints");
            UrdfRobotPtr robot = naming(keys, "robot.urdf", [&] { return UrdfRobot::load(urdf, urdfOptions); });
            if (robot->dimension() > 0)
                keys.require("start.joints");  // a fixed robot (no movable joint) has a state of no numbers
            if (start.size() == robot->dimension() + 7)
            {
                urdfOptions.floatingBase = true;
                robot = naming(keys, "robot.urdf", [&] { return UrdfRobot::load(urdf, urdfOptions); });
            }
            checkJoints(keys, "start.joints", start, *robot);
            problem.start = start;
            if (keys.has("goal.joints"))
            {
                problem.goal = keys.numbers("goal.joints");
                checkJoints(keys, "goal.joints", *problem.goal, *robot);
            }
            // The payload first, so that the SRDF can name it.
            if (keys.has("attach"))
                attachPayload(keys, folder, options, *robot);
            if (keys.has("robot.srdf"))
            {
                const std::string srdf = existingFile(keys, "robot.srdf", keys.value("robot.srdf"), folder);
                naming(keys, "robot.srdf", [&] { return (readSrdf(*robot, srdf), 0); });
            }
            problem.robot = robot;
        }

        /** \brief robot.urdf, robot.srdf, scene and request: the robot, obstacles, start and goal MoveIt's files
            give. */
        void readMoveItKeys(const ConfigKeys &keys, const fs::path &folder, const BodyOptions &options,
                            RobotProblem &problem)
        {
            MoveItFiles files;
            files.urdf = existingFile(keys, "robot.urdf", keys.value("robot.urdf"), folder);
            if (keys.has("robot.srdf"))
                files.srdf = existingFile(keys, "robot.srdf", keys.value("robot.srdf"), folder);
            for (const char *key : {"scene", "request"})
                if (keys.has(key))
                    (key[0] == 's' ? files.scene : files.request) = existingFile(keys, key, keys.value(key), folder);
            files.packagePath = packagePath(keys, folder);
            const std::string key = keys.has("request") ? "request" : "scene";
            RobotProblem read = naming(keys, key, [&] { return readMoveItProblem(files, options); });
            problem.robot = read.robot;
            problem.obstacles = std::move(read.obstacles);
            problem.obstacleNames = std::move(read.obstacleNames);
            problem.allowedObstacles = std::move(read.allowedObstacles);
            problem.scene = files.scene;
            problem.request = files.request;
            problem.start = read.start;
            problem.goal = read.goal;
        }

        /** \brief robot.urdf, robot.srdf, attach, start.joints and goal.joints (or scene and request). */
        void readUrdfProblem(const ConfigKeys &keys, const fs::path &folder, const BodyOptions &options,
                             RobotProblem &problem)
        {
            if (keys.has("scene") || keys.has("request"))
            {
                readMoveItKeys(keys, folder, options, problem);
                const auto &robot = static_cast<const UrdfRobot &>(*problem.robot);
                for (const char *key : {"start.joints", "goal.joints"})
                    if (keys.has(key))
                    {
                        checkJoints(keys, key, keys.numbers(key), robot);
                        (key[0] == 's' ? problem.start : problem.goal.emplace()) = keys.numbers(key);
                    }
                if (keys.has("attach"))
                    attachPayload(keys, folder, options, *problem.robot);
            }
            else
                readUrdfKeys(keys, folder, problem, options);  // attaches the payload before reading the SRDF
            problem.urdf = true;
        }

        /** \brief The state numbers of body \e prefix ("start.2"): x y theta, or x y z qx qy qz qw. */
        void appendBodyState(const ConfigKeys &keys, const std::string &prefix, bool planar, std::vector<double> &out)
        {
            for (const char *field : {".x", ".y"})
                keys.require(prefix + field);
            if (!planar)
                keys.require(prefix + ".z");
            const double theta = keys.num(prefix + ".theta", 0.0);
            if (planar)
            {
                out.insert(out.end(), {keys.num(prefix + ".x", 0), keys.num(prefix + ".y", 0), theta});
                return;
            }
            const Eigen::Vector3d axis(keys.num(prefix + ".axis.x", 1), keys.num(prefix + ".axis.y", 0),
                                       keys.num(prefix + ".axis.z", 0));
            if (theta != 0.0 && axis.norm() == 0.0)
                throw Exception(keys.where(prefix + ".theta"), prefix + ".axis is the zero vector");
            const Eigen::Isometry3d X = poseFromAxisAngle(
                Eigen::Vector3d(keys.num(prefix + ".x", 0), keys.num(prefix + ".y", 0), keys.num(prefix + ".z", 0)),
                theta, axis);
            const Eigen::Quaterniond r(X.linear());
            out.insert(out.end(), {X.translation().x(), X.translation().y(), X.translation().z(), r.x(), r.y(), r.z(),
                                   r.w()});
        }

        /** \brief The number of bodies (robot.1 .. robot.K); throws for a gap or a start.N / goal.N of no body. */
        std::size_t countBodies(const ConfigFile &file)
        {
            std::set<std::size_t> bodies;
            for (const ConfigEntry &e : file.problem)
                if (const std::size_t n = bodyNumber(e.key, "robot."))
                    bodies.insert(n);
            for (std::size_t n = 1; n <= bodies.size(); ++n)
                if (!bodies.count(n))
                    throw Exception(file.path, "robot." + std::to_string(*bodies.rbegin()) + " is given but robot." +
                                                   std::to_string(n) + " is not (bodies are numbered 1, 2, ...)");
            for (const ConfigEntry &e : file.problem)
                for (const char *prefix : {"start.", "goal."})
                {
                    std::string rest;
                    const std::size_t n = bodyNumber(e.key, prefix, &rest);
                    if (n > bodies.size())
                        throw Exception(e.where, quote(e.key) + " names body " + std::to_string(n) +
                                                     ", but there are " + std::to_string(bodies.size()) +
                                                     " (robot.1 ..)");
                }
            return bodies.size();
        }

        /** \brief robot.N, start.N.*, goal.N.*: a MultiBodyRobot. */
        void readBodies(const ConfigFile &file, const ConfigKeys &keys, const fs::path &folder,
                        const BodyOptions &options, RobotProblem &problem)
        {
            const std::size_t count = countBodies(file);
            problem.planar = true;
            for (std::size_t n = 1; n <= count; ++n)
                problem.planar = problem.planar && !keys.has("start." + std::to_string(n) + ".z");
            std::vector<MultiBodyRobot::Part> parts;
            bool anyGoal = false;
            std::string rest;
            for (const ConfigEntry &e : file.problem)
                anyGoal = anyGoal || bodyNumber(e.key, "goal.", &rest) > 0;
            std::vector<double> goal;
            for (std::size_t n = 1; n <= count; ++n)
            {
                const std::string id = std::to_string(n), key = "robot." + id;
                if (problem.planar)
                    for (const char *field : {".z", ".axis.x", ".axis.y", ".axis.z"})
                        for (const std::string prefix : {"start.", "goal."})
                            if (keys.has(prefix + id + field))
                                throw Exception(keys.where(prefix + id + field),
                                                quote(prefix + id + field) +
                                                    " in a planar problem (no start.N.z: "
                                                    "SE(2), theta is the yaw about z); give start.N.z for SE(3)");
                const std::string path = existingFile(keys, key, keys.value(key), folder);
                const Mesh mesh = naming(keys, key, [&] { return loadRobotMesh(path, problem.planar); });
                parts.push_back({key, Body::build(mesh, options), problem.planar ? RigidSpace::SE2 : RigidSpace::SE3});
                appendBodyState(keys, "start." + id, problem.planar, problem.start);
                if (anyGoal)
                    appendBodyState(keys, "goal." + id, problem.planar, goal);
            }
            problem.robot = std::make_shared<MultiBodyRobot>(parts);
            if (anyGoal)
                problem.goal = goal;
        }
    }  // namespace

    Problem readProblem(const std::string &path, const BodyOptions &options)
    {
        Problem problem;
        if (robotProblemKey(readConfigFile(path)))
            problem.robot = readRobotProblem(path, options);
        else
            problem.rigidBody = readProblemConfig(path);
        return problem;
    }

    RobotProblem rigidBodyProblem(const ProblemConfig &config, const BodyOptions &options)
    {
        RobotProblem problem;
        static_cast<ProblemSettings &>(problem) = config;  // file, name, planar, world, volume, objective, ...
        const RigidSpace space = config.planar ? RigidSpace::SE2 : RigidSpace::SE3;
        problem.robot = std::make_shared<RigidBodyRobot>(
            Body::build(loadRobotMesh(config.robot, config.planar), options), space);
        for (Mesh &part : splitComponents(loadMesh(config.world)))
            problem.obstacles.push_back(Body::build(std::move(part), options));  // as Scene::fromMeshes() splits it
        problem.start = rigidState(space, config.start);
        if (config.goal)
            problem.goal = rigidState(space, *config.goal);
        return problem;
    }

    RobotScenePtr planningScene(const RobotProblem &problem)
    {
        const auto scene = std::make_shared<RobotScene>(problem.robot, problem.obstacles, problem.allowedObstacles);
        if (!scene->selfPairs().empty())
            scene->tabulateSelfPairs();
        return scene;
    }

    RobotProblem readAnyRobotProblem(const std::string &path, const BodyOptions &options)
    {
        Problem problem = readProblem(path, options);
        return problem.robot ? std::move(*problem.robot) : rigidBodyProblem(*problem.rigidBody, options);
    }

    RobotProblem readRobotProblem(const std::string &path, const BodyOptions &options)
    {
        const ConfigFile file = readConfigFile(path);
        for (const ConfigEntry &e : file.problem)
            if (e.key == "robot")
                throw Exception(e.where, quote("robot = " + e.value) +
                                             " makes this a single-body problem (one mesh in "
                                             "SE(2) or SE(3)), not a robot problem: read it as a "
                                             "single-body problem (readProblemConfig())");
        const ConfigKeys keys(file, robotKey);
        const bool urdf = keys.has("robot.urdf");
        if (!urdf && !keys.has("robot.1"))
            throw Exception(excerpt(path),
                            "a robot problem needs robot.urdf = FILE (a URDF robot) or robot.1 = FILE, "
                            "robot.2 = FILE, ... (several bodies)");
        if (urdf && keys.has("robot.1"))
            throw Exception(keys.where("robot.1"), "robot.1 and robot.urdf in one problem: either a URDF robot "
                                                   "or several bodies");
        RobotProblem problem;
        const fs::path folder = fs::path(path).parent_path();
        if (urdf)
        {
            countBodies(file);  // no start.N / goal.N without bodies
            readUrdfProblem(keys, folder, options, problem);
        }
        else
        {
            for (const char *key :
                 {"robot.srdf", "robot.package_path", "attach", "start.joints", "goal.joints", "scene", "request"})
                if (keys.has(key))
                    throw Exception(keys.where(key), std::string(key) + " applies to a URDF robot (robot.urdf)");
            readBodies(file, keys, folder, options, problem);
        }
        readProblemSettings(file, keys, problem);  // after the bodies: planar is known
        readWorld(keys, folder, options, problem);
        return problem;
    }
}  // namespace meshgap
