#include "meshgap/robot/Joint.h"

namespace meshgap
{
    /** \brief URDF's "continuous": one value, an unbounded angle about the axis through the joint frame's origin
        (SO(2): interpolated along the shorter arc). */
    class ContinuousJoint : public Joint
    {
    public:
        explicit ContinuousJoint(const JointSpec &spec) : Joint(unitAxis(spec)) {}

        const char *type() const override { return "continuous"; }
        std::size_t size() const override { return 1; }
        JointSpace space() const override { return JointSpace::SO2; }
        JointMotion motion() const override { return JointMotion::ROTATION; }

        void move(const double *q, Eigen::Isometry3d &X) const override { X.rotate(Eigen::AngleAxisd(*q, axis())); }

        void addJacobian(const double * /*q*/, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d &p, double scale,
                         Eigen::Matrix3Xd &J, Eigen::Index column) const override
        {
            J.col(column) += scale * (X_WC.linear() * axis()).cross(p - X_WC.translation());
        }
    };

    MESHGAP_REGISTER_JOINT(ContinuousJoint, "continuous")
}  // namespace meshgap
