#include "meshgap/robot/Primitives.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        void checkLength(const char *what, const char *name, double value)
        {
            if (!(value > 0.0) || !std::isfinite(value))
                throw Exception(what, std::string(name) + " " + std::to_string(value) + " is not positive and finite");
        }
    }  // namespace

    Mesh boxMesh(const Eigen::Vector3d &size)
    {
        for (int k = 0; k < 3; ++k)
            checkLength("box", "size", size[k]);
        Mesh mesh;
        mesh.source = "box";
        const Eigen::Vector3d h = size / 2.0;
        for (int i = 0; i < 8; ++i)  // corner i: bit 0 for x, bit 1 for y, bit 2 for z (set: the + side)
            mesh.vertices.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
        // Each face as a quad, counter-clockwise seen from outside.
        const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto &q : quads)
        {
            mesh.triangles.push_back({q[0], q[1], q[2]});
            mesh.triangles.push_back({q[0], q[2], q[3]});
        }
        return mesh;
    }

    namespace
    {
        void checkSegments(const char *what, unsigned int segments, unsigned int least)
        {
            if (segments < least)
                throw Exception(what, std::to_string(segments) + " segments (at least " + std::to_string(least) + ")");
        }

        /** \brief The latitude-longitude mesh of the unit sphere (every vertex on it), and the least distance from
            the centre to a face's plane (below 1: the mesh is inscribed). */
        Mesh unitSphere(unsigned int segments, double &nearestPlane)
        {
            const unsigned int bands = segments / 2;
            Mesh mesh;
            mesh.source = "sphere";
            mesh.vertices.emplace_back(0.0, 0.0, -1.0);  // 0: south pole
            for (unsigned int b = 1; b < bands; ++b)    // rings 1 .. bands - 1, from south to north
            {
                const double polar = M_PI * (1.0 - static_cast<double>(b) / bands);
                for (unsigned int i = 0; i < segments; ++i)
                {
                    const double a = 2.0 * M_PI * i / segments;
                    mesh.vertices.emplace_back(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a),
                                               std::cos(polar));
                }
            }
            const auto north = static_cast<std::uint32_t>(mesh.vertices.size());
            mesh.vertices.emplace_back(0.0, 0.0, 1.0);
            auto ring = [&](unsigned int b, unsigned int i) { return 1 + (b - 1) * segments + i % segments; };
            for (unsigned int i = 0; i < segments; ++i)
            {
                mesh.triangles.push_back({0, ring(1, i + 1), ring(1, i)});
                mesh.triangles.push_back({north, ring(bands - 1, i), ring(bands - 1, i + 1)});
                for (unsigned int b = 1; b + 1 < bands; ++b)
                {
                    mesh.triangles.push_back({ring(b, i), ring(b, i + 1), ring(b + 1, i + 1)});
                    mesh.triangles.push_back({ring(b, i), ring(b + 1, i + 1), ring(b + 1, i)});
                }
            }
            nearestPlane = 1.0;
            for (const Triangle &t : mesh.triangles)
            {
                const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
                nearestPlane = std::min(nearestPlane, (b - a).cross(c - a).normalized().dot(a));
            }
            return mesh;
        }

        /** \brief A regular \e segments-gon circumscribed about the circle of \e radius: its corners' distance from
            the centre (rounded outward). */
        double circumradius(double radius, unsigned int segments)
        {
            return radius / std::cos(M_PI / segments) * (1.0 + 4.0 * std::numeric_limits<double>::epsilon());
        }
    }  // namespace

    Mesh cylinderMesh(double radius, double length, unsigned int segments)
    {
        checkLength("cylinder", "radius", radius);
        checkLength("cylinder", "length", length);
        checkSegments("cylinder", segments, 3);
        Mesh mesh;
        mesh.source = "cylinder";
        const double z = length / 2.0, r = circumradius(radius, segments);
        for (unsigned int i = 0; i < segments; ++i)
        {
            const double a = 2.0 * M_PI * i / segments;
            mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), -z);  // 2 i: bottom
            mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);   // 2 i + 1: top
        }
        const std::uint32_t bottom = 2 * segments, top = bottom + 1;
        mesh.vertices.emplace_back(0.0, 0.0, -z);
        mesh.vertices.emplace_back(0.0, 0.0, z);
        for (std::uint32_t i = 0; i < segments; ++i)
        {
            const std::uint32_t j = (i + 1) % segments;
            mesh.triangles.push_back({2 * i, 2 * j, 2 * j + 1});
            mesh.triangles.push_back({2 * i, 2 * j + 1, 2 * i + 1});
            mesh.triangles.push_back({bottom, 2 * j, 2 * i});
            mesh.triangles.push_back({top, 2 * i + 1, 2 * j + 1});
        }
        return mesh;
    }

    Mesh sphereMesh(double radius, unsigned int segments)
    {
        checkLength("sphere", "radius", radius);
        checkSegments("sphere", segments, 4);
        double nearest;
        Mesh mesh = unitSphere(segments, nearest);
        // Every face's plane at least radius from the centre (rounded outward): the convex mesh holds the ball.
        const double scale = radius / nearest * (1.0 + 4.0 * std::numeric_limits<double>::epsilon());
        for (Eigen::Vector3d &v : mesh.vertices)
            v *= scale;
        return mesh;
    }

    double sphereExcess(double radius, unsigned int segments)
    {
        checkLength("sphere", "radius", radius);
        checkSegments("sphere", segments, 4);
        double nearest;
        unitSphere(segments, nearest);
        return radius / nearest * (1.0 + 4.0 * std::numeric_limits<double>::epsilon()) - radius;
    }

    Mesh coneMesh(double radius, double length, unsigned int segments)
    {
        checkLength("cone", "radius", radius);
        checkLength("cone", "length", length);
        checkSegments("cone", segments, 3);
        Mesh mesh;
        mesh.source = "cone";
        const double z = length / 2.0, r = circumradius(radius, segments);
        for (unsigned int i = 0; i < segments; ++i)
        {
            const double a = 2.0 * M_PI * i / segments;
            mesh.vertices.emplace_back(r * std::cos(a), r * std::sin(a), -z);  // i: the base's corners
        }
        const std::uint32_t base = segments, apex = segments + 1;
        mesh.vertices.emplace_back(0.0, 0.0, -z);
        mesh.vertices.emplace_back(0.0, 0.0, z);
        for (std::uint32_t i = 0; i < segments; ++i)
        {
            const std::uint32_t j = (i + 1) % segments;
            mesh.triangles.push_back({i, j, apex});
            mesh.triangles.push_back({base, j, i});
        }
        return mesh;
    }
}  // namespace meshgap
