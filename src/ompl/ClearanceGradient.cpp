#include "meshgap/ompl/ClearanceGradient.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <algorithm>
#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/distance/ExactDistance.h"

namespace meshgap
{
    namespace
    {
        constexpr unsigned MAX_PAIRS = 8;
        using Vector6 = Eigen::Matrix<double, 6, 1>;

        /** \brief One pair's gradient in tangent coordinates (SE(3): 6, SE(2): the first 3 used): the derivative of
            the signed distance, \e p the robot's witness point, \e n the unit direction that increases it. */
        Vector6 pairGradient(bool planar, const Eigen::Vector3d &origin, const Eigen::Vector3d &p,
                             const Eigen::Vector3d &n)
        {
            const Eigen::Vector3d w = (p - origin).cross(n);
            Vector6 g = Vector6::Zero();
            if (planar)
                g << n.x(), n.y(), w.z(), 0.0, 0.0, 0.0;
            else
                g << n, w;
            return g;
        }

        /** \brief The minimum-norm point of the convex hull of \e h[0..k) (Euclidean; an SE(2) gradient has zeros
            past its 3 coordinates, which change no norm), exactly:
            the best feasible affine minimum over every subset (k <= MAX_PAIRS, so at most 255 small systems). */
        Vector6 minNormPoint(const Vector6 *h, unsigned k)
        {
            using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, MAX_PAIRS + 1, MAX_PAIRS + 1>;
            using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MAX_PAIRS + 1, 1>;
            Vector6 best = h[0];
            double bestNorm = h[0].squaredNorm();
            for (unsigned i = 1; i < k; ++i)
                if (h[i].squaredNorm() < bestNorm)
                {
                    best = h[i];
                    bestNorm = h[i].squaredNorm();
                }
            for (unsigned mask = 1; mask < (1u << k); ++mask)
            {
                unsigned idx[MAX_PAIRS], m = 0;
                for (unsigned i = 0; i < k; ++i)
                    if (mask & (1u << i))
                        idx[m++] = i;
                if (m < 2)
                    continue;
                // KKT system of min |sum l_i h_i|^2 subject to sum l_i = 1.
                Small A(m + 1, m + 1);
                SmallVector b(m + 1);
                for (unsigned i = 0; i < m; ++i)
                {
                    for (unsigned j = 0; j < m; ++j)
                        A(i, j) = h[idx[i]].dot(h[idx[j]]);
                    A(i, m) = 1.0;
                    A(m, i) = 1.0;
                    b(i) = 0.0;
                }
                A(m, m) = 0.0;
                b(m) = 1.0;
                const SmallVector x = A.fullPivLu().solve(b);
                if (!x.allFinite() || !(A * x).isApprox(b, 1e-9))
                    continue;  // degenerate subset (affinely dependent points): a smaller subset covers it
                bool feasible = true;
                Vector6 point = Vector6::Zero();
                for (unsigned i = 0; i < m; ++i)
                {
                    feasible = feasible && x(i) >= -1e-12;
                    point += x(i) * h[idx[i]];
                }
                if (feasible && point.squaredNorm() < bestNorm)
                {
                    best = point;
                    bestNorm = point.squaredNorm();
                }
            }
            return best;
        }

        /** \brief The gradients of the nearly active pairs (at most MAX_PAIRS; when full, a closer pair replaces the
            farthest one, never the first), and their minimum-norm combination. */
        struct Bundle
        {
            Vector6 g[MAX_PAIRS];
            double distances[MAX_PAIRS];
            unsigned k{0};
            Vector6 scale;  ///< the metric |g_t|^2 + |g_w|^2 / L^2 as a scaling of the rotation part by 1 / L

            Bundle(bool planar, double L)
            {
                scale = Vector6::Ones();
                if (planar)
                    scale(2) = 1.0 / L;
                else
                    scale.tail<3>().setConstant(1.0 / L);
            }

            void add(const Vector6 &gi, double distance)
            {
                if (k < MAX_PAIRS)
                {
                    g[k] = gi;
                    distances[k++] = distance;
                    return;
                }
                const unsigned worst =
                    static_cast<unsigned>(std::max_element(distances + 1, distances + k) - distances);
                if (distance < distances[worst])
                {
                    g[worst] = gi;
                    distances[worst] = distance;
                }
            }

            /** \brief Minimum norm in the metric: scale the rotation part, solve, scale back. */
            Vector6 combine() const
            {
                if (k == 1)
                    return g[0];
                Vector6 h[MAX_PAIRS];
                for (unsigned i = 0; i < k; ++i)
                    h[i] = g[i].cwiseProduct(scale);
                return Vector6(minNormPoint(h, k).cwiseQuotient(scale));
            }
        };

        /** \brief What the gradient's steps share: the scene, the query's pose and answer, the frame. */
        struct GradientQuery
        {
            const Scene &scene;
            const SceneResult &r;
            const Eigen::Isometry3d X;
            const bool planar;
            const double L;     ///< the length scale of rotations (the robot's radius, 1 if none)
            const double tiny;  ///< a witness vector shorter than this has no direction
        };

        /** \brief Add the closest pairs of the other obstacles within \e tieTolerance of the clearance. */
        void addTiedObstacles(const GradientQuery &q, double tieTolerance, Bundle &bundle)
        {
            const double limit = q.r.distance + tieTolerance;
            for (std::size_t o = 0; o < q.scene.obstacles().size(); ++o)
            {
                if (o == q.r.obstacle)
                    continue;
                DistanceResult pair;
                DistanceRequest bounded;
                bounded.upperBound = std::nextafter(limit, HUGE_VAL);
                // Obstacles are in the world frame: X_AB is the robot's pose, and the witnesses are world points.
                refineExact(*q.scene.obstacles()[o], q.scene.robot(), q.X, pair, bounded);
                if (pair.inCollision || !(pair.distance <= limit))
                    continue;
                const Eigen::Vector3d d = pair.onB - pair.onA;
                if (d.norm() <= q.tiny)
                    continue;
                bundle.add(pairGradient(q.planar, q.X.translation(), pair.onB, d.normalized()), pair.distance);
            }
        }

        /** \brief X moved by alpha M^-1 g (M the metric): translation alpha g_t, rotation alpha g_w / L^2. */
        Eigen::Isometry3d stepPose(const GradientQuery &q, const Vector6 &g, double alpha)
        {
            Eigen::Isometry3d Y = q.X;
            if (q.planar)
            {
                Y.translation() += alpha * Eigen::Vector3d(g(0), g(1), 0.0);
                Y.linear() =
                    Eigen::AngleAxisd(alpha * g(2) / (q.L * q.L), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                    q.X.linear();
            }
            else
            {
                Y.translation() += alpha * g.head<3>();
                const Eigen::Vector3d w = alpha * g.tail<3>() / (q.L * q.L);
                if (w.norm() > 0.0)
                    Y.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix() * q.X.linear();
            }
            return Y;
        }

        /** \brief Probes for ties the per-obstacle test cannot see (two closest pairs on one obstacle): a step of
            length \e probeStep along the ascent direction should raise the clearance by about probeStep * ||g||; if
            it raises it by less than half that, the pair met there is a nearly active one: its gradient joins the
            bundle. Returns the combined gradient; \e probed counts the pairs added. */
        Vector6 probeHiddenPairs(const GradientQuery &q, const ClearanceGradientOptions &options, Bundle &bundle,
                                 Vector6 result, unsigned &probed)
        {
            const double h = options.probeStep > 0.0 ? options.probeStep : 0.05 * q.r.distance;
            SceneWarmStart warm;
            SceneRequest request;
            for (unsigned probe = 0; probe < options.probes && bundle.k < MAX_PAIRS; ++probe)
            {
                const double norm = result.cwiseProduct(bundle.scale).norm();  // ||g||
                if (!(norm > 1e-9))
                    break;
                // The step v = alpha M^-1 g with alpha = h / ||g||: it moves no robot point much further than h.
                const double alpha = h / norm;
                const Eigen::Isometry3d Y = stepPose(q, result, alpha);
                SceneResult s;
                q.scene.distance(Y, request, warm, s);
                if (s.inCollision || !std::isfinite(s.distance))
                    break;
                if (s.distance >= q.r.distance + 0.5 * alpha * norm * norm)
                    break;  // the direction raises the clearance as predicted: no hidden pair in the way
                const Eigen::Vector3d d = s.onA - s.onB;
                if (d.norm() <= q.tiny)
                    break;
                bundle.add(pairGradient(q.planar, Y.translation(), s.onA, d.normalized()), s.distance);
                ++probed;
                result = bundle.combine();
            }
            return result;
        }
    }  // namespace

    unsigned tangentDimension(const ompl::base::StateSpace &space)
    {
        if (space.getType() == ompl::base::STATE_SPACE_SE3)
            return 6;
        if (space.getType() == ompl::base::STATE_SPACE_SE2)
            return 3;
        throw Exception("ClearanceGradient", "state space " + quote(space.getName()) + " is neither SE(3) nor SE(2)");
    }

    void applyTangentStep(const ompl::base::StateSpace &space, const ompl::base::State *state, const double *step,
                          ompl::base::State *out)
    {
        if (space.getType() == ompl::base::STATE_SPACE_SE2)
        {
            const auto *s = state->as<ompl::base::SE2StateSpace::StateType>();
            const double x = s->getX() + step[0], y = s->getY() + step[1];
            const double yaw = std::remainder(s->getYaw() + step[2], 2.0 * M_PI);
            auto *o = out->as<ompl::base::SE2StateSpace::StateType>();
            o->setXY(x, y);
            o->setYaw(yaw);
            return;
        }
        Eigen::Isometry3d X = poseFromState(space, state);
        const Eigen::Vector3d w(step[3], step[4], step[5]);
        const double angle = w.norm();
        if (angle > 0.0)
            X.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() * X.linear();
        X.translation() += Eigen::Vector3d(step[0], step[1], step[2]);
        stateFromPose(space, X, out);
    }

    double clearanceGradient(const ClearanceChecker &checker, const ompl::base::State *state,
                             std::vector<double> &gradient, const ClearanceGradientOptions &options,
                             ClearanceGradientInfo *info)
    {
        if (checker.mode() != ClearanceChecker::Mode::CERTIFIED)
            throw Exception("ClearanceGradient", "needs a checker in CERTIFIED mode (exact witness points)");
        const ompl::base::StateSpace &space = *checker.spaceInformation().getStateSpace();
        const unsigned dim = tangentDimension(space);
        gradient.assign(dim, 0.0);
        ClearanceGradientInfo local;
        ClearanceGradientInfo &out = info != nullptr ? *info : local;
        out = ClearanceGradientInfo();

        const SceneResult r = checker.query(state);
        out.inCollision = r.inCollision;
        const Scene &scene = checker.scene();
        if (!std::isfinite(r.distance) || r.obstacle >= scene.obstacles().size())
            return r.distance;
        if (r.inCollision && r.penetration != Penetration::DEEPEST_NODE)
            return r.distance;  // no depth: the signed distance is CONTACT_DISTANCE, locally constant

        const Eigen::Isometry3d X = poseFromState(space, state);
        const double radius = scene.robot().radiusAboutOrigin();
        const GradientQuery q{
            scene, r, X, dim == 3, radius > 0.0 ? radius : 1.0, 1e-14 * (1.0 + radius + X.translation().norm())};
        const Eigen::Vector3d d0 =
            r.inCollision ? Eigen::Vector3d(r.onB - r.onA) : Eigen::Vector3d(r.onA - r.onB);
        if (d0.norm() <= q.tiny)
            return r.distance;  // coincident witnesses: no direction
        Bundle bundle(q.planar, q.L);
        bundle.add(pairGradient(q.planar, X.translation(), r.onA, d0.normalized()), r.distance);
        if (!r.inCollision)
            addTiedObstacles(q, options.tieTolerance >= 0.0 ? options.tieTolerance : 1e-9 * (1.0 + radius), bundle);
        out.hasDirection = true;
        Vector6 result = bundle.combine();
        if (!r.inCollision && options.probes > 0)
            result = probeHiddenPairs(q, options, bundle, result, out.probedPairs);
        out.activePairs = bundle.k;
        for (unsigned i = 0; i < dim; ++i)
            gradient[i] = result(i);
        return r.distance;
    }

    void ascentStep(const std::vector<double> &gradient, double lengthScale, double alpha, std::vector<double> &step)
    {
        const double L2 = lengthScale > 0.0 ? lengthScale * lengthScale : 1.0;
        step.resize(gradient.size());
        const std::size_t translations = gradient.size() == 3 ? 2 : 3;
        for (std::size_t i = 0; i < gradient.size(); ++i)
            step[i] = alpha * (i < translations ? gradient[i] : gradient[i] / L2);
    }
}  // namespace meshgap

namespace meshgap
{
    double ClearanceChecker::lengthScale() const
    {
        const double radius = scene().robot().radiusAboutOrigin();
        return radius > 0.0 ? radius : 1.0;
    }

    double ClearanceChecker::sweep(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        return sweepBound(*si_->getStateSpace(), s1, s2, scene().robot().radiusAboutOrigin());
    }

    unsigned ClearanceChecker::gradientDimension() const
    {
        return tangentDimension(*si_->getStateSpace());
    }

    double ClearanceChecker::gradient(const ompl::base::State *state, std::vector<double> &gradient,
                                      const ClearanceGradientOptions &options, ClearanceGradientInfo *info) const
    {
        return clearanceGradient(*this, state, gradient, options, info);
    }

    double ClearanceChecker::gradientNorm2(const std::vector<double> &gradient) const
    {
        const double L = lengthScale();
        const std::size_t translations = gradient.size() == 3 ? 2 : 3;
        double g2 = 0.0;
        for (std::size_t i = 0; i < gradient.size(); ++i)
            g2 += gradient[i] * gradient[i] / (i < translations ? 1.0 : L * L);
        return g2;
    }

    void ClearanceChecker::ascentStep(const std::vector<double> &gradient, double alpha,
                                      std::vector<double> &step) const
    {
        meshgap::ascentStep(gradient, lengthScale(), alpha, step);
    }

    void ClearanceChecker::applyStep(const ompl::base::State *state, const double *step, ompl::base::State *out) const
    {
        applyTangentStep(*si_->getStateSpace(), state, step, out);
    }
}  // namespace meshgap
