// FCL's load and build of mesh files as OMPL.app's FCL checker does it, for the load-and-build comparison of
// meshgap_bench_queries: assimp with OMPL.app's post-processing, every node transform applied, every three-index face
// as three points of its own (OMPL.app's getGeometryTriangles), then one BVHModel<OBBRSS> over all the files.
#ifndef MESHGAP_BENCH_FCL_LOAD_H
#define MESHGAP_BENCH_FCL_LOAD_H

#ifdef MESHGAP_HAVE_FCL
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcl/fcl.h>
#include <memory>
#include <string>
#include <vector>

#include "meshgap/Exception.h"

namespace meshgap::bench
{
    namespace detail
    {
        inline void collectTriangles(const aiScene *scene, const aiNode *node, aiMatrix4x4 transform,
                                     std::vector<fcl::Vector3d> &points)
        {
            transform *= node->mTransformation;
            for (unsigned int i = 0; i < node->mNumMeshes; ++i)
            {
                const aiMesh *m = scene->mMeshes[node->mMeshes[i]];
                for (unsigned int f = 0; f < m->mNumFaces; ++f)
                {
                    const aiFace &face = m->mFaces[f];
                    if (face.mNumIndices != 3)
                        continue;
                    for (int c = 0; c < 3; ++c)
                    {
                        const aiVector3D p = transform * m->mVertices[face.mIndices[c]];
                        points.emplace_back(p.x, p.y, p.z);
                    }
                }
            }
            for (unsigned int i = 0; i < node->mNumChildren; ++i)
                collectTriangles(scene, node->mChildren[i], transform, points);
        }
    }  // namespace detail

    /** \brief Every triangle of the files as assimp reads them with OMPL.app's flags, three points each; throws
        meshgap::Exception naming a file assimp cannot read. */
    inline std::vector<fcl::Vector3d> fclReadTriangles(const std::vector<std::string> &files)
    {
        std::vector<fcl::Vector3d> points;
        for (const std::string &file : files)
        {
            Assimp::Importer importer;
            const aiScene *scene =
                importer.ReadFile(file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                            aiProcess_SortByPType | aiProcess_OptimizeGraph | aiProcess_OptimizeMeshes);
            if (scene == nullptr || scene->mRootNode == nullptr)
                throw Exception(file, std::string("assimp cannot read it: ") + importer.GetErrorString());
            detail::collectTriangles(scene, scene->mRootNode, aiMatrix4x4(), points);
        }
        return points;
    }

    /** \brief One FCL BVHModel<OBBRSS> over \e points, three per triangle (OMPL.app's FCL checker's model). */
    inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclBuild(const std::vector<fcl::Vector3d> &points)
    {
        std::vector<fcl::Triangle> triangles;
        triangles.reserve(points.size() / 3);
        for (std::size_t i = 0; i + 2 < points.size(); i += 3)
            triangles.emplace_back(i, i + 1, i + 2);
        auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
        model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
        model->addSubModel(points, triangles);
        model->endModel();
        model->computeLocalAABB();
        return model;
    }
}  // namespace meshgap::bench
#endif

#endif
