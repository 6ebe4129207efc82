#include "meshgap/robot/Primitives.h"

#include <cmath>
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

    Mesh cylinderMesh(double radius, double length, unsigned int segments)
    {
        checkLength("cylinder", "radius", radius);
        checkLength("cylinder", "length", length);
        if (segments < 3)
            throw Exception("cylinder", std::to_string(segments) + " segments (at least 3)");
        Mesh mesh;
        mesh.source = "cylinder";
        const double z = length / 2.0;
        for (unsigned int i = 0; i < segments; ++i)
        {
            const double a = 2.0 * M_PI * i / segments;
            mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), -z);  // 2 i: bottom
            mesh.vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z);   // 2 i + 1: top
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
        if (segments < 4)
            throw Exception("sphere", std::to_string(segments) + " segments (at least 4)");
        const unsigned int bands = segments / 2;
        Mesh mesh;
        mesh.source = "sphere";
        mesh.vertices.emplace_back(0.0, 0.0, -radius);  // 0: south pole
        for (unsigned int b = 1; b < bands; ++b)        // rings 1 .. bands - 1, from south to north
        {
            const double polar = M_PI * (1.0 - static_cast<double>(b) / bands);
            for (unsigned int i = 0; i < segments; ++i)
            {
                const double a = 2.0 * M_PI * i / segments;
                mesh.vertices.emplace_back(radius * std::sin(polar) * std::cos(a),
                                           radius * std::sin(polar) * std::sin(a), radius * std::cos(polar));
            }
        }
        const auto north = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.emplace_back(0.0, 0.0, radius);
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
        return mesh;
    }
}  // namespace meshgap
