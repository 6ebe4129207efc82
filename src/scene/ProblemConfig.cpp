// boost::program_options::parse_config_file reads this format too, but it reports neither the line of a bad entry
// nor keeps the [planner] order, so this small reader does; the grammar is the same INI subset OMPL.app uses
// ("key = value", "[section]", '#' comments).

#include "meshgap/scene/ProblemConfig.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <set>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/scene/Pose.h"

namespace meshgap
{
    namespace
    {
        std::string trim(const std::string &s)
        {
            const auto b = s.find_first_not_of(" \t\r");
            if (b == std::string::npos)
                return "";
            const auto e = s.find_last_not_of(" \t\r");
            return s.substr(b, e - b + 1);
        }

        double number(const std::string &value, const std::string &where, const std::string &key)
        {
            double x = 0.0;
            if (parseNumber(value, x) && std::isfinite(x))
                return x;
            throw Exception(where, key + " = '" + value + "' is not a finite number");
        }
    }  // namespace

    ProblemConfig readProblemConfig(const std::string &path)
    {
        namespace fs = std::filesystem;
        std::ifstream in(path);
        if (!fs::exists(path))
            throw Exception(path, "no such file");
        if (!in)
            throw Exception(path, "cannot open the problem file");

        static const std::set<std::string> problemKeys = {
            "name",         "robot",        "world",        "objective",    "objective.threshold", "sampler",
            "start.x",      "start.y",      "start.z",      "start.theta",  "start.axis.x",        "start.axis.y",
            "start.axis.z", "goal.x",       "goal.y",       "goal.z",       "goal.theta",          "goal.axis.x",
            "goal.axis.y",  "goal.axis.z",  "volume.min.x", "volume.min.y", "volume.min.z",        "volume.max.x",
            "volume.max.y", "volume.max.z"};
        ProblemConfig config;
        config.file = path;
        std::map<std::string, std::pair<std::string, std::string>> problem;  // key -> (value, "file:line")
        std::string section, line;
        for (std::size_t number = 1; std::getline(in, line); ++number)
        {
            const std::string where = path + ":" + std::to_string(number);
            line = trim(line);
            if (line.empty() || line[0] == '#' || line[0] == ';')
                continue;
            if (line.front() == '[')
            {
                if (line.back() != ']')
                    throw Exception(where, "malformed section header '" + line + "'");
                section = trim(line.substr(1, line.size() - 2));
                if (section != "problem" && section != "benchmark" && section != "planner")
                    throw Exception(where, "unknown section [" + section + "] (expected problem, benchmark, planner)");
                continue;
            }
            const auto eq = line.find('=');
            if (eq == std::string::npos)
                throw Exception(where, "expected 'key = value', found '" + line + "'");
            const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
            if (key.empty())
                throw Exception(where, "empty key");
            if (section.empty())
                throw Exception(where, "'" + key + "' is outside any [section]");
            if (section == "problem")
            {
                if (!problemKeys.count(key))
                    throw Exception(where, "unknown key '" + key + "' in [problem]");
                if (problem.count(key))
                    throw Exception(where, "'" + key + "' is given twice (first at " + problem[key].second + ")");
                problem[key] = {value, where};
            }
            else if (section == "benchmark")
                config.benchmark.emplace_back(key, value);
            else
                config.planners.emplace_back(key, value);
        }

        auto has = [&](const std::string &key) { return problem.count(key) > 0; };
        auto num = [&](const std::string &key, double fallback) {
            return has(key) ? number(problem[key].first, problem[key].second, key) : fallback;
        };
        auto require = [&](const std::string &key) {
            if (!has(key) || problem[key].first.empty())
                throw Exception(path, "missing required key '" + key + "' in [problem]");
        };
        for (const char *key : {"robot", "world", "start.x", "start.y"})
            require(key);
        // OMPL.app's 2D problems have no start.z: SE(2), the yaw in start.theta.
        config.planar = !has("start.z");
        if (config.planar)
            for (const char *key : {"goal.z", "start.axis.x", "start.axis.y", "start.axis.z", "goal.axis.x",
                                    "goal.axis.y", "goal.axis.z", "volume.min.z", "volume.max.z"})
                if (has(key))
                    throw Exception(problem[key].second, "'" + std::string(key) +
                                                             "' in a planar problem (no start.z: SE(2), theta is the "
                                                             "yaw about z); give start.z for a 3D problem");

        const fs::path folder = fs::path(path).parent_path();
        auto meshPath = [&](const std::string &key) {
            fs::path p(problem[key].first);
            if (p.is_relative())
                p = folder / p;
            if (!fs::exists(p))
                throw Exception(problem[key].second, key + " mesh '" + p.string() + "' does not exist");
            return p.lexically_normal().string();
        };
        config.robot = meshPath("robot");
        config.world = meshPath("world");
        config.name = has("name") ? problem["name"].first : fs::path(path).stem().string();

        auto pose = [&](const std::string &prefix) {
            const Eigen::Vector3d position(num(prefix + ".x", 0), num(prefix + ".y", 0), num(prefix + ".z", 0));
            const double theta = num(prefix + ".theta", 0.0);
            const Eigen::Vector3d axis = config.planar ? Eigen::Vector3d::UnitZ() :
                                                         Eigen::Vector3d(num(prefix + ".axis.x", 1),
                                                                         num(prefix + ".axis.y", 0),
                                                                         num(prefix + ".axis.z", 0));
            if (theta != 0.0 && axis.norm() == 0.0)
                throw Exception(problem[prefix + ".theta"].second, prefix + ".axis is the zero vector");
            return poseFromAxisAngle(position, theta, axis);
        };
        config.start = pose("start");
        if (has("goal.x") || has("goal.y") || has("goal.z"))
            config.goal = pose("goal");
        static const char *bounds[] = {"volume.min.x", "volume.min.y", "volume.min.z",
                                       "volume.max.x", "volume.max.y", "volume.max.z"};
        int given = 0;
        for (const char *key : bounds)
            given += has(key);
        const int needed = config.planar ? 4 : 6;  // planar: no volume.*.z (rejected above)
        if (given == needed)
        {
            const Eigen::Vector3d lo(num(bounds[0], 0), num(bounds[1], 0), num(bounds[2], 0));
            const Eigen::Vector3d hi(num(bounds[3], 0), num(bounds[4], 0), num(bounds[5], 0));
            if ((hi.array() <= lo.array()).head(needed / 2).any())
                throw Exception(problem["volume.max.x"].second, "volume.max must exceed volume.min on every axis");
            config.volume = Eigen::AlignedBox3d(lo, hi);
        }
        else if (given > 0)
            throw Exception(path, config.planar ? "a planar volume needs the four keys volume.min.x/y, volume.max.x/y "
                                                  "(found " + std::to_string(given) + ")" :
                                                "volume needs all six keys volume.min.x .. volume.max.z (found " +
                                                    std::to_string(given) + ")");
        // A start or goal outside the volume is no problem any planner can solve: say so here, for every tool.
        if (config.volume)
        {
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
                    throw Exception(problem[std::string(label) + ".x"].second,
                                    std::string(label) + " " + text(p) + " lies outside the volume " +
                                        text(config.volume->min()) + " .. " + text(config.volume->max()));
            }
        }
        if (has("objective"))
            config.objective = problem["objective"].first;
        if (has("objective.threshold"))
            config.objectiveThreshold = num("objective.threshold", 0.0);
        if (has("sampler"))
            config.sampler = problem["sampler"].first;
        return config;
    }
}  // namespace meshgap
