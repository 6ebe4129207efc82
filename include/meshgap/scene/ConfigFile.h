#ifndef MESHGAP_SCENE_CONFIG_FILE_H
#define MESHGAP_SCENE_CONFIG_FILE_H

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace meshgap
{
    /** \brief One "key = value" line of a problem file, with where it was given ("file:line"). */
    struct ConfigEntry
    {
        std::string key, value, where;
    };

    /** \brief The sections of an OMPL.app-style problem file (.cfg): the INI subset OMPL.app uses ("key = value",
        "[section]", '#' comments to the end of any line as boost::program_options reads them, ';' comment lines),
        [problem] entries with their lines, [benchmark] and [planner] entries in
        file order. */
    struct ConfigFile
    {
        std::string path;
        std::vector<ConfigEntry> problem;
        std::vector<std::pair<std::string, std::string>> benchmark;  ///< [benchmark] entries
        std::vector<std::pair<std::string, std::string>> planners;   ///< [planner] entries
    };

    /** \brief Read the sections of \e path. Throws meshgap::Exception naming "file:line" for a malformed line, a
        section other than problem, benchmark and planner, or an entry outside any section, and "file" for a
        missing or unreadable file. Keys are not interpreted here (ProblemConfig, RobotProblem do). */
    ConfigFile readConfigFile(const std::string &path);

    /** \brief The first [problem] entry that makes \e file a robot problem (robot.urdf, robot.srdf,
        robot.package_path, attach, start.joints, goal.joints, or a numbered body "robot.N", "start.N.x", ...; read
        by readRobotProblem()), or null for a single-body problem (readProblemConfig()). */
    const ConfigEntry *robotProblemKey(const ConfigFile &file);

    /** \brief The [problem] keys of a file, each value with where it was given, checked against the keys a reader
        knows. */
    class ConfigKeys
    {
    public:
        /** \brief Take \e file's [problem] entries; throws meshgap::Exception naming "file:line" for a key
            \e known rejects or one given twice. */
        ConfigKeys(const ConfigFile &file, const std::function<bool(const std::string &)> &known);

        bool has(const std::string &key) const { return values_.count(key) > 0; }
        const std::string &value(const std::string &key) const { return values_.at(key).first; }
        /** \brief "file:line" of \e key, or the file when it is not given. */
        std::string where(const std::string &key) const;
        /** \brief The finite number \e key gives, or \e fallback when it is absent; throws meshgap::Exception naming
            "file:line" for a value that is not a finite number, or beyond MAX_MAGNITUDE (meshgap/Limits.h) for a key
            other than an axis's. */
        double num(const std::string &key, double fallback) const;
        /** \brief The whitespace-separated finite numbers \e key gives (throws as num()). */
        std::vector<double> numbers(const std::string &key) const;
        /** \brief Throws meshgap::Exception naming the file when \e key is absent or empty. */
        void require(const std::string &key) const;
        const std::string &path() const { return path_; }

    private:
        std::string path_;
        std::map<std::string, std::pair<std::string, std::string>> values_;
    };
}  // namespace meshgap

#endif
