#include "meshgap/mesh/MeshLoader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ompl/util/Console.h>

#include <assimp/Importer.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <tuple>

#include "meshgap/Exception.h"
#include "meshgap/InputFile.h"
#include "meshgap/Text.h"

namespace meshgap
{
    namespace
    {
        struct Collector
        {
            const aiScene *scene;
            const std::string &where;  ///< the file, for messages (excerpt())
            Mesh &mesh;
            LoadReport &report;
            aiVector3D centerSum{0.f, 0.f, 0.f};

            // Depth-first over the node tree in the order OMPL.app's extractVerticesAux uses, with the same
            // float matrix products, so positions and the centre match it exactly.
            void visit(const aiNode *node, aiMatrix4x4 transform)
            {
                transform *= node->mTransformation;
                for (unsigned int i = 0; i < node->mNumMeshes; ++i)
                {
                    const aiMesh *m = scene->mMeshes[node->mMeshes[i]];
                    const auto offset = static_cast<std::uint32_t>(mesh.vertices.size());
                    for (unsigned int k = 0; k < m->mNumVertices; ++k)
                    {
                        const aiVector3D p = transform * m->mVertices[k];
                        centerSum += p;
                        const Eigen::Vector3d &v = mesh.vertices.emplace_back(p.x, p.y, p.z);
                        checkVertex(where, mesh.vertices.size() - 1, v);  // NaN, Inf, beyond MAX_MAGNITUDE
                    }
                    report.rawVertices += m->mNumVertices;
                    for (unsigned int f = 0; f < m->mNumFaces; ++f)
                    {
                        const aiFace &face = m->mFaces[f];
                        if (face.mNumIndices != 3)
                        {
                            ++report.skippedPrimitives;
                            continue;
                        }
                        Triangle t;
                        for (int c = 0; c < 3; ++c)
                        {
                            if (face.mIndices[c] >= m->mNumVertices)
                                throw Exception(where, "face " + std::to_string(f) + " of mesh " +
                                                                   quote(m->mName.C_Str()) + " uses vertex index " +
                                                                   std::to_string(face.mIndices[c]) +
                                                                   " but the mesh has " +
                                                                   std::to_string(m->mNumVertices) + " vertices");
                            t[c] = offset + face.mIndices[c];
                        }
                        mesh.triangles.push_back(t);
                        ++report.rawTriangles;
                    }
                }
                for (unsigned int c = 0; c < node->mNumChildren; ++c)
                    visit(node->mChildren[c], transform);
            }
        };

        /** \brief Debian's assimp 5.2 hangs on a PLY header with bytes that are not text (found by fuzzing:
            fuzz/known/assimp_ply_header_hang.bin). A PLY header is ASCII by the format's definition, magic "ply" to
            "end_header", so check that before assimp reads the file. */
        void checkPlyHeader(const std::string &path)
        {
            std::ifstream in(path, std::ios::binary);
            std::string head(64 * 1024, '\0');
            in.read(&head[0], static_cast<std::streamsize>(head.size()));
            head.resize(static_cast<std::size_t>(in.gcount()));
            if (head.compare(0, 3, "ply") != 0 && head.compare(0, 3, "PLY") != 0)
                throw Exception(excerpt(path), "corrupt PLY header (the file does not start with 'ply')");
            const std::size_t end = head.find("end_header");
            if (end == std::string::npos)
                throw Exception(excerpt(path), "corrupt PLY header (no 'end_header' in the first 64 KiB)");
            for (std::size_t i = 0; i < end; ++i)
            {
                const unsigned char c = static_cast<unsigned char>(head[i]);
                if (!(c == '\n' || c == '\r' || c == '\t' || (c >= 32 && c < 127)))
                    throw Exception(excerpt(path),
                                    "corrupt PLY header (a byte that is not text at offset " + std::to_string(i) + ")");
            }
        }

        bool hasExtension(const std::string &path, const char *extension)
        {
            std::string ext = std::filesystem::path(path).extension().string();
            for (char &c : ext)
                c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            return ext == extension;
        }
    }  // namespace

    void warnIfNotClosed(const std::string &name, const EdgeReport &edges)
    {
        if (edges.closed())
            return;
        // Once per process for a name and its counts: a tool or a notebook that loads the same file again (one
        // checker after another, one scene after another) is not told twice.
        static std::mutex mutex;
        static std::set<std::tuple<std::string, std::size_t, std::size_t>> warned;
        {
            const std::lock_guard<std::mutex> lock(mutex);
            if (!warned.emplace(name, edges.boundaryEdges, edges.nonManifoldEdges).second)
                return;
        }
        OMPL_WARN("%s: not a closed surface: %zu boundary edges (used by one triangle), %zu non-manifold edges "
                      "(used by three or more); no inside: nothing counts as inside it (no containment, no "
                      "penetration depth into it)",
                      name.c_str(), edges.boundaryEdges, edges.nonManifoldEdges);
    }

    Mesh loadMesh(const std::string &path, LoadReport *reportOut, const LoadOptions &options)
    {
        namespace fs = std::filesystem;
        std::error_code ec;
        checkInputFile(path);
        if (fs::file_size(path, ec) == 0)
            throw Exception(excerpt(path), "the file is empty");
        if (hasExtension(path, ".ply"))
            checkPlyHeader(path);

        Assimp::Importer importer;
        // OMPL.app's post-processing, plus assimp's own validation, which runs first: without it a face index out of
        // range (a corrupt binary PLY, say) reaches the other steps and crashes inside assimp. It only checks.
        // GenNormals gives each corner its face's normal and JoinIdenticalVertices joins equal (position, normal)
        // pairs: they change only which copies of a position assimp returns, which the weld below makes one anyway,
        // but OMPL.app's centre is the mean of those copies, so they run only when it is asked for.
        unsigned int flags = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType |
                             aiProcess_OptimizeGraph;
        if (options.omplAppCenter)
            flags |= aiProcess_JoinIdenticalVertices | aiProcess_GenNormals;
        const aiScene *scene = importer.ReadFile(path, flags);
        if (scene == nullptr)
        {
            const std::string why = importer.GetErrorString();
            // assimp's validation words an empty scene its own way; say it as the rest of meshgap does.
            if (why.find("contains no faces") != std::string::npos || why.find("mNumMeshes is 0") != std::string::npos)
                throw Exception(excerpt(path), "no triangles (an empty scene, a point cloud or only lines?)");
            throw Exception(excerpt(path),
                            "cannot read the mesh (" + (why.empty() ? std::string("unknown format") : why) + ")");
        }
        if (scene->mRootNode == nullptr || !scene->HasMeshes())
            throw Exception(excerpt(path), "no triangles (the file holds no mesh)");

        Mesh mesh;
        mesh.source = path;
        LoadReport report;
        // Room for every mesh once (a mesh that several nodes place grows the arrays past it).
        std::size_t vertices = 0, faces = 0;
        for (unsigned int i = 0; i < scene->mNumMeshes; ++i)
        {
            vertices += scene->mMeshes[i]->mNumVertices;
            faces += scene->mMeshes[i]->mNumFaces;
        }
        mesh.vertices.reserve(vertices);
        mesh.triangles.reserve(faces);
        const std::string where = excerpt(path);
        Collector collector{scene, where, mesh, report};
        collector.visit(scene->mRootNode, aiMatrix4x4());
        if (options.omplAppCenter && report.rawVertices > 0)
        {
            aiVector3D c = collector.centerSum;
            c /= static_cast<float>(report.rawVertices);
            report.omplAppCenter = Eigen::Vector3d(c.x, c.y, c.z);
        }

        // The vertices were checked as they were read, the indices as the faces were.
        if (mesh.triangles.empty())
            throw Exception(where, "no triangles (an empty scene, a point cloud or only lines?)");
        report.clean = cleanMesh(mesh);
        if (mesh.triangles.empty())
            throw Exception(where, "no triangles left: all " + std::to_string(report.rawTriangles) +
                                   " triangles are degenerate (zero area)");
        if (report.clean.degenerate > 0)
            OMPL_WARN("%s: dropped %zu degenerate (zero-area) triangles", path.c_str(), report.clean.degenerate);
        if (report.clean.duplicates > 0)
            OMPL_INFORM("%s: dropped %zu duplicated triangles (same three vertices)", path.c_str(),
                        report.clean.duplicates);
        report.components = countComponents(mesh);
        report.edges = countEdges(mesh);
        warnIfNotClosed(path, report.edges);
        if (reportOut)
            *reportOut = report;
        return mesh;
    }
}  // namespace meshgap
