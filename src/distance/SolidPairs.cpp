#include "SolidPairs.h"

#include <algorithm>

#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/BvhSolid.h"
#include "meshgap/geometry/ConvexHull.h"
#include "meshgap/geometry/PrimitiveDistance.h"

namespace meshgap
{
    namespace solids
    {
        namespace
        {
            /** \brief Every solid of \e a against every solid of \e b. */
            void solidsAgainstSolids(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, double stopBelow,
                                     Nearest &best)
            {
                const std::vector<Primitive> &pa = a.primitives(), &pb = b.primitives();
                const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
                for (std::uint32_t i = 0; i < pa.size(); ++i)
                    for (std::uint32_t j = 0; j < pb.size(); ++j)
                    {
                        if (best.found && best.d <= stopBelow)
                            return;
                        ++best.triangleTests;
                        const SolidGap g = primitiveGap(pa[i], identity, pb[j], X_AB, best.d);
                        if (g.distance < best.d)
                            best = {g.distance, true, i, j, g.onA, g.onB, best.boxTests, best.triangleTests, false};
                    }
            }

            /** \brief Every solid of \e solids against the mesh of \e mesh, the solids' body placed in the mesh's
                frame by \e X_MS; \e meshIsA says which of the query's bodies the mesh is (the witnesses go to A's
                frame: \e X_AM places the mesh's frame there). */
            void solidsAgainstMesh(const Body &mesh, const Body &solids, const Eigen::Isometry3d &X_MS,
                                   const Eigen::Isometry3d &X_AM, bool meshIsA, double stopBelow, std::size_t budget,
                                   std::uint32_t seedTriangle, std::uint32_t seedSolid, Nearest &best)
            {
                const std::vector<Primitive> &ps = solids.primitives();
                const auto n = static_cast<std::uint32_t>(ps.size());
                for (std::uint32_t k = 0; k < n; ++k)
                {
                    // The seed's solid first (its distance prunes the rest), then the others in order.
                    const std::uint32_t j = seedSolid < n ? (k == 0 ? seedSolid : k <= seedSolid ? k - 1 : k) : k;
                    if ((best.found && best.d <= stopBelow) || best.exhausted)
                        return;
                    BvhSolidResult r;
                    const std::size_t spent = best.boxTests + best.triangleTests;
                    const std::size_t left = budget > 0 ? (budget > spent ? budget - spent : 1) : 0;
                    bvhSolidDistance(mesh.bvh(), ps[j], X_MS, best.d, stopBelow, r,
                                     j == seedSolid ? seedTriangle : UINT32_MAX, left);
                    best.boxTests += r.boxTests;
                    best.triangleTests += r.triangleTests;
                    best.exhausted = r.exhausted;
                    if (!r.found)
                        continue;
                    best.d = r.distance;
                    best.found = true;
                    best.partA = meshIsA ? r.triangle : j;
                    best.partB = meshIsA ? j : r.triangle;
                    best.onA = X_AM * (meshIsA ? r.onMesh : r.onSolid);
                    best.onB = X_AM * (meshIsA ? r.onSolid : r.onMesh);
                }
            }
        }  // namespace

        Nearest nearest(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, double upperBound,
                        double stopBelow, std::size_t budget, std::uint32_t seedA, std::uint32_t seedB)
        {
            Nearest best;
            best.d = upperBound;
            const bool solidA = asSolids(a), solidB = asSolids(b);
            if (solidA && solidB)
                solidsAgainstSolids(a, b, X_AB, stopBelow, best);
            else if (solidB)
                solidsAgainstMesh(a, b, X_AB, Eigen::Isometry3d::Identity(), true, stopBelow, budget, seedA, seedB,
                                  best);
            else
                solidsAgainstMesh(b, a, X_AB.inverse(), X_AB, false, stopBelow, budget, seedB, seedA, best);
            if (!(best.d < upperBound))
                best.d = std::numeric_limits<double>::infinity();
            return best;
        }

        bool touch(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
        {
            const bool solidA = asSolids(a), solidB = asSolids(b);
            if (solidA && solidB)
                return nearest(a, b, X_AB, std::numeric_limits<double>::min(), 0.0, 0).d == 0.0;
            const Body &mesh = solidA ? b : a, &solid = solidA ? a : b;
            const Eigen::Isometry3d X_MS = solidA ? X_AB.inverse() : X_AB;
            return std::any_of(solid.primitives().begin(), solid.primitives().end(),
                               [&](const Primitive &p) { return bvhSolidCollide(mesh.bvh(), p, X_MS); });
        }

        bool outerApart(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, double bound)
        {
            const std::vector<Primitive> &pa = a.primitives(), &pb = b.primitives();
            const ConvexHull *ha = pa.empty() ? a.convexHull() : nullptr;
            const ConvexHull *hb = pb.empty() ? b.convexHull() : nullptr;
            if ((pa.empty() && ha == nullptr) || (pb.empty() && hb == nullptr))
                return false;
            if (ha != nullptr && hb != nullptr)
                return hullGap(*ha, *hb, X_AB, bound) > bound;
            const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
            if (ha != nullptr)
                return std::all_of(pb.begin(), pb.end(),
                                   [&](const Primitive &p) { return hullPrimitiveGap(*ha, p, X_AB, bound) > bound; });
            if (hb != nullptr)
            {
                const Eigen::Isometry3d X_BA = X_AB.inverse();
                return std::all_of(pa.begin(), pa.end(),
                                   [&](const Primitive &p) { return hullPrimitiveGap(*hb, p, X_BA, bound) > bound; });
            }
            for (const Primitive &p : pa)
                for (const Primitive &q : pb)
                    if (!(primitiveGap(p, identity, q, X_AB, bound).distance > bound))
                        return false;
            return true;
        }

        bool inside(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
        {
            const bool solidA = asSolids(a), solidB = asSolids(b);
            if (solidA == solidB)
                return false;  // two bodies of solids: overlap is touching; two meshes are not answered here
            const Body &mesh = solidA ? b : a, &solid = solidA ? a : b;
            if (!mesh.isClosed())
                return false;
            const Eigen::Isometry3d X_MS = solidA ? X_AB.inverse() : X_AB;
            return std::any_of(solid.primitives().begin(), solid.primitives().end(),
                               [&](const Primitive &p) { return insideClosedBody(mesh, X_MS * p.pose.translation()); });
        }
    }  // namespace solids
}  // namespace meshgap
