#include "meshgap/ompl/WorkspaceMedialSampler.h"

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace meshgap
{
    namespace
    {
        /** \brief A regular tetrahedron of circumradius \e size about the origin: the point-sized probe. */
        Mesh tetrahedron(double size)
        {
            Mesh m;
            const double s = size / std::sqrt(3.0);
            m.vertices = {{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
            m.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
            m.source = "workspace_medial probe";
            return m;
        }
    }  // namespace

    RobotAxis RobotAxis::of(const Mesh &robot)
    {
        RobotAxis a;
        if (robot.vertices.empty())
            return a;
        for (const Eigen::Vector3d &v : robot.vertices)
            a.centre += v;
        a.centre /= static_cast<double>(robot.vertices.size());
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (const Eigen::Vector3d &v : robot.vertices)
            covariance += (v - a.centre) * (v - a.centre).transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
        a.direction = eigen.eigenvectors().col(2).normalized();  // eigenvalues ascending: the largest spread
        for (const Eigen::Vector3d &v : robot.vertices)
        {
            const double along = (v - a.centre).dot(a.direction);
            a.halfLength = std::max(a.halfLength, std::abs(along));
            a.radius = std::max(a.radius, (v - a.centre - along * a.direction).norm());
        }
        return a;
    }

    WorkspaceMedialSampler::WorkspaceMedialSampler(const ompl::base::SpaceInformation *si)
        : ompl::base::ValidStateSampler(si), sampler_(si->allocStateSampler()), retraction_(si)
    {
        name_ = "workspace_medial";
        checker_ = std::dynamic_pointer_cast<const ClearanceChecker>(si->getStateValidityChecker());
        if (checker_ && checker_->mode() != ClearanceChecker::Mode::CERTIFIED)
            checker_.reset();
        const auto *se3 = dynamic_cast<const ompl::base::SE3StateSpace *>(si->getStateSpace().get());
        if (!checker_ || !se3)
        {
            checker_.reset();
            OMPL_WARN("workspace_medial: needs a certified meshgap ClearanceChecker on SE(3); sampling uniformly");
        }
        else
        {
            const Scene &scene = checker_->scene();
            axis_ = RobotAxis::of(scene.robot().surface());
            BodyOptions options;
            options.gridSize = 0.0;  // the probe as it is
            probe_ = std::make_shared<Scene>(Body::build(tetrahedron(1e-6 * std::max(axis_.radius, 1e-3)), options),
                                             scene.obstacles());
            const ompl::base::RealVectorBounds &b = se3->getBounds();
            box_ = Eigen::AlignedBox3d(Eigen::Vector3d(b.low[0], b.low[1], b.low[2]),
                                       Eigen::Vector3d(b.high[0], b.high[1], b.high[2]));
        }
        params_.declareParam<double>(
            "uniform_probability", [this](double p) { setUniformProbability(p); },
            [this] { return getUniformProbability(); });
        params_.declareParam<double>(
            "max_radius_factor", [this](double f) { setMaxRadiusFactor(f); }, [this] { return getMaxRadiusFactor(); });
    }

    WorkspaceMedialSampler::~WorkspaceMedialSampler() = default;

    double WorkspaceMedialSampler::pointDistance(const Eigen::Vector3d &p, Eigen::Vector3d &nearest, double bound) const
    {
        SceneRequest request;
        request.upperBound = bound;
        SceneResult r;
        probe_->distance(Eigen::Isometry3d(Eigen::Translation3d(p)), request, r);
        nearest = r.onB;
        if (r.atLeast)
            return bound;
        return r.inCollision ? std::min(r.distance, 0.0) : r.distance;
    }

    bool WorkspaceMedialSampler::medialPoint(const Eigen::Vector3d &p, Eigen::Vector3d &medial, double &radius,
                                             Eigen::Vector3d &normal) const
    {
        const double largest = maxRadiusFactor_ * axis_.radius;
        Eigen::Vector3d w0, w;
        const double d0 = pointDistance(p, w0, 2.0 * largest);  // far from everything: a cheap bounded answer
        if (!(d0 > 0.0) || d0 > largest)
            return false;
        normal = (p - w0).normalized();
        // Along the ray from the nearest obstacle point w0 through p, the nearest point stays behind (on w0's
        // side) up to the medial axis and is ahead after it; inside an obstacle counts as ahead.
        const auto behind = [&](double t, bool &tooWide)
        {
            const Eigen::Vector3d q = w0 + t * normal;
            const double d = pointDistance(q, w, 2.0 * largest);
            tooWide = d > largest;
            return d > 0.0 && (q - w).dot(normal) > 0.0;
        };
        bool tooWide = false;
        double lo = d0, hi = 2.0 * largest;
        if (behind(hi, tooWide) || tooWide)
            return false;  // no medial point within the largest radius (an open space)
        for (int k = 0; k < 12; ++k)
        {
            const double mid = 0.5 * (lo + hi);
            if (behind(mid, tooWide))
                lo = mid;
            else
                hi = mid;
            if (tooWide)
                return false;
        }
        medial = w0 + 0.5 * (lo + hi) * normal;
        radius = pointDistance(medial, w);
        if (!(radius > 0.0) || !box_.contains(medial))
            return false;
        // A passage has walls on opposite sides: just past the medial point the nearest obstacle point must lie
        // across from w0 (more than 120 degrees round), not beside it as at a concave edge, whose bisector is
        // medial too.
        const Eigen::Vector3d past = w0 + hi * normal;
        if (!(pointDistance(past, w, 2.0 * largest) > 0.0))
            return false;
        return (past - w).normalized().dot(normal) < -0.5;
    }

    bool WorkspaceMedialSampler::samplePassage(ompl::base::State *state)
    {
        if (!checker_)
            return false;
        const Eigen::Vector3d p(rng_.uniformReal(box_.min().x(), box_.max().x()),
                                rng_.uniformReal(box_.min().y(), box_.max().y()),
                                rng_.uniformReal(box_.min().z(), box_.max().z()));
        Eigen::Vector3d m, n, w;
        double rho;
        if (!medialPoint(p, m, rho, n) || rho < axis_.radius)
            return false;  // no passage here, or one too thin for the robot's cross-section
        // The passage's direction: of the directions normal to n, the one the workspace stays open along longest.
        const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
        Eigen::Vector3d best = e1;
        double bestScore = -1.0;
        for (unsigned k = 0; k < directions_; ++k)
        {
            const double theta = M_PI * (k + rng_.uniform01()) / directions_;
            const Eigen::Vector3d e = std::cos(theta) * e1 + std::sin(theta) * e2;
            const double score =
                std::min(pointDistance(m + rho * e, w, 2.0 * rho), pointDistance(m - rho * e, w, 2.0 * rho));
            if (score > bestScore)
            {
                bestScore = score;
                best = e;
            }
        }
        if (rng_.uniformBool())
            best = -best;
        // The robot's long axis onto the passage's, rolled at random, a random point of it at m.
        const Eigen::Quaterniond onto = Eigen::Quaterniond::FromTwoVectors(axis_.direction, best);
        const Eigen::Matrix3d R = Eigen::AngleAxisd(rng_.uniformReal(-M_PI, M_PI), best) * onto.toRotationMatrix();
        // An offset up to twice the half length: in the passage, entering it, or lined up in front of it (the
        // states that join a passage's roadmap to the open space on either side).
        const double offset = rng_.uniformReal(-2.0 * axis_.halfLength, 2.0 * axis_.halfLength);
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = R;
        X.translation() = m - R * (axis_.centre + offset * axis_.direction);
        stateFromPose(*si_->getStateSpace(), X, state);
        if (!si_->satisfiesBounds(state))
            return false;
        return retraction_.retract(state) && si_->satisfiesBounds(state);
    }

    bool WorkspaceMedialSampler::sample(ompl::base::State *state)
    {
        if (checker_ && !(rng_.uniform01() < uniformProbability_))
        {
            // Most workspace points are in open space or in no passage the robot fits: many cheap draws.
            for (unsigned attempt = 0; attempt < passageAttempts_; ++attempt)
                if (samplePassage(state))
                    return true;
            return false;
        }
        for (unsigned attempt = 0; attempt < attempts_; ++attempt)
        {
            sampler_->sampleUniform(state);
            if (si_->isValid(state))
                return true;
        }
        return false;
    }

    bool WorkspaceMedialSampler::sampleNear(ompl::base::State *state, const ompl::base::State *near, double distance)
    {
        return retraction_.sampleNear(state, near, distance);
    }

}  // namespace meshgap
