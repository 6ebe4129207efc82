#ifndef MESHGAP_PLANNERS_SUPPORT_ROBOT_DISTANCE_H
#define MESHGAP_PLANNERS_SUPPORT_ROBOT_DISTANCE_H

// meshgap_distance's answers on a problem of any kind (a single body is a robot of one link): the whole robot's exact
// clearance at one state (text or JSON) or at every state of a file (CSV or JSON).

#include <ostream>
#include <string>

#include "meshgap/robot/RobotProblem.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief The first columns of meshgap_distance --poses on a robot problem, one row per state (index from
            0): the whole robot's exact signed clearance, whether it is in collision, whether certified, the pair
            that attains it (link, and other_link for two links or obstacle, the obstacle's index, for a link
            against the world; the other one empty), its witness points (world frame: witness_a on the link,
            witness_b on the other link or the obstacle, RobotResult::onA and onB); then clearance_LINK, each link's
            clearance, in the order of the robot's links. */
        inline constexpr const char *ROBOT_CSV_COLUMNS =
            "index,distance,in_collision,certified,link,other_link,obstacle,witness_a_x,witness_a_y,witness_a_z,"
            "witness_b_x,witness_b_y,witness_b_z";

        /** \brief How meshgap_distance answers a problem (robotDistance()). */
        struct RobotDistanceOptions
        {
            bool json{false};   ///< JSON instead of text or CSV: one object, or an array with states
            bool cold{false};   ///< no warm start: a cold query at every state
            bool depth{true};   ///< in collision, the penetration depth (RobotRequest::computeDepth)
        };

        /** \brief meshgap_distance on the problem \e p (any kind: a single body is a robot of one link): at the start
            (\e stateText empty and \e statesFile empty) or at the state \e stateText, a text block of the whole
            robot's exact signed clearance, the pair that attains it (a link and an obstacle, or two links), its
            witnesses and every link's clearance; at every state of \e statesFile (one a line, as a .path of the
            problem), the same as CSV (ROBOT_CSV_COLUMNS), and the time per query (median, mean) on stderr; with
            options.json, JSON objects of the same fields and the time. One warm start is carried from state to
            state unless options.cold. Throws meshgap::Exception naming file:line for a state of the wrong dimension
            or a malformed number. */
        void robotDistance(const RobotProblem &p, const std::string &stateText, const std::string &statesFile,
                           const RobotDistanceOptions &options, std::ostream &out);
    }  // namespace cli
}  // namespace meshgap

#endif
