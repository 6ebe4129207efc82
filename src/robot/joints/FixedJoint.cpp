#include "meshgap/robot/Joint.h"

namespace meshgap
{
    /** \brief URDF's "fixed": no values, no motion (the child frame sits at the joint origin). */
    class FixedJoint : public Joint
    {
    public:
        explicit FixedJoint(const JointSpec & /*spec*/) : Joint(Eigen::Vector3d::UnitX()) {}

        const char *type() const override { return "fixed"; }
        std::size_t size() const override { return 0; }
        JointSpace space() const override { return JointSpace::NONE; }
        JointMotion motion() const override { return JointMotion::FIXED; }
        void move(const double * /*q*/, Eigen::Isometry3d & /*X*/) const override {}
        void addJacobian(const double * /*q*/, const Eigen::Isometry3d & /*X_WC*/, const Eigen::Vector3d & /*p*/,
                         double /*scale*/, Eigen::Matrix3Xd & /*J*/, Eigen::Index /*column*/) const override
        {
        }
    };

    MESHGAP_REGISTER_JOINT(FixedJoint, "fixed")
}  // namespace meshgap
