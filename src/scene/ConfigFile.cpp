// boost::program_options::parse_config_file reads this format too, but it reports neither the line of a bad entry
// nor keeps the [planner] order, so this small reader does; the grammar is the same INI subset OMPL.app uses
// ("key = value", "[section]", '#' comments). As in boost, a '#' anywhere starts a comment that runs to the end of the
// line ("robot.urdf = arm.urdf   # the arm" gives "arm.urdf"), so no value can hold a '#'.

#include "meshgap/scene/ConfigFile.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Limits.h"
#include "meshgap/Text.h"

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
            if (!parseNumber(value, x) || !std::isfinite(x))
                throw Exception(where, key + " = " + quote(value) + " is not a finite number");
            // An axis is a direction (normalised): any magnitude; every other number is a position, an angle, a size.
            if (std::abs(x) > MAX_MAGNITUDE && key.find("axis") == std::string::npos)
                throw Exception(where, key + " = " + quote(value) +
                                           " is beyond 1e12 in magnitude, the largest meshgap's "
                                           "geometry answers reliably");
            return x;
        }

        /** \brief True for "robot.N", "start.N.x", "goal.N.theta", ...: a key of a numbered body. */
        bool numberedBodyKey(const std::string &key)
        {
            for (const char *prefix : {"robot.", "start.", "goal."})
            {
                const std::string p(prefix);
                if (key.compare(0, p.size(), p) != 0 || key.size() == p.size() ||
                    !std::isdigit(static_cast<unsigned char>(key[p.size()])))
                    continue;
                return true;
            }
            return false;
        }
    }  // namespace

    ConfigFile readConfigFile(const std::string &path)
    {
        checkInputFile(path);
        std::ifstream in(path);
        if (!in)
            throw Exception(excerpt(path), "cannot open the problem file");
        ConfigFile file;
        file.path = path;
        std::string section, line;
        for (std::size_t number = 1; std::getline(in, line); ++number)
        {
            const std::string where = excerpt(path) + ":" + std::to_string(number);
            line = trim(line.substr(0, line.find('#')));
            if (line.empty() || line[0] == '#' || line[0] == ';')
                continue;
            if (line.front() == '[')
            {
                if (line.back() != ']')
                    throw Exception(where, "malformed section header " + quote(line));
                section = trim(line.substr(1, line.size() - 2));
                if (section != "problem" && section != "benchmark" && section != "planner")
                    throw Exception(where, "unknown section " + quote("[" + section + "]") +
                                               " (expected problem, benchmark, planner)");
                continue;
            }
            const auto eq = line.find('=');
            if (eq == std::string::npos)
                throw Exception(where, "expected 'key = value', found " + quote(line));
            const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
            if (key.empty())
                throw Exception(where, "empty key");
            if (section.empty())
                throw Exception(where, quote(key) + " is outside any [section]");
            if (section == "problem")
                file.problem.push_back({key, value, where});
            else if (section == "benchmark")
                file.benchmark.emplace_back(key, value);
            else
                file.planners.emplace_back(key, value);
        }
        return file;
    }

    const ConfigEntry *robotProblemKey(const ConfigFile &file)
    {
        for (const ConfigEntry &e : file.problem)
            if (e.key == "robot.urdf" || e.key == "robot.srdf" || e.key == "robot.package_path" || e.key == "attach" ||
                e.key == "start.joints" || e.key == "goal.joints" || numberedBodyKey(e.key))
                return &e;
        return nullptr;
    }

    ConfigKeys::ConfigKeys(const ConfigFile &file, const std::function<bool(const std::string &)> &known)
      : path_(file.path)
    {
        for (const ConfigEntry &e : file.problem)
        {
            if (!known(e.key))
                throw Exception(e.where, "unknown key " + quote(e.key) + " in [problem]");
            if (has(e.key))
                throw Exception(e.where, quote(e.key) + " is given twice (first at " + where(e.key) + ")");
            values_[e.key] = {e.value, e.where};
        }
    }

    std::string ConfigKeys::where(const std::string &key) const
    {
        return has(key) ? values_.at(key).second : path_;
    }

    double ConfigKeys::num(const std::string &key, double fallback) const
    {
        return has(key) ? number(value(key), where(key), key) : fallback;
    }

    std::vector<double> ConfigKeys::numbers(const std::string &key) const
    {
        std::vector<double> out;
        if (!has(key))
            return out;
        std::istringstream fields(value(key));
        std::string token;
        while (fields >> token)
            out.push_back(number(token, where(key), key));
        return out;
    }

    void ConfigKeys::require(const std::string &key) const
    {
        if (!has(key) || value(key).empty())
            throw Exception(excerpt(path_), "missing required key " + quote(key) + " in [problem]");
    }
}  // namespace meshgap
