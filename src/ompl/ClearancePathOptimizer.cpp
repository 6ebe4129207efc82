#include "meshgap/ompl/ClearancePathOptimizer.h"

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <queue>

#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceGradient.h"

namespace meshgap
{
    namespace ob = ompl::base;
    namespace og = ompl::geometric;

    /** \brief The path being optimised, with what is known about it: c[i] the clearance of state i, m[i] the
        certified lower bound on the clearance along motion i (states i, i + 1), b[i] its least clear sample and f[i]
        where along it, alpha[i] state i's step length. */
    struct ClearancePathOptimizer::Work
    {
        std::vector<ob::State *> &states;
        std::vector<double> c, m, b, f, alpha;
        double length{0.0};
        explicit Work(std::vector<ob::State *> &s) : states(s) {}
    };

    ClearancePathOptimizer::ClearancePathOptimizer(const ob::SpaceInformationPtr &si, ClearanceCheckerPtr checker)
        : si_(si), checker_(std::move(checker))
    {
        if (!checker_)
            throw Exception("ClearancePathOptimizer", "no checker");
        if (checker_->mode() != ClearanceChecker::Mode::CERTIFIED)
            throw Exception("ClearancePathOptimizer", "needs a checker in CERTIFIED mode (exact clearance)");
        tangentDimension(*si_->getStateSpace());  // throws for spaces other than SE(3) and SE(2)
        validator_ = std::make_shared<ClearanceMotionValidator>(si_, checker_);
        params_.declareParam<double>(
            "time_limit", [this](double v) { setTimeLimit(v); }, [this] { return getTimeLimit(); });
        params_["time_limit"].setRangeSuggestion("0.:1.:3600.");
        params_.declareParam<double>(
            "target_clearance", [this](double v) { setTargetClearance(v); }, [this] { return getTargetClearance(); });
        params_.declareParam<double>(
            "max_length_factor", [this](double v) { setMaxLengthFactor(v); }, [this] { return getMaxLengthFactor(); });
        params_["max_length_factor"].setRangeSuggestion("1.:0.5:100.");
        params_.declareParam<unsigned long>(
            "seed", [this](unsigned long v) { setSeed(v); }, [this] { return getSeed(); });
        params_.declareParam<unsigned>(
            "max_rounds", [this](unsigned v) { setMaxRounds(v); }, [this] { return getMaxRounds(); });
        params_["max_rounds"].setRangeSuggestion("1:1:100000");
        params_.declareParam<bool>(
            "shortcut", [this](bool v) { setShortcut(v); }, [this] { return getShortcut(); });
        params_["shortcut"].setRangeSuggestion("0,1");
        params_.declareParam<double>(
            "tolerance", [this](double v) { setTolerance(v); }, [this] { return getTolerance(); });
    }

    ClearancePathOptimizer::MotionBound ClearancePathOptimizer::motionBound(const ob::State *s1, const ob::State *s2,
                                                                            double c1, double c2, double tolerance,
                                                                            double relative, double refuteBelow) const
    {
        const ob::StateSpace &space = *si_->getStateSpace();
        const double sweep = sweepBound(space, s1, s2, checker_->scene().robot().radiusAboutOrigin());
        MotionBound r;
        r.best = c1;
        r.at = 0.0;
        if (c2 < r.best)
        {
            r.best = c2;
            r.at = 1.0;
        }
        struct Interval
        {
            double a, b, ca, cb, bound;
            bool operator<(const Interval &o) const { return bound > o.bound; }  // lowest bound on top
        };
        auto lower = [sweep](double a, double b, double ca, double cb) { return 0.5 * (ca + cb - sweep * (b - a)); };
        std::priority_queue<Interval> open;
        open.push({0.0, 1.0, c1, c2, lower(0.0, 1.0, c1, c2)});
        ob::State *s = si_->allocState();
        // The best sample can only fall; stop when no interval can hold a point more than the tolerance below it,
        // or at the sample cap (the bound is still certified, only looser).
        for (unsigned samples = 0; !open.empty() && samples < MAX_SAMPLES_PER_MOTION; ++samples)
        {
            // Out of time while optimising: give up on this motion (a refuted bound rejects the change).
            if (ptc_ != nullptr && samples % 16 == 15 && (*ptc_)())
            {
                r.refuted = true;
                break;
            }
            const Interval iv = open.top();
            // Tight enough, and (when a floor is given) the floor proven: every interval bounded at or above it.
            if (iv.bound >= std::max(r.best - std::max(tolerance, relative * r.best), refuteBelow))
                break;
            open.pop();
            const double mid = 0.5 * (iv.a + iv.b);
            space.interpolate(s1, s2, mid, s);
            const double cm = checker_->clearance(s);
            if (cm < r.best)
            {
                r.best = cm;
                r.at = mid;
            }
            if (cm < refuteBelow)
            {
                r.refuted = true;
                break;
            }
            open.push({iv.a, mid, iv.ca, cm, lower(iv.a, mid, iv.ca, cm)});
            open.push({mid, iv.b, cm, iv.cb, lower(mid, iv.b, cm, iv.cb)});
        }
        si_->freeState(s);
        r.lower = r.refuted ? -std::numeric_limits<double>::infinity()
                            : std::min(r.best, open.empty() ? r.best : open.top().bound);
        return r;
    }

    double ClearancePathOptimizer::defaultTolerance(const std::vector<double> &clearances) const
    {
        return std::max(1e-3 * std::max(*std::min_element(clearances.begin(), clearances.end()), 0.0),
                        1e-9 * checker_->scene().robot().radiusAboutOrigin());
    }

    double ClearancePathOptimizer::minClearance(const og::PathGeometric &path, double tolerance) const
    {
        const std::size_t n = path.getStateCount();
        if (n == 0)
            return std::numeric_limits<double>::infinity();
        std::vector<double> c(n);
        for (std::size_t i = 0; i < n; ++i)
            c[i] = checker_->clearance(path.getState(i));
        if (!(tolerance > 0.0))
            tolerance = defaultTolerance(c);
        double best = c[0];
        for (std::size_t i = 0; i + 1 < n; ++i)
            best = std::min(best, motionBound(path.getState(i), path.getState(i + 1), c[i], c[i + 1], tolerance,
                                              MEASURE_RELATIVE_TOLERANCE)
                                      .best);
        return best;
    }

    void ClearancePathOptimizer::validateInput(const og::PathGeometric &path) const
    {
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            if (!si_->satisfiesBounds(path.getState(i)))
                throw Exception("ClearancePathOptimizer",
                                "state " + std::to_string(i) + " of the input path is out of bounds");
            if (!checker_->isValid(path.getState(i)))
                throw Exception("ClearancePathOptimizer",
                                "state " + std::to_string(i) + " of the input path is in collision");
        }
        for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i)
            if (!validator_->checkMotion(path.getState(i), path.getState(i + 1)))
                throw Exception("ClearancePathOptimizer",
                                "the input path's motion from state " + std::to_string(i) + " to " +
                                    std::to_string(i + 1) +
                                    " is refused by the certified clearance motion validator (it collides or grazes "
                                    "an obstacle closer than the validator can prove free)");
    }

    bool ClearancePathOptimizer::optimize(og::PathGeometric &path)
    {
        return optimize(path, ob::timedPlannerTerminationCondition(timeLimit_));
    }

    bool ClearancePathOptimizer::optimize(og::PathGeometric &path, const ob::PlannerTerminationCondition &ptc)
    {
        const auto start = std::chrono::steady_clock::now();
        stats_ = Stats();
        if (path.getSpaceInformation() != si_)
            throw Exception("ClearancePathOptimizer", "the path belongs to another space information");
        if (!(maxLengthFactor_ >= 1.0))
            throw Exception("ClearancePathOptimizer", "max_length_factor must be at least 1");
        validateInput(path);
        const std::size_t n0 = path.getStateCount();
        stats_.statesBefore = stats_.statesAfter = static_cast<unsigned>(n0);
        stats_.lengthBefore = stats_.lengthAfter = path.length();
        if (n0 < 2)
        {
            stats_.minClearanceBefore = stats_.minClearanceAfter =
                n0 == 0 ? 0.0 : checker_->clearance(path.getState(0));
            return false;
        }

        const ob::StateSpace &space = *si_->getStateSpace();
        const double L = checker_->scene().robot().radiusAboutOrigin();
        const og::PathGeometric input(path);
        struct ClearPtc  // ptc_ is set only while the optimisation loop runs (never while measuring)
        {
            const ob::PlannerTerminationCondition *&ptc;
            ~ClearPtc() { ptc = nullptr; }
        } clearPtc{ptc_};
        Work w(path.getStates());
        w.c.resize(n0);
        for (std::size_t i = 0; i < n0; ++i)
            w.c[i] = checker_->clearance(w.states[i]);
        const double tolerance = tolerance_ > 0.0 ? tolerance_ : defaultTolerance(w.c);
        // The input measured now (before the clock matters), the output at the end, the same way.
        const double inputMeasure = minClearance(input, tolerance);
        // While optimising, a motion's bound need only be as tight as a fraction of its own clearance: a motion far
        // above the path's minimum is not worth many queries. The bounds kept (m) are certified lower bounds.
        const double relative = 0.02;
        w.m.resize(n0 - 1);
        w.b.resize(n0 - 1);
        w.f.resize(n0 - 1);
        auto keep = [&w](std::size_t i, const MotionBound &r)
        {
            w.m[i] = r.lower;
            w.b[i] = r.best;
            w.f[i] = r.at;
        };
        for (std::size_t i = 0; i + 1 < n0; ++i)
            keep(i, motionBound(w.states[i], w.states[i + 1], w.c[i], w.c[i + 1], tolerance, relative));
        w.length = stats_.lengthBefore;
        const double maxLength = maxLengthFactor_ * stats_.lengthBefore;
        const std::size_t maxStates = std::max<std::size_t>(4 * n0, 200);
        w.alpha.assign(n0, 0.0);
        for (std::size_t i = 0; i < n0; ++i)
            w.alpha[i] = std::max(0.5 * w.c[i], 1e-3 * L);

        ompl::RNG rng(seed_);
        std::vector<double> gradient, step;
        ob::State *candidate = si_->allocState();
        auto report = [this](const ob::State *a, const ob::State *b)
        {
            if (onMotion_)
                onMotion_(a, b);
        };
        auto currentMin = [&w] { return *std::min_element(w.m.begin(), w.m.end()); };
        auto insertAt =
            [&w](std::size_t i, ob::State *s, double cs, double alpha, const MotionBound &ra, const MotionBound &rb)
        {
            const auto at = static_cast<long>(i) + 1;
            w.states.insert(w.states.begin() + at, s);
            w.c.insert(w.c.begin() + at, cs);
            w.alpha.insert(w.alpha.begin() + at, alpha);
            w.m.insert(w.m.begin() + at, rb.lower);
            w.b.insert(w.b.begin() + at, rb.best);
            w.f.insert(w.f.begin() + at, rb.at);
            w.m[i] = ra.lower;
            w.b[i] = ra.best;
            w.f[i] = ra.at;
        };

        // Split motion i at \e fraction (the same curve), kept only if both halves are certified by the validator
        // and their bounds are no lower than the whole's; true if done.
        auto split = [&](std::size_t i, double fraction)
        {
            ob::State *s = si_->allocState();
            space.interpolate(w.states[i], w.states[i + 1], fraction, s);
            const double cs = checker_->clearance(s);
            if (!(cs > 0.0) || !validator_->checkMotion(w.states[i], s) || !validator_->checkMotion(s, w.states[i + 1]))
            {
                si_->freeState(s);
                return false;
            }
            // The halves trace the same curve as the whole (OMPL's interpolation along a geodesic), so the whole's
            // certified bound holds for both; their own bounds can only tighten it.
            MotionBound ra = motionBound(w.states[i], s, w.c[i], cs, tolerance, relative);
            MotionBound rb = motionBound(s, w.states[i + 1], cs, w.c[i + 1], tolerance, relative);
            ra.lower = std::max(ra.lower, w.m[i]);
            rb.lower = std::max(rb.lower, w.m[i]);
            report(w.states[i], s);
            report(s, w.states[i + 1]);
            insertAt(i, s, cs, std::max(0.5 * cs, 1e-3 * L), ra, rb);
            ++stats_.inserted;
            return true;
        };
        // Insert a state at the interior dip of motion i, if it is meaningfully below both ends.
        auto insertAtDip = [&](std::size_t i)
        {
            return w.states.size() < maxStates && w.f[i] > 0.02 && w.f[i] < 0.98 &&
                   w.b[i] < std::min(w.c[i], w.c[i + 1]) - std::max(tolerance, relative * w.b[i]) && split(i, w.f[i]);
        };

        // Move interior state i up the gradient (backtracking); true if a step was accepted.
        auto move = [&](std::size_t i)
        {
            ob::State *prev = w.states[i - 1], *next = w.states[i + 1];
            ClearanceGradientOptions options;
            options.tieTolerance = 0.05 * std::max(w.c[i], 0.0) + 1e-9 * (1.0 + L);
            options.probes = 3;
            ClearanceGradientInfo info;
            clearanceGradient(*checker_, w.states[i], gradient, options, &info);
            double g2 = 0.0;
            for (std::size_t k = 0; k < gradient.size(); ++k)
                g2 += k < (gradient.size() == 3 ? 2u : 3u) ? gradient[k] * gradient[k]
                                                           : gradient[k] * gradient[k] / (L * L);
            if (!info.hasDirection || !(g2 > 1e-12))
                return false;
            const double floor = std::min(w.m[i - 1], w.m[i]);
            const double oldSegments = si_->distance(prev, w.states[i]) + si_->distance(w.states[i], next);
            // alpha is the step's length scale; normalise so the first trial moves about alpha.
            double alpha = w.alpha[i] / std::sqrt(g2);
            for (int trial = 0; trial < 6 && !ptc(); ++trial, alpha *= 0.5)
            {
                ascentStep(gradient, L, alpha, step);
                applyTangentStep(space, w.states[i], step.data(), candidate);
                if (!si_->satisfiesBounds(candidate))
                    continue;
                const double cc = checker_->clearance(candidate);
                if (!(cc > w.c[i]))
                    continue;
                const double newLength =
                    w.length - oldSegments + si_->distance(prev, candidate) + si_->distance(candidate, next);
                if (newLength > maxLength)
                    continue;
                const MotionBound ra = motionBound(prev, candidate, w.c[i - 1], cc, tolerance, relative, floor);
                if (ra.lower < floor)
                    continue;
                const MotionBound rb = motionBound(candidate, next, cc, w.c[i + 1], tolerance, relative, floor);
                if (rb.lower < floor)
                    continue;
                if (!validator_->checkMotion(prev, candidate) || !validator_->checkMotion(candidate, next))
                    continue;
                report(prev, candidate);
                report(candidate, next);
                si_->copyState(w.states[i], candidate);
                w.c[i] = cc;
                keep(i - 1, ra);
                keep(i, rb);
                w.length = newLength;
                w.alpha[i] = std::min(2.0 * alpha * std::sqrt(g2), L);
                ++stats_.moves;
                return true;
            }
            w.alpha[i] = std::max(alpha * std::sqrt(g2), 1e-6 * L);
            return false;
        };

        // Replace states i+1 .. j-1 by the single motion i -> j if its bound is no lower; true if done.
        auto bridge = [&](std::size_t i, std::size_t j)
        {
            const double floor =
                *std::min_element(w.m.begin() + static_cast<long>(i), w.m.begin() + static_cast<long>(j));
            const MotionBound r = motionBound(w.states[i], w.states[j], w.c[i], w.c[j], tolerance, relative, floor);
            if (r.lower < floor || !validator_->checkMotion(w.states[i], w.states[j]))
                return false;
            report(w.states[i], w.states[j]);
            double removedLength = 0.0;
            for (std::size_t k = i; k < j; ++k)
                removedLength += si_->distance(w.states[k], w.states[k + 1]);
            w.length += si_->distance(w.states[i], w.states[j]) - removedLength;
            for (std::size_t k = i + 1; k < j; ++k)
                si_->freeState(w.states[k]);
            const auto first = static_cast<long>(i) + 1, last = static_cast<long>(j);
            w.states.erase(w.states.begin() + first, w.states.begin() + last);
            w.c.erase(w.c.begin() + first, w.c.begin() + last);
            w.alpha.erase(w.alpha.begin() + first, w.alpha.begin() + last);
            w.m.erase(w.m.begin() + first, w.m.begin() + last);
            w.b.erase(w.b.begin() + first, w.b.begin() + last);
            w.f.erase(w.f.begin() + first, w.f.begin() + last);
            keep(i, r);
            return true;
        };

        ptc_ = &ptc;
        // The path's minimum can never exceed its ends' clearance: once the bound is there, nothing is left to gain.
        const double ceiling = (1.0 - relative) * std::min(w.c.front(), w.c.back()) - tolerance;
        auto done = [&] { return ptc() || currentMin() >= target_ || currentMin() >= ceiling; };
        // First give the path room to bend: split long motions (sweep above 1/32 of the whole) at their middle.
        if (!done())
        {
            double total = 0.0;
            for (std::size_t i = 0; i + 1 < w.states.size(); ++i)
                total += sweepBound(space, w.states[i], w.states[i + 1], L);
            const double longest = total / 32.0;
            for (std::size_t i = 0; i + 1 < w.states.size() && w.states.size() < maxStates && !ptc();)
                if (sweepBound(space, w.states[i], w.states[i + 1], L) <= longest || !split(i, 0.5))
                    ++i;
        }

        std::vector<std::size_t> order;
        while (!done() && stats_.rounds < maxRounds_)
        {
            ++stats_.rounds;
            bool changed = false;
            for (std::size_t i = 0; i + 1 < w.states.size() && !ptc(); ++i)
                if (insertAtDip(i))
                {
                    changed = true;
                    ++i;
                }
            // Interior states, least clear neighbourhood first.
            order.resize(w.states.size() > 2 ? w.states.size() - 2 : 0);
            std::iota(order.begin(), order.end(), std::size_t{1});
            std::stable_sort(order.begin(), order.end(),
                             [&w](std::size_t a, std::size_t b)
                             { return std::min(w.m[a - 1], w.m[a]) < std::min(w.m[b - 1], w.m[b]); });
            for (std::size_t i : order)
            {
                if (ptc())
                    break;
                changed = move(i) || changed;
            }
            for (std::size_t i = 1; i + 1 < w.states.size() && !ptc();)
                if (bridge(i - 1, i + 1))
                {
                    ++stats_.removed;
                    changed = true;
                }
                else
                    ++i;
            if (shortcut_)
                for (std::size_t attempt = 0; attempt < w.states.size() && w.states.size() > 3 && !ptc(); ++attempt)
                {
                    const int last = static_cast<int>(w.states.size()) - 1;
                    std::size_t i = static_cast<std::size_t>(rng.uniformInt(0, last));
                    std::size_t j = static_cast<std::size_t>(rng.uniformInt(0, last));
                    if (i > j)
                        std::swap(i, j);
                    if (j < i + 3)
                        continue;  // neighbours' neighbours are the redundancy pass's
                    if (bridge(i, j))
                    {
                        ++stats_.shortcuts;
                        stats_.removed += static_cast<unsigned>(j - i - 1);
                        changed = true;
                    }
                }
            if (!changed)
                break;
        }
        ptc_ = nullptr;
        si_->freeState(candidate);
        stats_.lowerBoundAfter = currentMin();

        // Measured again from scratch, the same way as the input: never hand back a less clear path.
        const bool changed = stats_.moves + stats_.inserted + stats_.removed > 0;
        const double after = changed ? minClearance(path, tolerance) : inputMeasure;
        const double inputAgain = inputMeasure;
        if (after < inputAgain)
        {
            path = input;
            stats_.minClearanceAfter = inputAgain;
            stats_.restored = true;
        }
        else
            stats_.minClearanceAfter = after;
        stats_.minClearanceBefore = inputAgain;
        stats_.statesAfter = static_cast<unsigned>(path.getStateCount());
        stats_.lengthAfter = path.length();
        stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats_.minClearanceAfter > stats_.minClearanceBefore;
    }
}  // namespace meshgap
