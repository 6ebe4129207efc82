#include "meshgap/ompl/ClearanceChecker.h"

#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ThreadInstances.h"
#include "meshgap/distance/SolverFactory.h"

namespace meshgap
{
    namespace
    {
        /** \brief A control model's state (ControlModels.h): a compound space whose subspace 0 is the pose, the rest
            velocities; null for any other space. */
        const ompl::base::CompoundStateSpace *withPoseSubspace(const ompl::base::StateSpace &space)
        {
            if (space.getType() == ompl::base::STATE_SPACE_SE2 || space.getType() == ompl::base::STATE_SPACE_SE3 ||
                !space.isCompound())
                return nullptr;
            const auto *compound = space.as<ompl::base::CompoundStateSpace>();
            const int pose = compound->getSubspaceCount() > 0 ? compound->getSubspace(0)->getType() : -1;
            return pose == ompl::base::STATE_SPACE_SE2 || pose == ompl::base::STATE_SPACE_SE3 ? compound : nullptr;
        }
    }  // namespace

    Eigen::Isometry3d poseFromState(const ompl::base::StateSpace &space, const ompl::base::State *state)
    {
        if (const auto *compound = withPoseSubspace(space))
            return poseFromState(*compound->getSubspace(0), state->as<ompl::base::CompoundState>()->components[0]);
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        if (space.getType() == ompl::base::STATE_SPACE_SE3)
        {
            const auto *s = state->as<ompl::base::SE3StateSpace::StateType>();
            const auto &r = s->rotation();
            X.linear() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
            X.translation() = Eigen::Vector3d(s->getX(), s->getY(), s->getZ());
            return X;
        }
        if (space.getType() == ompl::base::STATE_SPACE_SE2)
        {
            const auto *s = state->as<ompl::base::SE2StateSpace::StateType>();
            X.linear() = Eigen::AngleAxisd(s->getYaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
            X.translation() = Eigen::Vector3d(s->getX(), s->getY(), 0.0);
            return X;
        }
        throw Exception("ClearanceChecker", "state space " + quote(space.getName()) + " is neither SE(3) nor SE(2)");
    }

    void stateFromPose(const ompl::base::StateSpace &space, const Eigen::Isometry3d &X, ompl::base::State *state)
    {
        if (const auto *compound = withPoseSubspace(space))
            return stateFromPose(*compound->getSubspace(0), X, state->as<ompl::base::CompoundState>()->components[0]);
        if (space.getType() == ompl::base::STATE_SPACE_SE3)
        {
            auto *s = state->as<ompl::base::SE3StateSpace::StateType>();
            const Eigen::Quaterniond q(X.linear());
            s->setXYZ(X.translation().x(), X.translation().y(), X.translation().z());
            s->rotation().x = q.x();
            s->rotation().y = q.y();
            s->rotation().z = q.z();
            s->rotation().w = q.w();
            return;
        }
        if (space.getType() == ompl::base::STATE_SPACE_SE2)
        {
            auto *s = state->as<ompl::base::SE2StateSpace::StateType>();
            s->setXY(X.translation().x(), X.translation().y());
            s->setYaw(std::atan2(X.linear()(1, 0), X.linear()(0, 0)));
            return;
        }
        throw Exception("ClearanceChecker", "state space " + quote(space.getName()) + " is neither SE(3) nor SE(2)");
    }

    double sweepBound(const ompl::base::StateSpace &space, const ompl::base::State *s1, const ompl::base::State *s2,
                      double radius)
    {
        const Eigen::Isometry3d X1 = poseFromState(space, s1), X2 = poseFromState(space, s2);
        const double translation = (X2.translation() - X1.translation()).norm();
        const double angle = Eigen::AngleAxisd(X1.linear().transpose() * X2.linear()).angle();
        return translation + radius * angle;
    }

    namespace
    {
        /** \brief A thread keeps the warm starts of its last few checkers (threadInstanceFor()): a warm start holds
            certificates (up to megabytes on large meshes), and a benchmark makes a checker per run. */
        constexpr std::size_t WARM_STARTS_PER_THREAD = 8;
        /** \brief Certificates each of them keeps (SceneWarmStart): a planner's queries return to a few regions in
            turn (the two trees of RRTConnect, the motions out of a tree node), each carried from its own. */
        constexpr std::size_t CERTIFICATES_PER_WARM_START = 4;

        SceneWarmStart &warmStartFor(std::uint64_t id)
        {
            return threadInstanceFor<SceneWarmStart, WARM_STARTS_PER_THREAD>(id, CERTIFICATES_PER_WARM_START);
        }

        std::uint64_t nanosecondsSince(std::chrono::steady_clock::time_point start)
        {
            return static_cast<std::uint64_t>(
                std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
        }

        /** \brief A seed from the pose's bits: the same state always gets the same node-level answer. */
        std::uint64_t seedOf(const Eigen::Isometry3d &X)
        {
            std::uint64_t h = 1469598103934665603ull;
            const double *p = X.matrix().data();
            for (int k = 0; k < 16; ++k)
            {
                std::uint64_t bits;
                std::memcpy(&bits, p + k, sizeof bits);
                h = (h ^ bits) * 1099511628211ull;
            }
            return h;
        }
    }  // namespace

    ClearanceChecker::ClearanceChecker(const ompl::base::SpaceInformationPtr &si, SceneConstPtr scene, Mode mode,
                                       std::string fastSolver)
      : ompl::base::StateValidityChecker(si), scene_(std::move(scene)), mode_(mode), fastSolver_(std::move(fastSolver)),
        id_(newInstanceId())
    {
        if (!scene_)
            throw Exception("ClearanceChecker", "no scene");
        allocSolver(fastSolver_);  // an unknown name: one error listing the valid ones
        specs_.clearanceComputationType = mode_ == Mode::CERTIFIED ? ompl::base::StateValidityCheckerSpecs::EXACT :
                                                                     ompl::base::StateValidityCheckerSpecs::APPROXIMATE;
        specs_.hasValidDirectionComputation = true;
    }

    bool ClearanceChecker::isValid(const ompl::base::State *state) const
    {
        const auto start = std::chrono::steady_clock::now();
        counts_.add(VALIDITY_CALLS, 1);
        const bool valid = si_->satisfiesBounds(state) && !scene_->inCollision(poseFromState(*si_->getStateSpace(), state));
        counts_.add(NANOSECONDS, nanosecondsSince(start));
        return valid;
    }

    bool ClearanceChecker::isValid(const ompl::base::State *state, double &dist) const
    {
        if (!si_->satisfiesBounds(state))
        {
            counts_.add(VALIDITY_CALLS, 1);
            dist = 0.0;
            return false;
        }
        SceneRequest request;
        request.computeDepth = false;  // the verdict, and the clearance of a valid state
        const SceneResult r = query(state, true, request);
        dist = r.distance;
        return !r.inCollision;
    }

    double ClearanceChecker::clearance(const ompl::base::State *state) const
    {
        return query(state, false).distance;
    }

    double ClearanceChecker::clearanceOrContact(const ompl::base::State *state) const
    {
        // Stopping at a distance of 0 stops only in collision: a free state's answer is complete.
        SceneRequest request;
        request.stopBelow = 0.0;
        return query(state, false, request).distance;
    }

    double ClearanceChecker::clearanceBelow(const ompl::base::State *state, double bound) const
    {
        SceneRequest request;
        request.stopBelow = 0.0;
        request.upperBound = bound;
        return std::min(query(state, false, request).distance, bound);  // fast mode has no bound: min() it
    }

    double ClearanceChecker::clearance(const ompl::base::State *state, ompl::base::State *validState,
                                       bool &validStateAvailable) const
    {
        const SceneResult r = query(state, false);
        validStateAvailable = validState != nullptr && validStateAway(state, r, validState);
        return r.distance;
    }

    bool ClearanceChecker::validStateAway(const ompl::base::State *state, const SceneResult &r,
                                          ompl::base::State *out) const
    {
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        const bool planar = space.getType() == ompl::base::STATE_SPACE_SE2;
        const Eigen::Isometry3d X = poseFromState(space, state);
        auto flat = [planar](Eigen::Vector3d v) {
            if (planar)
                v.z() = 0.0;  // an SE(2) robot only moves in its plane
            return v;
        };
        Eigen::Vector3d direction = flat(r.inCollision ? r.onB - r.onA : r.onA - r.onB);
        const double radius = scene_->robot().radiusAboutOrigin();
        const double tiny = 1e-12 * (1.0 + radius + X.translation().norm());
        if (direction.norm() <= tiny)  // touching witnesses give no direction: move from the contact to the origin
            direction = flat(X.translation() - r.onB);
        if (direction.norm() <= tiny || !std::isfinite(r.distance))
            return false;
        direction.normalize();
        const bool wasValid = !r.inCollision && si_->satisfiesBounds(state);
        double step = std::abs(r.distance) + 0.02 * radius;
        for (int attempt = 0; attempt < 5; ++attempt, step *= 2.0)
        {
            si_->copyState(out, state);
            const Eigen::Vector3d t = X.translation() + step * direction;
            if (planar)
                out->as<ompl::base::SE2StateSpace::StateType>()->setXY(t.x(), t.y());
            else
                out->as<ompl::base::SE3StateSpace::StateType>()->setXYZ(t.x(), t.y(), t.z());
            space.enforceBounds(out);
            double d;
            if (isValid(out, d) && (!wasValid || d > r.distance))
                return true;
        }
        return false;
    }

    SceneResult ClearanceChecker::query(const ompl::base::State *state) const
    {
        return query(state, false);
    }

    SceneResult ClearanceChecker::query(const ompl::base::State *state, const SceneRequest &request) const
    {
        return query(state, false, request);
    }

    SceneResult ClearanceChecker::query(const ompl::base::State *state, bool countAsValidity,
                                        SceneRequest request) const
    {
        const auto start = std::chrono::steady_clock::now();
        counts_.add(countAsValidity ? VALIDITY_CALLS : CLEARANCE_CALLS, 1);
        const Eigen::Isometry3d X = poseFromState(*si_->getStateSpace(), state);
        request.exact = mode_ == Mode::CERTIFIED;
        request.solver = fastSolver_;
        request.computeDepth = request.computeDepth && computeDepth_;
        SceneResult result;
        if (request.exact || fastSolver_ == "warm-fast")  // warm-fast: the paper's warm start along this thread's run
        {
            scene_->distance(X, request, warmStartFor(id_), result);
            if (request.exact)
                counts_.add(result.warmStartUse == SceneWarmStart::Use::CARRY   ? CARRIED
                            : result.warmStartUse == SceneWarmStart::Use::WRITE ? WRITTEN
                                                                                 : COLD,
                            1);
        }
        else
        {
            request.seed = seedOf(X);
            scene_->distance(X, request, result);  // fast mode is a pure function of the state: no history
        }
        counts_.add(EVALUATIONS, result.evaluations);
        counts_.add(WARM_HITS, result.warmStartHit ? 1 : 0);
        counts_.add(NANOSECONDS, nanosecondsSince(start));
        return result;
    }

    CheckerStats ClearanceChecker::stats() const
    {
        CheckerStats s;
        s.validityCalls = counts_.sum(VALIDITY_CALLS);
        s.clearanceCalls = counts_.sum(CLEARANCE_CALLS);
        s.evaluations = counts_.sum(EVALUATIONS);
        s.warmStartHits = counts_.sum(WARM_HITS);
        s.carried = counts_.sum(CARRIED);
        s.written = counts_.sum(WRITTEN);
        s.cold = counts_.sum(COLD);
        s.seconds = 1e-9 * static_cast<double>(counts_.sum(NANOSECONDS));
        return s;
    }
}  // namespace meshgap
