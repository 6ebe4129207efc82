#ifndef MESHGAP_SCENE_SCENE_H
#define MESHGAP_SCENE_SCENE_H

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "meshgap/ClassForward.h"
#include "meshgap/distance/DistanceQuery.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/WarmFast.h"
#include "meshgap/geometry/Body.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(Scene);

    /** \brief What one scene query should do: a DistanceRequest (its stopBelow and upperBound apply to the whole
        scene, its seed to the node-level search) and which answer. */
    struct SceneRequest : DistanceRequest
    {
        /** \brief Exact, certified surface distance (true) or the node-level answer of the paper (false). */
        bool exact{true};
        /** \brief The node-level solver of fast mode (exact == false), by its SolverFactory name; its seed is
            DistanceRequest::seed (the same seed gives the same answer). */
        std::string solver{"comb-GA-wl"};
        /** \brief Fast mode: never the node search where it costs more than the exact query. A node search started
            cold (a solver without a warm start carried: every one but "warm-fast" with a SceneWarmStart; a pose far
            from the last, the robot moved over COHERENCE radii; a warm-fast pair empty, far from its last pose, due
            for its periodic global search or climbed too far above its last global answer) costs 1.4 to 140 times
            the exact query, more on a body's first use (its mesh distances are built then): bench/README.md, "Fast
            mode against the exact query". The exact answer is given instead: the whole query (SceneResult::fellBack)
            for a stateless solver or a far pose, the pair (SceneResult::exactPairs) for warm-fast, whose state it
            seeds (the closest triangles' corners as the node pair, the exact distance as its global answer), so that
            warm-fast only climbs. false: the solver's node search as it is (the paper's algorithms, for their
            benches and tests). */
        bool fallBack{true};
    };

    /** \brief One certificate: what a query left for the next one near its pose (paper III-D): the obstacle of its
        minimum, visited first; in exact mode, per obstacle, the closest triangle pair and the certificate of the last
        traversal (ExactWarmStart); in fast mode, the last node pair. */
    struct SceneCertificate
    {
        bool valid{false};
        std::size_t obstacle{0};            ///< obstacle of the last minimum
        NodePair nodes;                     ///< fast mode: its node pair
        std::vector<ExactWarmStart> pairs;  ///< exact mode: one per obstacle, sized by the first exact query
        std::vector<WarmFastState> fast;    ///< fast mode with the warm-fast solver: one per obstacle
        /** \brief The robot's pose at the last query that carried or wrote this certificate (exact mode), and
            whether there was one (its fronts are that pose's). */
        Eigen::Isometry3d pose{Eigen::Isometry3d::Identity()};
        bool posed{false};
        std::uint64_t lastUse{0};  ///< SceneWarmStart::queries at that query (the least recent goes first)

        /** \brief Record that the query at \e X_WR (the \e use'th) carried or wrote this certificate. */
        void stamp(const Eigen::Isometry3d &X_WR, std::uint64_t use)
        {
            pose = X_WR;
            posed = true;
            lastUse = use;
        }

        /** \brief Forget the history but keep the memory, so that a caller who resets allocates nothing. */
        void reset()
        {
            valid = false;
            posed = false;
            for (WarmFastState &f : fast)
                f.valid = false;
            for (ExactWarmStart &p : pairs)
            {
                p.valid = false;
                p.front.clear();
                p.collision.clear();
                p.penetration.valid = false;
            }
        }

        /** \brief Bytes held, this object included (the fronts grow with the geometry, not with the queries). */
        std::size_t memoryBytes() const
        {
            std::size_t bytes = sizeof(*this) + (pairs.capacity() - pairs.size()) * sizeof(ExactWarmStart) +
                                fast.capacity() * sizeof(WarmFastState);
            for (const ExactWarmStart &p : pairs)
                bytes += p.memoryBytes();
            return bytes;
        }
    };

    /** \brief What one caller (one thread) carries from one query to the next: up to capacity() certificates of
        recent answers (SceneCertificate), the one in use (this object's own fields) and the others. Changes the cost
        of a query, never its answer. Never shared between threads; bound to the scene it was last used with (another
        scene starts it afresh).

        Which certificate an exact query (or a collision test) starts from is decided here, in one place
        (Scene::distance() asks choose()): the one whose pose is nearest to the query's by the motion bound (how far
        any robot point moved, its bounding sphere's displacement), if that motion is within COHERENCE times the
        robot's radius; a pose further from every certificate is unrelated to them (a planner's new sample) and is
        answered cold, without paying for a certificate that cannot help. A new certificate is written only when
        the stream shows it is local: the query lies within that motion of one of the last capacity() queries' poses
        (the start of a run of nearby poses, or of a region the stream returns to in turn); it replaces the least
        recently used one. So a stream of unrelated poses costs what cold queries cost, a path costs what one
        certificate carried along it costs, and a stream that alternates between a few regions (RRTConnect's two
        trees, a sampler returning to a region) keeps one certificate per region. Fast mode always carries the
        certificate in use (the paper's warm start, III-D). */
    struct SceneWarmStart : SceneCertificate
    {
        /** \brief A pose is near a certificate when the robot moved at most this many radii since it. */
        static constexpr double COHERENCE = 0.5;

        /** \brief How a query uses the warm start (choose()). */
        enum class Use
        {
            CARRY,  ///< near the certificate in use (chosen among the recent ones): carried from there
            WRITE,  ///< near a recent query's pose only: a fresh certificate is written, the least recent one goes
            COLD    ///< unrelated to every certificate and recent pose: a cold query, no certificate written
        };

        /** \brief Keep up to \e capacity certificates (at least 1; the default keeps one, carried along a run of
            poses). Each holds up to SceneCertificate::memoryBytes() (the fronts of every obstacle near its pose). */
        explicit SceneWarmStart(std::size_t capacity = 1) : capacity_(std::max<std::size_t>(capacity, 1)) {}

        std::size_t capacity() const { return capacity_; }
        /** \brief Forget the history (the next query is answered as a cold one would be) but keep the memory, so
            that a caller who resets allocates nothing. */
        void reset()
        {
            SceneCertificate::reset();
            for (SceneCertificate &c : recent)
                c.reset();
            posesSeen = 0;
        }

        /** \brief Bytes held, this object included. */
        std::size_t memoryBytes() const
        {
            std::size_t bytes = SceneCertificate::memoryBytes() + sizeof(*this) - sizeof(SceneCertificate) +
                                (recent.capacity() - recent.size()) * sizeof(SceneCertificate) +
                                lastPoses.capacity() * sizeof(Eigen::Isometry3d);
            for (const SceneCertificate &c : recent)
                bytes += c.memoryBytes();
            return bytes;
        }

        /** \brief Decide how the query at robot pose \e X_WR uses this warm start (see the class), for a robot whose
            bounding sphere has centre \e center (robot frame) and \e radius; the chosen certificate becomes the one
            in use (CARRY), or the least recent one is emptied to be written (WRITE). Records \e X_WR among the
            recent poses. Allocates only when a certificate is first kept. */
        Use choose(const Eigen::Isometry3d &X_WR, const Eigen::Vector3d &center, double radius);
        /** \brief Record that the query at \e X_WR carried or wrote the certificate in use. */
        void stamp(const Eigen::Isometry3d &X_WR) { SceneCertificate::stamp(X_WR, queries); }

        std::vector<SceneCertificate> recent;  ///< the other certificates kept (up to capacity() - 1)
        std::uint64_t scene{0};                ///< Scene::id() of the scene the certificates belong to
        std::uint64_t queries{0};              ///< queries that chose (the clock of lastUse)
        /** \brief The poses of the last capacity() queries (a ring, sized by the first choose(); posesSeen of them
            written so far). */
        std::vector<Eigen::Isometry3d> lastPoses;
        std::size_t posesSeen{0};
        /** \brief Statistics: queries carried from a certificate, that wrote a fresh one, answered cold. */
        std::uint64_t carried{0}, written{0}, cold{0};

    private:
        std::size_t capacity_;
    };

    /** \brief The answer for one robot pose. */
    struct SceneResult
    {
        /** \brief Minimum over all robot/obstacle pairs; negative in collision (a signed distance). */
        double distance{std::numeric_limits<double>::infinity()};
        std::size_t obstacle{0};  ///< which obstacle is closest
        /** \brief Witness points, world frame: on the robot (A) and on the obstacle (B), as DistanceResult names
            them. */
        Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
        /** \brief The robot collides with an obstacle (intersecting, touching or one inside the other, decided
            exactly). distance is then negative (a signed distance, see Scene::distance()). */
        bool inCollision{false};
        /** \brief In collision: the penetration depth estimate behind distance (>= 0) and how it was found. */
        double penetrationDepth{0.0};
        Penetration penetration{Penetration::NONE};
        /** \brief The robot, or the obstacle of the answer (none when atLeast), is not closed (Body::isClosed()):
            the answer is exact, but an open body has no inside (DistanceResult::openBody says what it means). */
        bool openBody{false};
        bool certified{false};        ///< exact and proven (every pair that survived the broad phase completed)
        std::size_t pairsChecked{0};  ///< robot/obstacle pairs that survived the broad phase
        std::size_t evaluations{0};   ///< node-pair evaluations (fast mode)
        /** \brief The work of an exact query, summed over the pairs it visited (DistanceResult's counts): a cost
            that does not depend on the machine's load. */
        std::size_t triangleTests{0}, boxTests{0};
        bool warmStartHit{false};     ///< the minimum was at the warm start's obstacle
        /** \brief Fast mode (SceneRequest::fallBack): the query was answered by the exact query (the answer is
            then exact mode's, certified as it is), or this many obstacle pairs by the exact pair query. */
        bool fellBack{false};
        std::size_t exactPairs{0};
        /** \brief Exact mode with a warm start: whether it carried a certificate, wrote a fresh one, or the query
            was answered cold (SceneWarmStart::choose()); COLD without a warm start. */
        SceneWarmStart::Use warmStartUse{SceneWarmStart::Use::COLD};
        /** \brief The distance is at least SceneRequest::upperBound, which distance then holds (certified; no
            witnesses, obstacle = obstacles().size()). */
        bool atLeast{false};
    };

    /** \brief A robot (one body, moving) among obstacles (bodies fixed in the world frame). Immutable once built,
        shared between threads; per-caller state lives in SceneWarmStart. */
    class Scene
    {
    public:
        /** \brief \e robot in its own frame; obstacles in the world frame. */
        Scene(BodyConstPtr robot, std::vector<BodyConstPtr> obstacles);
        /** \brief \e robot among the obstacles of \e others, sharing their broad phase (built once for, say, every
            link of a robot; it is immutable) rather than building a copy. A scene of its own (its own id()). */
        Scene(BodyConstPtr robot, const Scene &others);

        /** \brief Build from a robot mesh and a world mesh, the world split into its connected parts
            (splitComponents()), one obstacle body each. A relative grid size (the default) is relative to each
            part's own size. */
        static ScenePtr fromMeshes(const Mesh &robot, const Mesh &world, const BodyOptions &options = BodyOptions());

        const Body &robot() const { return *robot_; }
        /** \brief Unique per scene, never reused (keys the warm starts made with it). */
        std::uint64_t id() const { return id_; }
        const std::vector<BodyConstPtr> &obstacles() const { return obstacles_; }

        /** \brief Exact collision test of the robot at \e X_WR against every obstacle; stops at the first hit. Every
            query here throws meshgap::Exception for a pose that is not finite or whose position is beyond
            MAX_MAGNITUDE (meshgap/Limits.h): no answer rather than a wrong one. */
        bool inCollision(const Eigen::Isometry3d &X_WR) const;
        /** \brief The same verdict, each obstacle's surface test carried from the caller's last one (the collision
            front of \e warm's pair for that obstacle): along a run of nearby poses most of it is proven without a
            test. Thread-safe given a warm start per caller; allocates nothing once warmed up. */
        bool inCollision(const Eigen::Isometry3d &X_WR, SceneWarmStart &warm) const;

        /** \brief Minimum distance from the robot at \e X_WR to the obstacles, as \e request asks: exact and
            certified, or fast mode's upper bound (request.exact); only below request.upperBound (else atLeast);
            ended at request.stopBelow (then an upper bound, not certified). In collision the distance is signed,
            negative: the deepest penetration over every colliding obstacle, a pure function of the pose; with
            request.computeDepth false, CONTACT_DISTANCE (the verdict alone, as FCL's 0) and the first colliding
            obstacle met, which may depend on the visiting order. \e warm
            carries what the caller's last query found (SceneWarmStart) and changes the cost, never the answer: a
            complete exact answer is the cold one bit for bit. Thread-safe given a warm start per caller; allocates
            nothing once the calling thread has warmed up (tests/alloc). How: Scene.cpp, exactDistance(). */
        void distance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                      SceneResult &result) const;
        /** \brief The same answer with no warm start: a cold query, which keeps nothing (and allocates nothing once
            the calling thread has warmed up). */
        void distance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneResult &result) const;

    private:
        /** \brief The broad phase (an R-tree over the obstacles' world-frame boxes, Boost.Geometry) and the fast
            mode's solver, built once; defined in Scene.cpp so Boost.Geometry stays out of this header. */
        struct Impl;

        /** \brief The first obstacle (in R-tree order) the robot at \e X_WR collides with, or obstacles_.size(). */
        std::size_t firstCollision(const Eigen::Isometry3d &X_WR, SceneWarmStart *warm = nullptr) const;
        /** \brief Bind \e warm to this scene (one pair warm start per obstacle), starting it afresh if it was made
            with another scene. */
        void bind(SceneWarmStart &warm) const;
        /** \brief Bind \e warm, and decide how the query at \e X_WR uses it (SceneWarmStart::choose()): the warm
            start to carry from (its certificate in use, made ready), or null for a cold query; how, into \e use. */
        SceneWarmStart *choose(const Eigen::Isometry3d &X_WR, SceneWarmStart &warm,
                               SceneWarmStart::Use *use = nullptr) const;
        /** \brief The most negative signed distance (deepest penetration, setPenetration()) over every obstacle the
            robot at \e X_WR collides with, into \e best (ties: the smallest index); returns that obstacle, or
            obstacles_.size() if none collides. \e known is an obstacle already known to collide (no test made
            again), or obstacles_.size(); pairs tested are added to \e pairsChecked, and best.triangleTests counts
            the tests of every depth found. \e warm: each pair's deepest node carries over (setPenetration()'s warm
            start). */
        std::size_t deepestCollision(const Eigen::Isometry3d &X_WR, std::size_t known, DistanceResult &best,
                                     std::size_t &pairsChecked, SceneWarmStart *warm = nullptr) const;
        void query(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart *warm,
                   SceneResult &result) const;
        void exactDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart *warm,
                           SceneResult &result) const;
        void fastDistance(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                          bool carried, SceneResult &result) const;
        /** \brief Fast mode with warm-fast along a run: obstacle \e k's answer into \e r, warm-fast's from \e state,
            or (request.fallBack, where warm-fast would search globally) the exact pair query's below \e bound,
            which seeds \e state; returns true for the latter. */
        bool warmFastPair(std::size_t k, const Eigen::Isometry3d &X_WR, const SceneRequest &request,
                          const WarmFast &solver, double bound, WarmFastState &state, DistanceResult &r) const;
        /** \brief Fast mode's exact collision verdict: true (and \e result filled as exact mode would) when the
            robot at \e X_WR collides. */
        bool fastCollision(const Eigen::Isometry3d &X_WR, const SceneRequest &request, SceneWarmStart &warm,
                           bool warmValid, SceneResult &result) const;

        BodyConstPtr robot_;
        std::vector<BodyConstPtr> obstacles_;
        std::uint64_t id_;
        std::shared_ptr<const Impl> impl_;
    };
}  // namespace meshgap

#endif
