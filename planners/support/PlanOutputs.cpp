#include "support/PlanOutputs.h"

#include <algorithm>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ostream>

#include "meshgap/AtomicFile.h"
#include "meshgap/ompl/ClearanceChecker.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace cli
    {
        namespace
        {
            /** \brief The coordinates of \e s as the CSV spells them. */
            void writeState(const ob::State *s, bool planar, std::ostream &out)
            {
                if (planar)
                {
                    const auto *se2 = s->as<ob::SE2StateSpace::StateType>();
                    out << "," << se2->getX() << "," << se2->getY() << "," << se2->getYaw();
                    return;
                }
                const auto *se3 = s->as<ob::SE3StateSpace::StateType>();
                const auto &q = se3->rotation();
                out << "," << se3->getX() << "," << se3->getY() << "," << se3->getZ() << "," << q.x << "," << q.y << ","
                    << q.z << "," << q.w;
            }
        }  // namespace

        void writeClearanceCsv(const DenseClearance &d, const std::string &file)
        {
            writeStreamAtomically(
                file,
                [&d](std::ostream &out)
                {
                    const ob::StateSpace &space = *d.path.getSpaceInformation()->getStateSpace();
                    const bool planar = space.getType() == ob::STATE_SPACE_SE2;
                    out << "index,arc_length,fraction," << (planar ? "x,y,theta" : "x,y,z,qx,qy,qz,qw")
                        << ",clearance,in_collision\n";
                    out.precision(17);
                    const double total = d.arcLength.empty() ? 0.0 : d.arcLength.back();
                    for (std::size_t i = 0; i < d.path.getStateCount(); ++i)
                    {
                        out << i << "," << d.arcLength[i] << "," << (total > 0.0 ? d.arcLength[i] / total : 0.0);
                        writeState(d.path.getState(i), planar, out);
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

        std::vector<Eigen::Isometry3d> posesAlong(const DenseClearance &d, unsigned count)
        {
            std::vector<Eigen::Isometry3d> poses;
            const ob::StateSpace &space = *d.path.getSpaceInformation()->getStateSpace();
            const std::size_t n = d.path.getStateCount(), k = std::min<std::size_t>(count, n);
            for (std::size_t i = 0; i < k; ++i)
            {
                const std::size_t at = k == 1 ? 0 : (i * (n - 1) + (k - 1) / 2) / (k - 1);
                poses.push_back(poseFromState(space, d.path.getState(at)));
            }
            return poses;
        }
    }  // namespace cli
}  // namespace meshgap
