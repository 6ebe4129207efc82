#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_REPORT_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_REPORT_H

#include <Eigen/Geometry>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/PathGeometric.h>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshgap/robot/RobotScene.h"
#include "support/DenseClearance.h"

namespace meshgap
{
    /** \brief What a plan report shows besides the scene: the summary table and, per state of the (dense) path, every
        link's pose (a single body is a robot of one link), arc length, the whole robot's exact signed clearance,
        collision flag, the closest-point segment of the pair that attains it, and each link's clearance. */
    struct PlanReportData
    {
        std::string title;
        std::vector<std::pair<std::string, std::string>> summary;  ///< table rows, in order
        /** \brief The links' names, in the order of RobotScene::links(). */
        std::vector<std::string> linkNames;
        /** \brief Every link's pose at every state (state-major: state k's link i at k * links + i; at least one
            state). */
        std::vector<Eigen::Isometry3d> poses;
        std::vector<double> arcLength, clearance;  ///< empty without a path
        std::vector<char> inCollision;
        std::vector<Eigen::Vector3d> onA, onB;  ///< the witnesses on the link (A) and on the other body (B)
        /** \brief Each link's clearance at every state (the order of poses); empty without a path. */
        std::vector<double> linkClearance;
    };

    /** \brief The space information a report interpolates a robot's path in: robotStateSpace() within \e volume's
        bounds (as the planner's space), else (a report of a path alone) within bounds around \e states' first three
        numbers, or a unit box for a robot with no free base: only the validity-check segment count depends on them.
        Its states are always valid (a report checks every state itself). */
    ompl::base::SpaceInformationPtr reportSpaceInformation(const RobotModel &robot,
                                                           const std::optional<Eigen::AlignedBox3d> &volume,
                                                           const std::vector<std::vector<double>> &states);

    /** \brief \e states (robotStateFromVector()) as a path of \e si's states. */
    ompl::geometric::PathGeometric robotPath(const ompl::base::SpaceInformationPtr &si,
                                             const std::vector<std::vector<double>> &states);

    /** \brief The report of a dense path (denseClearance(), with every link's clearance): every link's pose, the
        whole robot's clearance, the attaining pair's witness points, each link's clearance, the arc length; \e summary
        gets "min clearance" and "dense path free" rows when it has none. */
    PlanReportData reportFromDense(const RobotScene &scene, const DenseClearance &dense,
                                   std::vector<std::pair<std::string, std::string>> summary);

    /** \brief The report of a problem without a path: the robot at \e states (its start and goal), no plot. */
    PlanReportData reportAtStates(const RobotScene &scene, const std::vector<std::vector<double>> &states,
                                  std::vector<std::pair<std::string, std::string>> summary);

    /** \brief meshgap_plan's summary text ("key" padded to 16 columns, then the value, one per line) as rows. */
    std::vector<std::pair<std::string, std::string>> summaryRows(const std::string &text);

    /** \brief Whether three.js was found when meshgap was built, so writePlanReport() can run. */
    bool planReportAvailable();

    /** \brief Write one self-contained HTML file (no network access needed): three.js from Debian's libjs-three
        (embedded at build time), the scene as glTF 2.0 binary (writeGlb(): every obstacle, and every link in its own
        frame) in base64, and the per-state arrays as base64 float32. The page draws the world and the robot at the
        slider's state (orbit controls; it starts at the state of least clearance), the closest-point segment
        there coloured by clearance (red at contact, green at the largest clearance), a plot of clearance against
        arc length linked to the slider with its minimum marked, beside it (a robot of several links) the clearance of
        every link, and the summary as a table; it sets `<div id="status">` to "ready: loaded T triangles, S states"
        once the scene is loaded and its first frame drawn (or "error: ..." on any script error) for a headless
        browser to wait for and read back. A robot of one link (a single body) is drawn as "robot", without a
        per-link plot (its link's clearance is the robot's). Written under a temporary name and renamed over \e file
        once complete. Throws meshgap::Exception naming the file when it cannot be written, if three.js was not found
        when meshgap was built, and for data whose poses or link clearances are not one per link and state. */
    void writePlanReport(const RobotScene &scene, const PlanReportData &data, const std::string &file);
}  // namespace meshgap

#endif
