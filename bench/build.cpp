// Load and build time per mesh file, meshgap against FCL 0.7 in the same run.
//
// meshgap: loadMesh() (assimp, weld, clean), splitComponents() (one obstacle part per connected component, as
// Scene::fromMeshes does) and Body::build() of every part with the default options (triangle BVH, edges, orientation,
// one point per component; the node layer -- node grid, surface maps, surface graph, clusters -- and the mesh
// distances are built on first use by the node solvers, seeds or penetration depth, so not here; --nodes builds the
// node layer too, as the first such query would). FCL, as OMPL.app's FCL checker
// does it: the same assimp import with OMPL.app's post-processing, the triangles gathered, one BVHModel<OBBRSS> of the
// whole file. Each file is run --repeat times, the two sides interleaved; the table gives the median of each phase in
// ms and the ratio of the totals (meshgap / FCL).
//
// The generated inputs of bench/scaling.md (a world of 100 parts, a 250k-triangle mesh) come from
// bench/build_inputs.py.
//
//   build/bench/meshgap_bench_build [--repeat 5] [--nodes] FILE...

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <boost/program_options.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "CliMain.h"
#include "FclOracle.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"

namespace
{
    using namespace meshgap;
    using Clock = std::chrono::steady_clock;

    double ms(Clock::time_point t0)
    {
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    }

    double median(std::vector<double> v)
    {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    }

    /** \brief The phases of one load and build, ms. */
    struct Phases
    {
        std::vector<double> load, split, build, total;
        void add(double l, double s, double b)
        {
            load.push_back(l);
            split.push_back(s);
            build.push_back(b);
            total.push_back(l + s + b);
        }
    };

    /** \brief meshgap's load, split into parts and Body::build of each (\e withNodes: and its node layer); returns
        the part and triangle counts. */
    std::pair<std::size_t, std::size_t> meshgapOnce(const std::string &file, bool withNodes, Phases &phases)
    {
        auto t0 = Clock::now();
        const Mesh mesh = loadMesh(file);
        const double load = ms(t0);
        t0 = Clock::now();
        std::vector<Mesh> parts = splitComponents(mesh);
        const double split = ms(t0);
        t0 = Clock::now();
        std::vector<BodyConstPtr> bodies;
        bodies.reserve(parts.size());
        for (Mesh &part : parts)
        {
            bodies.push_back(Body::build(std::move(part)));
            if (withNodes)
                bodies.back()->numNodes();  // builds the node layer
        }
        phases.add(load, split, ms(t0));
        return {bodies.size(), mesh.triangles.size()};
    }

#ifdef MESHGAP_HAVE_FCL
    /** \brief Every triangle of \e node and below, placed by the node transforms (as OMPL.app gathers them). */
    void gather(const aiScene *scene, const aiNode *node, aiMatrix4x4 transform, Mesh &out)
    {
        transform *= node->mTransformation;
        for (unsigned int i = 0; i < node->mNumMeshes; ++i)
        {
            const aiMesh *m = scene->mMeshes[node->mMeshes[i]];
            const auto offset = static_cast<std::uint32_t>(out.vertices.size());
            for (unsigned int k = 0; k < m->mNumVertices; ++k)
            {
                const aiVector3D p = transform * m->mVertices[k];
                out.vertices.emplace_back(p.x, p.y, p.z);
            }
            for (unsigned int f = 0; f < m->mNumFaces; ++f)
                if (m->mFaces[f].mNumIndices == 3)
                    out.triangles.push_back({offset + m->mFaces[f].mIndices[0], offset + m->mFaces[f].mIndices[1],
                                             offset + m->mFaces[f].mIndices[2]});
        }
        for (unsigned int c = 0; c < node->mNumChildren; ++c)
            gather(scene, node->mChildren[c], transform, out);
    }

    /** \brief FCL's side: assimp with OMPL.app's post-processing, then one BVHModel<OBBRSS>. */
    void fclOnce(const std::string &file, Phases &phases)
    {
        auto t0 = Clock::now();
        Assimp::Importer importer;
        const aiScene *scene =
            importer.ReadFile(file, aiProcess_GenNormals | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                        aiProcess_SortByPType | aiProcess_OptimizeGraph);
        if (scene == nullptr || scene->mRootNode == nullptr)
            throw Exception(file, std::string("assimp cannot read it: ") + importer.GetErrorString());
        Mesh mesh;
        gather(scene, scene->mRootNode, aiMatrix4x4(), mesh);
        const double load = ms(t0);
        t0 = Clock::now();
        const auto model = test::fclModel(mesh);
        phases.add(load, 0.0, ms(t0));
        if (model->num_tris != static_cast<int>(mesh.triangles.size()))
            throw Exception(file, "FCL kept " + std::to_string(model->num_tris) + " of the triangles");
    }
#endif

    int run(int argc, char **argv)
    {
        namespace po = boost::program_options;
        po::options_description options("meshgap_bench_build");
        options.add_options()("help,h", "print this help")("repeat", po::value<int>()->default_value(5),
                                                            "runs per file (median)")(
            "nodes", "also build each body's node layer (what the first node-solver query would build)")(
            "file", po::value<std::vector<std::string>>()->required(), "mesh files (positional)");
        po::positional_options_description positional;
        positional.add("file", -1);
        po::variables_map vm;
        if (!cli::parseCommandLine(argc, argv, options, vm, &positional))
            return 0;
        const int repeat = vm["repeat"].as<int>();
        const bool withNodes = vm.count("nodes") > 0;
        if (repeat < 1)
            throw Exception("--repeat", "must be at least 1");
        ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
#ifndef MESHGAP_HAVE_FCL
        throw Exception("meshgap_bench_build", "built without FCL (libfcl-dev): nothing to compare against");
#else
        std::printf("Load and build per file, ms (median of %d runs): meshgap load / split into parts / Body::build "
                    "of every part, FCL load (assimp as OMPL.app) / BVHModel<OBBRSS> build; ratio of the totals.\n\n"
                    "| file | triangles | parts | meshgap load | split | build | total | FCL load | FCL build | "
                    "FCL total | meshgap / FCL |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
                    repeat);
        for (const std::string &file : vm["file"].as<std::vector<std::string>>())
        {
            Phases ours, fcl;
            std::pair<std::size_t, std::size_t> counts;
            for (int r = 0; r < repeat; ++r)
            {
                counts = meshgapOnce(file, withNodes, ours);
                fclOnce(file, fcl);
            }
            const double a = median(ours.total), b = median(fcl.total);
            std::printf("| %s | %zu | %zu | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | **%.2f** |\n",
                        std::filesystem::path(file).filename().c_str(), counts.second, counts.first,
                        median(ours.load), median(ours.split), median(ours.build), a, median(fcl.load),
                        median(fcl.build), b, a / b);
        }
        return 0;
#endif
    }
}  // namespace

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, run);
}
