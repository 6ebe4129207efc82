#ifndef MESHGAP_ROBOT_ROBOT_SCENE_H
#define MESHGAP_ROBOT_ROBOT_SCENE_H

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/robot/RobotModel.h"
#include "meshgap/robot/SelfPairTable.h"
#include "meshgap/scene/Scene.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(RobotScene);

    /** \brief What one whole-robot query should do (exact, certified answers): a DistanceRequest, as SceneRequest
        is, whose fields mean for the whole robot what they mean for one pair, and which pairs to answer.
        - stopBelow: the query stops at the first pair at or below it (the answer then an upper bound, not
          certified, and a collision without depth).
        - upperBound: pairs at or above it are pruned; when none is below, RobotResult::atLeast says so. Must be
          positive (else meshgap::Exception).
        - computeDepth: in collision, each colliding pair's penetration depth (false: the verdict alone, a
          colliding pair's distance CONTACT_DISTANCE).
        - outerBoundFirst: asked of every pair (a link against the obstacles of its scene, a self pair), each
          bounded by upperBound or, without everyPair, by the best distance so far.
        - Ignored: seed, start, maxEvaluations and recordHistory (node-level: the whole-robot query is exact), and
          maxTests (every pair is answered to the end; RobotScene::pairApart() takes a budget). */
    struct RobotRequest : DistanceRequest
    {
        /** \brief Answer every pair exactly (the clearance of every link and every pair, RobotResult::pairs),
            rather than pruning each pair at the best distance found so far (cheaper; the minimum is the same). */
        bool everyPair{false};
        /** \brief Check link against link (the pairs RobotModel::selfPairs() gives), not only against the world. */
        bool selfCollision{true};
    };

    /** \brief What one query found about one pair: a link against the obstacles, or two links. */
    struct RobotPairAnswer
    {
        /** \brief How far the query went with the pair. */
        enum class Status
        {
            EXACT,        ///< distance is the pair's signed distance (certified when the query is)
            AT_LEAST,     ///< pruned: the pair's distance is at least distance
            NOT_CHECKED   ///< not looked at (an early stop, or self pairs not asked for); distance is +infinity
        };
        double distance{std::numeric_limits<double>::infinity()};
        Status status{Status::NOT_CHECKED};
        /** \brief For a link against the obstacles: the closest (or deepest) obstacle, when EXACT. */
        std::size_t obstacle{0};
    };

    /** \brief The answer for one robot state. */
    struct RobotResult
    {
        /** \brief Minimum signed distance over every pair checked; negative in collision (the deepest penetration
            over every colliding pair, each pair's signed distance as Scene::distance() and refineExact() give it). */
        double distance{std::numeric_limits<double>::infinity()};
        /** \brief The pair that attains it: link against obstacle \e other (selfPair false), or link \e link
            against link \e other (selfPair true, link < other). Indices in RobotScene::links(), obstacles(). */
        bool selfPair{false};
        std::size_t link{0}, other{0};
        /** \brief Witness points, world frame: on the link \e link (A) and on what it is measured against (B: the
            obstacle, or the link \e other), as DistanceResult names them. */
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
        bool inCollision{false};
        double penetrationDepth{0.0};  ///< in collision: the depth estimate behind distance (>= 0)
        bool certified{false};         ///< every pair completed (or a collision, proven)
        /** \brief No pair is below RobotRequest::upperBound, which distance then holds (certified; no pair, no
            witnesses). */
        bool atLeast{false};
        std::size_t pairsChecked{0};  ///< pairs answered by the exact layer (not pruned by the broad phase)
        /** \brief Per pair: links().size() link-against-obstacles pairs (index = link), then the self pairs in
            RobotScene::selfPairs() order. */
        std::vector<RobotPairAnswer> pairs;
        /** \brief Per link: the least of its pairs' distances (a lower bound where a pair is AT_LEAST), its
            clearance from everything it is checked against. */
        std::vector<double> linkClearance;
    };

    /** \brief A box in the world frame: its centre, its axes (the columns of a rotation), its half extents. */
    struct WorldBox
    {
        Eigen::Vector3d center{Eigen::Vector3d::Zero()};
        Eigen::Matrix3d axes{Eigen::Matrix3d::Identity()};
        Eigen::Vector3d half{Eigen::Vector3d::Zero()};
    };

    /** \brief A lower bound of the distance between two boxes (the largest gap along the 15 axes of the
        separating-axis test, less a pad against roundoff of 1e-9 of the sizes and coordinates involved); 0 or less
        when they may overlap. Never larger than their true distance. */
    double boxGap(const WorldBox &a, const WorldBox &b);

    /** \brief What one caller (one thread) carries from one query to the next, nearby state: per link its scene's
        warm start, per self pair an exact warm start, the pair of the last minimum (visited first), and the
        pose buffers. Changes the cost of a query, never its answer (ties between pairs aside). Never shared
        between threads; bound to the robot scene it was last used with. */
    struct RobotWarmStart
    {
        std::vector<SceneWarmStart> links;
        std::vector<ExactWarmStart> self;
        std::vector<Eigen::Isometry3d> frames, poses;
        /** \brief The state placed (its numbers). */
        std::vector<double> state;
        /** \brief At the state placed: per link, its BVH root box in the world, the axis-aligned box around it
            (padded against roundoff) and its bounding sphere's centre in the world. */
        std::vector<WorldBox> boxes;
        std::vector<Eigen::AlignedBox3d> aabbs;
        std::vector<Eigen::Vector3d> centers;
        /** \brief The collision verdict's warm start per link and obstacle of its scene (linkObstacles()), for the
            obstacles answered by the exact layer; and its traversal stack. */
        std::vector<ExactWarmStart> obstaclePairs;
        std::vector<std::uint32_t> stack;
        /** \brief Per question of RobotScene::sweptApart() (a link against one obstacle or one primitive solid of
            it, a self pair), the last direction its GJK looked along (zero: none yet), the next piece's first. */
        std::vector<Eigen::Vector3d> sweepAxes;
        bool valid{false};
        std::size_t pair{0};  ///< the last minimum's pair (RobotResult::pairs order)
        std::uint64_t scene{0};

        /** \brief Forget the history (the next query is answered as a cold one would be) but keep the memory. */
        void reset()
        {
            valid = false;
            for (SceneWarmStart &w : links)
                w.reset();
            for (auto *pairs : {&self, &obstaclePairs})
                for (ExactWarmStart &p : *pairs)
                {
                    p.valid = false;
                    p.front.clear();
                    p.collision.clear();
                    p.penetration.valid = false;
                }
            std::fill(sweepAxes.begin(), sweepAxes.end(), Eigen::Vector3d::Zero());
        }
    };

    /** \brief A robot (RobotModel) among obstacles (bodies fixed in the world frame): whole-robot collision and
        distance. Each link is answered against the obstacles by a Scene of its own (with its warm start) around
        one broad phase, an R-tree of the obstacles' boxes, shared by every link that checks the same obstacles;
        each self pair by the exact layer (refineExact(), inCollision()) after a bounding-sphere test, one exact warm
        start per pair. Immutable once built, shared between threads; per-caller state lives in RobotWarmStart; no
        allocation once a caller has warmed up.

        The collision verdict (inCollision(), pairCollides()) has a broad phase of its own, shared by every link:
        each link's BVH root box placed in the world once a state, against each obstacle's axis-aligned box, then
        against the boxes of its primitive solids (or its BVH root's) by the separating-axis test; only a pair
        that survives is put to the exact layer. An obstacle of boxes alone is answered as the solid boxes it is
        (a triangle of the link touching or inside a box, or the box inside the closed link), by a traversal of
        the link's BVH that prunes a node apart from the box and stops at the first node inside it; a self pair
        is first looked up in the self-pair table when the scene has one (tabulateSelfPairs()), then tested by
        bounding spheres, then by the links' root boxes; a pair of links fixed to one another
        (no joint between them moves with the state) is proven apart once, when the scene is built, and never
        asked again (pairApart() too, for a margin below that clearance). */
    class RobotScene
    {
    public:
        /** \brief \e robot as it is now (its links and pairs are copied: later attach() calls are not seen); the
            obstacles in the world frame; \e allowedObstacles, (link, obstacle) pairs never checked (a MoveIt
            scene's allowed collision matrix, RobotProblem::allowedObstacles). Throws meshgap::Exception for a pair
            naming a link or obstacle that is not there. */
        RobotScene(RobotModelConstPtr robot, std::vector<BodyConstPtr> obstacles,
                   const std::vector<LinkPair> &allowedObstacles = {});

        const RobotModel &robot() const { return *robot_; }
        const std::vector<RobotLink> &links() const { return links_; }
        const std::vector<LinkPair> &selfPairs() const { return selfPairs_; }
        const std::vector<BodyConstPtr> &obstacles() const { return obstacles_; }
        /** \brief Link \e i's scene (the link as the robot, the obstacles it is checked against as the world: every
            obstacle but those allowed with it, in obstacles()' order; linkObstacles() maps their indices). */
        const Scene &linkScene(std::size_t i) const { return *scenes_[i]; }
        /** \brief For link \e i, the index in obstacles() of each obstacle of its scene. */
        const std::vector<std::size_t> &linkObstacles(std::size_t i) const { return linkObstacles_[i]; }
        /** \brief Number of pairs: one per link (against the obstacles), then one per self pair. */
        std::size_t numPairs() const { return links_.size() + selfPairs_.size(); }
        /** \brief Tabulate the self pairs over their joints (SelfPairTable, with \e options): from then on a self
            pair's verdict at a state in one of its proven cells is that look-up. Costs what the table's questions
            cost (a fraction of a second for an arm); call it before the scene is shared, as a RobotModel is
            configured before. */
        void tabulateSelfPairs(const SelfPairTable::Options &options = SelfPairTable::Options());
        /** \brief The table of tabulateSelfPairs(), or null. */
        const SelfPairTable *selfPairTable() const { return table_.get(); }

        /** \brief Unique per robot scene (keys the warm starts made with it). */
        std::uint64_t id() const { return id_; }

        /** \brief Exact collision verdict at \e state (a link against an obstacle, or two links not allowed to
            touch; containment included); stops at the first collision. Throws meshgap::Exception for a state of
            the wrong dimension. */
        bool inCollision(const double *state, std::size_t size, RobotWarmStart &warm,
                         bool selfCollision = true) const;
        /** \brief Minimum signed distance over the pairs at \e state, as \e request asks. Throws
            meshgap::Exception for a state of the wrong dimension or a bound not positive. */
        void distance(const double *state, std::size_t size, const RobotRequest &request, RobotWarmStart &warm,
                      RobotResult &result) const;
        /** \brief The same, cold (no warm start). */
        void distance(const std::vector<double> &state, const RobotRequest &request, RobotResult &result) const;

        /** \brief Pair by pair, for callers that ask different pairs different questions (a motion validator):
            place the robot at \e state in \e warm, then ask pairApart() and pairCollides() about any pair at that
            state. Throws meshgap::Exception for a state of the wrong dimension. */
        void place(const double *state, std::size_t size, RobotWarmStart &warm) const;
        /** \brief At the state last placed in \e warm: true when pair \e k (RobotResult::pairs order) is certified
            more than \e margin (>= 0) apart, its signed distance above margin; false when some part of it is
            within margin, or collides. A bounded question: the pair's traversal prunes everything beyond margin
            and stops at the first triangle pair within it. With a \e budget (> 0, DistanceRequest::maxTests), a
            traversal that reaches it gives up: false, and \e gaveUp (if given) set true; it is set false
            otherwise. A pair whose distance lies just beyond the margin is the costly kind to prove (the traversal
            must open node pairs down to that small difference); one at twice the margin is cheap. */
        bool pairApart(std::size_t k, double margin, RobotWarmStart &warm, std::size_t budget = 0,
                       bool *gaveUp = nullptr) const;
        /** \brief At the state last placed in \e warm: the exact collision verdict of pair \e k (containment
            included). */
        bool pairCollides(std::size_t k, RobotWarmStart &warm) const;
        /** \brief pairApart()'s first, cheap stage alone: true when boxes and spheres prove pair \e k more than
            \e margin apart at the state last placed in \e warm (false: no claim). */
        bool pairBoundsApart(std::size_t k, double margin, const RobotWarmStart &warm) const;

        /** \brief The robot's poses at one end of a piece of motion: every frame's and every link's, in the world
            (RobotModel::framePoses(), and each link's frame pose times its RobotLink::X_FL). */
        struct Placement
        {
            std::vector<Eigen::Isometry3d> frames, links;
        };
        /** \brief Fill \e at with the poses at \e state (throws meshgap::Exception for a state of the wrong
            dimension). */
        void placeEnds(const double *state, std::size_t size, Placement &at) const;
        /** \brief True when pair \e k is proven free along a piece of motion whose ends place the robot as \e at0
            and \e at1, each link straying at most \e grow (its own, or the pair's first and second link's, from
            MotionBound::bend(): in the world for a link against the obstacles, in the frame of the two links' nearest
            common ancestor for a self pair) from the straight line between each of its points' two places: the
            links' convex hulls swept between their two places (sweptHullGap()), grown so, are apart from every
            obstacle of the link's scene (its primitive solids, or its hull) or from each other. False (no claim)
            when a link or a mesh obstacle has no hull (Body::coarseHull(), the one used). A question of a few GJK
            runs, far cheaper than a traversal, and tight where a link moves along an obstacle: the margin it needs
            shrinks with the square of the piece's length, pairApart()'s with its length.

            \e stays, \e staysOther: the pair's first (or only) and second link stays where it is in that frame over
            the whole piece (no joint between moves: MotionBound::stays()), so it is placed once, at its pose at
            \e at0, not swept (half the support calls). Each GJK starts along the direction its question last ended
            on in \e warm (RobotWarmStart::sweepAxes; the scene's warm start, prepared by place()), and leaves its own
            there. */
        bool sweptApart(std::size_t k, const Placement &at0, const Placement &at1, double grow, double growOther,
                        RobotWarmStart &warm, bool stays = false, bool staysOther = false) const;

    private:
        /** \brief Size \e warm for this scene (afresh if it was made with another) and fill its poses. */
        void prepare(const double *state, std::size_t size, RobotWarmStart &warm) const;
        /** \brief True when the bounding spheres of self pair \e p's links are at least \e bound apart; their gap
            into \e gap. */
        bool spheresApart(std::size_t p, const RobotWarmStart &warm, double bound, double &gap) const;
        /** \brief Answer pair \e k (RobotResult::pairs order) below \e bound into \e answer (bound 0: only a
            collision matters); true when it is the best so far, then copied into \e best. \e complete turns false
            when the pair's answer is not certified. */
        bool answerPair(std::size_t k, const RobotRequest &request, double bound, RobotWarmStart &warm,
                        RobotPairAnswer &answer, RobotResult &best, bool &complete) const;
        /** \brief answerPair() for link \e i against the obstacles (its scene). */
        bool answerLink(std::size_t i, const RobotRequest &request, double bound, RobotWarmStart &warm,
                        RobotPairAnswer &answer, RobotResult &best, bool &complete) const;
        /** \brief answerPair() for self pair \e p (bounding spheres, then refineExact()). */
        bool answerSelf(std::size_t p, const RobotRequest &request, double bound, RobotWarmStart &warm,
                        RobotPairAnswer &answer, RobotResult &best, bool &complete) const;
        void finish(RobotResult &result) const;
        /** \brief The verdict's obstacle bounds and pair offsets (from the constructor). */
        void buildVerdictBounds();
        /** \brief Each link's boxes and sphere centre in the world at the state placed in \e warm. */
        void placeBounds(RobotWarmStart &warm) const;
        /** \brief The collision verdict of link \e i against the obstacles of its scene, at the state placed. */
        bool linkCollides(std::size_t i, RobotWarmStart &warm) const;
        /** \brief True when link \e i's boxes prove it more than \e bound from every obstacle of its scene, at the
            state placed (false: no claim). */
        bool boundsApart(std::size_t i, double bound, const RobotWarmStart &warm) const;
        /** \brief For links \e a and \e b fixed to one another (no joint between them: every frame from each up to a
            common one fixed to its parent), their certified clearance (up to RIGID_CLEARANCE_CAP, less a pad
            against roundoff); 0 for any other pair, or one within the pad. */
        double rigidPairClearance(std::size_t a, std::size_t b) const;
        /** \brief The collision verdict of self pair \e p at the state placed: proven apart once if fixed together,
            or in a proven cell of the self-pair table, then spheres, root boxes, convex hulls, then exact
            (containment included). */
        bool selfVerdict(std::size_t p, RobotWarmStart &warm) const;

        /** \brief What the verdict's broad phase knows of an obstacle: its axis-aligned box (padded), the boxes of
            its parts (its primitive solids, or its BVH root), and whether it is boxes alone (answered as solids). */
        struct ObstacleBounds
        {
            Eigen::AlignedBox3d aabb;
            std::vector<WorldBox> parts;
            bool boxes{false};
        };

        RobotModelConstPtr robot_;
        std::vector<RobotLink> links_;
        std::vector<LinkPair> selfPairs_;
        std::vector<BodyConstPtr> obstacles_;
        std::vector<ScenePtr> scenes_;
        std::vector<std::vector<std::size_t>> linkObstacles_;
        std::vector<ObstacleBounds> obstacleBounds_;
        /** \brief Per self pair, the two links' nearest common frame (RobotModel::NONE: none, two roots). */
        std::vector<std::size_t> selfAncestor_;
        /** \brief Per self pair, rigidPairClearance(): a pair fixed together and this far apart at every state. */
        std::vector<double> rigidClearance_;
        /** \brief How far a rigid pair's clearance is computed (beyond it, it is this). */
        static constexpr double RIGID_CLEARANCE_CAP = 0.01;
        /** \brief Per link, where its pairs with the obstacles start in RobotWarmStart::obstaclePairs; their
            number last. */
        std::vector<std::size_t> pairOffset_;
        /** \brief Per link, where its sweptApart() questions start in RobotWarmStart::sweepAxes (one per obstacle of
            its scene, or per primitive solid of one); then the self pairs', one each; their number last. */
        std::vector<std::size_t> sweepOffset_;
        /** \brief Where the self pairs are proven apart in joint space (tabulateSelfPairs()), or null. */
        SelfPairTableConstPtr table_;
        std::uint64_t id_;
    };
}  // namespace meshgap

#endif
