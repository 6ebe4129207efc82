#include "support/MeshWriter.h"

#include <assimp/Exporter.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"

namespace meshgap
{
    void writeObj(const Mesh &mesh, const std::string &path)
    {
        for (const Triangle &t : mesh.triangles)
            for (std::uint32_t i : t)
                if (i >= mesh.vertices.size())
                    throw Exception(path, "cannot write a triangle that uses vertex " + std::to_string(i) +
                                              " of " + std::to_string(mesh.vertices.size()));
        writeAtomically(path,
                        [&](const std::string &temporary)
                        {
                            errno = 0;
                            std::unique_ptr<std::FILE, int (*)(std::FILE *)> file(std::fopen(temporary.c_str(), "w"),
                                                                                  &std::fclose);
                            const auto reason = [] { return errno != 0 ? std::string(": ") + std::strerror(errno) : ""; };
                            if (!file)
                                throw Exception(path, "cannot open for writing" + reason());
                            bool ok = std::fprintf(file.get(), "# %s: %zu vertices, %zu triangles (written by meshgap)\n",
                                                   mesh.source.empty() ? "mesh" : mesh.source.c_str(),
                                                   mesh.vertices.size(), mesh.triangles.size()) > 0;
                            for (const Eigen::Vector3d &v : mesh.vertices)
                                ok = ok && std::fprintf(file.get(), "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z()) > 0;
                            for (const Triangle &t : mesh.triangles)
                                ok = ok && std::fprintf(file.get(), "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1) > 0;
                            ok = ok && std::fflush(file.get()) == 0;
                            if (std::fclose(file.release()) != 0 || !ok)
                                throw Exception(path, "write failed" + reason());
                        });
    }

    namespace
    {
        void checkPart(const ColoredMesh &part, const std::string &path)
        {
            const Mesh &mesh = part.mesh;
            for (const Eigen::Vector3d &v : mesh.vertices)
                if (!v.allFinite())
                    throw Exception(path, "cannot write part " + quote(part.name) + ": a coordinate is not finite");
            for (const Triangle &t : mesh.triangles)
                for (std::uint32_t i : t)
                    if (i >= mesh.vertices.size())
                        throw Exception(path, "cannot write part " + quote(part.name) + ": a triangle uses vertex " +
                                                  std::to_string(i) + " of " + std::to_string(mesh.vertices.size()));
        }

        /** \brief One (checked) part as an assimp mesh (owned by the scene it is put in). */
        aiMesh *toAssimpMesh(const ColoredMesh &part, unsigned int material)
        {
            const Mesh &mesh = part.mesh;
            auto out = std::make_unique<aiMesh>();
            out->mName = part.name;
            out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
            out->mMaterialIndex = material;
            out->mNumVertices = static_cast<unsigned int>(mesh.vertices.size());
            out->mVertices = new aiVector3D[mesh.vertices.size()];
            for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
                out->mVertices[i] = aiVector3D(static_cast<ai_real>(mesh.vertices[i].x()),
                                               static_cast<ai_real>(mesh.vertices[i].y()),
                                               static_cast<ai_real>(mesh.vertices[i].z()));
            out->mNumFaces = static_cast<unsigned int>(mesh.triangles.size());
            out->mFaces = new aiFace[mesh.triangles.size()];
            for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
            {
                out->mFaces[f].mNumIndices = 3;
                out->mFaces[f].mIndices = new unsigned int[3];
                for (int k = 0; k < 3; ++k)
                    out->mFaces[f].mIndices[k] = mesh.triangles[f][k];
            }
            return out.release();
        }

        aiMaterial *toAssimpMaterial(const ColoredMesh &part)
        {
            auto material = std::make_unique<aiMaterial>();
            const aiString name(part.name);
            material->AddProperty(&name, AI_MATKEY_NAME);
            const aiColor4D color(static_cast<ai_real>(part.color[0]), static_cast<ai_real>(part.color[1]),
                                  static_cast<ai_real>(part.color[2]), static_cast<ai_real>(part.color[3]));
            material->AddProperty(&color, 1, AI_MATKEY_BASE_COLOR);
            material->AddProperty(&color, 1, AI_MATKEY_COLOR_DIFFUSE);
            const ai_real opacity = color.a;
            material->AddProperty(&opacity, 1, AI_MATKEY_OPACITY);
            return material.release();
        }
    }  // namespace

    void writeGlb(const std::vector<ColoredMesh> &parts, const std::string &path)
    {
        std::vector<const ColoredMesh *> kept;
        for (const ColoredMesh &part : parts)
            if (!part.mesh.triangles.empty())
            {
                checkPart(part, path);  // every check before anything is allocated for assimp
                kept.push_back(&part);
            }
        if (kept.empty())
            throw Exception(path, "nothing to write: no part has triangles");
        // aiScene's destructor frees its meshes, materials and nodes (counted ones: counts follow the arrays).
        aiScene scene;
        scene.mRootNode = new aiNode("meshgap");
        scene.mMeshes = new aiMesh *[kept.size()]();
        scene.mMaterials = new aiMaterial *[kept.size()]();
        scene.mRootNode->mChildren = new aiNode *[kept.size()]();
        for (std::size_t i = 0; i < kept.size(); ++i)
        {
            const auto index = static_cast<unsigned int>(i);
            scene.mMeshes[i] = toAssimpMesh(*kept[i], index);
            ++scene.mNumMeshes;
            scene.mMaterials[i] = toAssimpMaterial(*kept[i]);
            ++scene.mNumMaterials;
            aiNode *node = new aiNode(kept[i]->name);
            node->mParent = scene.mRootNode;
            node->mNumMeshes = 1;
            node->mMeshes = new unsigned int[1]{index};
            scene.mRootNode->mChildren[i] = node;
            ++scene.mRootNode->mNumChildren;
        }
        writeAtomically(path,
                        [&](const std::string &temporary)
                        {
                            Assimp::Exporter exporter;
                            if (exporter.Export(&scene, "glb2", temporary) != aiReturn_SUCCESS)
                                throw Exception(path, std::string("glTF export failed: ") + exporter.GetErrorString());
                        });
    }
}  // namespace meshgap
