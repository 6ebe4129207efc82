#include "meshgap/distance/ExactDistance.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "meshgap/Exception.h"
#include "meshgap/distance/HillClimb.h"
#include "meshgap/distance/PenetrationDepth.h"
#include "meshgap/geometry/SolidAngle.h"
#include "meshgap/geometry/TriangleDistance.h"
#include "SolidPairs.h"

namespace meshgap
{
    namespace
    {
        struct TriangleCandidate
        {
            double d{std::numeric_limits<double>::infinity()};
            std::uint32_t ta{0}, tb{0};
            Eigen::Vector3d onA{Eigen::Vector3d::Zero()}, onB{Eigen::Vector3d::Zero()};
        };

        /** \brief Exact distance of surface triangle ta of A to surface triangle tb of B (B's corners in A's frame). */
        double pairDistance(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint32_t ta,
                            std::uint32_t tb, Eigen::Vector3d &onA, Eigen::Vector3d &onB)
        {
            const Mesh &sa = a.surface(), &sb = b.surface();
            const Triangle &fa = sa.triangles[ta], &fb = sb.triangles[tb];
            // R v + t, exactly as bvhDistance() places B's corners, so a seed pair and the same pair found by the
            // traversal give the same bits (warm and cold queries then agree exactly).
            const Eigen::Matrix3d R = X_AB.linear();
            const Eigen::Vector3d t = X_AB.translation();
            return triangleDistance(sa.vertices[fa[0]], sa.vertices[fa[1]], sa.vertices[fa[2]],
                                    R * sb.vertices[fb[0]] + t, R * sb.vertices[fb[1]] + t, R * sb.vertices[fb[2]] + t,
                                    onA, onB);
        }

        void consider(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, std::uint32_t ta, std::uint32_t tb,
                      TriangleCandidate &best, std::size_t &tests)
        {
            Eigen::Vector3d onA, onB;
            ++tests;
            const double d = pairDistance(a, b, X_AB, ta, tb, onA, onB);
            if (d < best.d)
                best = {d, ta, tb, onA, onB};
        }

        /** \brief Seed from a node pair: all pairs of surface triangles around the two nodes, then descend over
            corner-sharing neighbours of the current pair while the distance improves. */
        TriangleCandidate seedFromNodes(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB,
                                        const NodePair &nodes, std::size_t &tests)
        {
            TriangleCandidate best;
            for (const std::uint32_t *ta = a.beginNodeTriangles(nodes.a); ta != a.endNodeTriangles(nodes.a); ++ta)
                for (const std::uint32_t *tb = b.beginNodeTriangles(nodes.b); tb != b.endNodeTriangles(nodes.b); ++tb)
                    consider(a, b, X_AB, *ta, *tb, best, tests);
            for (bool improved = std::isfinite(best.d); improved && best.d > 0.0;)
            {
                const TriangleCandidate before = best;
                for (const std::uint32_t *n = a.beginTriangleNeighbours(before.ta);
                     n != a.endTriangleNeighbours(before.ta); ++n)
                    consider(a, b, X_AB, *n, before.tb, best, tests);
                for (const std::uint32_t *n = b.beginTriangleNeighbours(before.tb);
                     n != b.endTriangleNeighbours(before.tb); ++n)
                    consider(a, b, X_AB, before.ta, *n, best, tests);
                improved = best.d < before.d;
            }
            return best;
        }

    }  // namespace

    namespace
    {
        /** \brief The opening of both point-in-body tests: only a closed body has an inside, and it lies in the
            body's bounding box. */
        bool mayContain(const Body &body, const Eigen::Vector3d &p)
        {
            return body.isClosed() && !body.bvh().nodes()[0].outside(p);
        }

        /** \brief The generalised winding number of \e body's surface about \e p is above 1/2 (summed solid angles). */
        bool windingAboveHalf(const Body &body, const Eigen::Vector3d &p)
        {
            const Mesh &m = body.surface();
            double total = 0.0;
            for (const Triangle &f : m.triangles)
                total += solidAngle(m.vertices[f[0]] - p, m.vertices[f[1]] - p, m.vertices[f[2]] - p);
            return std::abs(total) > 2.0 * M_PI;  // winding number |total / 4 pi| > 1/2
        }
    }  // namespace

    bool containsPoint(const Body &body, const Eigen::Vector3d &p)
    {
        return mayContain(body, p) && windingAboveHalf(body, p);
    }

    bool insideClosedBody(const Body &body, const Eigen::Vector3d &p)
    {
        if (!mayContain(body, p))
            return false;
        // Directions off every axis and diagonal (OMPL.app's walls are axis-aligned: a ray along an axis would graze
        // their edges).
        static const Eigen::Vector3d directions[] = {Eigen::Vector3d(0.5773, 0.6532, 0.4898),
                                                     Eigen::Vector3d(-0.3217, 0.8469, -0.4234),
                                                     Eigen::Vector3d(0.7071, -0.2764, -0.6508)};
        for (const Eigen::Vector3d &d : directions)
        {
            int winding = 0;
            if (bvhRayWinding(body.bvh(), p, d, winding))
                return winding != 0;
        }
        return windingAboveHalf(body, p);
    }

    namespace
    {
        /** \brief One body wholly inside the other (they have no surface contact): one point of each decides. */
        /** \brief Whether a part (connected component) of \e inner lies inside the closed body \e outer. Called when
            no surface pair touches, so each part is wholly inside or wholly outside: one point per part decides.
            (One point per body is not enough: a robot of several parts, one of them inside an obstacle, collides;
            found by fuzzing, tests/resources/fuzz/distance/two_parts_one_inside.) */
        bool anyPartInside(const Body &inner, const Body &outer, const Eigen::Isometry3d &X_outer_inner)
        {
            if (!outer.isClosed())
                return false;
            for (const std::uint32_t node : inner.componentNodes())
                // O(log n); containsPoint() is O(n)
                if (insideClosedBody(outer, X_outer_inner * inner.surface().vertices[node]))
                    return true;
            return false;
        }

        bool oneInsideTheOther(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
        {
            return anyPartInside(b, a, X_AB) || anyPartInside(a, b, X_AB.inverse());
        }

        /** \brief The signed distance once result.inCollision is decided: nothing to add when free; in collision the
            depth (setPenetration()), unless the caller asked for the verdict only (\e verdictOnly: an early stop, or
            DistanceRequest::computeDepth false). */
        void finishCollision(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, bool verdictOnly,
                             DistanceResult &result, ExactWarmStart *warm)
        {
            result.penetrationDepth = 0.0;
            result.penetration = Penetration::NONE;
            if (!result.inCollision)
                return;
            if (verdictOnly)
            {
                result.distance = CONTACT_DISTANCE;
                result.penetration = Penetration::NOT_COMPUTED;
            }
            else
                setPenetration(a, b, X_AB, result, warm ? &warm->penetration : nullptr);
        }
    }  // namespace

    bool inCollision(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, ExactWarmStart *warm)
    {
        if (solids::answered(a, b))
            return solids::touch(a, b, X_AB) || solids::inside(a, b, X_AB);
        const bool touching =
            warm ? bvhCollide(a.bvh(), b.bvh(), X_AB, warm->collision) : bvhCollide(a.bvh(), b.bvh(), X_AB);
        return touching || oneInsideTheOther(a, b, X_AB);
    }

    namespace
    {
        /** \brief The closest pair of parts as the solids they are (solids::nearest()), seeded by the warm start's
            last pair; into \e best, \e exhausted. */
        void nearestSolids(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                           const ExactWarmStart *warm, TriangleCandidate &best, bool &exhausted, DistanceResult &result)
        {
            const bool seeded = warm && warm->valid;
            const solids::Nearest n =
                solids::nearest(a, b, X_AB, request.upperBound, request.stopBelow >= 0.0 ? request.stopBelow : 0.0,
                                request.maxTests, seeded ? warm->triangleA : UINT32_MAX,
                                seeded ? warm->triangleB : UINT32_MAX);
            result.triangleTests += n.triangleTests;
            result.boxTests += n.boxTests;
            exhausted = n.exhausted;
            if (n.d < request.upperBound)
                best = {n.d, n.partA, n.partB, n.onA, n.onB};
        }

        /** \brief The closest surface triangle pair: a seed (the warm start's pair, or the surface around the
            result's node pair), then the BVH traversal below it (bvhDistance()); into \e best, \e exhausted. */
        void nearestTriangles(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB,
                              const DistanceRequest &request, ExactWarmStart *warm, TriangleCandidate &best,
                              bool &exhausted, DistanceResult &result)
        {
            const double stopBelow = request.stopBelow, upperBound = request.upperBound;
            if (warm && warm->valid && warm->triangleA < a.surface().triangles.size() &&
                warm->triangleB < b.surface().triangles.size())
            {
                // The last closest pair: one test, and most often still the closest pair (or near it).
                consider(a, b, X_AB, warm->triangleA, warm->triangleB, best, result.triangleTests);
            }
            // A seed whose nodes are not below the caller's bound is not worth its descent: the traversal, pruned at
            // the bound, is then cheaper than walking the surface towards a pair that most likely does not matter.
            else if (result.distance < upperBound && result.nodes.a < a.numNodes() && result.nodes.b < b.numNodes())
                best = seedFromNodes(a, b, X_AB, result.nodes, result.triangleTests);

            // With an early stop, a seed at or below stopBelow is already the answer. Otherwise the traversal stops
            // at the first pair at or below max(stopBelow, 0) (0: a touching pair, nothing can be closer).
            const bool mayStop = stopBelow >= 0.0;
            if (mayStop && best.d <= stopBelow)
                return;
            BvhDistanceResult traversal;
            const bool seeded = std::isfinite(best.d);
            // A seed that is the starting bound, apart, is not tested again: its distance and direction are known.
            const bool known = seeded && best.d <= upperBound && best.d > 0.0;
            const Eigen::Vector3d seedAxis =
                known ? Eigen::Vector3d((best.onB - best.onA) / (best.onB - best.onA).norm()) : Eigen::Vector3d::Zero();
            bvhDistance(a.bvh(), b.bvh(), X_AB, std::min(best.d, upperBound), mayStop ? stopBelow : 0.0, traversal,
                        seeded ? best.ta : UINT32_MAX, seeded ? best.tb : UINT32_MAX, warm ? &warm->front : nullptr,
                        known ? &seedAxis : nullptr, request.maxTests);
            exhausted = traversal.exhausted;
            result.triangleTests += traversal.triangleTests;
            result.boxTests += traversal.boxTests;
            if (traversal.found)
                best = {traversal.distance, traversal.triangleA, traversal.triangleB, traversal.onA, traversal.onB};
        }
    }  // namespace

    void refineExact(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, DistanceResult &result,
                     const DistanceRequest &request, ExactWarmStart *warm)
    {
        const double stopBelow = request.stopBelow, upperBound = request.upperBound;
        result.nodeDistance = result.distance;
        result.openBody = !a.isClosed() || !b.isClosed();
        const bool mayStop = stopBelow >= 0.0;
        const bool verdictOnly = mayStop || !request.computeDepth;  // a collision gets no depth
        if (request.outerBoundFirst && upperBound < std::numeric_limits<double>::infinity() &&
            solids::outerApart(a, b, X_AB, upperBound))
        {
            // The convex outer bounds are apart by more than the bound: no pair is closer, none touches, neither
            // body holds the other (each lies in its own outer bound).
            result.distance = std::numeric_limits<double>::infinity();
            result.certified = true;
            result.inCollision = false;
            result.penetrationDepth = 0.0;
            result.penetration = Penetration::NONE;
            ++result.outerBoundProofs;
            return;
        }
        const bool solid = solids::answered(a, b);
        TriangleCandidate best;
        bool exhausted = false;
        if (solid)
            nearestSolids(a, b, X_AB, request, warm, best, exhausted, result);
        else
            nearestTriangles(a, b, X_AB, request, warm, best, exhausted, result);
        // A part of one body inside the other, when no part touches.
        auto inside = [&] { return solid ? solids::inside(a, b, X_AB) : oneInsideTheOther(a, b, X_AB); };
        if (a.surface().triangles.empty() || b.surface().triangles.empty())
            throw Exception("exact distance", "a body has no triangles");
        if (!(best.d < upperBound))
        {
            // Nothing closer than the caller's bound (the seed, if any, was not either): proven, but no pair to
            // report. A part of one body may still lie inside the other.
            result.distance = std::numeric_limits<double>::infinity();
            result.certified = !exhausted;
            result.inCollision = inside();
            finishCollision(a, b, X_AB, verdictOnly, result, warm);
            return;
        }

        if (warm)
        {
            warm->valid = true;
            warm->triangleA = best.ta;
            warm->triangleB = best.tb;
        }
        result.distance = best.d;
        result.onA = best.onA;
        result.onB = best.onB;
        result.triangleA = best.ta;
        result.triangleB = best.tb;
        result.inCollision = best.d <= 0.0;
        // The traversal ran to its end, or stopped at a touching pair (distance 0). An answer at or below stopBelow
        // may have ended it early (bvhDistance() does not say whether it did): then it is only an upper bound.
        const bool stoppedEarly = mayStop && best.d <= stopBelow && !result.inCollision;
        result.certified = !stoppedEarly && (!exhausted || result.inCollision);
        if (!result.inCollision && !stoppedEarly)
            result.inCollision = inside();  // the witnesses stay the closest surface points
        finishCollision(a, b, X_AB, verdictOnly, result, warm);
    }

    void ExactSolver::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                            DistanceResult &result) const
    {
        const auto start = std::chrono::steady_clock::now();
        result = DistanceResult();
        checkRequest(a, b, request);
        if (request.start)
        {
            NodePair pair = *request.start;
            PairEvaluator evaluator(a, b, X_AB);
            double d2 = evaluator.d2(pair);
            result.localSteps = hillClimb(evaluator, pair, d2, request.maxEvaluations);
            evaluator.fill(pair, d2, result);
        }
        refineExact(a, b, X_AB, result, request);
        result.iterations = 1;
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}  // namespace meshgap
