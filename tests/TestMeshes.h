#ifndef MESHGAP_TESTS_TEST_MESHES_H
#define MESHGAP_TESTS_TEST_MESHES_H

// Small meshes with known geometry, built in code (as libigl's tests use cube.off): every expected answer in the
// tests comes from analytic geometry or a brute-force oracle, never from meshgap itself.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>

#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    namespace test
    {
        /** \brief Closed surface of the box [-hx,hx]x[-hy,hy]x[-hz,hz], each face an n x n grid of squares (two
            triangles each), vertices shared along the box edges: 6n^2+2 nodes, 12n^2 triangles. */
        inline Mesh box(double hx, double hy, double hz, int n = 1)
        {
            Mesh m;
            m.source = "test::box";
            std::map<std::tuple<long, long, long>, std::uint32_t> index;  // integer lattice key -> node
            auto node = [&](long i, long j, long k) {
                auto it = index.find({i, j, k});
                if (it != index.end())
                    return it->second;
                const auto id = static_cast<std::uint32_t>(m.vertices.size());
                m.vertices.emplace_back(hx * (2.0 * i / n - 1.0), hy * (2.0 * j / n - 1.0), hz * (2.0 * k / n - 1.0));
                index.emplace(std::make_tuple(i, j, k), id);
                return id;
            };
            // For each of the 6 faces: axis a fixed at 0 or n, the other two (b, c) run over the grid.
            for (int a = 0; a < 3; ++a)
                for (int side = 0; side < 2; ++side)
                {
                    const int b = (a + 1) % 3, c = (a + 2) % 3;
                    for (long s = 0; s < n; ++s)
                        for (long t = 0; t < n; ++t)
                        {
                            auto at = [&](long u, long v) {
                                long ijk[3];
                                ijk[a] = side ? n : 0;
                                ijk[b] = u;
                                ijk[c] = v;
                                return node(ijk[0], ijk[1], ijk[2]);
                            };
                            const std::uint32_t p00 = at(s, t), p10 = at(s + 1, t), p11 = at(s + 1, t + 1),
                                                p01 = at(s, t + 1);
                            if (side)  // outward winding
                            {
                                m.triangles.push_back({p00, p10, p11});
                                m.triangles.push_back({p00, p11, p01});
                            }
                            else
                            {
                                m.triangles.push_back({p00, p11, p10});
                                m.triangles.push_back({p00, p01, p11});
                            }
                        }
                }
            return m;
        }

        /** \brief Icosphere of radius r: an icosahedron subdivided \e level times, nodes pushed onto the sphere. */
        inline Mesh icosphere(double r, int level)
        {
            Mesh m;
            m.source = "test::icosphere";
            const double t = (1.0 + std::sqrt(5.0)) / 2.0;
            const double raw[12][3] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},   {-t, 0, -1}, {-t, 0, 1}};
            for (const auto &p : raw)
                m.vertices.push_back(Eigen::Vector3d(p[0], p[1], p[2]).normalized() * r);
            m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                           {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                           {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
            for (int l = 0; l < level; ++l)
            {
                std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
                auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
                    const auto key = std::minmax(a, b);
                    auto it = mid.find(key);
                    if (it != mid.end())
                        return it->second;
                    const auto id = static_cast<std::uint32_t>(m.vertices.size());
                    m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized() * r);
                    mid.emplace(key, id);
                    return id;
                };
                std::vector<Triangle> next;
                for (const Triangle &f : m.triangles)
                {
                    const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
                    next.push_back({f[0], ab, ca});
                    next.push_back({f[1], bc, ab});
                    next.push_back({f[2], ca, bc});
                    next.push_back({ab, bc, ca});
                }
                m.triangles.swap(next);
            }
            return m;
        }

        /** \brief Flat (open) grid in the z = 0 plane over [0,w]x[0,h], nx x ny squares split into triangles. */
        inline Mesh grid(double w, double h, int nx, int ny)
        {
            Mesh m;
            m.source = "test::grid";
            for (int j = 0; j <= ny; ++j)
                for (int i = 0; i <= nx; ++i)
                    m.vertices.emplace_back(w * i / nx, h * j / ny, 0.0);
            auto id = [nx](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i)
                {
                    m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                    m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
                }
            return m;
        }

        /** \brief Move every vertex by \e X. */
        inline Mesh transformed(Mesh m, const Eigen::Isometry3d &X)
        {
            for (Eigen::Vector3d &v : m.vertices)
                v = X * v;
            return m;
        }

        /** \brief Two meshes as one (a body with two connected components). */
        inline Mesh merged(const Mesh &a, const Mesh &b)
        {
            Mesh m = a;
            const auto offset = static_cast<std::uint32_t>(a.vertices.size());
            m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
            for (Triangle t : b.triangles)
            {
                for (std::uint32_t &i : t)
                    i += offset;
                m.triangles.push_back(t);
            }
            return m;
        }

        /** \brief A pure translation. */
        inline Eigen::Isometry3d translation(double x, double y, double z)
        {
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.translation() = Eigen::Vector3d(x, y, z);
            return X;
        }

        /** \brief A concave body of three overlapping closed shells (a U): winding number 2 where they overlap. */
        inline Mesh uShape()
        {
            Mesh m = merged(transformed(box(1.5, 0.2, 0.5, 3), translation(0, -1.0, 0)),
                            transformed(box(0.2, 1.0, 0.5, 3), translation(-1.3, 0, 0)));
            return merged(m, transformed(box(0.2, 1.0, 0.5, 3), translation(1.3, 0, 0)));
        }

        /** \brief A body of the test mesh as it is (no refinement: gridSize 0). */
        inline BodyPtr unrefinedBody(const Mesh &m)
        {
            BodyOptions options;
            options.gridSize = 0;
            return Body::build(m, options);
        }

        /** \brief A random rigid pose: uniform rotation, translation uniform in a cube of half-side \e radius. */
        inline Eigen::Isometry3d randomPose(std::uint32_t seed, double radius)
        {
            std::mt19937 rng(seed);
            std::normal_distribution<double> gauss;
            std::uniform_real_distribution<double> uni(-radius, radius);
            Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
            q.normalize();
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q.toRotationMatrix();
            X.translation() = Eigen::Vector3d(uni(rng), uni(rng), uni(rng));
            return X;
        }

        /** \brief Total area of the mesh's triangles. */
        inline double area(const Mesh &m)
        {
            double s = 0.0;
            for (const Triangle &t : m.triangles)
                s += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
            return s;
        }

        /** \brief Every undirected edge and the number of triangles using it. */
        inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse(const Mesh &m)
        {
            std::map<std::pair<std::uint32_t, std::uint32_t>, int> use;
            for (const Triangle &t : m.triangles)
                for (int k = 0; k < 3; ++k)
                    ++use[std::minmax(t[k], t[(k + 1) % 3])];
            return use;
        }

        /** \brief The smallest corner angle of any triangle (radians). */
        inline double minimumAngle(const Mesh &m)
        {
            double least = M_PI;
            for (const Triangle &t : m.triangles)
                for (int k = 0; k < 3; ++k)
                {
                    const Eigen::Vector3d u = m.vertices[t[(k + 1) % 3]] - m.vertices[t[k]];
                    const Eigen::Vector3d w = m.vertices[t[(k + 2) % 3]] - m.vertices[t[k]];
                    least = std::min(least, std::acos(u.normalized().dot(w.normalized())));
                }
            return least;
        }
    }  // namespace test
}  // namespace meshgap

#endif
