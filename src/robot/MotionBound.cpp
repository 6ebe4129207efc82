#include "meshgap/robot/MotionBound.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    namespace
    {
        /** \brief The 8 corners of BVH node \e n's box, in its body's frame. */
        std::array<Eigen::Vector3d, 8> boxCorners(const TriangleBvh::Node &n)
        {
            std::array<Eigen::Vector3d, 8> corners;
            for (int c = 0; c < 8; ++c)
            {
                const Eigen::Vector3d sign((c & 1) ? 1.0 : -1.0, (c & 2) ? 1.0 : -1.0, (c & 4) ? 1.0 : -1.0);
                corners[c] = n.center + n.axes * sign.cwiseProduct(n.half);
            }
            return corners;
        }
    }  // namespace

    MotionBound::MotionBound(const RobotModel &robot)
    {
        std::vector<FrameMotion> motions;
        for (std::size_t f = 0; f < robot.frames().size(); ++f)
            motions.push_back(robot.frameMotion(f));
        offsets_.push_back(0);
        for (const RobotLink &link : robot.links())
        {
            double reach = 0.0;  // from the current frame's origin to any point of the link
            for (const Eigen::Vector3d &v : link.body->surface().vertices)
                reach = std::max(reach, (link.X_FL * v).norm());
            std::vector<std::size_t> chain;
            std::vector<double> chainReach;
            for (std::size_t f = link.frame, step = 0; f != RobotModel::NONE; f = robot.frames()[f].parent, ++step)
            {
                chain.push_back(f);
                chainReach.push_back(reach);
                if (motions[f].kind != FrameMotion::Kind::FIXED && !std::isfinite(reach))
                    throw Exception("MotionBound", "frame " + quote(robot.frames()[f].name) +
                                                       " moves a frame that moves free (no bound on its reach)");
                addTerms(motions[f], f, step, reach, terms_);
                // Up to the parent frame: a rotation keeps the distance from the frame's origin, the frame's own
                // origin lies within its reach of the parent's.
                reach += motions[f].reach;
            }
            offsets_.push_back(terms_.size());
            chains_.push_back(chain);
            chainReach_.push_back(chainReach);
            corners_.push_back(boxCorners(link.body->bvh().nodes().front()));
            centres_.push_back(link.body->bvh().nodes().front().center);
            radii_.push_back(link.body->bvh().nodes().front().radius);
        }
        // Every pair of links' nearest common ancestor, once (the proof asks it for every self pair of every piece).
        const std::size_t n = chains_.size();
        common_.resize(n * n);
        for (std::size_t a = 0; a < n; ++a)
            for (std::size_t b = 0; b < n; ++b)
            {
                const std::vector<std::size_t> &up1 = chains_[a], &up2 = chains_[b];
                common_[a * n + b] = {up1.size(), up2.size()};
                for (std::size_t i = 0; i < up1.size() && common_[a * n + b].first == up1.size(); ++i)
                    for (std::size_t k = 0; k < up2.size(); ++k)
                        if (up1[i] == up2[k])
                        {
                            common_[a * n + b] = {i, k};
                            break;
                        }
            }
    }

    void MotionBound::addTerms(const FrameMotion &m, std::size_t frame, std::size_t step, double reach,
                               std::vector<Term> &terms)
    {
        const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
        switch (m.kind)
        {
            case FrameMotion::Kind::FIXED:
                break;
            case FrameMotion::Kind::ROTATION:
                terms.push_back({m.angle ? Measure::ARC : Measure::SCALAR, m.variable, m.scale, reach, step, frame,
                                 Lever::AXIS, m.axis});
                break;
            case FrameMotion::Kind::TRANSLATION:
                terms.push_back({Measure::SCALAR, m.variable, m.scale, 1.0, step, frame, Lever::NONE, m.axis});
                break;
            case FrameMotion::Kind::SE2:
                terms.push_back({Measure::PLANE_MOVE, m.variable, 1.0, 1.0, step, frame, Lever::NONE, z});
                terms.push_back({Measure::PLANE_TURN, m.variable + 2, 1.0, reach, step, frame, Lever::ORIGIN, z});
                break;
            case FrameMotion::Kind::SE3:
                terms.push_back({Measure::SPACE_MOVE, m.variable, 1.0, 1.0, step, frame, Lever::NONE, z});
                terms.push_back({Measure::SPACE_TURN, m.variable + 3, 1.0, reach, step, frame, Lever::ORIGIN, z});
                break;
        }
    }

    double MotionBound::termMove(const Term &t, const std::vector<double> &a, const std::vector<double> &b)
    {
        const std::size_t v = t.variable;
        double change = 0.0;
        switch (t.measure)
        {
            case Measure::SCALAR:
                change = std::abs(b[v] - a[v]);
                break;
            case Measure::ARC:
            case Measure::PLANE_TURN:
                change = std::abs(b[v] - a[v]);
                change = std::min(change, std::abs(2.0 * M_PI - change));
                break;
            case Measure::PLANE_MOVE:
                change = std::hypot(b[v] - a[v], b[v + 1] - a[v + 1]);
                break;
            case Measure::SPACE_MOVE:
                change = (Eigen::Vector3d(b[v], b[v + 1], b[v + 2]) - Eigen::Vector3d(a[v], a[v + 1], a[v + 2])).norm();
                break;
            case Measure::SPACE_TURN:
            {
                // The relative rotation's angle, 2 atan2(|vec|, |w|): the shorter way, accurate for small angles.
                const Eigen::Quaterniond qa = Eigen::Quaterniond(a[v + 3], a[v], a[v + 1], a[v + 2]).normalized();
                const Eigen::Quaterniond qb = Eigen::Quaterniond(b[v + 3], b[v], b[v + 1], b[v + 2]).normalized();
                const Eigen::Quaterniond r = qa.conjugate() * qb;
                change = 2.0 * std::atan2(r.vec().norm(), std::abs(r.w()));
                break;
            }
        }
        return t.scale * change;
    }

    std::pair<std::size_t, std::size_t> MotionBound::pairTerms(std::size_t first, std::size_t second) const
    {
        // The nearest common ancestor: its place on each link's way up (past the end: none, two separate roots).
        const auto [at1, at2] = commonSteps(first, second);
        auto below = [&](std::size_t link, std::size_t at)
        {
            std::size_t n = 0;
            for (std::size_t t = offsets_[link]; t < offsets_[link + 1] && terms_[t].step < at; ++t)
                ++n;
            return n;
        };
        return {below(first, at1), below(second, at2)};
    }

    double MotionBound::pairDisplacement(std::size_t first, std::size_t second, const std::vector<double> &a,
                                         const std::vector<double> &b) const
    {
        const auto [n1, n2] = pairTerms(first, second);
        double d = 0.0;
        for (std::size_t t = offsets_[first]; t < offsets_[first] + n1; ++t)
            d += termMove(terms_[t], a, b) * terms_[t].reach;
        for (std::size_t t = offsets_[second]; t < offsets_[second] + n2; ++t)
            d += termMove(terms_[t], a, b) * terms_[t].reach;
        return d;
    }

    void MotionBound::linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                                        std::vector<double> &out) const
    {
        out.resize(chains_.size());
        for (std::size_t i = 0; i < chains_.size(); ++i)
        {
            double d = 0.0;
            for (std::size_t t = offsets_[i]; t < offsets_[i + 1]; ++t)
                d += termMove(terms_[t], a, b) * terms_[t].reach;
            out[i] = d;
        }
    }

    void MotionBound::motion(const std::vector<double> &a, const std::vector<double> &b, Motion &out) const
    {
        out.move.resize(terms_.size());
        out.crude.resize(terms_.size());
        for (std::size_t t = 0; t < terms_.size(); ++t)
        {
            out.move[t] = termMove(terms_[t], a, b);
            out.crude[t] = out.move[t] * terms_[t].reach;
        }
    }

    double MotionBound::bend(std::size_t link, std::size_t terms, const Motion &motion) const
    {
        double bend = 0.0, above = 0.0;
        for (std::size_t t = offsets_[link] + terms; t-- > offsets_[link];)
        {
            const double m = motion.move[t];
            if (terms_[t].lever == Lever::NONE)
                bend += 2.0 * m * above;
            else
            {
                bend += m * terms_[t].reach * (3.0 * above + m);
                above += m;
            }
        }
        return bend;
    }

    void MotionBound::pieceBounds(const Motion &motion, const std::vector<Eigen::Isometry3d> &frames,
                                  const std::vector<Eigen::Isometry3d> &links, double half,
                                  std::vector<double> &out, const std::vector<unsigned char> *only) const
    {
        out.resize(terms_.size() + chains_.size());
        std::array<Eigen::Vector3d, 8> corners;
        for (std::size_t i = 0; i < chains_.size(); ++i)
        {
            if (only && !(*only)[i])
                continue;
            for (int c = 0; c < 8; ++c)
                corners[c] = links[i] * corners_[i][c];
            // below: the crude bound of the frames nearer the link than the current term's (its own motion
            // relative to that frame); terms of one frame (a free body's move and turn) share a step.
            double sum = 0.0, crude = 0.0, below = 0.0;
            std::size_t at = offsets_[i] + i, step = RobotModel::NONE;
            out[at] = 0.0;
            for (std::size_t t = offsets_[i]; t < offsets_[i + 1]; ++t)
            {
                const Term &term = terms_[t];
                if (term.step != step)
                {
                    below = crude;
                    step = term.step;
                }
                double add = motion.move[t] * half;
                if (term.lever != Lever::NONE)
                {
                    const Eigen::Vector3d o = frames[term.frame].translation();
                    const Eigen::Vector3d u = frames[term.frame].linear() * term.axis;
                    double rho2 = 0.0;  // squared, one root for the 8 (the root is monotone, so the same)
                    for (const Eigen::Vector3d &x : corners)
                    {
                        const Eigen::Vector3d r = x - o;
                        rho2 = std::max(rho2, term.lever == Lever::AXIS ? r.cross(u).squaredNorm() : r.squaredNorm());
                    }
                    double rho = std::sqrt(rho2);
                    rho += 1e-12 * (1.0 + rho + o.norm());  // roundoff in the world coordinates
                    // The crude lever bounds the distance at every state: keep the smaller.
                    add *= std::min(term.reach, rho + 0.5 * half * below);
                }
                crude += motion.crude[t];
                sum += add;
                out[++at] = sum;
            }
        }
    }
}  // namespace meshgap

namespace meshgap
{
    std::size_t MotionBound::pairSplits(std::size_t first, std::size_t second,
                                        std::pair<std::size_t, std::size_t> terms) const
    {
        return commonSteps(first, second).first < chains_[first].size() ? terms.first + terms.second + 1 : 1;
    }

    double MotionBound::charged(std::size_t own, std::size_t other, std::pair<std::size_t, std::size_t> counts,
                                std::size_t kept, const std::vector<double> &sums, const Motion &motion, double half,
                                const std::vector<Eigen::Isometry3d> &frames,
                                const std::vector<Eigen::Isometry3d> &links) const
    {
        const auto [count, otherCount] = counts;
        const auto [atOwn, atOther] = commonSteps(own, other);
        const double common = chainReach_[own][atOwn] + chainReach_[other][atOther];
        const std::size_t o = offsets_[own];
        // How fast the other link's points move about a frame of own's way (per unit of the motion): its own
        // terms below the common ancestor, then own's terms above that frame (each frame's terms together).
        double below = 0.0, pending = 0.0;
        for (std::size_t t = offsets_[other]; t < offsets_[other] + otherCount; ++t)
            below += motion.crude[t];
        const Eigen::Vector3d centre = links[other] * centres_[other];
        double suffix = 0.0, least = std::numeric_limits<double>::infinity();
        std::size_t step = RobotModel::NONE;
        for (std::size_t i = count; i-- > 0;)
        {
            const Term &term = terms_[o + i];
            if (term.step != step)
            {
                below += pending;
                pending = 0.0;
                step = term.step;
            }
            const double move = motion.move[o + i];
            if (move != 0.0)
            {
                // At any state, the other link's points lie within common - own's reach there of the frame's origin;
                // at the middle, within the other's root sphere, its centre this far from the axis (or origin).
                const double crude = term.lever == Lever::NONE ? 1.0 : common - chainReach_[own][term.step];
                double lever = crude;
                if (term.lever != Lever::NONE)
                {
                    const Eigen::Vector3d origin = frames[term.frame].translation();
                    const Eigen::Vector3d r = centre - origin;
                    double d = term.lever == Lever::AXIS ? r.cross(frames[term.frame].linear() * term.axis).norm()
                                                         : r.norm();
                    d += radii_[other] + 1e-12 * (1.0 + d + origin.norm() + centre.norm());  // roundoff
                    lever = std::min(crude, d + 0.5 * half * below);
                }
                suffix += move * half * lever;
                pending += move * crude;
            }
            // Own keeps its terms below i (its piece sums), charges i and those above to the other link; not
            // between two terms of one frame (a free frame's move and turn), which is no split between frames.
            const bool between = i == 0 || terms_[o + i - 1].step != term.step;
            const double bound = between ? sums[o + own + i] + suffix : std::numeric_limits<double>::infinity();
            if (i == kept)
                return bound;
            least = std::min(least, bound);
        }
        return least;
    }

    double MotionBound::pairSplitBound(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                                       std::size_t split, const std::vector<double> &sums, const Motion &motion,
                                       double half, const std::vector<Eigen::Isometry3d> &frames,
                                       const std::vector<Eigen::Isometry3d> &links) const
    {
        if (pairSplits(first, second, terms) == 1 || split == terms.first)
            return pairBound(first, second, terms, sums);  // each link its own terms
        if (split < terms.first)
            return charged(first, second, terms, split, sums, motion, half, frames, links) +
                   sums[offsets_[second] + second + terms.second];
        return sums[offsets_[first] + first + terms.first] +
               charged(second, first, {terms.second, terms.first}, terms.first + terms.second - split, sums, motion,
                       half, frames, links);
    }

    std::size_t MotionBound::splitFrame(std::size_t first, std::size_t second,
                                        std::pair<std::size_t, std::size_t> terms, std::size_t split) const
    {
        const auto [at1, at2] = commonSteps(first, second);
        if (at1 >= chains_[first].size())
            return RobotModel::NONE;
        if (split < terms.first)
            return chains_[first][terms_[offsets_[first] + split].step];
        const std::size_t kept = terms.first + terms.second - split;  // the second link's terms it keeps
        return kept < terms.second ? chains_[second][terms_[offsets_[second] + kept].step] : chains_[first][at1];
    }

    bool MotionBound::pairNumbers(std::size_t first, std::size_t second, std::vector<std::size_t> &numbers,
                                  std::vector<unsigned char> &arcs) const
    {
        numbers.clear();
        arcs.clear();
        if (commonSteps(first, second).first >= chains_[first].size())
            return false;  // two separate roots
        const auto [n1, n2] = pairTerms(first, second);
        for (auto [link, count] : {std::pair(first, n1), std::pair(second, n2)})
            for (std::size_t t = offsets_[link]; t < offsets_[link] + count; ++t)
            {
                const Term &term = terms_[t];
                if (term.measure != Measure::SCALAR && term.measure != Measure::ARC)
                    return false;
                const auto at = std::lower_bound(numbers.begin(), numbers.end(), term.variable);
                if (at != numbers.end() && *at == term.variable)
                    continue;
                arcs.insert(arcs.begin() + (at - numbers.begin()), term.measure == Measure::ARC ? 1 : 0);
                numbers.insert(at, term.variable);
            }
        return true;
    }

    double MotionBound::pairPieceBound(std::size_t first, std::size_t second, std::pair<std::size_t, std::size_t> terms,
                                       const std::vector<double> &sums, const Motion &motion, double half,
                                       const std::vector<Eigen::Isometry3d> &frames,
                                       const std::vector<Eigen::Isometry3d> &links) const
    {
        const double held = pairBound(first, second, terms, sums);
        if (pairSplits(first, second, terms) == 1)
            return held;
        const double firstSide =
            charged(first, second, terms, ALL_SPLITS, sums, motion, half, frames, links) +
            sums[offsets_[second] + second + terms.second];
        const double secondSide = sums[offsets_[first] + first + terms.first] +
                                  charged(second, first, {terms.second, terms.first}, ALL_SPLITS, sums, motion, half,
                                          frames, links);
        return std::min({held, firstSide, secondSide});
    }
}  // namespace meshgap
