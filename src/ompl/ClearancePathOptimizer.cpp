#include "meshgap/ompl/ClearancePathOptimizer.h"

#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <queue>

#include "meshgap/Exception.h"
#include "meshgap/ompl/MotionValidatorFactory.h"

namespace meshgap
{
    namespace ob = ompl::base;
    namespace og = ompl::geometric;

    ClearancePathOptimizer::ClearancePathOptimizer(const ob::SpaceInformationPtr &si, ClearanceFieldPtr checker)
        : si_(si), checker_(std::move(checker))
    {
        if (!checker_)
            throw Exception("ClearancePathOptimizer", "no checker");
        if (!checker_->certified())
            throw Exception("ClearancePathOptimizer", "needs a checker in CERTIFIED mode (exact clearance)");
        checker_->gradientDimension();  // throws for spaces the checker has no gradient in
        validator_ = allocCertifiedMotionValidator(si_, checker_);
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
        params_.declareParam<bool>(
            "repair", [this](bool v) { setRepair(v); }, [this] { return getRepair(); });
        params_["repair"].setRangeSuggestion("0,1");
    }

    ClearancePathOptimizer::MotionBound ClearancePathOptimizer::motionBound(const ob::State *s1, const ob::State *s2,
                                                                            double c1, double c2, double tolerance,
                                                                            double relative, double refuteBelow) const
    {
        const ob::StateSpace &space = *si_->getStateSpace();
        const double sweep = checker_->sweep(s1, s2);
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
            // Only a sample below this matters exactly: at or above it, both halves' bounds are at least the best
            // sample (or the floor), so the cap (a lower bound on the sample's clearance, which keeps every bound
            // certified) prunes them as the exact value would. A bounded query prunes everything farther.
            const double cap = std::max(r.best + 0.5 * sweep * (iv.b - iv.a), refuteBelow);
            const double cm = cap > 0.0 ? checker_->clearanceBelow(s, cap) : checker_->clearance(s);
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
                        1e-9 * checker_->lengthScale());
    }

    double ClearancePathOptimizer::minClearance(const og::PathGeometric &path, double tolerance) const
    {
        return measure(path, tolerance, nullptr);
    }

    double ClearancePathOptimizer::measure(const og::PathGeometric &path, double tolerance,
                                           std::vector<MotionBound> *bounds) const
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
        if (bounds != nullptr)
            bounds->clear();
        for (std::size_t i = 0; i + 1 < n; ++i)
        {
            const MotionBound r = motionBound(path.getState(i), path.getState(i + 1), c[i], c[i + 1], tolerance,
                                              MEASURE_RELATIVE_TOLERANCE);
            best = std::min(best, r.best);
            if (bounds != nullptr)
                bounds->push_back(r);
        }
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
        deadline_ = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                            std::chrono::duration<double>(timeLimit_));
        struct ClearDeadline
        {
            std::optional<std::chrono::steady_clock::time_point> &deadline;
            ~ClearDeadline() { deadline.reset(); }
        } clear{deadline_};
        return optimize(path, ob::timedPlannerTerminationCondition(timeLimit_));
    }

    /** \brief One optimize() call: the path being optimised, with what is known about it (c[i] the clearance of state
        i, m[i] the certified lower bound on the clearance along motion i (states i, i + 1), b[i] its least clear
        sample and f[i] where along it, alpha[i] state i's step length), the call's settings, and its steps. */
    struct ClearancePathOptimizer::Work
    {
        Work(ClearancePathOptimizer &optimizer, std::vector<ob::State *> &s, const ob::PlannerTerminationCondition &p)
            : opt(optimizer),
              states(s),
              ptc(p),
              space(*optimizer.si_->getStateSpace()),
              L(optimizer.checker_->lengthScale())
        {
        }

        ClearancePathOptimizer &opt;
        std::vector<ob::State *> &states;
        const ob::PlannerTerminationCondition &ptc;
        const ob::StateSpace &space;
        const double L;  ///< the robot's radius about its origin: the length scale of rotations
        std::vector<double> c, m, b, f, alpha;
        double length{0.0};
        double tolerance{0.0};
        /** \brief While optimising, a motion's bound need only be as tight as a fraction of its own clearance: a
            motion far above the path's minimum is not worth many queries. The bounds kept (m) are certified lower
            bounds. */
        double relative{0.02};
        double maxLength{0.0};
        std::size_t maxStates{0};
        std::vector<double> gradient, step;  ///< move()'s buffers
        ob::State *candidate{nullptr};       ///< move()'s trial state

        MotionBound bound(const ob::State *s1, const ob::State *s2, double c1, double c2,
                          double refuteBelow = -std::numeric_limits<double>::infinity()) const
        {
            return opt.motionBound(s1, s2, c1, c2, tolerance, relative, refuteBelow);
        }
        void keep(std::size_t i, const MotionBound &r)
        {
            m[i] = r.lower;
            b[i] = r.best;
            f[i] = r.at;
        }
        void report(const ob::State *s1, const ob::State *s2) const
        {
            if (opt.onMotion_)
                opt.onMotion_(s1, s2);
        }
        double currentMin() const { return *std::min_element(m.begin(), m.end()); }
        double initialAlpha(double clearance) const { return std::max(0.5 * clearance, 1e-3 * L); }

        void start(const ClearancePathOptimizer::Stats &stats, const std::vector<MotionBound> &bounds);
        void insertAt(std::size_t i, ob::State *s, double cs, const MotionBound &ra, const MotionBound &rb);
        bool split(std::size_t i, double fraction);
        bool insertAtDip(std::size_t i);
        bool move(std::size_t i);
        bool bridge(std::size_t i, std::size_t j);
        void eraseStates(std::size_t first, std::size_t last);
        void splitLongMotions();
        bool insertAtDips();
        bool moveStates(std::vector<std::size_t> &order);
        bool removeRedundant();
        bool shortcuts(ompl::RNG &rng);
    };

    /** \brief The bounds of every motion (\e bounds: the input's measurement, tighter than the rounds need), and
        the step lengths, of the path as given (c and tolerance set). */
    void ClearancePathOptimizer::Work::start(const ClearancePathOptimizer::Stats &stats,
                                             const std::vector<MotionBound> &bounds)
    {
        const std::size_t n0 = states.size();
        m.resize(n0 - 1);
        b.resize(n0 - 1);
        f.resize(n0 - 1);
        for (std::size_t i = 0; i + 1 < n0; ++i)
            keep(i, bounds[i]);
        length = stats.lengthBefore;
        maxLength = opt.maxLengthFactor_ * stats.lengthBefore;
        maxStates = std::max<std::size_t>(4 * n0, 200);
        alpha.assign(n0, 0.0);
        for (std::size_t i = 0; i < n0; ++i)
            alpha[i] = initialAlpha(c[i]);
    }

    void ClearancePathOptimizer::Work::insertAt(std::size_t i, ob::State *s, double cs, const MotionBound &ra,
                                                const MotionBound &rb)
    {
        const auto at = static_cast<long>(i) + 1;
        states.insert(states.begin() + at, s);
        c.insert(c.begin() + at, cs);
        alpha.insert(alpha.begin() + at, initialAlpha(cs));
        m.insert(m.begin() + at, rb.lower);
        b.insert(b.begin() + at, rb.best);
        f.insert(f.begin() + at, rb.at);
        keep(i, ra);
    }

    /** \brief Split motion i at \e fraction (the same curve), kept only if both halves are certified by the validator
        and their bounds are no lower than the whole's; true if done. */
    bool ClearancePathOptimizer::Work::split(std::size_t i, double fraction)
    {
        ob::State *s = opt.si_->allocState();
        space.interpolate(states[i], states[i + 1], fraction, s);
        const double cs = opt.checker_->clearance(s);
        if (!(cs > 0.0) || !opt.validator_->checkMotion(states[i], s) || !opt.validator_->checkMotion(s, states[i + 1]))
        {
            opt.si_->freeState(s);
            return false;
        }
        // The halves trace the same curve as the whole (OMPL's interpolation along a geodesic), so the whole's
        // certified bound holds for both; their own bounds can only tighten it.
        MotionBound ra = bound(states[i], s, c[i], cs);
        MotionBound rb = bound(s, states[i + 1], cs, c[i + 1]);
        ra.lower = std::max(ra.lower, m[i]);
        rb.lower = std::max(rb.lower, m[i]);
        report(states[i], s);
        report(s, states[i + 1]);
        insertAt(i, s, cs, ra, rb);
        ++opt.stats_.inserted;
        return true;
    }

    /** \brief Insert a state at the interior dip of motion i, if it is meaningfully below both ends. */
    bool ClearancePathOptimizer::Work::insertAtDip(std::size_t i)
    {
        return states.size() < maxStates && f[i] > 0.02 && f[i] < 0.98 &&
               b[i] < std::min(c[i], c[i + 1]) - std::max(tolerance, relative * b[i]) && split(i, f[i]);
    }

    /** \brief Move interior state i up the gradient (backtracking); true if a step was accepted. */
    bool ClearancePathOptimizer::Work::move(std::size_t i)
    {
        ob::State *prev = states[i - 1], *next = states[i + 1];
        ClearanceGradientOptions options;
        options.tieTolerance = 0.05 * std::max(c[i], 0.0) + 1e-9 * (1.0 + L);
        options.probes = 3;
        ClearanceGradientInfo info;
        opt.checker_->gradient(states[i], gradient, options, &info);
        const double g2 = opt.checker_->gradientNorm2(gradient);
        if (!info.hasDirection || !(g2 > 1e-12))
            return false;
        const double floor = std::min(m[i - 1], m[i]);
        const double oldSegments = opt.si_->distance(prev, states[i]) + opt.si_->distance(states[i], next);
        // alpha is the step's length scale; normalise so the first trial moves about alpha.
        double a = alpha[i] / std::sqrt(g2);
        for (int trial = 0; trial < 6 && !ptc(); ++trial, a *= 0.5)
        {
            opt.checker_->ascentStep(gradient, a, step);
            opt.checker_->applyStep(states[i], step.data(), candidate);
            if (!opt.si_->satisfiesBounds(candidate))
                continue;
            const double cc = opt.checker_->clearance(candidate);
            if (!(cc > c[i]))
                continue;
            const double newLength =
                length - oldSegments + opt.si_->distance(prev, candidate) + opt.si_->distance(candidate, next);
            if (newLength > maxLength)
                continue;
            const MotionBound ra = bound(prev, candidate, c[i - 1], cc, floor);
            if (ra.lower < floor)
                continue;
            const MotionBound rb = bound(candidate, next, cc, c[i + 1], floor);
            if (rb.lower < floor)
                continue;
            if (!opt.validator_->checkMotion(prev, candidate) || !opt.validator_->checkMotion(candidate, next))
                continue;
            report(prev, candidate);
            report(candidate, next);
            opt.si_->copyState(states[i], candidate);
            c[i] = cc;
            keep(i - 1, ra);
            keep(i, rb);
            length = newLength;
            alpha[i] = std::min(2.0 * a * std::sqrt(g2), L);
            ++opt.stats_.moves;
            return true;
        }
        alpha[i] = std::max(a * std::sqrt(g2), 1e-6 * L);
        return false;
    }

    /** \brief Remove states first .. last - 1 (freed) and what is known about them. */
    void ClearancePathOptimizer::Work::eraseStates(std::size_t first, std::size_t last)
    {
        for (std::size_t k = first; k < last; ++k)
            opt.si_->freeState(states[k]);
        const auto from = static_cast<long>(first), to = static_cast<long>(last);
        states.erase(states.begin() + from, states.begin() + to);
        c.erase(c.begin() + from, c.begin() + to);
        alpha.erase(alpha.begin() + from, alpha.begin() + to);
        m.erase(m.begin() + from, m.begin() + to);
        b.erase(b.begin() + from, b.begin() + to);
        f.erase(f.begin() + from, f.begin() + to);
    }

    /** \brief Replace states i+1 .. j-1 by the single motion i -> j if its bound is no lower; true if done. */
    bool ClearancePathOptimizer::Work::bridge(std::size_t i, std::size_t j)
    {
        const double floor = *std::min_element(m.begin() + static_cast<long>(i), m.begin() + static_cast<long>(j));
        const MotionBound r = bound(states[i], states[j], c[i], c[j], floor);
        if (r.lower < floor || !opt.validator_->checkMotion(states[i], states[j]))
            return false;
        report(states[i], states[j]);
        double removedLength = 0.0;
        for (std::size_t k = i; k < j; ++k)
            removedLength += opt.si_->distance(states[k], states[k + 1]);
        length += opt.si_->distance(states[i], states[j]) - removedLength;
        eraseStates(i + 1, j);
        keep(i, r);
        return true;
    }

    /** \brief Give the path room to bend: split long motions (sweep above 1/32 of the whole) at their middle. */
    void ClearancePathOptimizer::Work::splitLongMotions()
    {
        double total = 0.0;
        for (std::size_t i = 0; i + 1 < states.size(); ++i)
            total += opt.checker_->sweep(states[i], states[i + 1]);
        const double longest = total / 32.0;
        for (std::size_t i = 0; i + 1 < states.size() && states.size() < maxStates && !ptc();)
            if (opt.checker_->sweep(states[i], states[i + 1]) <= longest || !split(i, 0.5))
                ++i;
    }

    bool ClearancePathOptimizer::Work::insertAtDips()
    {
        bool changed = false;
        for (std::size_t i = 0; i + 1 < states.size() && !ptc(); ++i)
            if (insertAtDip(i))
            {
                changed = true;
                ++i;
            }
        return changed;
    }

    /** \brief move() every interior state, least clear neighbourhood first. */
    bool ClearancePathOptimizer::Work::moveStates(std::vector<std::size_t> &order)
    {
        order.resize(states.size() > 2 ? states.size() - 2 : 0);
        std::iota(order.begin(), order.end(), std::size_t{1});
        std::stable_sort(order.begin(), order.end(),
                         [this](std::size_t p, std::size_t q)
                         { return std::min(m[p - 1], m[p]) < std::min(m[q - 1], m[q]); });
        bool changed = false;
        for (std::size_t i : order)
        {
            if (ptc())
                break;
            changed = move(i) || changed;
        }
        return changed;
    }

    /** \brief Bridge over every state whose neighbours see each other no less clearly. */
    bool ClearancePathOptimizer::Work::removeRedundant()
    {
        bool changed = false;
        for (std::size_t i = 1; i + 1 < states.size() && !ptc();)
            if (bridge(i - 1, i + 1))
            {
                ++opt.stats_.removed;
                changed = true;
            }
            else
                ++i;
        return changed;
    }

    /** \brief Random shortcuts (as many tries as states) between states at least three apart. */
    bool ClearancePathOptimizer::Work::shortcuts(ompl::RNG &rng)
    {
        bool changed = false;
        for (std::size_t attempt = 0; attempt < states.size() && states.size() > 3 && !ptc(); ++attempt)
        {
            const int last = static_cast<int>(states.size()) - 1;
            std::size_t i = static_cast<std::size_t>(rng.uniformInt(0, last));
            std::size_t j = static_cast<std::size_t>(rng.uniformInt(0, last));
            if (i > j)
                std::swap(i, j);
            if (j < i + 3)
                continue;  // neighbours' neighbours are the redundancy pass's
            if (bridge(i, j))
            {
                ++opt.stats_.shortcuts;
                opt.stats_.removed += static_cast<unsigned>(j - i - 1);
                changed = true;
            }
        }
        return changed;
    }

    void ClearancePathOptimizer::improve(Work &w)
    {
        // The path's minimum can never exceed its ends' clearance: once the bound is there, nothing is left to gain.
        const double ceiling = (1.0 - w.relative) * std::min(w.c.front(), w.c.back()) - w.tolerance;
        auto done = [&] { return w.ptc() || w.currentMin() >= target_ || w.currentMin() >= ceiling; };
        if (!done())
            w.splitLongMotions();
        ompl::RNG rng(seed_);
        std::vector<std::size_t> order;
        while (!done() && stats_.rounds < maxRounds_)
        {
            ++stats_.rounds;
            bool changed = w.insertAtDips();
            changed = w.moveStates(order) || changed;
            changed = w.removeRedundant() || changed;
            if (shortcut_)
                changed = w.shortcuts(rng) || changed;
            if (!changed)
                break;
        }
    }

    bool ClearancePathOptimizer::optimize(og::PathGeometric &path, const ob::PlannerTerminationCondition &ptc)
    {
        const auto start = std::chrono::steady_clock::now();
        stats_ = Stats();
        if (path.getSpaceInformation() != si_)
            throw Exception("ClearancePathOptimizer", "the path belongs to another space information");
        if (!(maxLengthFactor_ >= 1.0))
            throw Exception("ClearancePathOptimizer", "max_length_factor must be at least 1");
        if (repair_)
        {
            CertifiedPathRepair repair(si_, checker_);
            repair.repair(path, ptc);  // throws naming a motion it cannot repair in time
            stats_.repair = repair.lastStats();
        }
        else
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

        const og::PathGeometric input(path);
        struct ClearPtc  // ptc_ is set only while the optimisation loop runs (never while measuring)
        {
            const ob::PlannerTerminationCondition *&ptc;
            ~ClearPtc() { ptc = nullptr; }
        } clearPtc{ptc_};
        // With a deadline, the rounds end while there is time left to measure the output (reserve: twice what the
        // input's measurement took, for a path that may have grown).
        std::chrono::steady_clock::duration reserve{0};
        const ob::PlannerTerminationCondition late(
            [this, &reserve] { return deadline_ && std::chrono::steady_clock::now() + reserve >= *deadline_; });
        const ob::PlannerTerminationCondition rounds = ob::plannerOrTerminationCondition(ptc, late);
        Work w(*this, path.getStates(), rounds);
        w.c.resize(n0);
        for (std::size_t i = 0; i < n0; ++i)
            w.c[i] = checker_->clearance(w.states[i]);
        w.tolerance = tolerance_ > 0.0 ? tolerance_ : defaultTolerance(w.c);
        // The input measured now (before the clock matters), the output at the end, the same way.
        const auto measuring = std::chrono::steady_clock::now();
        std::vector<MotionBound> inputBounds;
        const double inputMeasure = measure(input, w.tolerance, &inputBounds);
        reserve = 2 * (std::chrono::steady_clock::now() - measuring);
        w.start(stats_, inputBounds);
        w.candidate = si_->allocState();
        ptc_ = &rounds;
        improve(w);
        ptc_ = nullptr;
        si_->freeState(w.candidate);
        stats_.lowerBoundAfter = w.currentMin();
        keepTheClearer(path, input, inputMeasure, w.tolerance);
        stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats_.minClearanceAfter > stats_.minClearanceBefore;
    }

    void ClearancePathOptimizer::keepTheClearer(og::PathGeometric &path, const og::PathGeometric &input,
                                                double inputMeasure, double tolerance)
    {
        // Measured again from scratch, the same way as the input: never hand back a less clear path.
        const bool changed = stats_.moves + stats_.inserted + stats_.removed > 0;
        const double after = changed ? minClearance(path, tolerance) : inputMeasure;
        if (after < inputMeasure)
        {
            path = input;
            stats_.minClearanceAfter = inputMeasure;
            stats_.restored = true;
        }
        else
            stats_.minClearanceAfter = after;
        stats_.minClearanceBefore = inputMeasure;
        stats_.statesAfter = static_cast<unsigned>(path.getStateCount());
        stats_.lengthAfter = path.length();
    }
}  // namespace meshgap
