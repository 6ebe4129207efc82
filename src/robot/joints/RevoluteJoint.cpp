#include "meshgap/robot/Joint.h"

#include <limits>

namespace meshgap
{
    /** \brief URDF's "revolute": one value, the angle about the axis through the joint frame's origin, within the
        URDF's limits (unbounded when it gives none). */
    class RevoluteJoint : public Joint
    {
    public:
        explicit RevoluteJoint(const JointSpec &spec)
          : Joint(unitAxis(spec))
          , lower_(spec.hasLimits ? spec.lower : -std::numeric_limits<double>::infinity())
          , upper_(spec.hasLimits ? spec.upper : std::numeric_limits<double>::infinity())
        {
        }

        const char *type() const override { return "revolute"; }
        std::size_t size() const override { return 1; }
        JointSpace space() const override { return JointSpace::REAL; }
        JointMotion motion() const override { return JointMotion::ROTATION; }
        double lower(std::size_t /*k*/) const override { return lower_; }
        double upper(std::size_t /*k*/) const override { return upper_; }

        void move(const double *q, Eigen::Isometry3d &X) const override { X.rotate(Eigen::AngleAxisd(*q, axis())); }

        void addJacobian(const double * /*q*/, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d &p, double scale,
                         Eigen::Matrix3Xd &J, Eigen::Index column) const override
        {
            // The child frame turns about the axis through its own origin.
            J.col(column) += scale * (X_WC.linear() * axis()).cross(p - X_WC.translation());
        }

    private:
        double lower_, upper_;
    };

    MESHGAP_REGISTER_JOINT(RevoluteJoint, "revolute")
}  // namespace meshgap
