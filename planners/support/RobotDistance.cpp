#include "support/RobotDistance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <ompl/util/Console.h>
#include <sstream>

#include "meshgap/robot/RobotScene.h"
#include "support/DenseClearance.h"
#include "support/PathFile.h"

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief One state's answer: the clearance, its pair and witnesses, every link's clearance. */
            void printAnswer(const RobotScene &scene, const RobotResult &r, std::size_t index, std::ostream &out)
            {
                out << "state " << index << ": clearance " << r.distance << " ("
                    << (r.certified ? "exact, certified" : "not certified") << ")"
                    << (r.inCollision ? ", IN COLLISION" : "") << "\n";
                out << "  closest pair   " << pairText(scene, r) << "\n";
                out << "  witnesses      (" << r.onA.transpose() << ") on the link, (" << r.onB.transpose()
                    << ") on the other\n";
                for (std::size_t i = 0; i < scene.links().size(); ++i)
                {
                    char name[40];
                    std::snprintf(name, sizeof name, "  link %-24s", scene.links()[i].name.c_str());
                    out << name << " " << r.linkClearance[i] << "\n";
                }
            }

            /** \brief "N states, whole robot: median X us, mean Y us per query" on stderr (whatever the log level),
                as meshgap_distance prints for a single body. */
            void printQueryTimes(std::vector<double> micros, bool cold)
            {
                if (micros.empty())
                    return;
                double sum = 0.0;
                for (double us : micros)
                    sum += us;
                std::sort(micros.begin(), micros.end());
                std::fprintf(stderr, "meshgap_distance: %zu states, whole robot, every pair exact, %s: median %.1f us, "
                                     "mean %.1f us per query\n",
                             micros.size(), cold ? "cold" : "warm start carried", micros[micros.size() / 2],
                             sum / double(micros.size()));
            }

            /** \brief \e text as a JSON string (quotes, backslashes and control characters escaped). */
            std::string jsonString(const std::string &text)
            {
                std::string s = "\"";
                for (unsigned char c : text)
                {
                    if (c == '"' || c == '\\')
                        s += std::string("\\") + char(c);
                    else if (c < 0x20)
                    {
                        char escaped[8];
                        std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
                        s += escaped;
                    }
                    else
                        s += char(c);
                }
                return s + "\"";
            }

            /** \brief \e v as a JSON number, null when not finite (a link with nothing to be checked against). */
            std::string jsonNumber(double v)
            {
                std::ostringstream text;
                text.precision(17);
                if (std::isfinite(v))
                    text << v;
                else
                    text << "null";
                return text.str();
            }

            /** \brief One state's answer as a JSON object: the fields of the CSV (ROBOT_CSV_COLUMNS; witnesses as
                arrays, link clearances as an object by link name), pairs_checked and the query's time. */
            std::string jsonAnswer(const RobotScene &scene, const RobotResult &r, double micros)
            {
                std::ostringstream o;
                o << "{\"distance\": " << jsonNumber(r.distance) << ", \"in_collision\": "
                  << (r.inCollision ? "true" : "false") << ", \"certified\": " << (r.certified ? "true" : "false")
                  << ", \"link\": " << jsonString(scene.links()[r.link].name) << ", \"other_link\": "
                  << (r.selfPair ? jsonString(scene.links()[r.other].name) : "null")
                  << ", \"obstacle\": " << (r.selfPair ? std::string("null") : std::to_string(r.other));
                for (const auto &[key, v] : {std::pair{"witness_a", &r.onA}, {"witness_b", &r.onB}})
                    o << ", \"" << key << "\": [" << jsonNumber(v->x()) << ", " << jsonNumber(v->y()) << ", "
                      << jsonNumber(v->z()) << "]";
                o << ", \"pairs_checked\": " << r.pairsChecked << ", \"time_us\": " << jsonNumber(micros)
                  << ", \"link_clearance\": {";
                for (std::size_t i = 0; i < scene.links().size(); ++i)
                    o << (i ? ", " : "") << jsonString(scene.links()[i].name) << ": " << jsonNumber(r.linkClearance[i]);
                o << "}}";
                return o.str();
            }

            /** \brief \e text as one CSV field: quoted (quotes doubled) when it holds a comma, quote or line end. */
            std::string csvField(const std::string &text)
            {
                if (text.find_first_of(",\"\n\r") == std::string::npos)
                    return text;
                std::string quoted = "\"";
                for (char c : text)
                    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
                return quoted + "\"";
            }

            /** \brief The header of --poses' CSV (ROBOT_CSV_COLUMNS, then a clearance column per link). */
            void printCsvHeader(const RobotScene &scene, std::ostream &out)
            {
                out << ROBOT_CSV_COLUMNS;
                for (const RobotLink &link : scene.links())
                    out << "," << csvField("clearance_" + link.name);
                out << "\n";
            }

            /** \brief One state's answer as a CSV row: index, clearance, collision, certified, the pair (a link and an
                obstacle index, or two links), its witnesses, every link's clearance. */
            void printCsvRow(const RobotScene &scene, const RobotResult &r, std::size_t index, std::ostream &out)
            {
                // The numbers through snprintf ("%.17g", what the stream's precision 17 prints): formatting them
                // through the stream costs more than a warm query's own work on a single body.
                char number[32];
                auto put = [&](double v)
                {
                    std::snprintf(number, sizeof number, ",%.17g", v);
                    out << number;
                };
                out << index;
                put(r.distance);
                out << "," << (r.inCollision ? 1 : 0) << "," << (r.certified ? 1 : 0) << ","
                    << csvField(scene.links()[r.link].name) << ","
                    << (r.selfPair ? csvField(scene.links()[r.other].name) : std::string()) << ","
                    << (r.selfPair ? std::string() : std::to_string(r.other));
                for (const Eigen::Vector3d *v : {&r.onA, &r.onB})
                    for (int k = 0; k < 3; ++k)
                        put((*v)[k]);
                for (double c : r.linkClearance)
                    put(c);
                out << "\n";
            }
        }  // namespace

        void robotDistance(const RobotProblem &p, const std::string &stateText, const std::string &statesFile,
                           const RobotDistanceOptions &options, std::ostream &out)
        {
            const RobotScene scene(p.robot, p.obstacles, p.allowedObstacles);
            const std::size_t n = p.robot->dimension();
            std::vector<std::vector<double>> states = {p.start};
            if (!stateText.empty())
                states = {parseRobotState(stateText, *p.robot, "--pose")};
            const bool many = !statesFile.empty();
            if (many)
                states = readRobotPathFile(statesFile, *p.robot);
            OMPL_INFORM("%s: %s, links %zu, self pairs %zu, obstacles %zu; exact, every pair, %s", p.name.c_str(),
                        p.robot->description().c_str(), scene.links().size(), scene.selfPairs().size(),
                        scene.obstacles().size(), options.cold ? "a cold query per state (--cold)" :
                                                                 "one warm start carried from state to state");
            RobotRequest request;
            request.everyPair = true;
            request.computeDepth = options.depth;
            RobotWarmStart warm;
            RobotResult r;
            out << std::setprecision(many || options.json ? 17 : 10);
            if (many)
                out << (options.json ? "[\n" : "");
            if (many && !options.json)
                printCsvHeader(scene, out);
            std::vector<double> micros;
            for (std::size_t i = 0; i < states.size(); ++i)
            {
                if (options.cold)
                    warm.reset();
                const auto start = std::chrono::steady_clock::now();
                scene.distance(states[i].data(), n, request, warm, r);
                micros.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e6);
                if (options.json)
                    out << (many ? "  " : "") << jsonAnswer(scene, r, micros.back())
                        << (many && i + 1 < states.size() ? ",\n" : "\n");
                else if (many)
                    printCsvRow(scene, r, i, out);
                else
                    printAnswer(scene, r, i + 1, out);
            }
            if (many && options.json)
                out << "]\n";
            if (many)
                printQueryTimes(micros, options.cold);
        }
    }  // namespace cli
}  // namespace meshgap
