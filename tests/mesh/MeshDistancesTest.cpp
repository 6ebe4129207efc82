// Mesh distances (the paper's D and P, Section II-A.2). Oracles: Floyd-Warshall over the mesh's triangle edges,
// computed here from the vertex positions (independent of SurfaceGraph and of Dijkstra), and hand-worked answers.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/DistanceCache.h"
#include "meshgap/mesh/MeshDistances.h"
#include "meshgap/mesh/SurfaceGraph.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    constexpr double INF = std::numeric_limits<double>::infinity();
    constexpr double REL = 1e-12;

    /** \brief All-pairs shortest paths over the mesh's triangle edges by Floyd-Warshall. */
    struct Oracle
    {
        explicit Oracle(const Mesh &mesh) : mesh_(mesh), n(static_cast<std::uint32_t>(mesh.vertices.size()))
        {
            D.assign(std::size_t(n) * n, INF);
            for (std::uint32_t i = 0; i < n; ++i)
                D[std::size_t(i) * n + i] = 0.0;
            for (const Triangle &t : mesh.triangles)
                for (int k = 0; k < 3; ++k)
                {
                    const std::uint32_t a = t[k], b = t[(k + 1) % 3];
                    edges.insert(std::minmax(a, b));
                    D[std::size_t(a) * n + b] = D[std::size_t(b) * n + a] = length(a, b);
                }
            for (std::uint32_t k = 0; k < n; ++k)
                for (std::uint32_t i = 0; i < n; ++i)
                    for (std::uint32_t j = 0; j < n; ++j)
                        D[std::size_t(i) * n + j] =
                            std::min(D[std::size_t(i) * n + j], D[std::size_t(i) * n + k] + D[std::size_t(k) * n + j]);
        }

        double length(std::uint32_t a, std::uint32_t b) const { return (mesh_.vertices[a] - mesh_.vertices[b]).norm(); }
        bool isEdge(std::uint32_t a, std::uint32_t b) const { return edges.count(std::minmax(a, b)) > 0; }
        double d(std::uint32_t a, std::uint32_t b) const { return D[std::size_t(a) * n + b]; }
        double maxFinite() const
        {
            double m = 0.0;
            for (double x : D)
                if (x < INF)
                    m = std::max(m, x);
            return m;
        }

        const Mesh &mesh_;
        std::uint32_t n;
        std::vector<double> D;
        std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    };

    ::testing::AssertionResult relNear(double expected, double actual)
    {
        if (expected == actual)  // also +inf == +inf
            return ::testing::AssertionSuccess();
        if (std::isfinite(expected) && std::isfinite(actual) &&
            std::abs(expected - actual) <= REL * std::max(std::abs(expected), std::abs(actual)))
            return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure()
               << "expected " << expected << ", got " << actual << " (difference " << actual - expected << ")";
    }

    struct NamedMesh
    {
        std::string name;
        Mesh mesh;
    };

    Mesh twoBoxes()
    {
        Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
        far.translation() = Eigen::Vector3d(10.0, 0.0, 0.0);
        return test::merged(test::box(1, 1, 1, 2), test::transformed(test::box(0.5, 1, 1.5, 1), far));
    }

    std::vector<NamedMesh> smallMeshes()
    {
        return {{"box(1,2,3,3)", test::box(1, 2, 3, 3)},
                {"icosphere(1,2)", test::icosphere(1, 2)},
                {"grid(3,2,6,4)", test::grid(3, 2, 6, 4)},
                {"two boxes", twoBoxes()}};
    }

    std::shared_ptr<const SurfaceGraph> graphOf(const Mesh &mesh)
    {
        return std::make_shared<const SurfaceGraph>(mesh);
    }

    MeshDistancesOptions denseOptions(unsigned int threads = 2)
    {
        MeshDistancesOptions o;
        o.memoryBudgetBytes = std::size_t(1) << 30;
        o.threads = threads;
        return o;
    }

    MeshDistancesOptions onDemandOptions()
    {
        MeshDistancesOptions o;
        o.memoryBudgetBytes = 1;  // any table of one node or more is over budget
        return o;
    }

    /** \brief Bitwise comparison of two MeshDistances on all pairs: distances and paths. */
    void expectIdentical(const MeshDistances &a, const MeshDistances &b)
    {
        const std::uint32_t n = a.graph().numNodes();
        ASSERT_EQ(n, b.graph().numNodes());
        std::size_t distanceMismatches = 0, pathMismatches = 0;
        std::vector<std::uint32_t> pa, pb;
        for (std::uint32_t u = 0; u < n; ++u)
            for (std::uint32_t v = 0; v < n; ++v)
            {
                const double da = a.distance(u, v), db = b.distance(u, v);
                if (std::memcmp(&da, &db, sizeof da) != 0)
                {
                    if (distanceMismatches++ < 5)
                        ADD_FAILURE() << "distance(" << u << ", " << v << "): " << da << " vs " << db;
                }
                a.path(u, v, pa);
                b.path(u, v, pb);
                if (pa != pb && pathMismatches++ < 5)
                    ADD_FAILURE() << "path(" << u << ", " << v << ") differs";
            }
        EXPECT_EQ(distanceMismatches, 0u);
        EXPECT_EQ(pathMismatches, 0u);
    }

    /** \brief Collects OMPL warnings while alive (the test main sets the log level to LOG_WARN). */
    class MentionedWarningCapture : public ompl::msg::OutputHandler
    {
    public:
        MentionedWarningCapture() : previousLevel_(ompl::msg::getLogLevel())
        {
            ompl::msg::useOutputHandler(this);
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        }
        ~MentionedWarningCapture() override
        {
            ompl::msg::restorePreviousOutputHandler();
            ompl::msg::setLogLevel(previousLevel_);
        }
        void log(const std::string &text, ompl::msg::LogLevel level, const char * /*filename*/, int /*line*/) override
        {
            if (level >= ompl::msg::LOG_WARN)
                warnings.push_back(text);
        }
        bool mentions(const std::string &what) const
        {
            return std::any_of(warnings.begin(), warnings.end(),
                               [&](const std::string &w) { return w.find(what) != std::string::npos; });
        }
        std::vector<std::string> warnings;

    private:
        ompl::msg::LogLevel previousLevel_;
    };

    std::uint32_t nodeAt(const Mesh &mesh, const Eigen::Vector3d &p)
    {
        for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i)
            if ((mesh.vertices[i] - p).norm() < 1e-12)
                return i;
        ADD_FAILURE() << "no node at " << p.transpose();
        return 0;
    }
}  // namespace

TEST(MeshDistances, DenseTableBytesAndStrategyChoice)
{
    EXPECT_EQ(MeshDistances::denseTableBytes(0), 0u);
    EXPECT_EQ(MeshDistances::denseTableBytes(1), 12u);
    EXPECT_EQ(MeshDistances::denseTableBytes(1000), 12000000u);
    EXPECT_EQ(MeshDistances::denseTableBytes(16226), std::size_t(12) * 16226 * 16226);
    // No overflow for absurd sizes: saturates instead of wrapping to something small.
    EXPECT_EQ(MeshDistances::denseTableBytes(std::size_t(1) << 40), std::numeric_limits<std::size_t>::max());

    const auto g = graphOf(test::box(1, 1, 1, 2));  // 26 nodes
    const std::size_t bytes = MeshDistances::denseTableBytes(g->numNodes());
    MeshDistancesOptions o;
    o.memoryBudgetBytes = bytes;
    EXPECT_TRUE(MeshDistances::build(g, o)->isDense());
    o.memoryBudgetBytes = bytes - 1;
    EXPECT_FALSE(MeshDistances::build(g, o)->isDense());
    EXPECT_TRUE(MeshDistances::build(g)->isDense());  // the default budget (512 MiB) holds 26 nodes
    EXPECT_THROW(MeshDistances::build(nullptr), Exception);
}

TEST(MeshDistances, DenseMatchesFloydWarshall)
{
    for (const NamedMesh &m : smallMeshes())
    {
        SCOPED_TRACE(m.name);
        const Oracle oracle(m.mesh);
        const auto g = graphOf(m.mesh);
        const auto md = MeshDistances::build(g, denseOptions());
        ASSERT_TRUE(md->isDense());
        std::size_t bad = 0, infinite = 0;
        for (std::uint32_t u = 0; u < oracle.n; ++u)
            for (std::uint32_t v = 0; v < oracle.n; ++v)
            {
                const double d = md->distance(u, v);
                if (!relNear(oracle.d(u, v), d) && bad++ < 5)
                    ADD_FAILURE() << "D[" << u << "][" << v << "]: " << relNear(oracle.d(u, v), d).message();
                // +inf exactly across components, finite within one.
                EXPECT_EQ(std::isinf(d), g->component(u) != g->component(v));
                infinite += std::isinf(d) ? 1 : 0;
            }
        EXPECT_EQ(bad, 0u);
        if (m.name == "two boxes")
            EXPECT_EQ(infinite, 2u * 26 * 8);  // 26-node box x 8-node box, both directions
        else
            EXPECT_EQ(infinite, 0u);
    }
}

TEST(MeshDistances, PathsAreShortestMeshPaths)
{
    for (const NamedMesh &m : smallMeshes())
        for (const bool dense : {true, false})
        {
            SCOPED_TRACE(m.name + (dense ? " dense" : " on demand"));
            const Oracle oracle(m.mesh);
            const auto md = MeshDistances::build(graphOf(m.mesh), dense ? denseOptions() : onDemandOptions());
            ASSERT_EQ(md->isDense(), dense);
            std::vector<std::uint32_t> p;
            std::size_t bad = 0;
            for (std::uint32_t u = 0; u < oracle.n; ++u)
                for (std::uint32_t v = 0; v < oracle.n; ++v)
                {
                    md->path(u, v, p);
                    if (oracle.d(u, v) == INF)
                    {
                        if (!p.empty() && bad++ < 5)
                            ADD_FAILURE() << "path(" << u << ", " << v << ") across components is not empty";
                        continue;
                    }
                    bool ok = !p.empty() && p.front() == u && p.back() == v;
                    double sum = 0.0;
                    for (std::size_t k = 1; ok && k < p.size(); ++k)
                    {
                        ok = oracle.isEdge(p[k - 1], p[k]);
                        sum += ok ? oracle.length(p[k - 1], p[k]) : 0.0;
                    }
                    ok = ok && std::set<std::uint32_t>(p.begin(), p.end()).size() == p.size();  // simple path
                    ok = ok && relNear(md->distance(u, v), sum) && relNear(oracle.d(u, v), sum);
                    if (!ok && bad++ < 5)
                        ADD_FAILURE() << "path(" << u << ", " << v << ") of " << p.size()
                                      << " nodes is not a shortest mesh path: length " << sum << ", D "
                                      << md->distance(u, v) << ", oracle " << oracle.d(u, v);
                }
            EXPECT_EQ(bad, 0u);
            md->path(3, 3, p);
            EXPECT_EQ(p, std::vector<std::uint32_t>{3});
        }
}

TEST(MeshDistances, OnDemandIdenticalToDense)
{
    std::vector<NamedMesh> meshes = smallMeshes();
    // Regular grids have many equally short paths: the two strategies must still pick the same one.
    meshes.push_back({"grid(10,10,10,10)", test::grid(10, 10, 10, 10)});
    meshes.push_back({"box(1,1,1,4)", test::box(1, 1, 1, 4)});
    for (const NamedMesh &m : meshes)
    {
        SCOPED_TRACE(m.name);
        const auto g = graphOf(m.mesh);
        const auto dense = MeshDistances::build(g, denseOptions());
        const auto onDemand = MeshDistances::build(g, onDemandOptions());
        ASSERT_TRUE(dense->isDense());
        ASSERT_FALSE(onDemand->isDense());
        expectIdentical(*dense, *onDemand);
    }
}

TEST(MeshDistances, NodesWithinMatchesBruteForce)
{
    for (const NamedMesh &m : smallMeshes())
    {
        SCOPED_TRACE(m.name);
        const Oracle oracle(m.mesh);
        const auto g = graphOf(m.mesh);
        const auto dense = MeshDistances::build(g, denseOptions());
        const auto onDemand = MeshDistances::build(g, onDemandOptions());
        std::vector<std::uint32_t> got;
        for (std::uint32_t u = 0; u < oracle.n; u += 7)
        {
            // Radii halfway between consecutive distinct oracle distances from u (no rounding ambiguity), plus 0,
            // +inf and a negative radius.
            std::vector<double> ds;
            for (std::uint32_t w = 0; w < oracle.n; ++w)
                if (oracle.d(u, w) < INF)
                    ds.push_back(oracle.d(u, w));
            std::sort(ds.begin(), ds.end());
            ds.erase(std::unique(ds.begin(), ds.end(), [](double a, double b) { return b - a < 1e-9; }), ds.end());
            std::vector<double> radii{0.0, INF, -1.0};
            for (std::size_t k = 0; k + 1 < ds.size(); k += std::max<std::size_t>(1, ds.size() / 6))
                radii.push_back(0.5 * (ds[k] + ds[k + 1]));
            for (double r : radii)
            {
                std::set<std::uint32_t> expected;
                for (std::uint32_t w = 0; w < oracle.n; ++w)
                    if (oracle.d(u, w) <= r && oracle.d(u, w) < INF)  // never across components
                        expected.insert(w);
                for (const MeshDistances *md : {dense.get(), onDemand.get()})
                {
                    md->nodesWithin(u, r, got);
                    const std::set<std::uint32_t> gotSet(got.begin(), got.end());
                    EXPECT_EQ(gotSet.size(), got.size()) << "duplicates, u " << u << " r " << r;
                    EXPECT_EQ(gotSet, expected) << (md->isDense() ? "dense" : "on demand") << ", u " << u << " r " << r;
                }
            }
            // An infinite radius gives exactly u's connected component.
            std::set<std::uint32_t> component;
            for (std::uint32_t w = 0; w < oracle.n; ++w)
                if (g->component(w) == g->component(u))
                    component.insert(w);
            for (const MeshDistances *md : {dense.get(), onDemand.get()})
            {
                md->nodesWithin(u, INF, got);
                EXPECT_EQ(std::set<std::uint32_t>(got.begin(), got.end()), component);
            }
            // A radius exactly equal to a table distance includes that node (<=), on both strategies alike.
            for (std::uint32_t w = 0; w < oracle.n; w += 5)
            {
                const double r = dense->distance(u, w);
                if (r == INF)
                    continue;
                std::set<std::uint32_t> expected;
                for (std::uint32_t x = 0; x < oracle.n; ++x)
                    if (dense->distance(u, x) <= r)
                        expected.insert(x);
                ASSERT_EQ(expected.count(w), 1u);
                for (const MeshDistances *md : {dense.get(), onDemand.get()})
                {
                    md->nodesWithin(u, r, got);
                    EXPECT_EQ(std::set<std::uint32_t>(got.begin(), got.end()), expected);
                }
            }
        }
    }
}

TEST(MeshDistances, KnownAnswers)
{
    const double s2 = std::sqrt(2.0);
    for (const bool dense : {true, false})
    {
        SCOPED_TRACE(dense ? "dense" : "on demand");
        const MeshDistancesOptions o = dense ? denseOptions() : onDemandOptions();

        // Two unit squares side by side, node (i, j) = j * 3 + i at (i, j); diagonals run from (i, j) to
        // (i+1, j+1) only, so going up-left has no shortcut.
        const Mesh grid = test::grid(2, 1, 2, 1);
        const auto g = MeshDistances::build(graphOf(grid), o);
        EXPECT_TRUE(relNear(1.0, g->distance(0, 1)));       // along an edge
        EXPECT_TRUE(relNear(2.0, g->distance(0, 2)));       // two edges in line
        EXPECT_TRUE(relNear(s2, g->distance(0, 4)));        // across a diagonal
        EXPECT_TRUE(relNear(s2, g->distance(1, 5)));        // across the other square's diagonal
        EXPECT_TRUE(relNear(1.0 + s2, g->distance(0, 5)));  // diagonal then edge
        EXPECT_TRUE(relNear(3.0, g->distance(2, 3)));       // against the diagonals: three edges
        EXPECT_TRUE(relNear(2.0, g->distance(1, 3)));
        EXPECT_TRUE(relNear(g->distance(0, 5), g->distance(5, 0)));
        std::vector<std::uint32_t> p;
        g->path(0, 4, p);
        EXPECT_EQ(p, (std::vector<std::uint32_t>{0, 4}));
        g->path(0, 2, p);
        EXPECT_EQ(p, (std::vector<std::uint32_t>{0, 1, 2}));
        if (dense)
            EXPECT_TRUE(relNear(3.0, g->maxDistance()));  // (2,0)-(0,1) is the farthest pair
        else  // double sweep: farthest from node 0 is node 5 (1 + sqrt 2), and nothing is farther from node 5
            EXPECT_TRUE(relNear(1.0 + s2, g->maxDistance()));

        // Unit cube, one diagonal per face: opposite corners differ in three coordinates, a step changes at most
        // two (a face diagonal), so the best is one diagonal plus one edge, 1 + sqrt(2), for every such pair.
        const Mesh cube = test::box(0.5, 0.5, 0.5, 1);
        const auto c = MeshDistances::build(graphOf(cube), o);
        for (const Eigen::Vector3d &corner : {Eigen::Vector3d(-0.5, -0.5, -0.5), Eigen::Vector3d(0.5, -0.5, -0.5),
                                              Eigen::Vector3d(-0.5, 0.5, -0.5), Eigen::Vector3d(-0.5, -0.5, 0.5)})
        {
            const std::uint32_t a = nodeAt(cube, corner), b = nodeAt(cube, -corner);
            EXPECT_TRUE(relNear(1.0 + s2, c->distance(a, b))) << corner.transpose();
            c->path(a, b, p);
            EXPECT_EQ(p.size(), 3u);
        }

        // Icosahedron of circumradius 1: edge a = 4 / sqrt(10 + 2 sqrt 5); antipodal vertices are three edges apart.
        const Mesh ico = test::icosphere(1.0, 0);
        const double edge = 4.0 / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
        const auto ic = MeshDistances::build(graphOf(ico), o);
        for (std::uint32_t i = 0; i < 12; ++i)
            EXPECT_TRUE(relNear(3.0 * edge, ic->distance(i, nodeAt(ico, -ico.vertices[i]))));
        EXPECT_TRUE(relNear(3.0 * edge, ic->maxDistance()));
    }
}

TEST(MeshDistances, MaxDistance)
{
    std::vector<NamedMesh> meshes = smallMeshes();
    meshes.push_back({"grid(10,10,10,10)", test::grid(10, 10, 10, 10)});
    for (const NamedMesh &m : meshes)
    {
        SCOPED_TRACE(m.name);
        const Oracle oracle(m.mesh);
        const auto g = graphOf(m.mesh);
        const double exact = oracle.maxFinite();
        const auto dense = MeshDistances::build(g, denseOptions());
        EXPECT_TRUE(relNear(exact, dense->maxDistance()));
        const auto onDemand = MeshDistances::build(g, onDemandOptions());
        const double bound = onDemand->maxDistance();
        EXPECT_LE(bound, dense->maxDistance());
        EXPECT_GT(bound, 0.0);
        EXPECT_EQ(bound, onDemand->maxDistance());  // computed once
    }
    // The double sweep on a 20 x 1 strip of unit squares, diagonals from (i, j) to (i+1, j+1), worked by hand: from
    // node (0,0) the farthest is (20,1) at 19 + sqrt 2 (beating (20,0) at 20); from (20,1) nothing is farther than
    // (0,0). The true diameter is 21, from (20,0) to (0,1) against the diagonals: the sweep is only a lower bound.
    const Mesh strip = test::grid(20, 1, 20, 1);
    const Oracle oracle(strip);
    EXPECT_TRUE(relNear(21.0, oracle.maxFinite()));
    const auto onDemand = MeshDistances::build(graphOf(strip), onDemandOptions());
    EXPECT_TRUE(relNear(19.0 + std::sqrt(2.0), onDemand->maxDistance()));
    EXPECT_TRUE(relNear(21.0, MeshDistances::build(graphOf(strip), denseOptions())->maxDistance()));
}

TEST(MeshDistances, ConcurrentOnDemandQueriesMatchOneThread)
{
    const Mesh mesh = test::icosphere(1.0, 3);  // 642 nodes
    const auto g = graphOf(mesh);
    const auto md = MeshDistances::build(g, onDemandOptions());
    ASSERT_FALSE(md->isDense());
    const std::uint32_t n = g->numNodes();

    struct Query
    {
        std::uint32_t u, v;
        double r;
    };
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::uint32_t> node(0, n - 1);
    std::uniform_real_distribution<double> radius(0.0, 1.5);
    std::vector<Query> queries(1500);
    for (Query &q : queries)
        q = {node(rng), node(rng), radius(rng)};

    struct Answer
    {
        double d;
        std::vector<std::uint32_t> path, within;
    };
    auto answer = [&](const Query &q)
    {
        Answer a;
        a.d = md->distance(q.u, q.v);
        md->path(q.u, q.v, a.path);
        md->nodesWithin(q.u, q.r, a.within);
        return a;
    };
    std::vector<Answer> reference;
    for (const Query &q : queries)
        reference.push_back(answer(q));

    std::atomic<std::size_t> mismatches{0}, answered{0};
    std::vector<std::thread> threads;
    for (unsigned int t = 0; t < 4; ++t)
        threads.emplace_back(
            [&, t]
            {
                for (std::size_t k = 0; k < queries.size(); ++k)
                {
                    const std::size_t i = (k + t * 377) % queries.size();  // each thread in its own order
                    const Answer a = answer(queries[i]);
                    if (a.d != reference[i].d || a.path != reference[i].path || a.within != reference[i].within)
                        ++mismatches;
                    ++answered;
                }
            });
    for (std::thread &th : threads)
        th.join();
    EXPECT_EQ(answered.load(), 4 * queries.size());
    EXPECT_EQ(mismatches.load(), 0u);

    // And the single-thread answers are the dense table's.
    const auto dense = MeshDistances::build(g, denseOptions());
    std::vector<std::uint32_t> p;
    for (std::size_t i = 0; i < queries.size(); ++i)
    {
        EXPECT_EQ(reference[i].d, dense->distance(queries[i].u, queries[i].v));
        dense->path(queries[i].u, queries[i].v, p);
        EXPECT_EQ(reference[i].path, p);
    }
}

TEST(MeshDistances, DenseBuildIndependentOfThreadCount)
{
    const auto g = graphOf(test::icosphere(1.0, 2));
    const auto one = MeshDistances::build(g, denseOptions(1));
    const auto four = MeshDistances::build(g, denseOptions(4));
    expectIdentical(*one, *four);
    EXPECT_EQ(one->maxDistance(), four->maxDistance());
}

TEST(MeshDistances, OutOfRangeNodesThrow)
{
    const auto g = graphOf(test::box(1, 1, 1, 1));
    std::vector<std::uint32_t> out;
    for (const bool dense : {true, false})
    {
        const auto md = MeshDistances::build(g, dense ? denseOptions() : onDemandOptions());
        EXPECT_THROW(md->distance(0, 8), Exception);
        EXPECT_THROW(md->distance(8, 0), Exception);
        EXPECT_THROW(md->path(0, 8, out), Exception);
        EXPECT_THROW(md->nodesWithin(8, 1.0, out), Exception);
    }
}

// ---------------------------------------------------------------------------------------------------------------
// On-disk cache

TEST(MeshDistances, GraphHashSeesEveryBitOfTheLengths)
{
    const Mesh a = test::box(1, 1, 1, 2);
    Mesh b = a;
    b.vertices[5].x() = std::nextafter(b.vertices[5].x(), INF);  // one ulp: changes edge-length bits only
    const SurfaceGraph ga(a), gb(b);
    ASSERT_EQ(ga.offsets(), gb.offsets());
    ASSERT_EQ(ga.neighbours(), gb.neighbours());
    ASSERT_NE(ga.lengths(), gb.lengths());
    EXPECT_NE(graphHash(ga), graphHash(gb));
    EXPECT_EQ(graphHash(ga), graphHash(SurfaceGraph(a)));

    // hashBytes is xxHash64: its published values for "" and "abc" with seed 0.
    EXPECT_EQ(hashBytes("", 0), 0xEF46DB3751D8E999ull);
    EXPECT_EQ(hashBytes("abc", 3), 0x44BC2CF5AD770999ull);

    // hashBytes: every single-bit flip and every length change of a buffer gives a different value.
    std::vector<unsigned char> bytes(77);
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<unsigned char>(i * 37 + 11);
    std::set<std::uint64_t> seen{hashBytes(bytes.data(), bytes.size())};
    for (std::size_t i = 0; i < bytes.size(); ++i)
        for (int bit = 0; bit < 8; ++bit)
        {
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
            seen.insert(hashBytes(bytes.data(), bytes.size()));
            bytes[i] ^= static_cast<unsigned char>(1u << bit);
        }
    for (std::size_t len = 0; len < bytes.size(); ++len)
        seen.insert(hashBytes(bytes.data(), len));
    EXPECT_EQ(seen.size(), 1 + bytes.size() * 8 + bytes.size());
    EXPECT_NE(hashBytes(bytes.data(), bytes.size(), 1), hashBytes(bytes.data(), bytes.size(), 2));
}

class MeshDistancesCache : public ::testing::Test
{
protected:
    void SetUp() override
    {
        static int counter = 0;
        dir_ = fs::temp_directory_path() /
               ("meshgap-dist-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        ASSERT_FALSE(fs::exists(dir_));
    }

    void TearDown() override
    {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    MeshDistancesOptions cached(const fs::path &dir) const
    {
        MeshDistancesOptions o = denseOptions();
        o.cacheDir = dir.string();
        return o;
    }

    static std::size_t filesIn(const fs::path &dir)
    {
        std::size_t count = 0;
        for (const auto &entry : fs::directory_iterator(dir))
        {
            (void)entry;
            ++count;
        }
        return count;
    }

    static void flipByte(const fs::path &file, std::uintmax_t offset)
    {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        ASSERT_TRUE(f.good());
        f.seekg(static_cast<std::streamoff>(offset));
        char c = 0;
        f.read(&c, 1);
        c = static_cast<char>(c ^ 0x10);
        f.seekp(static_cast<std::streamoff>(offset));
        f.write(&c, 1);
        ASSERT_TRUE(f.good());
    }

    /** \brief Build from the (damaged) cache: it must be rejected with a warning naming the file, and the answers
        must be those of a freshly computed table; afterwards the file has been rewritten and is accepted. */
    void expectRejectedAndRebuilt(const Mesh &mesh, const std::string &what)
    {
        SCOPED_TRACE(what);
        const auto g = graphOf(mesh);
        const std::string file = distanceCachePath(dir_.string(), graphHash(*g));
        {
            MentionedWarningCapture capture;
            const auto md = MeshDistances::build(g, cached(dir_));
            EXPECT_FALSE(md->fromCache());
            EXPECT_TRUE(capture.mentions(file)) << "no warning naming " << file;
            expectIdentical(*md, *MeshDistances::build(g, denseOptions()));
            const Oracle oracle(mesh);
            EXPECT_TRUE(relNear(oracle.d(0, oracle.n - 1), md->distance(0, oracle.n - 1)));
        }
        const auto again = MeshDistances::build(g, cached(dir_));
        EXPECT_TRUE(again->fromCache());
    }

    fs::path dir_;
};

TEST_F(MeshDistancesCache, WritesThenReadsIdenticalTable)
{
    const Mesh mesh = test::box(1, 2, 3, 3);
    const auto g = graphOf(mesh);
    const fs::path dir = dir_ / "nested" / "folder";  // does not exist yet
    const std::string file = distanceCachePath(dir.string(), graphHash(*g));
    EXPECT_EQ(fs::path(file).parent_path(), dir);

    const auto first = MeshDistances::build(g, cached(dir));
    EXPECT_TRUE(first->isDense());
    EXPECT_FALSE(first->fromCache());
    ASSERT_TRUE(fs::exists(file));
    EXPECT_EQ(filesIn(dir), 1u);  // no temporary left behind
    EXPECT_EQ(fs::file_size(file), 48 + MeshDistances::denseTableBytes(g->numNodes()));

    MentionedWarningCapture capture;
    const auto second = MeshDistances::build(g, cached(dir));
    EXPECT_TRUE(second->fromCache());
    EXPECT_TRUE(capture.warnings.empty());
    expectIdentical(*first, *second);
    EXPECT_EQ(first->maxDistance(), second->maxDistance());
    const Oracle oracle(mesh);
    for (std::uint32_t v = 0; v < oracle.n; ++v)
        EXPECT_TRUE(relNear(oracle.d(7, v), second->distance(7, v)));

    // A different mesh has a different key, so it misses the cache and gets its own file.
    const auto other = MeshDistances::build(graphOf(test::box(1, 2, 3.5, 3)), cached(dir));
    EXPECT_FALSE(other->fromCache());
    EXPECT_EQ(filesIn(dir), 2u);
}

TEST_F(MeshDistancesCache, RejectsCorruptPayload)
{
    const Mesh mesh = twoBoxes();  // with infinite distances and sentinel predecessors in the table
    const auto g = graphOf(mesh);
    const fs::path file = distanceCachePath(dir_.string(), graphHash(*g));
    MeshDistances::build(g, cached(dir_));
    const std::uintmax_t size = fs::file_size(file);
    flipByte(file, size / 3);  // in D
    expectRejectedAndRebuilt(mesh, "byte flipped in D");
    flipByte(file, size - 1);  // in P
    expectRejectedAndRebuilt(mesh, "byte flipped in P");
}

TEST_F(MeshDistancesCache, RejectsCorruptHeader)
{
    const Mesh mesh = test::box(1, 1, 1, 2);
    const auto g = graphOf(mesh);
    const fs::path file = distanceCachePath(dir_.string(), graphHash(*g));
    MeshDistances::build(g, cached(dir_));
    // Offsets of the documented header fields: magic, version, byte order, node count, hash, size, checksum.
    for (std::uintmax_t offset : {0, 8, 12, 16, 24, 32, 40})
    {
        flipByte(file, offset);
        expectRejectedAndRebuilt(mesh, "header byte " + std::to_string(offset));
    }
}

TEST_F(MeshDistancesCache, RejectsTruncatedOrPaddedFile)
{
    const Mesh mesh = test::icosphere(1.0, 1);
    const auto g = graphOf(mesh);
    const fs::path file = distanceCachePath(dir_.string(), graphHash(*g));
    MeshDistances::build(g, cached(dir_));
    const std::uintmax_t size = fs::file_size(file);
    fs::resize_file(file, size - 1);
    expectRejectedAndRebuilt(mesh, "one byte short");
    fs::resize_file(file, 20);
    expectRejectedAndRebuilt(mesh, "cut inside the header");
    fs::resize_file(file, 0);
    expectRejectedAndRebuilt(mesh, "empty");
    fs::resize_file(file, size + 8);
    expectRejectedAndRebuilt(mesh, "eight bytes too long");
}

TEST_F(MeshDistancesCache, RejectsFileOfAnotherMesh)
{
    // Same node count and connectivity, different edge lengths: a file written for one must not serve the other
    // even when it sits under the other's name.
    const Mesh a = test::box(1, 1, 1, 2), b = test::box(1, 1, 1.5, 2);
    const auto ga = graphOf(a), gb = graphOf(b);
    ASSERT_EQ(ga->numNodes(), gb->numNodes());
    ASSERT_NE(graphHash(*ga), graphHash(*gb));
    MeshDistances::build(ga, cached(dir_));
    const fs::path fileA = distanceCachePath(dir_.string(), graphHash(*ga));
    const fs::path fileB = distanceCachePath(dir_.string(), graphHash(*gb));
    ASSERT_TRUE(fs::exists(fileA));
    EXPECT_FALSE(fs::exists(fileB));
    fs::copy_file(fileA, fileB);
    expectRejectedAndRebuilt(b, "file of mesh a under mesh b's name");
    EXPECT_TRUE(MeshDistances::build(ga, cached(dir_))->fromCache());
}

TEST_F(MeshDistancesCache, UnwritableFolderWarnsAndStillWorks)
{
    fs::create_directories(dir_);
    const fs::path blocker = dir_ / "a-file";
    std::ofstream(blocker) << "not a folder";
    const Mesh mesh = test::grid(3, 2, 6, 4);
    const auto g = graphOf(mesh);
    MentionedWarningCapture capture;
    const auto md = MeshDistances::build(g, cached(blocker / "cache"));  // cannot be created: parent is a file
    EXPECT_TRUE(md->isDense());
    EXPECT_FALSE(md->fromCache());
    EXPECT_FALSE(capture.warnings.empty());
    expectIdentical(*md, *MeshDistances::build(g, denseOptions()));
}

TEST_F(MeshDistancesCache, OnDemandWritesNoCache)
{
    MeshDistancesOptions o = onDemandOptions();
    o.cacheDir = dir_.string();
    const auto md = MeshDistances::build(graphOf(test::box(1, 1, 1, 2)), o);
    EXPECT_FALSE(md->isDense());
    EXPECT_FALSE(md->fromCache());
    EXPECT_FALSE(fs::exists(dir_));
}
