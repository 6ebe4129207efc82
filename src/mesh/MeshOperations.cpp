#include "meshgap/mesh/MeshOperations.h"

#include <string>

#include "meshgap/Exception.h"

namespace meshgap
{
    double signedVolume(const Mesh &mesh)
    {
        double v = 0.0;
        for (const Triangle &t : mesh.triangles)
            v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
        return v / 6.0;
    }

    Mesh mergeMeshes(const std::vector<Mesh> &parts, const std::string &name)
    {
        Mesh m;
        m.source = name;
        for (const Mesh &part : parts)
        {
            const auto offset = static_cast<std::uint32_t>(m.vertices.size());
            m.vertices.insert(m.vertices.end(), part.vertices.begin(), part.vertices.end());
            for (Triangle t : part.triangles)
            {
                for (std::uint32_t &i : t)
                    i += offset;
                m.triangles.push_back(t);
            }
        }
        return m;
    }

    void transformMesh(Mesh &mesh, const Eigen::Isometry3d &X)
    {
        for (Eigen::Vector3d &p : mesh.vertices)
            p = X * p;
    }

    Eigen::Vector3d vertexMean(const Mesh &mesh)
    {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (const Eigen::Vector3d &p : mesh.vertices)
            sum += p;
        return mesh.vertices.empty() ? sum : Eigen::Vector3d(sum / static_cast<double>(mesh.vertices.size()));
    }

    std::vector<Mesh> splitComponents(const Mesh &mesh)
    {
        const std::size_t n = mesh.vertices.size();
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t v : t)
                if (v >= n)
                    throw Exception(mesh.source, "triangle index " + std::to_string(v) + " out of range (" +
                                                     std::to_string(n) + " vertices)");
        std::uint32_t numLabels = 0;
        const std::vector<std::uint32_t> label = labelComponents(mesh, numLabels);

        // Parts numbered in order of first triangle; a label no triangle uses (an unused vertex) gets no part.
        std::vector<std::uint32_t> partOfLabel(numLabels, UINT32_MAX);
        std::uint32_t numParts = 0;
        for (const Triangle &t : mesh.triangles)
            if (partOfLabel[label[t[0]]] == UINT32_MAX)
                partOfLabel[label[t[0]]] = numParts++;
        std::vector<Mesh> parts(numParts);
        for (std::uint32_t p = 0; p < numParts; ++p)
            parts[p].source = numParts == 1 ? mesh.source : mesh.source + "#" + std::to_string(p);
        // Each part's vertices in their original order; vertices no triangle uses are dropped.
        std::vector<std::uint32_t> local(n, UINT32_MAX);
        for (std::uint32_t v = 0; v < n; ++v)
        {
            const std::uint32_t p = partOfLabel[label[v]];
            if (p == UINT32_MAX)
                continue;
            local[v] = static_cast<std::uint32_t>(parts[p].vertices.size());
            parts[p].vertices.push_back(mesh.vertices[v]);
        }
        for (const Triangle &f : mesh.triangles)
            parts[partOfLabel[label[f[0]]]].triangles.push_back({local[f[0]], local[f[1]], local[f[2]]});
        return parts;
    }
}  // namespace meshgap
