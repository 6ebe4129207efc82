#include "meshgap/robot/Joint.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace meshgap
{
    /** \brief URDF's "prismatic": one value, the translation along the axis, within the URDF's limits. */
    class PrismaticJoint : public Joint
    {
    public:
        explicit PrismaticJoint(const JointSpec &spec)
          : Joint(unitAxis(spec))
          , lower_(spec.hasLimits ? spec.lower : -std::numeric_limits<double>::infinity())
          , upper_(spec.hasLimits ? spec.upper : std::numeric_limits<double>::infinity())
        {
        }

        const char *type() const override { return "prismatic"; }
        std::size_t size() const override { return 1; }
        JointSpace space() const override { return JointSpace::REAL; }
        JointMotion motion() const override { return JointMotion::TRANSLATION; }
        double lower(std::size_t /*k*/) const override { return lower_; }
        double upper(std::size_t /*k*/) const override { return upper_; }

        void move(const double *q, Eigen::Isometry3d &X) const override { X.translate(*q * axis()); }

        double reach(double lowest, double highest) const override
        {
            return std::max(std::abs(lowest), std::abs(highest));
        }

        void addJacobian(const double * /*q*/, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d & /*p*/,
                         double scale, Eigen::Matrix3Xd &J, Eigen::Index column) const override
        {
            J.col(column) += scale * (X_WC.linear() * axis());
        }

    private:
        double lower_, upper_;
    };

    MESHGAP_REGISTER_JOINT(PrismaticJoint, "prismatic")
}  // namespace meshgap
