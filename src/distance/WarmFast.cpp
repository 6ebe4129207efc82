#include "meshgap/distance/WarmFast.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "meshgap/distance/HillClimb.h"
#include "meshgap/distance/PairEvaluator.h"
#include "meshgap/geometry/TriangleDistance.h"

namespace meshgap
{
    namespace
    {
        /** \brief Bound on how far any node of B (radius r about its origin) moves between poses X1 and X2 in A's
            frame: |(R2 - R1) b + (t2 - t1)| <= 2 sin(theta / 2) r + |t2 - t1|, theta the angle of R1^T R2. */
        double displacement(const Eigen::Isometry3d &X1, const Eigen::Isometry3d &X2, double r)
        {
            const double theta = Eigen::Quaterniond(X1.linear()).angularDistance(Eigen::Quaterniond(X2.linear()));
            return 2.0 * std::sin(0.5 * std::min(theta, M_PI)) * r + (X2.translation() - X1.translation()).norm();
        }

        /** \brief A triangle's corners with its centroid sphere (in A's frame). */
        struct Corners
        {
            Eigen::Vector3d p0, p1, p2, c;
            double r;
        };

        inline Corners corners(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, const Eigen::Vector3d &p2)
        {
            Corners k{p0, p1, p2, (p0 + p1 + p2) / 3.0, 0.0};
            k.r = std::sqrt(std::max({(p0 - k.c).squaredNorm(), (p1 - k.c).squaredNorm(), (p2 - k.c).squaredNorm()}));
            return k;
        }

        /** \brief When triangle q lies wholly on one side of triangle p's plane, its nearest corner's distance to that
            plane (a lower bound on the triangles' distance); 0 otherwise. */
        inline double planeGap(const Eigen::Vector3d &p0, const Eigen::Vector3d &p1, const Eigen::Vector3d &p2,
                               const Eigen::Vector3d &q0, const Eigen::Vector3d &q1, const Eigen::Vector3d &q2)
        {
            const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
            const double len = n.norm();
            if (!(len > 0.0))
                return 0.0;
            const double s0 = n.dot(q0 - p0) / len, s1 = n.dot(q1 - p0) / len, s2 = n.dot(q2 - p0) / len;
            if (s0 > 0.0 && s1 > 0.0 && s2 > 0.0)
                return std::min({s0, s1, s2});
            if (s0 < 0.0 && s1 < 0.0 && s2 < 0.0)
                return -std::max({s0, s1, s2});
            return 0.0;
        }

        /** \brief WarmFast::patch()'s search: the closest triangle pair found so far (ta, tb at distance best; none
            while ta is UINT32_MAX, best then the node pair's own distance: the patch only improves on it). */
        class PatchSearch
        {
        public:
            PatchSearch(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result)
                : a_(a), b_(b), sa_(a.surface()), sb_(b.surface()), X_AB_(X_AB), result_(result), best_(result.distance)
            {
            }

            bool found() const { return ta_ != UINT32_MAX; }

            /** \brief A's triangle \e t's corners; B's are carried by X_AB. Computed once per triangle where one side
                of the descent stays fixed (the profile: most candidate pairs end at a bound). */
            Corners cornersA(std::uint32_t t) const
            {
                const Triangle &f = sa_.triangles[t];
                return corners(sa_.vertices[f[0]], sa_.vertices[f[1]], sa_.vertices[f[2]]);
            }
            Corners cornersB(std::uint32_t t) const
            {
                const Triangle &f = sb_.triangles[t];
                return corners(X_AB_ * sb_.vertices[f[0]], X_AB_ * sb_.vertices[f[1]], X_AB_ * sb_.vertices[f[2]]);
            }

            void test(std::uint32_t ta, std::uint32_t tb) { test(cornersA(ta), cornersB(tb), ta, tb); }

            /** \brief Triangles ta of A and tb of B: their exact distance unless a bound shows they are no closer. */
            void test(const Corners &ka, const Corners &kb, std::uint32_t ta, std::uint32_t tb)
            {
                // Exact pruning: the gap between the triangles' centroid spheres is a lower bound on their distance.
                if ((ka.c - kb.c).norm() - ka.r - kb.r >= best_)
                    return;
                // And the plane bound, both ways.
                if (planeGap(ka.p0, ka.p1, ka.p2, kb.p0, kb.p1, kb.p2) >= best_ ||
                    planeGap(kb.p0, kb.p1, kb.p2, ka.p0, ka.p1, ka.p2) >= best_)
                    return;
                Eigen::Vector3d onA, onB;
                const double d = triangleDistance(ka.p0, ka.p1, ka.p2, kb.p0, kb.p1, kb.p2, onA, onB);
                ++result_.triangleTests;
                if (d < best_)
                {
                    best_ = d;
                    ta_ = ta;
                    tb_ = tb;
                    result_.onA = onA;
                    result_.onB = onB;
                }
            }

            /** \brief The triangles around the node pair: every pair of them when there are at most 64 pairs,
                otherwise (large fans, as at CAD vertices) each triangle around one node against the best triangle
                around the other (or the first one there). */
            void testFans()
            {
                const std::uint32_t *beginA = a_.beginNodeTriangles(result_.nodes.a);
                const std::uint32_t *endA = a_.endNodeTriangles(result_.nodes.a);
                const std::uint32_t *beginB = b_.beginNodeTriangles(result_.nodes.b);
                const std::uint32_t *endB = b_.endNodeTriangles(result_.nodes.b);
                if ((endA - beginA) * (endB - beginB) <= 64)  // small fans: every pair
                {
                    for (const std::uint32_t *i = beginA; i != endA; ++i)
                        for (const std::uint32_t *j = beginB; j != endB; ++j)
                            test(*i, *j);
                }
                else if (beginA != endA && beginB != endB)
                {
                    const std::uint32_t fixedB = tb_ != UINT32_MAX ? tb_ : *beginB;
                    for (const std::uint32_t *i = beginA; i != endA; ++i)
                        test(*i, fixedB);
                    const std::uint32_t fixedA = ta_ != UINT32_MAX ? ta_ : *beginA;
                    for (const std::uint32_t *j = beginB; j != endB; ++j)
                        test(fixedA, *j);
                }
            }

            /** \brief Descent over corner-sharing neighbours while the pair improves. */
            void descend()
            {
                for (bool improved = found(); improved;)
                {
                    const std::uint32_t ca = ta_, cb = tb_;
                    const Corners fixedA = cornersA(ca), fixedB = cornersB(cb);
                    for (const std::uint32_t *i = a_.beginTriangleNeighbours(ca); i != a_.endTriangleNeighbours(ca);
                         ++i)
                        test(cornersA(*i), fixedB, *i, cb);
                    for (const std::uint32_t *j = b_.beginTriangleNeighbours(cb); j != b_.endTriangleNeighbours(cb);
                         ++j)
                        test(fixedA, cornersB(*j), ca, *j);
                    improved = ta_ != ca || tb_ != cb;
                }
            }

            /** \brief The pair found, if any, into the result. */
            void finish()
            {
                if (!found())
                    return;
                result_.distance = best_;
                result_.triangleA = ta_;
                result_.triangleB = tb_;
            }

        private:
            const Body &a_, &b_;
            const Mesh &sa_, &sb_;
            const Eigen::Isometry3d &X_AB_;
            DistanceResult &result_;
            double best_;
            std::uint32_t ta_{UINT32_MAX}, tb_{UINT32_MAX};
        };
    }  // namespace

    WarmFast::WarmFast() : DistanceSolver("warm-fast")
    {
        params_.declareParam<int>(
            "global_every",
            [this](int n)
            {
                if (n < 0)
                    throw std::invalid_argument("global_every must not be negative");
                setGlobalEvery(static_cast<unsigned int>(n));
            },
            [this] { return static_cast<int>(getGlobalEvery()); });
        params_.declareParam<double>(
            "gap_tolerance", [this](double g) { setGapTolerance(g); }, [this] { return getGapTolerance(); });
        params_.declareParam<int>(
            "global_evaluations",
            [this](int n)
            {
                if (n <= 0)
                    throw std::invalid_argument("global_evaluations must be positive");
                setGlobalEvaluations(static_cast<unsigned int>(n));
            },
            [this] { return static_cast<int>(getGlobalEvaluations()); });
        params_.declareParam<bool>(
            "surface_patch", [this](bool on) { setSurfacePatch(on); }, [this] { return getSurfacePatch(); });
        params_.declareParam<std::string>(
            "global_search",
            [this](const std::string &s)
            {
                if (s == "multistart")
                    setGlobalGa(false);
                else if (s == "comb-GA-wl")
                    setGlobalGa(true);
                else
                    throw std::invalid_argument("global_search must be multistart or comb-GA-wl");
            },
            [this] { return std::string(getGlobalGa() ? "comb-GA-wl" : "multistart"); });
        params_.declareParam<std::string>(
            "global_seeding",
            [this](const std::string &s)
            {
                if (s == "random")
                    setGlobalSeeding(CombGA::Seeding::RANDOM);
                else if (s == "clusters")
                    setGlobalSeeding(CombGA::Seeding::CLUSTERS);
                else
                    throw std::invalid_argument("global_seeding must be random or clusters");
            },
            [this]
            { return std::string(getGlobalSeeding() == CombGA::Seeding::CLUSTERS ? "clusters" : "random"); });
    }

    void WarmFast::setGapTolerance(double g)
    {
        if (!(g >= 0.0))
            throw std::invalid_argument("gap_tolerance must be >= 0");
        gapTolerance_ = g;
    }

    void WarmFast::setGlobalEvaluations(unsigned int n)
    {
        if (n == 0)
            throw std::invalid_argument("global_evaluations must be positive");
        globalEvaluations_ = n;
    }

    void WarmFast::global(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint64_t seed,
                          DistanceResult &result) const
    {
        DistanceRequest request;
        request.seed = seed;
        request.maxEvaluations = globalEvaluations_;
        if (globalGa_ && a.distances().isDense() && b.distances().isDense())
        {
            ga_.solve(a, b, X_AB, request, result);
            return;
        }
        // Random-start climbs (the default, and beyond the dense budget): no mesh distances needed,
        // globalEvaluations_ d^2 in all.
        PairEvaluator evaluator(a, b, X_AB);
        std::mt19937_64 rng(seed);
        std::uniform_int_distribution<std::uint32_t> na(0, a.numNodes() - 1), nb(0, b.numNodes() - 1);
        NodePair best;
        double bestD2 = std::numeric_limits<double>::infinity();
        std::size_t steps = 0, climbs = 0;
        while (evaluator.evaluations() < globalEvaluations_)
        {
            NodePair pair{na(rng), nb(rng)};
            double d2 = evaluator.d2(pair);
            steps += hillClimb(evaluator, pair, d2, globalEvaluations_);
            ++climbs;
            if (d2 < bestD2)
            {
                bestD2 = d2;
                best = pair;
            }
        }
        evaluator.fill(best, bestD2, result);
        result.localSteps = steps;
        result.iterations = climbs;
    }

    void WarmFast::patch(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint32_t warmA,
                         std::uint32_t warmB, bool fans, DistanceResult &result) const
    {
        PatchSearch search(a, b, X_AB, result);
        // Seeds: the last answer's triangle pair (a warm start), then, if \e fans, the triangles around the two nodes.
        if (warmA != UINT32_MAX && warmA < a.surface().triangles.size() && warmB < b.surface().triangles.size())
            search.test(warmA, warmB);
        // When the node pair did not move, the last triangle pair and the descent suffice, unless it did not beat
        // the node pair.
        if (fans || !search.found())
            search.testFans();
        search.descend();
        search.finish();
    }

    void WarmFast::solveWarm(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, WarmFastState &state,
                             std::uint64_t seed, DistanceResult &result) const
    {
        const auto start = std::chrono::steady_clock::now();
        result = DistanceResult();
        NodePair pair;
        double d2 = std::numeric_limits<double>::infinity();
        std::size_t evaluations = 0, steps = 0;
        bool runGlobal = !state.valid;
        const bool wasValid = state.valid;
        const NodePair previous = state.pair;
        if (state.valid)
        {
            state.drift += displacement(state.X_AB, X_AB, b.radiusAboutOrigin());
            PairEvaluator evaluator(a, b, X_AB);
            pair = state.pair;
            d2 = evaluator.d2(pair);
            steps += hillClimb(evaluator, pair, d2);
            evaluations += evaluator.evaluations();
            const double d = std::sqrt(d2), lower = state.globalDistance - state.drift;
            runGlobal = (globalEvery_ > 0 && state.sinceGlobal + 1 >= globalEvery_) ||
                        (std::isfinite(gapTolerance_) && lower < (1.0 - gapTolerance_) * d);
        }
        std::size_t iterations = 1;
        if (runGlobal)
        {
            DistanceResult g;
            global(a, b, X_AB, seed, g);
            evaluations += g.evaluations;
            steps += g.localSteps;
            iterations += g.iterations;
            if (g.distance * g.distance < d2)
            {
                pair = g.nodes;
                d2 = g.distance * g.distance;
            }
            state.globalDistance = std::sqrt(d2);
            state.drift = 0.0;
            state.sinceGlobal = 0;
            ++state.globalSearches;
        }
        else
            ++state.sinceGlobal;
        state.valid = true;
        state.pair = pair;
        state.X_AB = X_AB;
        ++state.queries;

        const PairEvaluator evaluator(a, b, X_AB);
        evaluator.fill(pair, d2, result);
        result.evaluations = evaluations;
        result.localSteps = steps;
        result.iterations = iterations;
        if (surfacePatch_)
        {
            // The triangles around the nodes only need a look when the node pair moved (or nothing is warm).
            const bool fans = !wasValid || !(pair == previous) || state.triangleA == UINT32_MAX;
            patch(a, b, X_AB, state.triangleA, state.triangleB, fans, result);
            if (result.triangleTests > 0 && result.distance < std::sqrt(d2))
            {
                state.triangleA = result.triangleA;
                state.triangleB = result.triangleB;
            }
        }
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    void WarmFast::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                         DistanceResult &result) const
    {
        checkRequest(a, b, request);
        WarmFastState state;
        if (request.start)
        {
            state.valid = true;
            state.pair = *request.start;
            state.X_AB = X_AB;
            // No gap test (nothing is known of the global minimum): a stateless warm query climbs only.
            state.globalDistance = std::numeric_limits<double>::infinity();
        }
        solveWarm(a, b, X_AB, state, request.seed, result);
    }
}  // namespace meshgap
