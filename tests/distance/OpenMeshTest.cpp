// Open and non-manifold meshes: boundary and non-manifold edges counted at load (by hand on meshes built here) and
// warned about once per file; what collision, distance and depth mean when a body is open (no inside), against FCL
// and analytic geometry (a box without a lid, a disc, sheets), and the openBody flag of every answer.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/scene/Scene.h"
#include "support/MeshWriter.h"

using namespace meshgap;
namespace fs = std::filesystem;

namespace
{
    /** \brief The box [-h, h]^3 (test::box, n x n squares a face) without its top face z = h: an open box. Its
        top face's rim, 4n edges, is left used by one triangle each. */
    Mesh lidlessBox(double h, int n)
    {
        Mesh m = test::box(h, h, h, n);
        std::vector<Triangle> kept;
        for (const Triangle &t : m.triangles)
            if (!(m.vertices[t[0]].z() == h && m.vertices[t[1]].z() == h && m.vertices[t[2]].z() == h))
                kept.push_back(t);
        m.triangles = kept;
        m.source = "lidless box";
        return m;
    }

    /** \brief A disc of radius \e r in the plane z = 0 about the origin: a fan of \e k triangles (k rim edges). */
    Mesh disc(double r, int k)
    {
        Mesh m;
        m.source = "disc";
        m.vertices.emplace_back(0.0, 0.0, 0.0);
        for (int i = 0; i < k; ++i)
            m.vertices.emplace_back(r * std::cos(2 * M_PI * i / k), r * std::sin(2 * M_PI * i / k), 0.0);
        for (std::uint32_t i = 0; i < std::uint32_t(k); ++i)
            m.triangles.push_back({0u, 1 + i, 1 + (i + 1) % std::uint32_t(k)});
        return m;
    }

    /** \brief Three triangles on the edge (0,0,0)-(0,0,1), a "book" of three pages: 1 non-manifold edge, and each
        page's two other edges used once: 6 boundary edges. */
    Mesh book()
    {
        Mesh m;
        m.source = "book";
        for (const Eigen::Vector3d &v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0.5),
                                         Eigen::Vector3d(-0.5, 0.8, 0.5), Eigen::Vector3d(-0.5, -0.8, 0.5)})
            m.vertices.push_back(v);
        m.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}};
        return m;
    }

    /** \brief Two unit cubes sharing the edge x = y = 1 (corner to corner): that edge is used by four triangles,
        every other edge by two: 1 non-manifold edge, no boundary edge. Welded so the edge is one pair of vertices. */
    Mesh cubesOnAnEdge()
    {
        Mesh m = test::merged(test::transformed(test::box(0.5, 0.5, 0.5, 1), test::translation(0.5, 0.5, 0.5)),
                              test::transformed(test::box(0.5, 0.5, 0.5, 1), test::translation(1.5, 1.5, 0.5)));
        cleanMesh(m);
        return m;
    }

    DistanceResult exactAt(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB)
    {
        DistanceResult r;
        ExactSolver().solve(a, b, X_AB, DistanceRequest(), r);
        return r;
    }

    /** \brief The oracle of the depth against a closed box [-h, h]^3 (at the identity): the largest distance to the
        box's surface of \e body's nodes (placed by \e X) strictly inside it, or 0. */
    double deepestNodeInBox(const Body &body, const Eigen::Isometry3d &X, double h)
    {
        double deepest = 0.0;
        for (std::uint32_t i = 0; i < body.numNodes(); ++i)
        {
            const Eigen::Vector3d p = X * body.node(i);
            const double depth = h - p.cwiseAbs().maxCoeff();
            deepest = std::max(deepest, depth);
        }
        return deepest;
    }

    BodyPtr refined(const Mesh &m, double h)
    {
        BodyOptions options;
        options.gridSize = h;
        return Body::build(m, options);
    }

    /** \brief Collects OMPL warnings while alive. */
    class WarningCapture : public ompl::msg::OutputHandler
    {
    public:
        WarningCapture() : previousLevel_(ompl::msg::getLogLevel())
        {
            ompl::msg::useOutputHandler(this);
            ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
        }
        ~WarningCapture() override
        {
            ompl::msg::restorePreviousOutputHandler();
            ompl::msg::setLogLevel(previousLevel_);
        }
        void log(const std::string &text, ompl::msg::LogLevel level, const char * /*filename*/, int /*line*/) override
        {
            if (level >= ompl::msg::LOG_WARN)
                warnings.push_back(text);
        }
        std::vector<std::string> warnings;

    private:
        ompl::msg::LogLevel previousLevel_;
    };
}  // namespace

TEST(OpenMesh, EdgeCountsByHand)
{
    struct Case
    {
        Mesh mesh;
        std::size_t boundary, nonManifold;
    };
    const std::vector<Case> cases = {
        {test::box(1, 1, 1, 1), 0, 0},
        {test::box(1, 2, 3, 3), 0, 0},
        {test::icosphere(1.0, 2), 0, 0},
        {lidlessBox(1.0, 1), 4, 0},   // the lid's rim: 4 edges of one square
        {lidlessBox(1.0, 3), 12, 0},  // 4n with n = 3
        {disc(0.5, 12), 12, 0},       // the rim of the fan
        {test::grid(2.0, 1.0, 4, 2), 12, 0},  // 2 (nx + ny)
        {book(), 6, 1},
        {cubesOnAnEdge(), 0, 1},
        {test::merged(test::box(1, 1, 1, 1), disc(0.3, 5)), 5, 0},  // a closed part and an open one
    };
    for (const Case &c : cases)
    {
        SCOPED_TRACE(c.mesh.source + " with " + std::to_string(c.mesh.triangles.size()) + " triangles");
        const EdgeReport e = countEdges(c.mesh);
        EXPECT_EQ(e.boundaryEdges, c.boundary);
        EXPECT_EQ(e.nonManifoldEdges, c.nonManifold);
        const BodyPtr body = test::unrefinedBody(c.mesh);
        EXPECT_EQ(body->edges().boundaryEdges, c.boundary);
        EXPECT_EQ(body->edges().nonManifoldEdges, c.nonManifold);
        EXPECT_EQ(body->isClosed(), c.boundary == 0 && c.nonManifold == 0);
        // Refinement does not change the surface whose edges count.
        EXPECT_EQ(refined(c.mesh, 0.2)->isClosed(), body->isClosed());
    }
}

TEST(OpenMesh, LoaderCountsAndWarnsOncePerFile)
{
    // A new folder each time (the warning comes once per process for a file: a repeated test must not see none).
    static int call = 0;
    const fs::path dir = fs::temp_directory_path() /
                         ("meshgap_open_mesh_" + std::to_string(::getpid()) + "_" + std::to_string(call++));
    fs::create_directories(dir);
    struct Case
    {
        std::string name;
        Mesh mesh;
        std::size_t boundary, nonManifold;
    };
    // The world of two parts, a closed box and a box without a lid: one warning for the file, the counts summed.
    const std::vector<Case> cases = {
        {"closed.obj", test::box(1, 1, 1, 2), 0, 0},
        {"lidless.obj", lidlessBox(1.0, 2), 8, 0},
        {"book.obj", book(), 6, 1},
        {"two_parts.obj",
         test::merged(test::transformed(test::box(1, 1, 1, 1), test::translation(5, 0, 0)), lidlessBox(1.0, 1)), 4,
         0},
    };
    for (const Case &c : cases)
    {
        SCOPED_TRACE(c.name);
        const std::string path = (dir / c.name).string();
        writeObj(c.mesh, path);  // one vertex per corner: the loader's welding joins nothing new
        LoadReport report;
        WarningCapture capture;
        loadMesh(path, &report);
        EXPECT_EQ(report.edges.boundaryEdges, c.boundary);
        EXPECT_EQ(report.edges.nonManifoldEdges, c.nonManifold);
        if (c.boundary == 0 && c.nonManifold == 0)
        {
            EXPECT_TRUE(capture.warnings.empty()) << capture.warnings.front();
            continue;
        }
        ASSERT_EQ(capture.warnings.size(), 1u);
        const std::string &w = capture.warnings.front();
        EXPECT_NE(w.find(path), std::string::npos) << w;
        EXPECT_NE(w.find(std::to_string(c.boundary) + " boundary edges"), std::string::npos) << w;
        EXPECT_NE(w.find(std::to_string(c.nonManifold) + " non-manifold edges"), std::string::npos) << w;
        // Loaded again: counted again, not warned again.
        LoadReport again;
        loadMesh(path, &again);
        EXPECT_EQ(again.edges.boundaryEdges, c.boundary);
        EXPECT_EQ(capture.warnings.size(), 1u);
    }
    // The odd corpus's non-manifold file (three pages on one edge, its comment says): 1 and 6.
    LoadReport report;
    loadMesh(std::string(MESHGAP_TEST_RESOURCES_DIR) + "/odd/nonmanifold.obj", &report);
    EXPECT_EQ(report.edges.nonManifoldEdges, 1u);
    EXPECT_EQ(report.edges.boundaryEdges, 6u);
    fs::remove_all(dir);
}

TEST(OpenMesh, SheetThroughAClosedBox)
{
    // The box [-0.5, 0.5]^3 (closed) and a sheet in the plane z = 0.1 (open) crossing it.
    const double h = 0.5;
    const Mesh boxMesh = test::box(h, h, h, 2), sheetMesh = test::grid(2.0, 2.0, 1, 1);  // two triangles
    const BodyPtr box = test::unrefinedBody(boxMesh);
    const Eigen::Isometry3d X = test::translation(-1.0, -1.0, 0.1);
#ifdef MESHGAP_HAVE_FCL
    ASSERT_TRUE(test::fclCollide(test::fclModel(boxMesh), test::fclModel(sheetMesh), X));
#endif
    // Unrefined: the sheet's four corners are outside the box, no node of it is inside: contact, no depth.
    const BodyPtr coarse = test::unrefinedBody(sheetMesh);
    ASSERT_FALSE(coarse->isClosed());
    for (const DistanceResult &r : {exactAt(*box, *coarse, X), exactAt(*coarse, *box, X.inverse())})
    {
        EXPECT_TRUE(r.inCollision);
        EXPECT_TRUE(r.openBody);
        EXPECT_EQ(r.distance, CONTACT_DISTANCE);
        EXPECT_EQ(r.penetration, Penetration::NO_NODE_INSIDE);
        EXPECT_EQ(r.penetrationDepth, 0.0);
    }
    // Refined: the sheet's nodes inside the closed box count (the box has an inside); the box's nodes are never
    // "inside" the sheet. The depth is the deepest sheet node's, by brute force; at most 0.4, the lid's distance.
    const BodyPtr fine = refined(sheetMesh, 0.1);
    const double expected = deepestNodeInBox(*fine, X, h);
    ASSERT_GT(expected, 0.3);
    ASSERT_LE(expected, 0.4 + 1e-12);
    for (const DistanceResult &r : {exactAt(*box, *fine, X), exactAt(*fine, *box, X.inverse())})
    {
        EXPECT_TRUE(r.inCollision);
        EXPECT_TRUE(r.openBody);
        EXPECT_EQ(r.penetration, Penetration::DEEPEST_NODE);
        EXPECT_NEAR(r.penetrationDepth, expected, 1e-12);
        EXPECT_EQ(r.distance, -r.penetrationDepth);
    }
    // Wholly inside (a small sheet, no surface contact): the closed box contains it, a collision FCL does not see.
    const Mesh small = test::grid(0.4, 0.4, 2, 2);
    const Eigen::Isometry3d inside = test::translation(-0.2, -0.25, -0.1);
    const BodyPtr smallBody = refined(small, 0.1);
    const DistanceResult r = exactAt(*box, *smallBody, inside);
    EXPECT_TRUE(r.inCollision);
    EXPECT_TRUE(r.openBody);
    EXPECT_NEAR(r.penetrationDepth, deepestNodeInBox(*smallBody, inside, h), 1e-12);
#ifdef MESHGAP_HAVE_FCL
    EXPECT_FALSE(test::fclCollide(test::fclModel(boxMesh), test::fclModel(small), inside));
#endif
}

TEST(OpenMesh, ClosedBoxInsideABoxWithoutALid)
{
    // A closed box of half-side 0.25 inside [-1, 1]^3 without its lid z = 1: no inside, so no containment: free, at
    // the distance to the nearest wall or floor. The same box with its lid contains it: a collision.
    const Mesh open = lidlessBox(1.0, 2), closed = test::box(1.0, 1.0, 1.0, 2), small = test::box(0.25, 0.25, 0.25, 1);
    const BodyPtr openBox = test::unrefinedBody(open), closedBox = test::unrefinedBody(closed),
                  smallBox = Body::build(small);
    struct Case
    {
        Eigen::Isometry3d X;
        double gap;  // analytic: the nearest of x = +-1, y = +-1, z = -1
    };
    const std::vector<Case> cases = {
        {test::translation(0.1, -0.2, 0.05), std::min({1 - 0.1 - 0.25, 1 - 0.2 - 0.25, 1 + 0.05 - 0.25})},
        {test::translation(0.0, 0.3, 1.0), 1 - 0.3 - 0.25},    // through the open top: the lid would cut it
        {test::translation(-0.6, 0.0, -0.5), 1 - 0.6 - 0.25},  // near a wall
    };
#ifdef MESHGAP_HAVE_FCL
    const auto fclOpen = test::fclModel(open), fclSmall = test::fclModel(small);
#endif
    for (const Case &c : cases)
    {
        SCOPED_TRACE(c.X.translation().transpose());
        for (const DistanceResult &r : {exactAt(*openBox, *smallBox, c.X), exactAt(*smallBox, *openBox, c.X.inverse())})
        {
            EXPECT_FALSE(r.inCollision);
            EXPECT_TRUE(r.openBody);
            EXPECT_TRUE(r.certified);
            EXPECT_NEAR(r.distance, c.gap, 1e-12);
            EXPECT_EQ(r.penetration, Penetration::NONE);
        }
#ifdef MESHGAP_HAVE_FCL
        EXPECT_FALSE(test::fclCollide(fclOpen, fclSmall, c.X));
        EXPECT_NEAR(test::fclDistance(fclOpen, fclSmall, c.X), c.gap, 1e-9);
#endif
        const DistanceResult lid = exactAt(*closedBox, *smallBox, c.X);
        EXPECT_TRUE(lid.inCollision);
        EXPECT_FALSE(lid.openBody);
    }
}

TEST(OpenMesh, DiscOnAClosedBox)
{
    // A disc of radius 0.3 (open) on the top face z = 0.5 of the box [-0.5, 0.5]^3 (closed).
    const Mesh boxMesh = test::box(0.5, 0.5, 0.5, 2), discMesh = disc(0.3, 16);
    const BodyPtr box = test::unrefinedBody(boxMesh), d = refined(discMesh, 0.05);
#ifdef MESHGAP_HAVE_FCL
    const auto fb = test::fclModel(boxMesh), fd = test::fclModel(discMesh);
#endif
    // Lying on the face: touching, no node strictly inside: contact, depth 0.
    const Eigen::Isometry3d on = test::translation(0.1, 0.0, 0.5);
    const DistanceResult touching = exactAt(*box, *d, on);
    EXPECT_TRUE(touching.inCollision);
    EXPECT_TRUE(touching.openBody);
    EXPECT_EQ(touching.distance, CONTACT_DISTANCE);
    EXPECT_EQ(touching.penetration, Penetration::NO_NODE_INSIDE);
    // Lifted by 0.01: free, the gap.
    const Eigen::Isometry3d above = test::translation(0.1, 0.0, 0.51);
    const DistanceResult lifted = exactAt(*box, *d, above);
    EXPECT_FALSE(lifted.inCollision);
    EXPECT_TRUE(lifted.openBody);
    EXPECT_NEAR(lifted.distance, 0.01, 1e-12);
#ifdef MESHGAP_HAVE_FCL
    EXPECT_NEAR(test::fclDistance(fb, fd, above), 0.01, 1e-9);
#endif
    // Tilted through the face: collision, the depth of the disc's deepest node inside the box (brute force).
    Eigen::Isometry3d tilted = test::translation(0.0, 0.0, 0.5);
    tilted.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const DistanceResult crossing = exactAt(*box, *d, tilted);
    EXPECT_TRUE(crossing.inCollision);
    EXPECT_TRUE(crossing.openBody);
    EXPECT_EQ(crossing.penetration, Penetration::DEEPEST_NODE);
    EXPECT_NEAR(crossing.penetrationDepth, deepestNodeInBox(*d, tilted, 0.5), 1e-12);
    EXPECT_GT(crossing.penetrationDepth, 0.1);  // 0.3 sin(0.5) = 0.14 at the rim, less the mesh resolution
#ifdef MESHGAP_HAVE_FCL
    EXPECT_TRUE(test::fclCollide(fb, fd, tilted));
#endif
}

TEST(OpenMesh, TwoSheets)
{
    const Mesh sheet = test::grid(2.0, 1.0, 4, 2);
    const BodyPtr s = refined(sheet, 0.1);
    // Parallel, 0.3 apart and offset: free at the gap.
    const DistanceResult parallel = exactAt(*s, *s, test::translation(0.5, 0.2, 0.3));
    EXPECT_FALSE(parallel.inCollision);
    EXPECT_TRUE(parallel.openBody);
    EXPECT_NEAR(parallel.distance, 0.3, 1e-12);
    // Coplanar and overlapping: touching, no depth.
    const DistanceResult coplanar = exactAt(*s, *s, test::translation(0.5, 0.2, 0.0));
    EXPECT_TRUE(coplanar.inCollision);
    EXPECT_TRUE(coplanar.openBody);
    EXPECT_EQ(coplanar.distance, CONTACT_DISTANCE);
    EXPECT_EQ(coplanar.penetration, Penetration::OPEN_BODIES);
    // Crossing at right angles: no inside either, whatever the nodes.
    Eigen::Isometry3d X = test::translation(0.5, 0.5, -0.5);
    X.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const DistanceResult crossing = exactAt(*s, *s, X);
    EXPECT_TRUE(crossing.inCollision);
    EXPECT_EQ(crossing.penetration, Penetration::OPEN_BODIES);
    EXPECT_EQ(crossing.distance, CONTACT_DISTANCE);
#ifdef MESHGAP_HAVE_FCL
    const auto f = test::fclModel(sheet);
    EXPECT_NEAR(test::fclDistance(f, f, test::translation(0.5, 0.2, 0.3)), 0.3, 1e-9);
    EXPECT_TRUE(test::fclCollide(f, f, X));
#endif
}

TEST(OpenMesh, ClosedPairsAreNotFlagged)
{
    const BodyPtr a = Body::build(test::box(0.5, 0.7, 0.3, 2)), b = Body::build(test::icosphere(0.4, 2));
    std::size_t collisions = 0;
    for (std::uint32_t seed = 1; seed <= 60; ++seed)
    {
        const DistanceResult r = exactAt(*a, *b, test::randomPose(seed, 1.0));
        EXPECT_FALSE(r.openBody) << seed;
        collisions += r.inCollision;
    }
    EXPECT_GT(collisions, 0u);
    EXPECT_LT(collisions, 60u);
}

TEST(OpenMesh, SceneFlagsTheDecidingPair)
{
    // A world of two parts: a closed box about x = 5 and a box without a lid about the origin. A closed robot.
    const Mesh world =
        test::merged(test::transformed(test::box(1, 1, 1, 1), test::translation(5, 0, 0)), lidlessBox(1.0, 2));
    BodyOptions coarse;  // nodes every 0.5 at most: the fast mode's node search stays small
    coarse.gridSize = 0.5;
    const ScenePtr scene = Scene::fromMeshes(test::box(0.25, 0.25, 0.25, 1), world, coarse);
    ASSERT_EQ(scene->obstacles().size(), 2u);
    std::size_t openParts = 0;
    for (const BodyConstPtr &part : scene->obstacles())
        openParts += !part->isClosed();
    EXPECT_EQ(openParts, 1u);
    for (bool exact : {true, false})
    {
        SCOPED_TRACE(exact ? "exact" : "fast");
        SceneRequest request;
        request.exact = exact;
        SceneResult r;
        // Inside the open box: free, nearest the open part (the wall y = -1, 0.55 away).
        scene->distance(test::translation(0.1, -0.2, 0.05), request, r);
        EXPECT_FALSE(r.inCollision);
        EXPECT_TRUE(r.openBody);
        if (exact)
        {
            EXPECT_NEAR(r.distance, 0.55, 1e-12);
        }
        // Inside the closed box: a collision decided by the closed pair.
        scene->distance(test::translation(5.1, 0.0, 0.0), request, r);
        EXPECT_TRUE(r.inCollision);
        EXPECT_FALSE(r.openBody);
        // Beside the closed box, far from the open one: free, not flagged.
        scene->distance(test::translation(6.5, 0.0, 0.0), request, r);
        EXPECT_FALSE(r.inCollision);
        EXPECT_FALSE(r.openBody);
    }
    // An open robot: every answer is flagged.
    const ScenePtr discScene = Scene::fromMeshes(disc(0.2, 8), test::box(1, 1, 1, 1));
    SceneResult r;
    discScene->distance(test::translation(0.0, 0.0, 1.5), SceneRequest(), r);
    EXPECT_FALSE(r.inCollision);
    EXPECT_TRUE(r.openBody);
    EXPECT_NEAR(r.distance, 0.5, 1e-12);
}
