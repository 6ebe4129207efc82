#include "meshgap/geometry/TriangleBvh.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace meshgap
{
    namespace
    {
        /** \brief A triangle's place along one axis: its centroid's coordinate, ties broken by triangle index (a
            strict total order, so the sorted sequence is unique); \e k is its position in the node's range. */
        struct AxisKey
        {
            double key;
            std::uint32_t triangle, k;
            bool operator<(const AxisKey &o) const { return key < o.key || (key == o.key && triangle < o.triangle); }
        };

        /** \brief A rotated node's ranges of at least this many triangles are sorted by radixSort(), smaller ones by
            std::sort. (The presorted lists are sorted by radixSort() at every size: on world100's 100 parts of 1,152
            triangles it takes 100 M more instructions than std::sort, yet the build measured faster with it, 155-157
            ms against 170-174 before, and no faster than before with std::sort; std::sort's compares are branches
            that mispredict.) */
        constexpr std::uint32_t RADIX_FROM = 1024;

        /** \brief A coordinate's bits as an unsigned integer in the same order as the coordinates (finite ones; -0
            as +0, which compares equal to it): the sign bit set for positives, every bit flipped for negatives. */
        std::uint64_t orderedBits(double x)
        {
            x = x == 0.0 ? 0.0 : x;
            std::uint64_t bits;
            std::memcpy(&bits, &x, sizeof bits);
            return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t(1) << 63);
        }

        /** \brief Sorts \e items[0, n) by \e keys[0, n) (carried along), stably: a least-significant-digit radix sort,
            eleven bits a pass, a pass skipped where every key has the same digit (the sign and exponent bits of
            nearby coordinates), each pass from one pair of arrays into the other. \e keyTemp and \e itemTemp are
            working arrays of at least n. */
        void radixSort(std::uint64_t *keys, std::uint32_t *items, std::size_t n, std::uint64_t *keyTemp,
                       std::uint32_t *itemTemp)
        {
            constexpr int BITS = 11, DIGITS = (64 + BITS - 1) / BITS, BUCKETS = 1 << BITS;
            constexpr std::uint64_t MASK = BUCKETS - 1;
            std::vector<std::array<std::uint32_t, BUCKETS>> counts(DIGITS);
            for (std::size_t i = 0; i < n; ++i)
                for (int d = 0; d < DIGITS; ++d)
                    ++counts[d][(keys[i] >> (BITS * d)) & MASK];
            std::uint64_t *fromKeys = keys, *toKeys = keyTemp;
            std::uint32_t *fromItems = items, *toItems = itemTemp;
            for (int d = 0; d < DIGITS; ++d)
            {
                std::array<std::uint32_t, BUCKETS> &count = counts[d];
                if (count[(fromKeys[0] >> (BITS * d)) & MASK] == n)
                    continue;  // one digit for all: the order stays
                std::uint32_t sum = 0;
                for (std::uint32_t &c : count)
                {
                    const std::uint32_t here = c;
                    c = sum;
                    sum += here;
                }
                for (std::size_t i = 0; i < n; ++i)
                {
                    const std::uint32_t to = count[(fromKeys[i] >> (BITS * d)) & MASK]++;
                    toKeys[to] = fromKeys[i];
                    toItems[to] = fromItems[i];
                }
                std::swap(fromKeys, toKeys);
                std::swap(fromItems, toItems);
            }
            if (fromKeys != keys)
            {
                std::copy(fromKeys, fromKeys + n, keys);
                std::copy(fromItems, fromItems + n, items);
            }
        }

        /** \brief The build's working arrays, sized once for the whole mesh (no allocation per node), and what is
            computed once per triangle: its axis-aligned box and centroid. */
        struct BuildScratch
        {
            explicit BuildScratch(const Mesh &mesh)
            {
                const std::size_t n = mesh.triangles.size();
                corners.reserve(3 * n);
                boxes.resize(n);
                centre.resize(n);
                sorted.resize(n);
                bestSorted.resize(n);
                leftArea.resize(n);
                triangleBox.resize(n);
                centroid.resize(n);
                for (std::size_t t = 0; t < n; ++t)
                {
                    const Triangle &f = mesh.triangles[t];
                    for (std::uint32_t v : f)
                        triangleBox[t].extend(mesh.vertices[v]);
                    centroid[t] = (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]) / 3.0;
                }
                radixKeys.resize(n);
                radixTemp.resize(n);
                radixItems.resize(n);
                radixItemTemp.resize(n);
                for (int axis = 0; axis < 3; ++axis)
                {
                    // By centroid, ties by triangle index (AxisKey's order): a stable sort of the triangles in index
                    // order.
                    std::vector<std::uint32_t> &byAxis = axisOrder[axis];
                    byAxis.resize(n);
                    for (std::size_t t = 0; t < n; ++t)
                    {
                        radixKeys[t] = orderedBits(centroid[t][axis]);
                        byAxis[t] = static_cast<std::uint32_t>(t);
                    }
                    radixSort(radixKeys.data(), byAxis.data(), n, radixTemp.data(), radixItemTemp.data());
                }
                onLeft.assign(n, 0);
                partitionRight.resize(n);
            }
            std::vector<Eigen::Vector3d> corners;  ///< the node's triangle corners, in order
            std::vector<Eigen::AlignedBox3d> boxes;  ///< per position in the node's range: box along the node's axes
            std::vector<Eigen::Vector3d> centre;     ///< per position: centroid along the node's axes
            std::vector<AxisKey> sorted, bestSorted;
            std::vector<double> leftArea;
            std::vector<Eigen::AlignedBox3d> triangleBox;  ///< per triangle, axis-aligned
            std::vector<Eigen::Vector3d> centroid;         ///< per triangle
            /** \brief Per body axis, each pending node's triangles sorted by AxisKey along that axis, in the node's
                range (as order()): an aligned node's sorts are read here, not redone. */
            std::array<std::vector<std::uint32_t>, 3> axisOrder;
            std::vector<std::uint64_t> radixKeys, radixTemp;  ///< radixSort()'s keys and working array
            std::vector<std::uint32_t> radixItems, radixItemTemp;
            std::vector<std::uint8_t> onLeft;           ///< per triangle, set for the left side of the last split
            std::vector<std::uint32_t> partitionRight;  ///< the right side while partitioning a range
        };

        /** \brief The box of the points \e begin to \e end along \e axes (columns): each coordinate axes.col(c) . p
            summed as Eigen's axes.transpose() * p does, ((x + y) + z), in scalars (a product vector built per point
            and read back whole stalls on the store), and the bounds as AlignedBox3d::extend() keeps them. */
        Eigen::AlignedBox3d boxAlong(const Eigen::Matrix3d &axes, const Eigen::Vector3d *begin,
                                     const Eigen::Vector3d *end)
        {
            Eigen::AlignedBox3d box;
            double lo[3] = {box.min()[0], box.min()[1], box.min()[2]}, hi[3] = {box.max()[0], box.max()[1],
                                                                                box.max()[2]};
            for (const Eigen::Vector3d *p = begin; p != end; ++p)
                for (int c = 0; c < 3; ++c)
                {
                    const double q = (axes(0, c) * p->x() + axes(1, c) * p->y()) + axes(2, c) * p->z();
                    lo[c] = std::min(lo[c], q);
                    hi[c] = std::max(hi[c], q);
                }
            box.min() = Eigen::Vector3d(lo[0], lo[1], lo[2]);
            box.max() = Eigen::Vector3d(hi[0], hi[1], hi[2]);
            return box;
        }

        /** \brief A right-handed orthonormal frame along the eigenvectors of \e covariance: Eigen's closed-form 3 x 3
            solver (a tenth of the iterative one's instructions), its vectors made exactly orthonormal after it (the
            box fit needs an orthonormal frame, not exact eigenvectors: near a repeated eigenvalue any frame of the
            eigenspace serves). Not finite if the covariance is not. */
        Eigen::Matrix3d principalFrame(const Eigen::Matrix3d &covariance)
        {
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
            solver.computeDirect(covariance);
            // The largest eigenvalue's vector first (the most accurate), the next made orthogonal to it.
            Eigen::Matrix3d axes;
            const Eigen::Vector3d u = solver.eigenvectors().col(2).normalized();
            const Eigen::Vector3d w = solver.eigenvectors().col(1);
            Eigen::Vector3d v = w - w.dot(u) * u;
            if (!(v.squaredNorm() > 1e-12))  // degenerate: any unit vector orthogonal to u
                v = u.unitOrthogonal();
            v.normalize();
            axes.col(0) = v.cross(u);
            axes.col(1) = v;
            axes.col(2) = u;
            return axes;
        }

        /** \brief The box of the triangles order[first, first + count) of \e mesh: the tighter of the axis-aligned
            box and the box along the principal axes of their corners (kept only if clearly smaller, an aligned box
            making cheaper tests), with the bounding sphere about its centre; padded against roundoff. */
        TriangleBvh::Node fitNode(const Mesh &mesh, const std::vector<std::uint32_t> &order, std::uint32_t first,
                                  std::uint32_t count, std::vector<Eigen::Vector3d> &corners)
        {
            corners.clear();
            Eigen::AlignedBox3d box;
            Eigen::Vector3d mean = Eigen::Vector3d::Zero();
            for (std::uint32_t k = first; k < first + count; ++k)
                for (std::uint32_t v : mesh.triangles[order[k]])
                {
                    const Eigen::Vector3d &p = mesh.vertices[v];
                    corners.push_back(p);
                    box.extend(p);
                    mean += p;
                }
            mean /= 3.0 * count;
            TriangleBvh::Node node;
            node.center = box.center();
            node.half = 0.5 * box.sizes();
            // The principal box: along the eigenvectors of the corners' covariance. Kept if clearly smaller (an
            // aligned box makes cheaper tests).
            // Its six distinct entries summed (entry (i, j) adds d_i d_j, the same product as entry (j, i)).
            double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;
            for (const Eigen::Vector3d &p : corners)
            {
                const Eigen::Vector3d d = p - mean;
                xx += d.x() * d.x();
                xy += d.x() * d.y();
                xz += d.x() * d.z();
                yy += d.y() * d.y();
                yz += d.y() * d.z();
                zz += d.z() * d.z();
            }
            Eigen::Matrix3d covariance;
            covariance << xx, xy, xz, xy, yy, yz, xz, yz, zz;
            const Eigen::Matrix3d axes = principalFrame(covariance);
            const Eigen::AlignedBox3d principal = boxAlong(axes, corners.data(), corners.data() + corners.size());
            const Eigen::Vector3d principalHalf = 0.5 * principal.sizes();
            // Volumes of the boxes grown by a thousandth of the aligned box's half diagonal on every side, so that
            // flat boxes (a triangle's, or coplanar ones') compare by their area: a slanted sliver in an axis plane
            // has an aligned box of zero volume too, yet of up to hundreds of times its own area.
            const double grow = 1e-3 * node.half.norm();
            auto measure = [grow](const Eigen::Vector3d &h) { return (h.array() + grow).prod(); };
            if (axes.allFinite() && measure(principalHalf) < 0.8 * measure(node.half))
            {
                node.axes = axes;
                node.aligned = false;
                node.center = axes * principal.center();
                node.half = principalHalf;
            }
            double r2 = 0.0;
            for (const Eigen::Vector3d &p : corners)
                r2 = std::max(r2, (p - node.center).squaredNorm());
            // Rounding slack: bounds must never cut into the geometry they bound (a rotated box's corners are
            // projected with roundoff of a few 1e-16 of the coordinates).
            const double slack = 1e-12 * (node.center.norm() + node.half.norm() + mean.norm());
            node.radius = std::sqrt(r2) + slack;
            node.half.array() += slack;
            return node;
        }

        /** \brief Each triangle of order[first, first + count)'s box and centroid along the (rotated) node's axes,
            into the scratch arrays. */
        void boxesAlong(const Mesh &mesh, const TriangleBvh::Node &node, const std::vector<std::uint32_t> &order,
                        std::uint32_t first, std::uint32_t count, BuildScratch &scratch)
        {
            for (std::uint32_t k = 0; k < count; ++k)
            {
                const std::uint32_t t = order[first + k];
                const Triangle &f = mesh.triangles[t];
                const Eigen::Vector3d corners[3] = {mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]};
                scratch.boxes[k] = boxAlong(node.axes, corners, corners + 3);
                scratch.centre[k] = node.axes.transpose() * scratch.centroid[t];
            }
        }

        /** \brief Half the surface area of \e box: the sum of its sizes' pairwise products, ((x y + y z) + z x). */
        double halfArea(const Eigen::AlignedBox3d &box)
        {
            const Eigen::Vector3d d = box.sizes();
            return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
        }

        /** \brief The surface area heuristic's cuts of sorted[0, count) (\e boxOf: a triangle's box along the
            node's axes): the first k triangles on one side, the rest on the other, cost (side's box area) x (its
            count) summed over both sides. A cut cheaper than \e bestCost replaces \e bestCost and \e bestCut (of
            equal costs, the cut with the most on the left); returns whether one did. A template on \e boxOf, so the
            sweep has no test of the node's kind per triangle. (Growing the boxes in six scalars instead of Eigen's
            two-lane minima and maxima measured 150 M more instructions on a 250k-triangle mesh, and slower.) */
        template <class BoxOf>
        bool sweep(const AxisKey *sorted, std::uint32_t count, const BoxOf &boxOf, BuildScratch &scratch,
                   double &bestCost, std::uint32_t &bestCut)
        {
            double *leftArea = scratch.leftArea.data();
            Eigen::AlignedBox3d left, right;
            for (std::uint32_t k = 0; k < count; ++k)
                leftArea[k] = halfArea(left.extend(boxOf(sorted[k])));
            bool better = false;
            for (std::uint32_t k = count - 1; k >= 1; --k)
            {
                const double cost = leftArea[k - 1] * k + halfArea(right.extend(boxOf(sorted[k]))) * (count - k);
                if (cost < bestCost)
                {
                    bestCost = cost;
                    bestCut = k;
                    better = true;
                }
            }
            return better;
        }

        /** \brief A rotated node's triangles (order[first, first + count), their centroids along the node's axes in
            scratch.centre) in scratch.sorted by AxisKey along \e axis. Large ranges by radixSort() (stable: equal
            centroids stay in range order, then each such run sorted by triangle), small ones by std::sort. */
        void sortAlong(int axis, const std::vector<std::uint32_t> &order, std::uint32_t first, std::uint32_t count,
                       BuildScratch &scratch)
        {
            AxisKey *sorted = scratch.sorted.data();
            if (count < RADIX_FROM)
            {
                for (std::uint32_t k = 0; k < count; ++k)
                    sorted[k] = {scratch.centre[k][axis], order[first + k], k};
                std::sort(sorted, sorted + count);
                return;
            }
            std::uint64_t *keys = scratch.radixKeys.data();
            std::uint32_t *items = scratch.radixItems.data();
            for (std::uint32_t k = 0; k < count; ++k)
            {
                keys[k] = orderedBits(scratch.centre[k][axis]);
                items[k] = k;
            }
            radixSort(keys, items, count, scratch.radixTemp.data(), scratch.radixItemTemp.data());
            for (std::uint32_t j = 0; j < count; ++j)
            {
                const std::uint32_t k = items[j];
                sorted[j] = {scratch.centre[k][axis], order[first + k], k};
            }
            for (std::uint32_t j = 0; j < count;)
            {
                std::uint32_t end = j + 1;
                while (end < count && keys[end] == keys[j])
                    ++end;
                if (end - j > 1)
                    std::sort(sorted + j, sorted + end);
                j = end;
            }
        }

        /** \brief Split the triangles order[first, first + count) in two by the surface area heuristic: along each
            of the node's box axes, the triangles sorted by centroid, the cut that minimises the sum over both
            sides of (surface area of the side's box along the node's axes) x (its triangle count). The triangles
            are reordered, the first side first; returns its size (between 1 and count - 1). Boxes that fit their
            triangles tightly rather than halves of equal counts: on meshes of unequal density (a tube of slivers
            with capped ends, a fine part welded to a coarse one) far fewer box pairs overlap between two trees. */
        std::uint32_t splitBySurfaceArea(const Mesh &mesh, const TriangleBvh::Node &node, std::uint32_t first,
                                         std::uint32_t count, std::vector<std::uint32_t> &order, BuildScratch &scratch)
        {
            if (!node.aligned)
                boxesAlong(mesh, node, order, first, count, scratch);
            double bestCost = std::numeric_limits<double>::infinity();
            std::uint32_t bestCut = count / 2;
            bool haveBest = false;
            for (int axis = 0; axis < 3; ++axis)
            {
                AxisKey *sorted = scratch.sorted.data();
                if (node.aligned)  // already sorted along the body's axes
                    for (std::uint32_t k = 0; k < count; ++k)
                    {
                        const std::uint32_t t = scratch.axisOrder[axis][first + k];
                        sorted[k] = {scratch.centroid[t][axis], t, 0u};
                    }
                else
                    sortAlong(axis, order, first, count, scratch);
                // A triangle's box along the node's axes: an aligned node's is the triangle's own.
                const bool better =
                    node.aligned ? sweep(sorted, count, [&](const AxisKey &key) -> const Eigen::AlignedBox3d &
                                         { return scratch.triangleBox[key.triangle]; }, scratch, bestCost, bestCut)
                                 : sweep(sorted, count, [&](const AxisKey &key) -> const Eigen::AlignedBox3d &
                                         { return scratch.boxes[key.k]; }, scratch, bestCost, bestCut);
                if (better || !haveBest)
                {
                    scratch.bestSorted.swap(scratch.sorted);
                    haveBest = true;
                }
            }
            for (std::uint32_t k = 0; k < count; ++k)
                order[first + k] = scratch.bestSorted[k].triangle;
            return bestCut;
        }

        /** \brief After a split of order[first, first + count) (its first \e half on the left), each axis's sorted
            range partitioned the same way, keeping the sort on both sides. */
        void partitionAxes(const std::vector<std::uint32_t> &order, std::uint32_t first, std::uint32_t count,
                           std::uint32_t half, BuildScratch &scratch)
        {
            for (std::uint32_t k = 0; k < half; ++k)
                scratch.onLeft[order[first + k]] = 1;
            for (int axis = 0; axis < 3; ++axis)
            {
                std::uint32_t *range = scratch.axisOrder[axis].data() + first;
                std::uint32_t left = 0, right = 0;
                for (std::uint32_t k = 0; k < count; ++k)
                {
                    if (scratch.onLeft[range[k]])
                        range[left++] = range[k];
                    else
                        scratch.partitionRight[right++] = range[k];
                }
                std::copy(scratch.partitionRight.begin(), scratch.partitionRight.begin() + right, range + left);
            }
            for (std::uint32_t k = 0; k < half; ++k)
                scratch.onLeft[order[first + k]] = 0;
        }
    }  // namespace

    TriangleBvh::TriangleBvh(const Mesh &mesh) : mesh_(&mesh)
    {
        const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
        order_.resize(n);
        normals_.resize(n);
        for (std::uint32_t t = 0; t < n; ++t)
        {
            order_[t] = t;
            const Triangle &f = mesh.triangles[t];
            const Eigen::Vector3d c =
                (mesh.vertices[f[1]] - mesh.vertices[f[0]]).cross(mesh.vertices[f[2]] - mesh.vertices[f[0]]);
            const double length = c.norm();
            normals_[t] = length > 0.0 ? Eigen::Vector3d(c / length) : Eigen::Vector3d::Zero();  // zero: no bound
        }
        if (n == 0)
            return;
        BuildScratch scratch(mesh);
        nodes_.reserve(2 * n / LEAF_SIZE + 2);
        // Build top-down; each stack entry is (node index, first, count).
        struct Work
        {
            std::uint32_t node, first, count;
        };
        nodes_.push_back(Node());
        std::vector<Work> stack{{0u, 0u, n}};
        while (!stack.empty())
        {
            const Work w = stack.back();
            stack.pop_back();
            Node node = fitNode(mesh, order_, w.first, w.count, scratch.corners);
            if (w.count <= LEAF_SIZE)
            {
                node.first = w.first;
                node.count = w.count;
                nodes_[w.node] = node;
                continue;
            }
            const std::uint32_t half = splitBySurfaceArea(mesh, node, w.first, w.count, order_, scratch);
            partitionAxes(order_, w.first, w.count, half, scratch);
            const auto left = static_cast<std::uint32_t>(nodes_.size());
            nodes_.push_back(Node());
            nodes_.push_back(Node());
            node.first = left;
            node.count = 0;
            nodes_[w.node] = node;
            stack.push_back({left, w.first, half});
            stack.push_back({left + 1, w.first + half, w.count - half});
        }
    }
}  // namespace meshgap
