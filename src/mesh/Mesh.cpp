#include "meshgap/mesh/Mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <numeric>

#include "meshgap/Exception.h"
#include "meshgap/FlatIndexSet.h"
#include "meshgap/Limits.h"

namespace meshgap
{
    void detail::throwBadVertex(const std::string &where, std::size_t index, const Eigen::Vector3d &p)
    {
        std::string problem = "has a NaN or infinite coordinate";
        for (int k = 0; k < 3 && p.allFinite(); ++k)
            if (std::abs(p[k]) > MAX_MAGNITUDE)
            {
                char value[32];  // the shortest decimal that reads back as the coordinate
                const std::to_chars_result written = std::to_chars(value, value + sizeof value, p[k]);
                problem = std::string("has ") + "xyz"[k] + " = " + std::string(value, written.ptr) +
                          ", beyond 1e12 in magnitude, the largest meshgap's geometry answers reliably";
                break;
            }
        throw Exception(where, "vertex " + std::to_string(index) + " " + problem);
    }

    Eigen::AlignedBox3d Mesh::bounds() const
    {
        Eigen::AlignedBox3d box;
        for (const Eigen::Vector3d &v : vertices)
            box.extend(v);
        return box;
    }

    double Mesh::size() const
    {
        const Eigen::AlignedBox3d box = bounds();
        return box.isEmpty() ? 0.0 : box.diagonal().norm();
    }

    void Mesh::validate() const
    {
        const std::string where = source.empty() ? std::string("mesh") : source;
        if (triangles.empty())
            throw Exception(where, "no triangles (an empty scene, a point cloud or only lines?)");
        for (std::size_t i = 0; i < vertices.size(); ++i)
            checkVertex(where, i, vertices[i]);
        for (std::size_t t = 0; t < triangles.size(); ++t)
            for (std::uint32_t index : triangles[t])
                if (index >= vertices.size())
                    throw Exception(where, "triangle " + std::to_string(t) + " uses vertex index " +
                                               std::to_string(index) + " but there are only " +
                                               std::to_string(vertices.size()) + " vertices");
    }

    namespace
    {
        /** \brief The bits of a coordinate as welding compares it: -0 as +0 (the two are equal under ==). */
        std::uint64_t weldBits(double c)
        {
            c = c == 0.0 ? 0.0 : c;
            std::uint64_t bits;
            std::memcpy(&bits, &c, sizeof bits);
            return bits;
        }

        /** \brief SplitMix64's finaliser: every input bit moves every output bit. */
        std::uint64_t mixBits(std::uint64_t h)
        {
            h ^= h >> 30;
            h *= 0xbf58476d1ce4e5b9ull;
            h ^= h >> 27;
            h *= 0x94d049bb133111ebull;
            return h ^ (h >> 31);
        }

        /** \brief Equal positions (==, so -0 as +0) hash equal. */
        std::uint64_t positionHash(const Eigen::Vector3d &p)
        {
            return mixBits(mixBits(mixBits(weldBits(p.x())) ^ weldBits(p.y())) ^ weldBits(p.z()));
        }

        /** \brief Keyed by a triangle's sorted indices. */
        std::uint64_t triangleHash(const Triangle &key)
        {
            return mixBits(((std::uint64_t(key[0]) << 32) | key[1]) ^ mixBits(key[2]));
        }

        bool isDegenerate(const Mesh &mesh, const Triangle &t)
        {
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
                return true;
            const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
            const Eigen::Vector3d e0 = b - a, e1 = c - a, e2 = c - b;
            const double longest2 = std::max({e0.squaredNorm(), e1.squaredNorm(), e2.squaredNorm()});
            // Relative test: twice the area against the longest edge squared (1e-12: collinear within rounding).
            return e0.cross(e1).norm() <= 1e-12 * longest2;
        }
    }  // namespace

    CleanReport cleanMesh(Mesh &mesh)
    {
        CleanReport report;
        // 1. Weld identical positions (compared with ==, as the hash keys -0 as +0): each vertex to the first
        // vertex at its position.
        const std::vector<Eigen::Vector3d> &vertices = mesh.vertices;
        std::vector<std::uint32_t> weldTo(vertices.size());
        {
            FlatIndexSet firstAt(vertices.size() / 4);  // a flat-shaded file repeats a position about 6 times
            for (std::size_t i = 0; i < vertices.size(); ++i)
            {
                const Eigen::Vector3d &p = vertices[i];
                weldTo[i] = firstAt.findOrInsert(positionHash(p), static_cast<std::uint32_t>(i),
                                                 [&](std::uint32_t j) { return vertices[j] == p; });
            }
        }
        for (Triangle &t : mesh.triangles)
            for (std::uint32_t &index : t)
                index = weldTo[index];

        // 2. Drop degenerate and duplicated triangles (same vertex set, either winding).
        std::vector<Triangle> kept, keys;  // kept triangles, and each one's sorted indices
        kept.reserve(mesh.triangles.size());
        keys.reserve(mesh.triangles.size());
        {
            FlatIndexSet seen(mesh.triangles.size());
            for (const Triangle &t : mesh.triangles)
            {
                if (isDegenerate(mesh, t))
                {
                    ++report.degenerate;
                    continue;
                }
                Triangle key = t;
                std::sort(key.begin(), key.end());
                const auto next = static_cast<std::uint32_t>(keys.size());
                if (seen.findOrInsert(triangleHash(key), next, [&](std::uint32_t j) { return keys[j] == key; }) !=
                    next)
                {
                    ++report.duplicates;
                    continue;
                }
                keys.push_back(key);
                kept.push_back(t);
            }
        }
        mesh.triangles.swap(kept);

        // 3. Compact: keep used vertices, in their original order.
        std::vector<std::uint32_t> newIndex(mesh.vertices.size(), UINT32_MAX);
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t index : t)
                newIndex[index] = 0;
        std::vector<Eigen::Vector3d> used;
        used.reserve(mesh.vertices.size());
        for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
            if (newIndex[i] == 0)
            {
                newIndex[i] = static_cast<std::uint32_t>(used.size());
                used.push_back(mesh.vertices[i]);
            }
        report.unused = mesh.vertices.size() - used.size();
        // Welded-away copies are not "unused" vertices of the input: count only those no triangle referenced.
        std::size_t welded = 0;
        for (std::size_t i = 0; i < weldTo.size(); ++i)
            welded += weldTo[i] != i;
        report.unused -= std::min(report.unused, welded);
        mesh.vertices.swap(used);
        for (Triangle &t : mesh.triangles)
            for (std::uint32_t &index : t)
                index = newIndex[index];
        return report;
    }

    EdgeReport countEdges(const Mesh &mesh)
    {
        // Each undirected edge filed under its smaller vertex (a counting sort, O(n)), then each vertex's short row
        // of larger ends sorted: equal edges are then adjacent.
        std::uint32_t rows = 0;
        for (const Triangle &f : mesh.triangles)
            rows = std::max({rows, f[0] + 1, f[1] + 1, f[2] + 1});
        std::vector<std::uint32_t> offsets(std::size_t(rows) + 1, 0);
        for (const Triangle &f : mesh.triangles)
            for (int k = 0; k < 3; ++k)
                ++offsets[std::min(f[k], f[(k + 1) % 3]) + 1];
        for (std::uint32_t v = 0; v < rows; ++v)
            offsets[v + 1] += offsets[v];
        std::vector<std::uint32_t> ends(offsets.back()), fill(offsets.begin(), offsets.end() - 1);
        for (const Triangle &f : mesh.triangles)
            for (int k = 0; k < 3; ++k)
            {
                const auto [lo, hi] = std::minmax(f[k], f[(k + 1) % 3]);
                ends[fill[lo]++] = hi;
            }
        EdgeReport report;
        for (std::uint32_t v = 0; v < rows; ++v)
        {
            const auto begin = ends.begin() + offsets[v], end = ends.begin() + offsets[v + 1];
            std::sort(begin, end);
            for (auto i = begin; i != end;)
            {
                auto j = i + 1;
                while (j != end && *j == *i)
                    ++j;
                report.boundaryEdges += j - i == 1;
                report.nonManifoldEdges += j - i >= 3;
                i = j;
            }
        }
        return report;
    }

    std::vector<std::uint32_t> labelComponents(const Mesh &mesh, std::uint32_t &count)
    {
        // Union-find over the vertices, joined along triangle edges.
        const auto n = static_cast<std::uint32_t>(mesh.vertices.size());
        std::vector<std::uint32_t> parent(n);
        std::iota(parent.begin(), parent.end(), 0u);
        auto find = [&parent](std::uint32_t x)
        {
            while (parent[x] != x)
                x = parent[x] = parent[parent[x]];
            return x;
        };
        for (const Triangle &t : mesh.triangles)
            for (int k = 0; k < 2; ++k)
            {
                const std::uint32_t a = find(t[k]), b = find(t[k + 1]);
                if (a != b)
                    parent[a] = b;
            }
        // Renumbered in order of first vertex.
        std::vector<std::uint32_t> label(n), labelOfRoot(n, UINT32_MAX);
        count = 0;
        for (std::uint32_t v = 0; v < n; ++v)
        {
            std::uint32_t &l = labelOfRoot[find(v)];
            if (l == UINT32_MAX)
                l = count++;
            label[v] = l;
        }
        return label;
    }

    std::size_t countComponents(const Mesh &mesh)
    {
        std::uint32_t count = 0;
        labelComponents(mesh, count);
        return count;
    }

    double longestEdge(const Mesh &mesh)
    {
        double longest2 = 0.0;
        for (const Triangle &t : mesh.triangles)
            for (int k = 0; k < 3; ++k)
                longest2 = std::max(longest2, (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).squaredNorm());
        return std::sqrt(longest2);
    }
}  // namespace meshgap
