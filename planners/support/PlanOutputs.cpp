#include "support/PlanOutputs.h"

#include <algorithm>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ostream>

#include "meshgap/AtomicFile.h"
#include "meshgap/ompl/ClearanceChecker.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "support/MeshWriter.h"
#include "support/PlanReport.h"
#include "support/SceneExport.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        std::vector<std::string> stateColumns(const RobotModel &robot)
        {
            std::vector<std::string> columns;
            for (const StateBlock &block : robot.stateBlocks())
                columns.insert(columns.end(), block.names.begin(), block.names.end());
            if (robot.links().size() == 1 && columns.size() == 7)
                return {"x", "y", "z", "qx", "qy", "qz", "qw"};  // a single body in SE(3), as OMPL.app names it
            if (robot.links().size() == 1 && columns.size() == 3 && robot.stateBlocks().front().space == JointSpace::SE2)
                return {"x", "y", "theta"};
            return columns;
        }

        void writeClearanceCsv(const DenseClearance &d, const std::vector<std::string> &columns,
                               const std::string &file)
        {
            writeStreamAtomically(
                file,
                [&](std::ostream &out)
                {
                    const ob::StateSpace &space = *d.path.getSpaceInformation()->getStateSpace();
                    out << "index,arc_length,fraction";
                    for (const std::string &column : columns)
                        out << "," << column;
                    out << ",clearance,in_collision\n";
                    out.precision(17);
                    const double total = d.arcLength.empty() ? 0.0 : d.arcLength.back();
                    std::vector<double> q;
                    for (std::size_t i = 0; i < d.path.getStateCount(); ++i)
                    {
                        out << i << "," << d.arcLength[i] << "," << (total > 0.0 ? d.arcLength[i] / total : 0.0);
                        robotStateToVector(space, d.path.getState(i), q);
                        for (double v : q)
                            out << "," << v;
                        out << "," << d.clearance[i] << "," << int(d.inCollision[i]) << "\n";
                    }
                });
        }

        void writePathFile(const ompl::geometric::PathGeometric &path, const std::string &file)
        {
            writeStreamAtomically(file,
                                  [&path](std::ostream &out)
                                  {
                                      out.precision(17);  // full precision: the states must round-trip exactly
                                      path.printAsMatrix(out);
                                  });
        }

        void writeTextFile(const std::string &text, const std::string &file)
        {
            writeStreamAtomically(file, [&text](std::ostream &out) { out << text; });
        }

        std::vector<std::vector<double>> statesAlong(const DenseClearance &d, unsigned count)
        {
            std::vector<std::vector<double>> states;
            const ob::StateSpace &space = *d.path.getSpaceInformation()->getStateSpace();
            const std::size_t n = d.path.getStateCount(), k = std::min<std::size_t>(count, n);
            for (std::size_t i = 0; i < k; ++i)
            {
                const std::size_t at = k == 1 ? 0 : (i * (n - 1) + (k - 1) / 2) / (k - 1);
                robotStateToVector(space, d.path.getState(at), states.emplace_back());
            }
            return states;
        }

        void writeSceneFiles(const RobotScene &scene, const DenseClearance *dense,
                             const std::vector<std::vector<double>> &ends, const std::string &summary,
                             const PlanOptions &o, std::ostream &log)
        {
            if (!o.glb.empty())
            {
                const std::vector<std::vector<double>> states = dense ? statesAlong(*dense, o.exportStates) : ends;
                writeGlb(robotExportParts(scene, states), o.glb);
                log << "scene written   " << o.glb << " (" << states.size() << " robot states)\n";
            }
            if (!o.report.empty())
            {
                const auto rows = summaryRows(summary);
                writePlanReport(scene, dense ? reportFromDense(scene, *dense, rows) : reportAtStates(scene, ends, rows),
                                o.report);
                log << "report written  " << o.report << "\n";
            }
        }
    }  // namespace cli
}  // namespace meshgap
