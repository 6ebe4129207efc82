#include "meshgap/robot/Joint.h"

#include <limits>

#include "meshgap/robot/RobotModel.h"

namespace meshgap
{
    /** \brief URDF's "floating": seven values "x y z qx qy qz qw" (OMPL's SE(3) order, the quaternion scalar last and
        normalised, poseFromSE3()), the child frame the joint frame moved by (x, y, z) and then turned by the
        quaternion; the axis is unused. URDF gives no limits: the position is bounded by the problem's bounds (as a
        free-flying body's), the rotation is interpolated along the shorter great arc. A floating base
        (UrdfOptions::floatingBase) is this joint between the world and the root link. */
    class FloatingJoint : public Joint
    {
    public:
        explicit FloatingJoint(const JointSpec & /*spec*/) : Joint(Eigen::Vector3d::UnitZ()) {}

        const char *type() const override { return "floating"; }
        std::size_t size() const override { return 7; }
        JointSpace space() const override { return JointSpace::SE3; }
        JointMotion motion() const override { return JointMotion::SE3; }
        std::string valueName(std::size_t k) const override
        {
            static const char *names[7] = {"x", "y", "z", "qx", "qy", "qz", "qw"};
            return names[k];
        }
        double neutral(std::size_t k) const override { return k == 6 ? 1.0 : 0.0; }

        void move(const double *q, Eigen::Isometry3d &X) const override { X = X * poseFromSE3(q); }
        Eigen::Isometry3d pose(const double *q) const override { return poseFromSE3(q); }

        double reach(double /*lowest*/, double /*highest*/) const override
        {
            return std::numeric_limits<double>::infinity();
        }

        void addJacobian(const double *q, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d &p, double scale,
                         Eigen::Matrix3Xd &J, Eigen::Index column) const override
        {
            const Eigen::Quaterniond raw(q[6], q[3], q[4], q[5]);
            const double norm = raw.norm();
            const Eigen::Quaterniond unit(raw.coeffs() / norm);
            const Eigen::Matrix3d R_WJ = X_WC.linear() * unit.toRotationMatrix().transpose();
            for (int k = 0; k < 3; ++k)
                J.col(column + k) += scale * R_WJ.col(k);
            // Per quaternion number c: the unit quaternion moves by (e_c - q q_c) / |q|, which turns the child frame
            // by the angular velocity 2 (dq q*).vec (in the joint frame) about its own origin.
            const Eigen::Vector3d r = p - X_WC.translation();
            for (int c = 0; c < 4; ++c)  // x y z w, as Eigen's coeffs() and the state
            {
                Eigen::Quaterniond d(unit.coeffs() * -unit.coeffs()[c] / norm);
                d.coeffs()[c] += 1.0 / norm;
                const Eigen::Vector3d omega = 2.0 * (d * unit.conjugate()).vec();
                J.col(column + 3 + c) += scale * (R_WJ * omega).cross(r);
            }
        }
    };

    MESHGAP_REGISTER_JOINT(FloatingJoint, "floating")
}  // namespace meshgap
