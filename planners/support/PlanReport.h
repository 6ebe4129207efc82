#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_REPORT_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_REPORT_H

#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

#include "meshgap/robot/RobotScene.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/Scene.h"
#include "support/DenseClearance.h"

namespace meshgap
{
    /** \brief What a plan report shows besides the scene: the summary table and, per state of the (dense) path, the
        robot's pose, arc length, exact signed clearance, collision flag and closest-point segment. */
    struct PlanReportData
    {
        std::string title;
        std::vector<std::pair<std::string, std::string>> summary;  ///< table rows, in order
        std::vector<Eigen::Isometry3d> poses;                      ///< robot poses (at least one)
        std::vector<double> arcLength, clearance;                   ///< empty without a path
        std::vector<char> inCollision;
        std::vector<Eigen::Vector3d> onRobot, onObstacle;
        /** \brief A robot of many bodies (writeRobotReport()): its links' names. poses then holds every link's pose
            at every state (state-major: state k's link i at k * links + i), onRobot the witness point on the link
            of the attaining pair, and linkClearance each link's clearance at every state (the same order). */
        std::vector<std::string> linkNames;
        std::vector<double> linkClearance;
    };

    /** \brief The report of a dense path: its states, clearance and segments, and \e summary with "min clearance"
        and "dense path free" rows added when absent. */
    PlanReportData reportFromDense(const DenseClearance &dense,
                                   std::vector<std::pair<std::string, std::string>> summary);

    /** \brief The report of a problem without a path: the robot at the start and the goal, no plot. */
    PlanReportData reportWithoutPath(const ProblemConfig &config,
                                     std::vector<std::pair<std::string, std::string>> summary);

    /** \brief meshgap_plan's summary text ("key" padded to 16 columns, then the value, one per line) as rows. */
    std::vector<std::pair<std::string, std::string>> summaryRows(const std::string &text);

    /** \brief Whether three.js was found when meshgap was built, so writePlanReport() can run. */
    bool planReportAvailable();

    /** \brief Write one self-contained HTML file (no network access needed): three.js from Debian's libjs-three
        (embedded at build time), the scene as glTF 2.0 binary (writeGlb(): every obstacle, and the robot in its own
        frame) in base64, and the per-state arrays as base64 float32. The page draws the world and the robot at the
        slider's state (orbit controls; it starts at the state of least clearance), the closest-point segment
        there coloured by clearance (red at contact, green at the largest clearance), a plot of clearance against
        arc length linked to the slider with its minimum marked, and the summary as a table; it sets
        `<div id="status">` to "ready: loaded T triangles, S states" once the scene is loaded and its first frame
        drawn (or "error: ..." on any script error) for a headless browser to wait for and read back. Written under a temporary name and renamed over \e file once complete.
        Throws meshgap::Exception naming the file when it cannot be written, or if three.js was not found when
        meshgap was built. */
    void writePlanReport(const Scene &scene, const PlanReportData &data, const std::string &file);

    /** \brief The same page for a robot of many bodies: every link drawn at its pose at the slider's state
        (data.linkNames, data.poses per link), the closest-point segment of the attaining pair, and beside the
        whole robot's clearance the clearance of every link along the path. Throws as writePlanReport(), and for
        data whose poses or link clearances are not one per link and state. */
    void writeRobotReport(const RobotScene &scene, const PlanReportData &data, const std::string &file);
}  // namespace meshgap

#endif
