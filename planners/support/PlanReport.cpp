#include "support/PlanReport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ompl/base/StateValidityChecker.h>
#include <sstream>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "support/MeshWriter.h"
#include "support/SceneExport.h"

namespace meshgap
{
    // Generated at configure time (planners/support/CMakeLists.txt): three.js r111 with its OrbitControls and
    // GLTFLoader from Debian's libjs-three (empty when it was not found), and report_template.html.
    extern const char *const REPORT_THREE_JS;
    extern const char *const REPORT_TEMPLATE;

    namespace
    {
        std::string base64(const unsigned char *data, std::size_t size)
        {
            static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
            std::string out;
            out.reserve((size + 2) / 3 * 4);
            for (std::size_t i = 0; i < size; i += 3)
            {
                const unsigned v = (unsigned(data[i]) << 16) | (i + 1 < size ? unsigned(data[i + 1]) << 8 : 0u) |
                                   (i + 2 < size ? unsigned(data[i + 2]) : 0u);
                out += alphabet[(v >> 18) & 63];
                out += alphabet[(v >> 12) & 63];
                out += i + 1 < size ? alphabet[(v >> 6) & 63] : '=';
                out += i + 2 < size ? alphabet[v & 63] : '=';
            }
            return out;
        }

        /** \brief Doubles as little-endian float32 (x86-64's byte order, which the page's Float32Array reads), in
            base64: a quarter of the size of decimal text. */
        std::string floats(const std::vector<double> &values)
        {
            std::vector<float> f(values.begin(), values.end());
            return base64(reinterpret_cast<const unsigned char *>(f.data()), f.size() * sizeof(float));
        }

        /** \brief A JSON string literal, safe inside <script> (no "</" can close it). */
        std::string jsonString(const std::string &s)
        {
            std::string out = "\"";
            for (const char c : s)
            {
                switch (c)
                {
                    case '"':
                        out += "\\\"";
                        break;
                    case '\\':
                        out += "\\\\";
                        break;
                    case '\n':
                        out += "\\n";
                        break;
                    case '<':
                        out += "\\u003c";
                        break;
                    default:
                        if (static_cast<unsigned char>(c) < 0x20)
                        {
                            char buffer[8];
                            std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
                            out += buffer;
                        }
                        else
                            out += c;
                }
            }
            return out + "\"";
        }

        std::string jsonNumber(double x)
        {
            if (!std::isfinite(x))
                return "null";
            char buffer[32];
            std::snprintf(buffer, sizeof buffer, "%.9g", x);
            return buffer;
        }

        /** \brief \e parts (obstacles in the world frame; the robot, or each link, in its own frame) as glTF 2.0
            binary in base64. */
        std::string sceneGlb(const std::vector<ColoredMesh> &parts, const std::string &file)
        {
            // In the system's temporary folder: the report's own folder is checked first, by its own temporary file.
            const std::string temporary =
                temporaryPath((std::filesystem::temp_directory_path() / "meshgap_report.glb").string());
            writeGlb(parts, temporary);
            std::ifstream in(temporary, std::ios::binary);
            std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            const bool ok = static_cast<bool>(in) || in.eof();
            in.close();
            std::remove(temporary.c_str());
            if (!ok || bytes.empty())
                throw Exception(file, "cannot read back the scene written to " + temporary);
            return base64(reinterpret_cast<const unsigned char *>(bytes.data()), bytes.size());
        }

        void replaceOnce(std::string &text, const std::string &placeholder, const std::string &value)
        {
            const std::size_t at = text.find(placeholder);
            if (at == std::string::npos)
                throw Exception("report template", "no placeholder " + placeholder);
            text.replace(at, placeholder.size(), value);
        }
    }  // namespace

    namespace
    {
        /** \brief Bounds around \e states' first three numbers (a unit box at least). */
        ompl::base::RealVectorBounds boundsAround(const std::vector<std::vector<double>> &states)
        {
            ompl::base::RealVectorBounds bounds(3);
            bounds.setLow(-1.0);
            bounds.setHigh(1.0);
            for (const std::vector<double> &q : states)
                for (std::size_t k = 0; k < 3 && k < q.size(); ++k)
                {
                    bounds.low[k] = std::min(bounds.low[k], q[k] - 1.0);
                    bounds.high[k] = std::max(bounds.high[k], q[k] + 1.0);
                }
            return bounds;
        }

        /** \brief "min clearance" and "dense path free" rows, unless \e summary has them. */
        void addClearanceRows(const PlanReportData &r, std::size_t argmin, std::size_t collisions,
                              std::vector<std::pair<std::string, std::string>> &summary)
        {
            auto has = [&summary](const std::string &key)
            {
                for (const auto &row : summary)
                    if (row.first == key)
                        return true;
                return false;
            };
            if (!has("min clearance"))
            {
                std::ostringstream mc;
                mc.precision(6);
                mc << r.clearance[argmin] << " (exact, at arc length " << r.arcLength[argmin] << " of "
                   << r.arcLength.back() << ")";
                summary.emplace_back("min clearance", mc.str());
            }
            if (!has("dense path free"))
                summary.emplace_back("dense path free", collisions == 0 ? std::string("yes") :
                                                            "NO: " + std::to_string(collisions) + " states collide");
        }

        /** \brief The links' names and the summary, titled by its first row. */
        void finish(const RobotScene &scene, std::vector<std::pair<std::string, std::string>> summary,
                    PlanReportData &r)
        {
            for (const RobotLink &link : scene.links())
                r.linkNames.push_back(link.name);
            r.summary = std::move(summary);
            r.title = r.summary.empty() ? std::string("meshgap plan") : r.summary.front().second;
        }
    }  // namespace

    ompl::base::SpaceInformationPtr reportSpaceInformation(const RobotModel &robot,
                                                           const std::optional<Eigen::AlignedBox3d> &volume,
                                                           const std::vector<std::vector<double>> &states)
    {
        ompl::base::RealVectorBounds bounds = boundsAround(states);
        if (volume)
            for (int k = 0; k < 3; ++k)
            {
                bounds.low[k] = volume->min()[k];
                bounds.high[k] = volume->max()[k];
            }
        auto si = std::make_shared<ompl::base::SpaceInformation>(robotStateSpace(robot, bounds));
        si->setStateValidityChecker(std::make_shared<ompl::base::AllValidStateValidityChecker>(si));
        si->setup();
        return si;
    }

    ompl::geometric::PathGeometric robotPath(const ompl::base::SpaceInformationPtr &si,
                                             const std::vector<std::vector<double>> &states)
    {
        ompl::geometric::PathGeometric path(si);
        ompl::base::State *state = si->allocState();
        for (const std::vector<double> &q : states)
        {
            robotStateFromVector(*si->getStateSpace(), q, state);
            path.append(state);
        }
        si->freeState(state);
        return path;
    }

    PlanReportData reportFromDense(const RobotScene &scene, const DenseClearance &dense,
                                   std::vector<std::pair<std::string, std::string>> summary)
    {
        PlanReportData r;
        r.poses = dense.linkPoses;
        r.linkClearance = dense.linkClearance;
        r.arcLength = dense.arcLength;
        r.clearance = dense.clearance;
        r.inCollision = dense.inCollision;
        r.onA = dense.onA;
        r.onB = dense.onB;
        addClearanceRows(r, dense.argmin, dense.collisions, summary);
        finish(scene, std::move(summary), r);
        return r;
    }

    PlanReportData reportAtStates(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                  std::vector<std::pair<std::string, std::string>> summary)
    {
        PlanReportData r;
        std::vector<Eigen::Isometry3d> frames, poses;
        for (const std::vector<double> &q : states)
        {
            scene.robot().linkPoses(q.data(), q.size(), frames, poses);
            r.poses.insert(r.poses.end(), poses.begin(), poses.end());
        }
        finish(scene, std::move(summary), r);
        return r;
    }

    std::vector<std::pair<std::string, std::string>> summaryRows(const std::string &text)
    {
        std::vector<std::pair<std::string, std::string>> rows;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line))
        {
            // "key" padded to 16 columns; a longer key is followed by at least one space.
            std::size_t split = line.size() > 16 && line[15] == ' ' ? 16 : line.find(' ');
            if (split == std::string::npos)
                split = line.size();
            std::string key = line.substr(0, split), value = split < line.size() ? line.substr(split) : "";
            key.erase(key.find_last_not_of(' ') + 1);
            value.erase(0, value.find_first_not_of(' ') == std::string::npos ? value.size() :
                                                                                value.find_first_not_of(' '));
            if (!key.empty())
                rows.emplace_back(key, value);
        }
        return rows;
    }

    bool planReportAvailable()
    {
        return std::strlen(REPORT_THREE_JS) > 0;
    }

    namespace
    {
        void writeReportPage(const std::vector<ColoredMesh> &parts, const PlanReportData &data,
                             const std::string &file);
    }  // namespace

    void writePlanReport(const RobotScene &scene, const PlanReportData &data, const std::string &file)
    {
        const std::size_t links = scene.links().size();
        if (data.linkNames.size() != links || data.poses.size() % std::max<std::size_t>(links, 1) != 0 ||
            (!data.linkClearance.empty() && data.linkClearance.size() != data.poses.size()))
            throw Exception(file, "a plan report needs one pose (and one clearance) per link and state");
        const SceneExportOptions colors;
        std::vector<ColoredMesh> parts;
        for (std::size_t i = 0; i < scene.obstacles().size(); ++i)
            parts.push_back({"obstacle " + std::to_string(i), scene.obstacles()[i]->surface(), colors.worldColor});
        for (std::size_t i = 0; i < links; ++i)  // names the page finds them by (no spaces: GLTFLoader keeps these)
            parts.push_back({links == 1 ? std::string("robot") : "link_" + std::to_string(i),
                             scene.links()[i].body->surface(),
                             scene.links()[i].payload ? Eigen::Vector4d(0.85, 0.55, 0.15, 1.0) : colors.robotColor});
        writeReportPage(parts, data, file);
    }

    namespace
    {
        /** \brief The page of writePlanReport(): \e parts and \e data (one link: no per-link arrays, the page then
            draws the part named "robot"). */
        void writeReportPage(const std::vector<ColoredMesh> &parts, const PlanReportData &data, const std::string &file)
        {
            if (!planReportAvailable())
                throw Exception(file, "cannot write a plan report: three.js (Debian's libjs-three) was not found when "
                                      "meshgap was built");
            if (data.poses.empty())
                throw Exception(file, "a plan report needs at least one robot pose");
            const std::size_t links = std::max<std::size_t>(1, data.linkNames.size()), n = data.poses.size() / links;
            const bool perLink = data.linkNames.size() > 1;
            const bool hasPath = data.clearance.size() == n && n > 0;
            std::vector<double> poses, onA, onB;
            for (const Eigen::Isometry3d &X : data.poses)
            {
                const Eigen::Quaterniond q(X.linear());
                poses.insert(poses.end(), {X.translation().x(), X.translation().y(), X.translation().z(), q.x(), q.y(),
                                           q.z(), q.w()});
            }
            std::ostringstream json;
            json << "{\"title\": " << jsonString(data.title) << ", \"summary\": [";
            for (std::size_t i = 0; i < data.summary.size(); ++i)
                json << (i ? ", " : "") << "[" << jsonString(data.summary[i].first) << ", "
                     << jsonString(data.summary[i].second) << "]";
            json << "], \"states\": " << n << ", \"poses\": \"" << floats(poses) << "\"";
            if (perLink)
            {
                json << ", \"links\": [";
                for (std::size_t i = 0; i < data.linkNames.size(); ++i)
                    json << (i ? ", " : "") << jsonString(data.linkNames[i]);
                json << "]";
                if (!data.linkClearance.empty())
                    json << ", \"linkClearance\": \"" << floats(data.linkClearance) << "\"";
            }
            if (hasPath)
            {
                std::size_t argmin = 0;
                for (std::size_t i = 0; i < n; ++i)
                {
                    if (data.clearance[i] < data.clearance[argmin])
                        argmin = i;
                    for (int k = 0; k < 3; ++k)
                    {
                        onA.push_back(data.onA[i][k]);
                        onB.push_back(data.onB[i][k]);
                    }
                }
                std::vector<unsigned char> collide(data.inCollision.begin(), data.inCollision.end());
                json << ", \"arcLength\": \"" << floats(data.arcLength) << "\", \"clearance\": \""
                     << floats(data.clearance) << "\", \"inCollision\": \"" << base64(collide.data(), collide.size())
                     << "\", \"onA\": \"" << floats(onA) << "\", \"onB\": \"" << floats(onB)
                     << "\", \"argmin\": " << argmin << ", \"minClearance\": " << jsonNumber(data.clearance[argmin]);
            }
            else
                json << ", \"clearance\": null";

            // The temporary file is opened first, so an output folder that cannot be written fails before any work.
            writeStreamAtomically(
                file,
                [&](std::ostream &out)
                {
                    json << ", \"glb\": \"" << sceneGlb(parts, file) << "\"}";
                    std::string html = REPORT_TEMPLATE;
                    replaceOnce(html, "/*MESHGAP_THREE_JS*/", REPORT_THREE_JS);
                    replaceOnce(html, "/*MESHGAP_DATA*/null", json.str());
                    out << html;
                },
                /*binary=*/true);
        }
    }  // namespace
}  // namespace meshgap
