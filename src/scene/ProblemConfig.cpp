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

        /** \brief The volume, if given: all of its keys (four when planar) or none. */
        void readVolume(const ProblemKeys &problem, const std::string &path, ProblemConfig &config)
        {
            static const char *bounds[] = {"volume.min.x", "volume.min.y", "volume.min.z",
                                           "volume.max.x", "volume.max.y", "volume.max.z"};
            int given = 0;
            for (const char *key : bounds)
                given += problem.has(key);
            const int needed = config.planar ? 4 : 6;  // planar: no volume.*.z (rejected before)
            if (given == needed)
            {
                const Eigen::Vector3d lo(problem.num(bounds[0], 0), problem.num(bounds[1], 0), problem.num(bounds[2], 0));
                const Eigen::Vector3d hi(problem.num(bounds[3], 0), problem.num(bounds[4], 0), problem.num(bounds[5], 0));
                if ((hi.array() <= lo.array()).head(needed / 2).any())
                    throw Exception(problem.where("volume.max.x"), "volume.max must exceed volume.min on every axis");
                config.volume = Eigen::AlignedBox3d(lo, hi);
            }
            else if (given > 0)
                throw Exception(excerpt(path), config.planar
                                                   ? "a planar volume needs the four keys volume.min.x/y, "
                                                     "volume.max.x/y (found " +
                                                         std::to_string(given) + ")"
                                                   : "volume needs all six keys volume.min.x .. volume.max.z (found " +
                                                         std::to_string(given) + ")");
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
        config.file = path;
        config.benchmark = file.benchmark;
        config.planners = file.planners;
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
        config.name = problem.has("name") ? problem.value("name") : fs::path(path).stem().string();
        config.start = poseOf(problem, "start", config.planar);
        if (problem.has("goal.x") || problem.has("goal.y") || problem.has("goal.z"))
            config.goal = poseOf(problem, "goal", config.planar);
        readVolume(problem, path, config);
        checkInsideVolume(problem, config);
        if (problem.has("control"))
        {
            config.control = problem.value("control");
            const std::vector<std::string> &models = controlModelNames();
            if (std::find(models.begin(), models.end(), config.control) == models.end())
                throw Exception(problem.where("control"),
                                "unknown control model " + quote(config.control) + " (" + joinNames(models) + ")");
        }
        if (problem.has("objective"))
            config.objective = problem.value("objective");
        if (problem.has("objective.threshold"))
            config.objectiveThreshold = problem.num("objective.threshold", 0.0);
        if (problem.has("sampler"))
            config.sampler = problem.value("sampler");
        return config;
    }
}  // namespace meshgap
