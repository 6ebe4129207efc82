#ifndef MESHGAP_PLANNERS_SUPPORT_PLAN_OUTPUTS_H
#define MESHGAP_PLANNERS_SUPPORT_PLAN_OUTPUTS_H

// The files meshgap_plan writes besides its summary on stdout; each written whole or not at all (AtomicFile.h).

#include <Eigen/Geometry>
#include <ompl/geometric/PathGeometric.h>
#include <string>
#include <vector>

#include "meshgap/robot/RobotModel.h"
#include "meshgap/scene/Scene.h"
#include "support/DenseClearance.h"
#include "support/PlanOptions.h"

namespace meshgap
{
    namespace cli
    {
        /** \brief index,arc_length,fraction, the state's numbers, clearance,in_collision for every state of the dense
            path (any kind of problem: the whole robot's clearance). The state's columns are \e columns:
            stateColumns(). */
        void writeClearanceCsv(const DenseClearance &d, const std::vector<std::string> &columns,
                               const std::string &file);

        /** \brief The names of a state's numbers in the clearance CSV: x,y,z,qx,qy,qz,qw (x,y,theta in SE(2)) for a
            single body, else the robot's state numbers by name (JOINT, or JOINT.x ... for a free base or body). */
        std::vector<std::string> stateColumns(const RobotModel &robot);

        /** \brief The path in OMPL's .path format, at full precision (the states round-trip exactly). */
        void writePathFile(const ompl::geometric::PathGeometric &path, const std::string &file);

        /** \brief \e text as it is. */
        void writeTextFile(const std::string &text, const std::string &file);

        /** \brief \e count states evenly spaced (by index) along the dense path, the first and the last included, as
            the robot's state numbers (robotStateToVector()). */
        std::vector<std::vector<double>> statesAlong(const DenseClearance &d, unsigned count);

        /** \brief The files of the scene \e o asks for, any kind of problem (a single body is a robot of one link):
            --export-glb (robotExportParts() at o.exportStates states along the dense path, or at \e ends, the start
            and the goal, without one) and --report (writePlanReport(): the dense path, or \e ends; \e summary as its
            table), saying each on \e log. */
        void writeSceneFiles(const RobotScene &scene, const DenseClearance *dense,
                             const std::vector<std::vector<double>> &ends, const std::string &summary,
                             const PlanOptions &o, std::ostream &log);
    }  // namespace cli
}  // namespace meshgap

#endif
