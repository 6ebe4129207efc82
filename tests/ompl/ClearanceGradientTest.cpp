// The clearance gradient against central finite differences of the exact clearance (at random poses where the
// clearance is smooth: forward and backward differences agree), free and in collision, on every map, the OMPL.app
// problems (skipped when absent) and a planar SE(2) scene; and at a tie built analytically (a robot equidistant
// from two walls), where the subgradient is the minimum-norm element of the two pairs' gradients.

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/RandomNumbers.h>

#include <filesystem>

#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceGradient.h"
#include "meshgap/ompl/ProblemSetup.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;

namespace
{
    /** \brief What checkGradients() compared. */
    struct Checked
    {
        int free{0}, colliding{0}, nonSmooth{0};
    };

    /** \brief A state uniformly at random within the bounds (SE(3): a uniform rotation; SE(2): a uniform yaw). */
    void sampleUniform(const ob::StateSpace &space, ompl::RNG &rng, ob::State *state)
    {
        if (space.getType() == ob::STATE_SPACE_SE2)
        {
            const ob::RealVectorBounds &b = space.as<ob::SE2StateSpace>()->getBounds();
            auto *s = state->as<ob::SE2StateSpace::StateType>();
            s->setXY(rng.uniformReal(b.low[0], b.high[0]), rng.uniformReal(b.low[1], b.high[1]));
            s->setYaw(rng.uniformReal(-M_PI, M_PI));
            return;
        }
        const ob::RealVectorBounds &b = space.as<ob::SE3StateSpace>()->getBounds();
        auto *s = state->as<ob::SE3StateSpace::StateType>();
        s->setXYZ(rng.uniformReal(b.low[0], b.high[0]), rng.uniformReal(b.low[1], b.high[1]),
                  rng.uniformReal(b.low[2], b.high[2]));
        double q[4];
        rng.quaternion(q);
        s->rotation().x = q[0];
        s->rotation().y = q[1];
        s->rotation().z = q[2];
        s->rotation().w = q[3];
    }

    /** \brief The clearance of \e state moved by \e h along tangent coordinate \e j. */
    double clearanceAlong(const ClearanceChecker &checker, const ob::State *state, unsigned j, double h, ob::State *tmp)
    {
        const ob::StateSpace &space = *checker.spaceInformation().getStateSpace();
        double step[6] = {0, 0, 0, 0, 0, 0};
        step[j] = h;
        applyTangentStep(space, state, step, tmp);
        return checker.clearance(tmp);
    }

    /** \brief At \e samples random states of the space (half of them near or in an obstacle), compare the gradient
        with central differences, coordinate by coordinate, where forward and backward differences agree. */
    Checked checkGradients(const ClearanceChecker &checker, int samples, std::uint32_t seed, const std::string &name)
    {
        const ob::SpaceInformation *si = &checker.spaceInformation();
        const ob::StateSpace &space = *si->getStateSpace();
        const unsigned dim = tangentDimension(space);
        const double L = checker.scene().robot().radiusAboutOrigin();
        const double h = 1e-5 * L;
        ompl::RNG rng(seed);  // a local generator: the global one may have been seeded already
        ob::State *state = si->allocState(), *tmp = si->allocState();
        std::vector<double> gradient;
        Checked checked;
        int attempts = 0;
        while (checked.free + checked.colliding < samples && ++attempts < 200 * samples)
        {
            sampleUniform(space, rng, state);
            const double c = checker.clearance(state);
            const bool colliding = c < 0.0;
            const int want = colliding ? checked.colliding : checked.free;
            // Keep free states near obstacles (where paths are) and colliding ones with a depth.
            if ((!colliding && c > 0.3 * L) || want >= samples / 2)
                continue;
            ClearanceGradientInfo info;
            const double c0 = clearanceGradient(checker, state, gradient, ClearanceGradientOptions(), &info);
            EXPECT_EQ(c0, c) << name;
            EXPECT_EQ(info.inCollision, colliding) << name;
            if (colliding && !info.hasDirection)
                continue;  // no depth: nothing to differentiate
            EXPECT_TRUE(info.hasDirection) << name;
            bool smooth = true;
            std::vector<double> central(dim);
            for (unsigned j = 0; j < dim && smooth; ++j)
            {
                const double hj = j < (dim == 3 ? 2u : 3u) ? h : h / L;
                const double plus = clearanceAlong(checker, state, j, hj, tmp);
                const double minus = clearanceAlong(checker, state, j, -hj, tmp);
                const double forward = (plus - c0) / hj, backward = (c0 - minus) / hj;
                // Scale rotation derivatives (length per radian) to lengths per robot radius.
                const double unit = j < (dim == 3 ? 2u : 3u) ? 1.0 : L;
                smooth = std::abs(forward - backward) / unit < 1e-4 && (plus < 0.0) == colliding &&
                         (minus < 0.0) == colliding;
                central[j] = (plus - minus) / (2.0 * hj);
            }
            if (!smooth || info.activePairs != 1)
            {
                ++checked.nonSmooth;
                continue;
            }
            for (unsigned j = 0; j < dim; ++j)
            {
                const double unit = j < (dim == 3 ? 2u : 3u) ? 1.0 : L;
                EXPECT_NEAR(gradient[j] / unit, central[j] / unit, 1e-5)
                    << name << (colliding ? " colliding" : " free") << " coordinate " << j << " clearance " << c0;
            }
            ++(colliding ? checked.colliding : checked.free);
        }
        si->freeState(state);
        si->freeState(tmp);
        return checked;
    }

    void checkProblem(const fs::path &cfg, int samples, int minColliding)
    {
        const OmplProblem problem = setupProblem(readProblemConfig(cfg.string()), ClearanceChecker::Mode::CERTIFIED);
        const Checked checked = checkGradients(*problem.checker, samples, 7, cfg.filename().string());
        std::printf("%s: %d free, %d colliding, %d non-smooth\n", cfg.filename().string().c_str(), checked.free,
                    checked.colliding, checked.nonSmooth);
        EXPECT_GE(checked.free, samples / 2) << cfg;
        EXPECT_GE(checked.colliding, minColliding) << cfg;
        EXPECT_LE(checked.nonSmooth, checked.free + checked.colliding) << cfg << ": mostly non-smooth samples";
    }
}  // namespace

TEST(ClearanceGradient, MatchesFiniteDifferencesOnTheMaps)
{
    for (const char *map : {"slotted_wall", "battery_fixture", "handshake", "hand_bowl"})
        checkProblem(fs::path(MESHGAP_SOURCE_DIR) / "maps" / map / (std::string(map) + ".cfg"), 16, 2);
}

TEST(ClearanceGradient, MatchesFiniteDifferencesOnOmplAppProblems)
{
    const fs::path dir = fs::path(MESHGAP_SHARED_DATA_DIR) / "omplapp";
    int found = 0;
    for (const char *name : {"Easy", "cubicles", "Twistycool", "bugtrap", "Abstract"})
        if (fs::exists(dir / (std::string(name) + ".cfg")))
        {
            ++found;
            // Open worlds: a depth only where a world node lies inside the robot, so fewer colliding samples.
            checkProblem(dir / (std::string(name) + ".cfg"), 12, 0);
        }
    if (found == 0)
        GTEST_SKIP() << "OMPL.app problems not found under " << dir << "; skipping";
}

TEST(ClearanceGradient, MatchesFiniteDifferencesInSe2)
{
    // Posts and a wall in the plane, an L-shaped robot turning about z.
    const Mesh world =
        test::merged(test::merged(test::transformed(test::box(0.2, 2.0, 0.5, 2), test::translation(0, 0, 0)),
                                  test::transformed(test::box(0.3, 0.3, 0.5, 1), test::translation(-2, 1.5, 0))),
                     test::transformed(test::icosphere(0.6, 2), test::translation(2, -1.5, 0)));
    const Mesh robot = test::merged(test::box(0.5, 0.1, 0.1, 1),
                                    test::transformed(test::box(0.1, 0.4, 0.1, 1), test::translation(-0.4, 0.3, 0)));
    auto space = std::make_shared<ob::SE2StateSpace>();
    ob::RealVectorBounds bounds(2);
    bounds.setLow(-4);
    bounds.setHigh(4);
    space->setBounds(bounds);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(robot, world));
    si->setStateValidityChecker(checker);
    si->setup();
    const Checked checked = checkGradients(*checker, 40, 3, "planar");
    EXPECT_GE(checked.free, 20);
    EXPECT_GE(checked.colliding, 5);
}

namespace
{
    /** \brief An octahedron |x| + |y| + |z| <= r: every closest point to an axis-aligned face is a vertex. */
    Mesh octahedron(double r)
    {
        Mesh m;
        m.vertices = {{r, 0, 0}, {-r, 0, 0}, {0, r, 0}, {0, -r, 0}, {0, 0, r}, {0, 0, -r}};
        m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
        m.source = "octahedron";
        return m;
    }

    /** \brief Two separate walls (two obstacles): one with its face at x = -1, one with its face at y = -1, and
        space for an octahedron of radius 0.5 at the origin, 0.5 from each: a tie. Returns the space information
        with the checker: the checker only points to it, so the caller keeps it alive. */
    std::pair<ob::SpaceInformationPtr, std::shared_ptr<ClearanceChecker>> cornerChecker(const ob::StateSpacePtr &space)
    {
        const Mesh wallX =
            test::transformed(test::box(0.5, 1.45, 2.0, 1), test::translation(-1.5, 0.55, 0));  // y from -0.9
        const Mesh wallY =
            test::transformed(test::box(1.475, 0.5, 2.0, 1), test::translation(0.525, -1.5, 0));  // x from -0.95
        auto si = std::make_shared<ob::SpaceInformation>(space);
        auto checker =
            std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(octahedron(0.5), test::merged(wallX, wallY)));
        si->setStateValidityChecker(checker);
        si->setup();
        return {si, checker};
    }
}  // namespace

TEST(ClearanceGradient, TieGivesTheMinimumNormSubgradient)
{
    auto space = test::se3Space(4);
    const auto [si, checker] = cornerChecker(space);
    ASSERT_EQ(checker->scene().obstacles().size(), 2u);
    ob::ScopedState<ob::SE3StateSpace> s(space), t(space);
    s->setXYZ(0, 0, 0);
    s->rotation().setIdentity();

    // By hand: the vertex (-0.5, 0, 0) is 0.5 from the face x = -1 (gradient (1, 0, 0) in translation, no rotation
    // term: the vertex lies on the line through the origin along the normal), the vertex (0, -0.5, 0) 0.5 from
    // y = -1 (gradient (0, 1, 0)). The minimum-norm element of their hull is (1/2, 1/2, 0, 0, 0, 0).
    std::vector<double> g;
    ClearanceGradientInfo info;
    const double c = clearanceGradient(*checker, s.get(), g, ClearanceGradientOptions(), &info);
    EXPECT_NEAR(c, 0.5, 1e-12);
    EXPECT_EQ(info.activePairs, 2u);
    const std::vector<double> expected = {0.5, 0.5, 0, 0, 0, 0};
    for (int j = 0; j < 6; ++j)
        EXPECT_NEAR(g[j], expected[j], 1e-9) << j;

    // One-sided derivatives: along any v, (c(x + h v) - c(x)) / h -> min(g1 . v, g2 . v); along the ascent step
    // it is at least ||g*||^2 (= 1/2): every tied pair rises.
    const double h = 1e-6;
    std::vector<double> step;
    ascentStep(g, checker->scene().robot().radiusAboutOrigin(), h, step);
    applyTangentStep(*space, s.get(), step.data(), t.get());
    EXPECT_GE((checker->clearance(t.get()) - c) / h, 0.5 - 1e-6);
    ompl::RNG rng(5);
    for (int i = 0; i < 50; ++i)
    {
        double v[6];
        for (double &x : v)
            x = rng.uniformReal(-1, 1);
        double hv[6];
        for (int j = 0; j < 6; ++j)
            hv[j] = h * v[j];
        applyTangentStep(*space, s.get(), hv, t.get());
        const double derivative = (checker->clearance(t.get()) - c) / h;
        // Rotations move the vertices tangentially to the faces: second order, so the translation part decides.
        EXPECT_NEAR(derivative, std::min(v[0], v[1]), 1e-5) << i;
        EXPECT_LE(derivative, g[0] * v[0] + g[1] * v[1] + 1e-5) << i;  // a supergradient of a min of smooth functions
    }

    // Off the tie (nearer the x wall) only that wall's pair is active, and the gradient is its own.
    s->setX(-0.01);
    clearanceGradient(*checker, s.get(), g, ClearanceGradientOptions(), &info);
    EXPECT_EQ(info.activePairs, 1u);
    EXPECT_NEAR(g[0], 1.0, 1e-12);
    EXPECT_NEAR(g[1], 0.0, 1e-12);
    // ... unless the tie tolerance covers the gap (an epsilon-subgradient).
    ClearanceGradientOptions wide;
    wide.tieTolerance = 0.02;
    clearanceGradient(*checker, s.get(), g, wide, &info);
    EXPECT_EQ(info.activePairs, 2u);
    EXPECT_NEAR(g[0], 0.5, 1e-9);
    EXPECT_NEAR(g[1], 0.5, 1e-9);
}

TEST(ClearanceGradient, TieInSe2AndBetweenEqualWalls)
{
    // SE(2): the same corner, the robot's origin in the plane z = 0; and the robot centred between the corner's
    // walls along the diagonal, the minimum-norm element again (1/2, 1/2, 0).
    auto space = std::make_shared<ob::SE2StateSpace>();
    ob::RealVectorBounds bounds(2);
    bounds.setLow(-4);
    bounds.setHigh(4);
    space->setBounds(bounds);
    const auto [si, checker] = cornerChecker(space);
    ob::ScopedState<ob::SE2StateSpace> s(space);
    s->setXY(0, 0);
    s->setYaw(0);
    std::vector<double> g;
    ClearanceGradientInfo info;
    EXPECT_NEAR(clearanceGradient(*checker, s.get(), g, ClearanceGradientOptions(), &info), 0.5, 1e-12);
    ASSERT_EQ(g.size(), 3u);
    EXPECT_EQ(info.activePairs, 2u);
    EXPECT_NEAR(g[0], 0.5, 1e-9);
    EXPECT_NEAR(g[1], 0.5, 1e-9);
    EXPECT_NEAR(g[2], 0.0, 1e-9);

    // Between two equal walls (faces at x = -1 and x = 1): the two gradients cancel, g* = 0: no step raises both.
    const Mesh left = test::transformed(test::box(0.5, 2.0, 2.0, 1), test::translation(-1.5, 0, 0));
    const Mesh right = test::transformed(test::box(0.5, 2.0, 2.0, 1), test::translation(1.5, 0, 0));
    auto si2 = std::make_shared<ob::SpaceInformation>(space);
    auto between =
        std::make_shared<ClearanceChecker>(si2, Scene::fromMeshes(octahedron(0.5), test::merged(left, right)));
    si2->setStateValidityChecker(between);
    si2->setup();
    EXPECT_NEAR(clearanceGradient(*between, s.get(), g, ClearanceGradientOptions(), &info), 0.5, 1e-12);
    EXPECT_EQ(info.activePairs, 2u);
    for (double x : g)
        EXPECT_NEAR(x, 0.0, 1e-9);
}

TEST(ClearanceGradient, RefusesFastModeAndOtherSpaces)
{
    auto space = test::se3Space(4);
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto fast = std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(octahedron(0.5), test::box(0.5, 0.5, 0.5, 1)),
                                                   ClearanceChecker::Mode::FAST);
    si->setStateValidityChecker(fast);
    si->setup();
    ob::ScopedState<ob::SE3StateSpace> s(space);
    s->setXYZ(2, 0, 0);
    s->rotation().setIdentity();
    std::vector<double> g;
    EXPECT_THROW(clearanceGradient(*fast, s.get(), g), Exception);
    EXPECT_THROW(tangentDimension(ob::RealVectorStateSpace(3)), Exception);
}

TEST(ClearanceGradient, ProbesFindATieWithinOneObstacle)
{
    // The two equal walls (faces at x = -1 and x = 1) as ONE obstacle: the per-obstacle tie test cannot see the
    // second pair, the exact query returns one of the two; a probe along its ascent direction meets the other wall.
    auto space = test::se3Space(4);
    const Mesh walls = test::merged(test::transformed(test::box(0.5, 2.0, 2.0, 1), test::translation(-1.5, 0, 0)),
                                    test::transformed(test::box(0.5, 2.0, 2.0, 1), test::translation(1.5, 0, 0)));
    auto si = std::make_shared<ob::SpaceInformation>(space);
    auto checker = std::make_shared<ClearanceChecker>(
        si, std::make_shared<Scene>(test::unrefinedBody(octahedron(0.5)),
                                    std::vector<BodyConstPtr>{test::unrefinedBody(walls)}));
    si->setStateValidityChecker(checker);
    si->setup();
    ob::ScopedState<ob::SE3StateSpace> s(space);
    s->setXYZ(0.01, 0, 0);  // 0.49 from the right wall, 0.51 from the left: no exact tie
    s->rotation().setIdentity();
    std::vector<double> g;
    ClearanceGradientInfo info;
    ClearanceGradientOptions options;
    EXPECT_NEAR(clearanceGradient(*checker, s.get(), g, options, &info), 0.49, 1e-12);
    EXPECT_EQ(info.activePairs, 1u);
    EXPECT_NEAR(g[0], -1.0, 1e-12);  // away from the right wall, into the left one's reach
    options.probes = 3;
    options.probeStep = 0.1;
    clearanceGradient(*checker, s.get(), g, options, &info);
    EXPECT_EQ(info.activePairs, 2u);
    EXPECT_EQ(info.probedPairs, 1u);
    EXPECT_NEAR(g[0], 0.0, 1e-9);  // the minimum-norm element of (-1, 0, 0) and (1, 0, 0)
    // A probe step too short to bring the left wall nearer than the right one: no pair found.
    options.probeStep = 0.005;
    clearanceGradient(*checker, s.get(), g, options, &info);
    EXPECT_EQ(info.activePairs, 1u);
    EXPECT_NEAR(g[0], -1.0, 1e-12);
}
