#include "meshgap/ompl/RobotMotionValidator.h"

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "meshgap/Exception.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace meshgap
{
    RobotMotionValidator::RobotMotionValidator(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene,
                                               const RobotModel &robot)
        : ompl::base::MotionValidator(si), scene_(std::move(scene)), bound_(robot), states_(si->getStateSpace())
    {
        if (!scene_)
            throw Exception("RobotMotionValidator", "no robot scene");
        if (scene_->links().size() != robot.links().size() ||
            scene_->robot().frames().size() != robot.frames().size())
            throw Exception("RobotMotionValidator", "the robot scene was built with another set of links");
        for (const auto &[a, b] : scene_->selfPairs())
            pairTerms_.push_back(bound_.pairTerms(a, b));
        angles_.assign(robot.dimension(), 0);
        for (const StateBlock &block : robot.stateBlocks())
            if (block.space == JointSpace::SO2)
                angles_[block.first] = 1;
    }

    namespace
    {
        /** \brief Pieces of a motion halved further than this, or more of them than this, and the motion is
            refused unproven (conservative): a pair that stays within a hair of touching over a long stretch. */
        constexpr int MAX_DEPTH = 30;
        constexpr std::size_t MAX_PIECES = std::size_t(1) << 16;
        /** \brief Buffers grown past this many pieces by an unusual motion are released after it. */
        constexpr std::size_t KEPT_PIECES = std::size_t(1) << 12;
        /** \brief A pair's first question on a piece may cost this many box and triangle tests; one that gives up
            is asked again on both halves, with half the margin and four times the budget, and from the sixth time
            on with no budget. A pair just beyond its margin costs thousands of tests to prove, one at twice its
            margin tens: halving the piece is cheaper (bench/README.md, "Certified motions on MotionBenchMaker's
            problems": 30 to 3,000 tried, 100 the least total). */
        constexpr std::size_t FIRST_BUDGET = 100;
        constexpr unsigned int UNLIMITED_AFTER = 5;
        /** \brief Middles of pieces kept placed for their halves' ends, at most (beyond, a piece's ends are placed
            when it needs them); NO_PLACE: none kept. */
        constexpr std::size_t MAX_PLACES = 1024;
        constexpr std::size_t NO_PLACE = ~std::size_t(0);
        /** \brief A self pair's look-up in the self-pair table covers its piece's segment by a box, or by boxes around
            its halves, halves of halves, ... this many times deep (at most 2^(this + 1) - 1 look-ups). */
        constexpr unsigned int TABLE_SPLITS = 5;

        /** \brief A pair still to prove on a piece, and how many times a question about it gave up. */
        struct Pending
        {
            std::size_t pair;
            unsigned int gaveUp;
        };

        /** \brief A piece [t0, t1] of the motion and the pairs still to prove on it: Work::pending[first, first +
            count). */
        struct Piece
        {
            double t0, t1;
            std::size_t first, count;
            int depth;
            std::size_t end0, end1;  ///< the places of its ends: Work::places[end0], [end1]
        };

        /** \brief One thread's buffers, kept between motions (no allocation once warm). */
        struct Work
        {
            RobotWarmStart warm;
            MotionBound::Motion motion;
            std::vector<double> q0, q1, q, qEnd, moves, lambda, sums;
            /** \brief Per state number, its step over the motion (an angle's along the shorter arc, signed). */
            std::vector<double> steps;
            /** \brief Per pair, its links' bends over the motion (MotionBound::bend(); the second 0 for a link
                against the obstacles). */
            std::vector<double> bends;
            /** \brief Per pair, whether each of its links stays put over the motion (MotionBound::stays(): in the
                world, or in the self pair's nearest common frame), as bends. */
            std::vector<unsigned char> stays;
            /** \brief The robot placed at the motion's two ends ([0] and [1], placed when a pair first needs
                them, \e endsPlaced) and at the middle of every piece halved (copied from \e warm there): a piece's
                ends are its parent's end and middle, placed once. The first \e used are this motion's. */
            std::vector<RobotScene::Placement> places;
            RobotScene::Placement at0, at1;  ///< the ends of a piece past MAX_PLACES
            std::size_t used{0};
            bool endsPlaced[2]{false, false};
            std::vector<unsigned char> need;  ///< per link: in a pair pending on the piece (MotionBound bounds it)
            std::vector<Piece> pieces;        ///< breadth first: a queue read from its head
            std::vector<Pending> pending;     ///< a range per piece

            /** \brief Piece \e p's two ends placed, pointed to by \e end0 and \e end1: the motion's own placed the
                first time a pair needs them, the others kept as a middle (past MAX_PLACES, placed here, in \e at0
                and \e at1). \e middle is the working state (its own place is made already). True (for a
                condition). */
            bool placeEnds(const RobotScene &scene, const ompl::base::StateSpace &space, const Piece &p,
                           const ompl::base::State *s1, const ompl::base::State *s2, ompl::base::State *middle,
                           const RobotScene::Placement *&end0, const RobotScene::Placement *&end1)
            {
                for (auto [end, index, t, scratch] :
                     {std::tuple(&end0, p.end0, p.t0, &at0), std::tuple(&end1, p.end1, p.t1, &at1)})
                {
                    const bool kept = index != NO_PLACE && (index >= 2 || endsPlaced[index]);
                    if (!kept)
                    {
                        space.interpolate(s1, s2, t, middle);
                        robotStateToVector(space, middle, qEnd);
                        scene.placeEnds(qEnd.data(), qEnd.size(), index == NO_PLACE ? *scratch : places[index]);
                        if (index != NO_PLACE)
                            endsPlaced[index] = true;
                    }
                    *end = index == NO_PLACE ? scratch : &places[index];
                }
                return true;
            }

            /** \brief The whole motion as the first piece, every pair pending on it; no place kept yet. */
            void start(std::size_t pairs)
            {
                pending.clear();
                for (std::size_t k = 0; k < pairs; ++k)
                    pending.push_back({k, 0});
                pieces.assign(1, Piece{0.0, 1.0, 0, pairs, 0, 0, 1});
                if (places.size() < 2)
                    places.resize(2);
                used = 2;
                endsPlaced[0] = endsPlaced[1] = false;
            }

            /** \brief steps from q0 and q1; \e angles marks the numbers that are angles (their step along the
                shorter arc, as OMPL's SO(2) interpolation turns them). */
            void stepNumbers(const std::vector<unsigned char> &angles)
            {
                steps.resize(q0.size());
                for (std::size_t v = 0; v < q0.size(); ++v)
                {
                    const double step = q1[v] - q0[v];
                    steps[v] = angles[v] && std::abs(step) > M_PI ? step - std::copysign(2.0 * M_PI, step) : step;
                }
            }

            /** \brief need: the links of the pairs pending on piece \e p. */
            void markLinks(const RobotScene &scene, const Piece &p)
            {
                const std::size_t links = scene.links().size();
                need.assign(links, 0);
                for (std::size_t i = p.first; i < p.first + p.count; ++i)
                {
                    const std::size_t k = pending[i].pair;
                    if (k < links)
                        need[k] = 1;
                    else
                        need[scene.selfPairs()[k - links].first] = need[scene.selfPairs()[k - links].second] = 1;
                }
            }

            /** \brief The place of the middle just placed in \e warm, kept for the halves' ends (NO_PLACE past
                MAX_PLACES). */
            std::size_t keepMiddle()
            {
                if (used >= MAX_PLACES)
                    return NO_PLACE;
                const std::size_t mid = used++;
                if (places.size() < used)
                    places.resize(used);
                places[mid].frames = warm.frames;  // as RobotScene::placeEnds() places the middle state
                places[mid].links = warm.poses;
                return mid;
            }
        };
    }  // namespace

    bool RobotMotionValidator::proveFree(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        thread_local Work w;
        const ompl::base::StateSpace &space = *si_->getStateSpace();
        robotStateToVector(space, s1, w.q0);
        robotStateToVector(space, s2, w.q1);
        // No separate test of the end states: every piece's proof covers its ends, so a proven motion has free ends,
        // and an end in collision leaves the pieces next to it unproven (a middle state near it collides, or the
        // depth runs out). The states a planner connects have passed its validity checker already.
        // Each pair's displacement bound over the whole motion; over a piece it is (t1 - t0) times that (the
        // bound is linear in the joint steps, and the joints move linearly in t).
        const std::size_t links = scene_->links().size(), pairs = scene_->numPairs();
        bound_.linkDisplacements(w.q0, w.q1, w.moves);
        bound_.motion(w.q0, w.q1, w.motion);
        w.lambda.assign(w.moves.begin(), w.moves.begin() + links);
        for (const auto &[a, b] : scene_->selfPairs())
            w.lambda.push_back(bound_.pairDisplacement(a, b, w.q0, w.q1));
        pairBends(w.motion, w.bends, w.stays);
        const SelfPairTable *table = scene_->selfPairTable();
        if (table)
            w.stepNumbers(angles_);
        w.start(pairs);
        const StatePool::Lease lease(states_);
        ompl::base::State *middle = lease.get();
        bool free = true;
        for (std::size_t head = 0; free && head < w.pieces.size(); ++head)
        {
            const Piece p = w.pieces[head];
            const double t = 0.5 * (p.t0 + p.t1), half = 0.5 * (p.t1 - p.t0);
            // The piece's ends, for the swept hulls, placed when a pair first needs them. A point strays at most
            // h^2 / 8 times its bend from its chord.
            const RobotScene::Placement *at0 = nullptr, *at1 = nullptr;
            const double stray = 0.5 * half * half * (1.0 + 1e-9);
            space.interpolate(s1, s2, t, middle);  // OMPL's own interpolation (SO(2) by the shorter arc)
            robotStateToVector(space, middle, w.q);
            scene_->place(w.q.data(), w.q.size(), w.warm);
            w.markLinks(*scene_, p);
            bound_.pieceBounds(w.motion, w.warm.frames, w.warm.poses, half, w.sums, &w.need);
            const std::size_t start = w.pending.size();
            for (std::size_t i = p.first; free && i < p.first + p.count; ++i)
            {
                const auto [k, tries] = w.pending[i];
                // A self pair whose joints stay within cells of joint space proven apart: one look-up.
                if (table && k >= links &&
                    table->apartAlong(k - links, w.q.data(), w.steps.data(), half, TABLE_SPLITS))
                    continue;
                const std::size_t budget = tries >= UNLIMITED_AFTER ? 0 : FIRST_BUDGET << (2 * tries);
                bool gaveUp = false;
                const double margin =
                    std::min(half * w.lambda[k], pieceBound(k, w.sums, w.motion, half, w.warm.frames, w.warm.poses));
                // Cheapest first: boxes and spheres at the middle state, the swept hulls, then the meshes.
                if (scene_->pairBoundsApart(k, margin, w.warm) ||
                    ((at0 || w.placeEnds(*scene_, space, p, s1, s2, middle, at0, at1)) &&
                     scene_->sweptApart(k, *at0, *at1, stray * w.bends[2 * k],
                                        stray * w.bends[2 * k + 1], w.warm, w.stays[2 * k], w.stays[2 * k + 1])) ||
                    scene_->pairApart(k, margin, w.warm, budget, &gaveUp))
                    continue;
                // A pair given up on is within reach of its margin, not within it: no collision to look for.
                free = gaveUp || !scene_->pairCollides(k, w.warm);
                w.pending.push_back({k, tries + (gaveUp ? 1u : 0u)});
            }
            const std::size_t left = w.pending.size() - start;
            if (!free || left == 0)
                continue;
            free = p.depth + 1 < MAX_DEPTH && w.pieces.size() + 2 <= MAX_PIECES;
            if (!free)
                continue;
            const std::size_t mid = w.keepMiddle();
            w.pieces.push_back({p.t0, t, start, left, p.depth + 1, p.end0, mid});
            w.pieces.push_back({t, p.t1, start, left, p.depth + 1, mid, p.end1});
        }
        if (w.pieces.capacity() > KEPT_PIECES)
        {
            w.pieces = std::vector<Piece>();
            w.pending = std::vector<Pending>();
        }
        return free;
    }

    void RobotMotionValidator::pairBends(const MotionBound::Motion &motion, std::vector<double> &bends,
                                         std::vector<unsigned char> &stays) const
    {
        bends.clear();
        stays.clear();
        for (std::size_t i = 0; i < scene_->links().size(); ++i)
        {
            bends.insert(bends.end(), {bound_.bend(i, bound_.numTerms(i), motion), 0.0});
            stays.insert(stays.end(), {bound_.stays(i, bound_.numTerms(i), motion), false});
        }
        for (std::size_t p = 0; p < scene_->selfPairs().size(); ++p)
        {
            const auto [a, b] = scene_->selfPairs()[p];
            bends.insert(bends.end(), {bound_.bend(a, pairTerms_[p].first, motion),
                                       bound_.bend(b, pairTerms_[p].second, motion)});
            stays.insert(stays.end(), {bound_.stays(a, pairTerms_[p].first, motion),
                                       bound_.stays(b, pairTerms_[p].second, motion)});
        }
    }

    double RobotMotionValidator::pieceBound(std::size_t k, const std::vector<double> &sums,
                                            const MotionBound::Motion &motion, double half,
                                            const std::vector<Eigen::Isometry3d> &frames,
                                            const std::vector<Eigen::Isometry3d> &poses) const
    {
        const std::size_t links = scene_->links().size();
        if (k < links)
            return bound_.linkBound(k, sums);
        const auto [a, b] = scene_->selfPairs()[k - links];
        return bound_.pairPieceBound(a, b, pairTerms_[k - links], sums, motion, half, frames, poses);
    }

    bool RobotMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const
    {
        const bool free = proveFree(s1, s2);
        if (free)
            valid_++;
        else
            invalid_++;
        return free;
    }

    bool RobotMotionValidator::checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                                           std::pair<ompl::base::State *, double> &lastValid) const
    {
        const bool free = checkMotion(s1, s2);
        if (!free)
        {
            if (lastValid.first)
                si_->copyState(lastValid.first, s1);
            lastValid.second = 0.0;
        }
        return free;
    }
}  // namespace meshgap
