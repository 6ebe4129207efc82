#include "meshgap/scene/ProblemConfig.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"
#include "meshgap/scene/ConfigFile.h"
#include "meshgap/scene/Pose.h"

namespace meshgap
{
    namespace
    {
        using ProblemKeys = ConfigKeys;

        bool singleBodyKey(const std::string &key)
        {
            static const std::set<std::string> known = {
                "name",         "robot",        "world",        "objective",    "objective.threshold", "sampler", "control",
                "start.x",      "start.y",      "start.z",      "start.theta",  "start.axis.x",        "start.axis.y",
                "start.axis.z", "goal.x",       "goal.y",       "goal.z",       "goal.theta",          "goal.axis.x",
                "goal.axis.y",  "goal.axis.z",  "volume.min.x", "volume.min.y", "volume.min.z",        "volume.max.x",
                "volume.max.y", "volume.max.z"};
            return known.count(key) > 0;
        }

        /** \brief A mesh file named by \e key, relative to the cfg's folder; it must exist. */
        std::string meshPath(const ProblemKeys &problem, const std::string &key, const std::filesystem::path &folder)
        {
            std::filesystem::path p(problem.value(key));
            if (p.is_relative())
                p = folder / p;
            std::error_code error;  // a name too long or a folder that cannot be searched: checkInputFile() says so
            if (!std::filesystem::exists(p, error) && !error)
                throw Exception(problem.where(key), key + " mesh " + quote(p.string()) + " does not exist");
            try
            {
                checkInputFile(p.string());
            }
            catch (const Exception &e)
            {
                throw Exception(problem.where(key), key + " mesh " + e.what());
            }
            return p.lexically_normal().string();
        }

        /** \brief The pose of \e prefix (start or goal): position, and theta about the axis (z when planar). */
        Eigen::Isometry3d poseOf(const ProblemKeys &problem, const std::string &prefix, bool planar)
        {
            const Eigen::Vector3d position(problem.num(prefix + ".x", 0), problem.num(prefix + ".y", 0),
                                           problem.num(prefix + ".z", 0));
            const double theta = problem.num(prefix + ".theta", 0.0);
            const Eigen::Vector3d axis = planar ? Eigen::Vector3d::UnitZ() :
                                                  Eigen::Vector3d(problem.num(prefix + ".axis.x", 1),
                                                                  problem.num(prefix + ".axis.y", 0),
                                                                  problem.num(prefix + ".axis.z", 0));
            if (theta != 0.0 && axis.norm() == 0.0)
                throw Exception(problem.where(prefix + ".theta"), prefix + ".axis is the zero vector");
            return poseFromAxisAngle(position, theta, axis);
        }

        const char *const VOLUME_KEYS[] = {"volume.min.x", "volume.min.y", "volume.min.z",
                                           "volume.max.x", "volume.max.y", "volume.max.z"};

        /** \brief The volume, if given: all of its keys (four, x and y, when planar) or none. */
        void readVolume(const ProblemKeys &problem, ProblemSettings &settings)
        {
            if (settings.planar)
                for (const char *key : {"volume.min.z", "volume.max.z"})
                    if (problem.has(key))
                        throw Exception(problem.where(key), quote(key) +
                                                                " in a planar problem (no start.z: SE(2), x and y "
                                                                "only); give start.z for a 3D problem");
            int given = 0;
            for (const char *key : VOLUME_KEYS)
                given += problem.has(key);
            const int needed = settings.planar ? 4 : 6;
            if (given == 0)
                return;
            if (given != needed)
                throw Exception(excerpt(problem.path()), settings.planar
                                                             ? "a planar volume needs the four keys volume.min.x/y, "
                                                               "volume.max.x/y (found " +
                                                                   std::to_string(given) + ")"
                                                             : "volume needs all six keys volume.min.x .. "
                                                               "volume.max.z (found " +
                                                                   std::to_string(given) + ")");
            Eigen::Vector3d lo, hi;
            for (int k = 0; k < 3; ++k)
            {
                lo[k] = problem.num(VOLUME_KEYS[k], 0.0);
                hi[k] = problem.num(VOLUME_KEYS[3 + k], 0.0);
                if (k < needed / 2 && !(hi[k] > lo[k]))
                    throw Exception(problem.where(VOLUME_KEYS[3 + k]),
                                    "volume.max must exceed volume.min on every axis");
            }
            settings.volume = Eigen::AlignedBox3d(lo, hi);
        }

        /** \brief A start or goal outside the volume is no problem any planner can solve: say so here, for every
            tool. */
        void checkInsideVolume(const ProblemKeys &problem, const ProblemConfig &config)
        {
            if (!config.volume)
                return;
            const int axes = config.planar ? 2 : 3;
            auto inside = [&](const Eigen::Vector3d &p) {
                for (int k = 0; k < axes; ++k)
                    if (!(p[k] >= config.volume->min()[k] && p[k] <= config.volume->max()[k]))
                        return false;
                return true;
            };
            auto text = [&](const Eigen::Vector3d &p) {
                std::ostringstream out;
                out << "(" << p.head(axes).transpose() << ")";
                return out.str();
            };
            for (const char *label : {"start", "goal"})
            {
                const bool isStart = std::string(label) == "start";
                if (!isStart && !config.goal)
                    continue;
                const Eigen::Vector3d p = (isStart ? config.start : *config.goal).translation();
                if (!inside(p))
                    throw Exception(problem.where(std::string(label) + ".x"),
                                    std::string(label) + " " + text(p) + " lies outside the volume " +
                                        text(config.volume->min()) + " .. " + text(config.volume->max()));
            }
        }
    }  // namespace

    const std::vector<std::string> &controlModelNames()
    {
        static const std::vector<std::string> names = {"kinematic_car", "dynamic_car", "blimp", "quadrotor"};
        return names;
    }

    ProblemConfig readProblemConfig(const std::string &path)
    {
        namespace fs = std::filesystem;
        const ConfigFile file = readConfigFile(path);
        if (const ConfigEntry *key = robotProblemKey(file))
            throw Exception(key->where, quote(key->key) +
                                            " makes this a robot problem (a URDF robot or several "
                                            "bodies), not a single-body one: read it as a robot problem "
                                            "(readRobotProblem())");
        ProblemConfig config;
        const ProblemKeys problem(file, singleBodyKey);
        for (const char *key : {"robot", "world", "start.x", "start.y"})
            problem.require(key);
        // OMPL.app's 2D problems have no start.z: SE(2), the yaw in start.theta.
        config.planar = !problem.has("start.z");
        if (config.planar)
            for (const char *key : {"goal.z", "start.axis.x", "start.axis.y", "start.axis.z", "goal.axis.x",
                                    "goal.axis.y", "goal.axis.z", "volume.min.z", "volume.max.z"})
                if (problem.has(key))
                    throw Exception(problem.where(key), quote(key) +
                                                            " in a planar problem (no start.z: SE(2), theta is the "
                                                            "yaw about z); give start.z for a 3D problem");
        const fs::path folder = fs::path(path).parent_path();
        config.robot = meshPath(problem, "robot", folder);
        config.world = meshPath(problem, "world", folder);
        config.start = poseOf(problem, "start", config.planar);
        if (problem.has("goal.x") || problem.has("goal.y") || problem.has("goal.z"))
            config.goal = poseOf(problem, "goal", config.planar);
        readProblemSettings(file, problem, config);
        checkInsideVolume(problem, config);
        if (problem.has("control"))
        {
            config.control = problem.value("control");
            const std::vector<std::string> &models = controlModelNames();
            if (std::find(models.begin(), models.end(), config.control) == models.end())
                throw Exception(problem.where("control"),
                                "unknown control model " + quote(config.control) + " (" + joinNames(models) + ")");
        }
        return config;
    }

    void readProblemSettings(const ConfigFile &file, const ConfigKeys &keys, ProblemSettings &settings)
    {
        settings.file = file.path;
        settings.name = keys.has("name") ? keys.value("name") : std::filesystem::path(file.path).stem().string();
        settings.benchmark = file.benchmark;
        settings.planners = file.planners;
        readVolume(keys, settings);
        if (keys.has("objective"))
            settings.objective = keys.value("objective");
        if (keys.has("objective.threshold"))
            settings.objectiveThreshold = keys.num("objective.threshold", 0.0);
        if (keys.has("sampler"))
            settings.sampler = keys.value("sampler");
    }
}  // namespace meshgap
