#include "meshgap/robot/MotionBound.h"

#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    MotionBound::MotionBound(const RobotModel &robot)
    {
        std::vector<FrameMotion> motions;
        for (std::size_t f = 0; f < robot.frames().size(); ++f)
            motions.push_back(robot.frameMotion(f));
        for (const RobotLink &link : robot.links())
        {
            double reach = 0.0;  // from the current frame's origin to any point of the link
            for (const Eigen::Vector3d &v : link.body->surface().vertices)
                reach = std::max(reach, (link.X_FL * v).norm());
            std::vector<Term> terms;
            std::vector<std::size_t> chain;
            for (std::size_t f = link.frame, step = 0; f != RobotModel::NONE; f = robot.frames()[f].parent, ++step)
            {
                chain.push_back(f);
                if (motions[f].kind != FrameMotion::Kind::FIXED && !std::isfinite(reach))
                    throw Exception("MotionBound", "frame " + quote(robot.frames()[f].name) +
                                                       " moves a frame that moves free (no bound on its reach)");
                addTerms(motions[f], step, reach, terms);
                // Up to the parent frame: a rotation keeps the distance from the frame's origin, the frame's own
                // origin lies within its reach of the parent's.
                reach += motions[f].reach;
            }
            terms_.push_back(terms);
            chains_.push_back(chain);
        }
    }

    void MotionBound::addTerms(const FrameMotion &m, std::size_t step, double reach, std::vector<Term> &terms)
    {
        switch (m.kind)
        {
            case FrameMotion::Kind::FIXED:
                break;
            case FrameMotion::Kind::ROTATION:
                terms.push_back({m.angle ? Measure::ARC : Measure::SCALAR, m.variable, reach * m.scale, step});
                break;
            case FrameMotion::Kind::TRANSLATION:
                terms.push_back({Measure::SCALAR, m.variable, m.scale, step});
                break;
            case FrameMotion::Kind::SE2:
                terms.push_back({Measure::PLANE_MOVE, m.variable, 1.0, step});
                terms.push_back({Measure::PLANE_TURN, m.variable + 2, reach, step});
                break;
            case FrameMotion::Kind::SE3:
                terms.push_back({Measure::SPACE_MOVE, m.variable, 1.0, step});
                terms.push_back({Measure::SPACE_TURN, m.variable + 3, reach, step});
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
        return t.factor * change;
    }

    double MotionBound::pairDisplacement(std::size_t first, std::size_t second, const std::vector<double> &a,
                                         const std::vector<double> &b) const
    {
        // The nearest common ancestor: its place on each link's way up (past the end: none, two separate roots).
        const std::vector<std::size_t> &up1 = chains_[first], &up2 = chains_[second];
        std::size_t at1 = up1.size(), at2 = up2.size();
        for (std::size_t i = 0; i < up1.size() && at1 == up1.size(); ++i)
            for (std::size_t k = 0; k < up2.size(); ++k)
                if (up1[i] == up2[k])
                {
                    at1 = i;
                    at2 = k;
                    break;
                }
        double d = 0.0;
        for (const Term &t : terms_[first])
            if (t.step < at1)
                d += termMove(t, a, b);
        for (const Term &t : terms_[second])
            if (t.step < at2)
                d += termMove(t, a, b);
        return d;
    }

    void MotionBound::linkDisplacements(const std::vector<double> &a, const std::vector<double> &b,
                                        std::vector<double> &out) const
    {
        out.resize(terms_.size());
        for (std::size_t i = 0; i < terms_.size(); ++i)
        {
            double d = 0.0;
            for (const Term &t : terms_[i])
                d += termMove(t, a, b);
            out[i] = d;
        }
    }
}  // namespace meshgap
