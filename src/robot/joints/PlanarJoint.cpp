#include "meshgap/robot/Joint.h"

#include <cmath>
#include <limits>

namespace meshgap
{
    /** \brief URDF's "planar": three values "x y theta", free in the plane through the joint frame's origin normal to
        the axis n: the child frame is the joint frame moved by x u + y v, then turned by theta about n. The in-plane
        directions: u is the joint frame's x axis made normal to n (its y axis when x is within 26 degrees of n),
        v = n x u; for n = z (a mobile base on the floor) u = x, v = y, and the motion is an SE(2) pose. URDF gives no
        limits: x and y are bounded by the problem's bounds (their first two coordinates, as an SE(2) body's), theta
        is an angle (interpolated along the shorter arc). */
    class PlanarJoint : public Joint
    {
    public:
        explicit PlanarJoint(const JointSpec &spec) : Joint(unitAxis(spec))
        {
            const Eigen::Vector3d n = axis();
            const Eigen::Vector3d e = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
            u_ = (e - e.dot(n) * n).normalized();
            v_ = n.cross(u_);
        }

        const char *type() const override { return "planar"; }
        std::size_t size() const override { return 3; }
        JointSpace space() const override { return JointSpace::SE2; }
        JointMotion motion() const override { return JointMotion::SE2; }
        std::string valueName(std::size_t k) const override { return k == 0 ? "x" : k == 1 ? "y" : "theta"; }

        void move(const double *q, Eigen::Isometry3d &X) const override
        {
            X.translate(q[0] * u_ + q[1] * v_);
            X.rotate(Eigen::AngleAxisd(q[2], axis()));
        }

        double reach(double /*lowest*/, double /*highest*/) const override
        {
            return std::numeric_limits<double>::infinity();
        }

        void addJacobian(const double *q, const Eigen::Isometry3d &X_WC, const Eigen::Vector3d &p, double scale,
                         Eigen::Matrix3Xd &J, Eigen::Index column) const override
        {
            // The joint frame's rotation: the child's, turned back by theta about n (which that turn keeps).
            const Eigen::Matrix3d R_WJ = X_WC.linear() * Eigen::AngleAxisd(-q[2], axis()).toRotationMatrix();
            J.col(column) += scale * (R_WJ * u_);
            J.col(column + 1) += scale * (R_WJ * v_);
            J.col(column + 2) += scale * (X_WC.linear() * axis()).cross(p - X_WC.translation());
        }

    private:
        Eigen::Vector3d u_, v_;
    };

    MESHGAP_REGISTER_JOINT(PlanarJoint, "planar")
}  // namespace meshgap
