#ifndef MESHGAP_DISTANCE_WARM_FAST_H
#define MESHGAP_DISTANCE_WARM_FAST_H

#include <Eigen/Geometry>
#include <limits>

#include "meshgap/distance/CombGA.h"
#include "meshgap/distance/DistanceSolver.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(WarmFast);

    /** \brief What WarmFast carries from one query of a body pair to the next (one per body pair and caller thread;
        a default-constructed state means a cold start). */
    struct WarmFastState
    {
        bool valid{false};         ///< false: the next query is a cold start (global search)
        NodePair pair;             ///< the last answer's node pair
        std::uint32_t triangleA{UINT32_MAX}, triangleB{UINT32_MAX};  ///< the last surface patch's closest triangles
        Eigen::Isometry3d X_AB{Eigen::Isometry3d::Identity()};  ///< the pose of the last query
        double globalDistance{std::numeric_limits<double>::infinity()};  ///< node distance the last global search found
        double drift{0.0};          ///< how far B's nodes may have moved (summed) since that search
        std::size_t sinceGlobal{0}; ///< queries since that search
        std::size_t queries{0}, globalSearches{0};  ///< counters over the state's life
    };

    /**
       @anchor mgWarmFast
       @par Short description
       The paper's warm start (III-D) made a fast approximate query along a run of nearby poses: hill-climb
       (III-E) from the previous answer's node pair; run the global search only (1) on a cold start, (2) every
       \e global_every queries, so that a global minimum that moved to another region is found, or (3) when the
       climbed distance exceeds, by more than \e gap_tolerance relative, the lower bound that the last global
       search still gives: the node minimum can have dropped since then by at most the drift, how far any node of B
       has moved (each pose step moves a node at most |dt| + |dR| r_B, r_B = Body::radiusAboutOrigin()), so it is at
       least (global distance - drift) if that search was right. The global search is a bounded multistart of hill
       climbs (random starts, \e global_evaluations d^2 in all), which needs no mesh distances, so no query costs
       seconds; with \e global_search "comb-GA-wl" it is comb-GA-wl (Table I, capped at \e global_evaluations too)
       when both bodies' mesh distances are dense tables. The multistart is the default, from a profile of
       warm-fast: global searches were 98% of its instructions along cubicles' path, a third of comb-GA-wl's
       in its mesh operators (mating, paths), and the multistart's mean query was 0.27-0.77 of comb-GA-wl's on every
       path of meshgap_bench_warm_fast, with the same median error (0).

       The answer is APPROXIMATE: a node pair's distance, or with \e surface_patch (the default) the exact distance
       of the best surface triangle pair found by a descent over corner-sharing neighbouring triangles, seeded with
       the last answer's triangle pair and, when the climb moved the node pair (or on a cold start), with the triangles
       around the two nodes (all pairs of them, or for fans of more than 64 pairs each triangle around one node
       against the best one around the other);
       either is the distance of a real pair of surface points, so an upper bound on the exact distance, never
       below it, but not a proof of the minimum. No collision verdict: two nodes never coincide unless the surfaces meet, so a caller that needs the
       verdict tests collision exactly (inCollision() in ExactDistance.h). distance is set, nodes (the node pair),
       onA/onB (A's frame), evaluations, localSteps, iterations (1 + the global search's), triangleTests.

       Every global search asks both bodies whether their mesh distances are dense (Body::distances(), built once
       per body on first use: an all-pairs table can take a second or more for a few thousand nodes), so build them
       beforehand to keep that out of the queries. After that, a climb, the multistart and the patch allocate
       nothing (comb-GA-wl may).

       Use solveWarm() with one WarmFastState per body pair along a path (a scene calls it per obstacle with the
       obstacle as A and the robot as B); solve() is the stateless form: a warm start from DistanceRequest::start
       when given (climb only, with the patch), a cold start (global search) otherwise.
    */
    class WarmFast : public DistanceSolver
    {
    public:
        static constexpr unsigned int DEFAULT_GLOBAL_EVERY = 64;
        static constexpr double DEFAULT_GAP_TOLERANCE = 0.5;
        static constexpr unsigned int DEFAULT_GLOBAL_EVALUATIONS = 40000;

        WarmFast();
        WarmFast(const WarmFast &) = delete;
        WarmFast &operator=(const WarmFast &) = delete;

        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;

        /** \brief One query of the run that \e state follows (updated); \e seed seeds a global search if one runs.
            Thread-safe for distinct states. */
        void solveWarm(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, WarmFastState &state,
                       std::uint64_t seed, DistanceResult &result) const;

        /** \brief A global search at least every \e n queries (parameter "global_every"); 0: only on a cold start
            or a gap. */
        void setGlobalEvery(unsigned int n) { globalEvery_ = n; }
        unsigned int getGlobalEvery() const { return globalEvery_; }
        /** \brief Relative gap that triggers a global search (parameter "gap_tolerance", >= 0); infinity: never. */
        void setGapTolerance(double g);
        double getGapTolerance() const { return gapTolerance_; }
        /** \brief Cap on a global search's d^2 evaluations (parameter "global_evaluations", > 0). */
        void setGlobalEvaluations(unsigned int n);
        unsigned int getGlobalEvaluations() const { return globalEvaluations_; }
        /** \brief The global search (parameter "global_search"): a bounded multistart of hill climbs (false, the
            default: cheaper per evaluation, measured in bench/paper/README.md, "Warm-fast") or, when both bodies' mesh
            distances are dense tables, comb-GA-wl (true). */
        void setGlobalGa(bool ga) { globalGa_ = ga; }
        bool getGlobalGa() const { return globalGa_; }
        /** \brief How the dense global search (comb-GA-wl) draws its initial population (parameter
            "global_seeding": "random", the paper's and the default, or "clusters", CombGA::Seeding). */
        void setGlobalSeeding(CombGA::Seeding s) { ga_.setSeeding(s); }
        CombGA::Seeding getGlobalSeeding() const { return ga_.getSeeding(); }
        /** \brief Report the exact distance of the triangles around the node pair (parameter "surface_patch"). */
        void setSurfacePatch(bool on) { surfacePatch_ = on; }
        bool getSurfacePatch() const { return surfacePatch_; }

    private:
        void global(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint64_t seed,
                    DistanceResult &result) const;
        void patch(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint32_t warmA, std::uint32_t warmB,
                   bool fans, DistanceResult &result) const;

        CombGA ga_{true};
        unsigned int globalEvery_{DEFAULT_GLOBAL_EVERY};
        double gapTolerance_{DEFAULT_GAP_TOLERANCE};
        unsigned int globalEvaluations_{DEFAULT_GLOBAL_EVALUATIONS};
        bool surfacePatch_{true};
        bool globalGa_{false};
    };
}  // namespace meshgap

#endif
