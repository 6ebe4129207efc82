// The retraction and workspace-medial samplers against analytic geometry: a rod that fits a square channel only
// lined up with it. The medial point of a point in the channel is on the channel's medial axis at its analytic
// radius; a tilted rod in collision is retracted to a free, better aligned pose; the passage samples lie in the
// channel far more often than uniform ones; every state returned is free by the exact test and within bounds.

#include <gtest/gtest.h>
#include <ompl/base/spaces/SE3StateSpace.h>

#include "TestMeshes.h"
#include "TestScale.h"
#include "TestSpaces.h"
#include "meshgap/ompl/RetractionSampler.h"
#include "meshgap/ompl/SamplerFactory.h"
#include "meshgap/ompl/WorkspaceMedialSampler.h"

using namespace meshgap;
namespace ob = ompl::base;

namespace
{
    constexpr double HALF_WIDTH = 0.16;  ///< the channel's half width (its walls at y, z = +-HALF_WIDTH)
    constexpr double HALF_LENGTH = 1.0;  ///< the channel runs along x over [-1, 1]

    /** \brief A block [-1, 1] x [-1.16, 1.16]^2 with a square channel of half width 0.16 along x through it (four
        wall boxes), in the cube [-2, 2]^3; the robot a rod of half sizes 0.5 x 0.1 x 0.1 (its corners 0.141 from
        its axis), which passes the channel only lined up with x, within about 0.04 rad. */
    ob::SpaceInformationPtr channelProblem()
    {
        const double t = 0.5, w = HALF_WIDTH;
        Mesh world = test::transformed(test::box(HALF_LENGTH, w + 2 * t, t, 2), test::translation(0, 0, w + t));
        world = test::merged(
            world, test::transformed(test::box(HALF_LENGTH, w + 2 * t, t, 2), test::translation(0, 0, -w - t)));
        world = test::merged(world, test::transformed(test::box(HALF_LENGTH, t, w, 2), test::translation(0, w + t, 0)));
        world =
            test::merged(world, test::transformed(test::box(HALF_LENGTH, t, w, 2), test::translation(0, -w - t, 0)));
        auto space = test::se3Space(2);
        auto si = std::make_shared<ob::SpaceInformation>(space);
        si->setStateValidityChecker(
            std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(test::box(0.5, 0.1, 0.1, 2), world)));
        si->setup();
        return si;
    }

    const ClearanceChecker &checkerOf(const ob::SpaceInformationPtr &si)
    {
        return static_cast<const ClearanceChecker &>(*si->getStateValidityChecker());
    }

    /** \brief The rod's axis (its x axis) in the world. */
    Eigen::Vector3d rodAxis(const ob::SpaceInformationPtr &si, const ob::State *s)
    {
        return poseFromState(*si->getStateSpace(), s).linear().col(0);
    }

    /** \brief The rod's centre lies within the channel's cross-section (in the channel, entering it, or in front
        of it on its axis line). */
    bool inChannel(const ob::State *s)
    {
        const auto *p = s->as<ob::SE3StateSpace::StateType>();
        return std::abs(p->getY()) < HALF_WIDTH && std::abs(p->getZ()) < HALF_WIDTH;
    }

    /** \brief In the channel's cross-section and lined up with it (within 0.3 rad). */
    bool linedUp(const ob::SpaceInformationPtr &si, const ob::State *s)
    {
        return inChannel(s) && std::abs(rodAxis(si, s).x()) > std::cos(0.3);
    }

    /** \brief Of \e n sample() calls: how many returned a state lined up in the channel or in front of it (each
       returned state checked free by the exact test and within bounds); \e returned counts the states returned. */
    int channelSamples(const ob::SpaceInformationPtr &si, ob::ValidStateSampler &sampler, int n, int &returned)
    {
        ob::State *s = si->allocState();
        int count = 0;
        returned = 0;
        for (int i = 0; i < n; ++i)
        {
            if (!sampler.sample(s))
                continue;
            ++returned;
            EXPECT_TRUE(si->satisfiesBounds(s)) << sampler.getName();
            EXPECT_FALSE(checkerOf(si).scene().inCollision(poseFromState(*si->getStateSpace(), s)))
                << sampler.getName();
            count += linedUp(si, s);
        }
        si->freeState(s);
        return count;
    }
}  // namespace

TEST(WorkspaceMedialSampler, RobotAxisOfARod)
{
    const RobotAxis a = RobotAxis::of(test::box(0.5, 0.1, 0.1, 3));
    EXPECT_NEAR(std::abs(a.direction.x()), 1.0, 1e-9);
    EXPECT_NEAR(a.centre.norm(), 0.0, 1e-9);
    EXPECT_NEAR(a.halfLength, 0.5, 1e-9);
    EXPECT_NEAR(a.radius, std::sqrt(0.02), 1e-9);  // the corners of its 0.2 x 0.2 cross-section
}

TEST(WorkspaceMedialSampler, MedialPointOfTheChannelIsOnItsMedialAxis)
{
    const ob::SpaceInformationPtr si = channelProblem();
    const WorkspaceMedialSampler sampler(si.get());
    Eigen::Vector3d nearest;
    // Point distances against the analytic ones (inside the channel: to the nearest wall).
    // (The point-sized probe is a tetrahedron of circumradius 1e-6 of the rod's cross-section radius.)
    EXPECT_NEAR(sampler.pointDistance(Eigen::Vector3d(0.3, 0.05, -0.02), nearest), HALF_WIDTH - 0.05, 1e-6);
    EXPECT_NEAR(nearest.y(), HALF_WIDTH, 1e-9);
    EXPECT_LE(sampler.pointDistance(Eigen::Vector3d(0.3, 0.4, 0.0), nearest), 0.0);  // inside a wall
    // The square channel's medial axis (away from its ends) is its two diagonals |y| = |z|, each point at distance
    // HALF_WIDTH - |y| from the walls; every medial point returned must be on it.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> across(-0.14, 0.14), along(-0.7, 0.7);
    int found = 0;
    for (int i = 0; i < 50; ++i)
    {
        const Eigen::Vector3d p(along(rng), across(rng), across(rng));
        Eigen::Vector3d m, n;
        double radius;
        if (!sampler.medialPoint(p, m, radius, n))
            continue;
        ++found;
        EXPECT_NEAR(m.x(), p.x(), 1e-6) << "moved along the wall's normal only";
        EXPECT_NEAR(std::abs(m.y()), std::abs(m.z()), 2e-3) << p.transpose() << " -> " << m.transpose();
        EXPECT_NEAR(radius, HALF_WIDTH - std::max(std::abs(m.y()), std::abs(m.z())), 1e-6);
        EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    }
    // Points whose medial point has perpendicular walls on its two sides (a square's corner bisector) are
    // rejected; the others must be on the medial axis as above.
    std::printf("medial points accepted: %d of 50\n", found);
    EXPECT_GE(found, 5);
}

TEST(WorkspaceMedialSampler, RetractionLinesATiltedRodUpWithTheChannel)
{
    const ob::SpaceInformationPtr si = channelProblem();
    RetractionSampler retraction(si.get());
    ob::State *s = si->allocState();
    int freed = 0;
    for (double tilt : {0.25, 0.3, 0.35, -0.28, -0.4})
    {
        auto *p = s->as<ob::SE3StateSpace::StateType>();
        p->setXYZ(0.1, 0.02, -0.01);
        const Eigen::Quaterniond q(Eigen::AngleAxisd(tilt, Eigen::Vector3d(0.0, 0.6, 0.8)));
        p->rotation().w = q.w();
        p->rotation().x = q.x();
        p->rotation().y = q.y();
        p->rotation().z = q.z();
        ASSERT_TRUE(checkerOf(si).scene().inCollision(poseFromState(*si->getStateSpace(), s))) << tilt;
        if (!retraction.retract(s))
            continue;
        ++freed;
        EXPECT_FALSE(checkerOf(si).scene().inCollision(poseFromState(*si->getStateSpace(), s))) << tilt;
        EXPECT_TRUE(si->satisfiesBounds(s));
        // Turned towards the channel's direction, not only pushed: better lined up than it started.
        if (inChannel(s))
        {
            EXPECT_GT(std::abs(rodAxis(si, s).x()), std::cos(std::abs(tilt)) + 0.01) << tilt;
        }
    }
    EXPECT_GE(freed, 4);
    si->freeState(s);
}

TEST(WorkspaceMedialSampler, PassageSamplesCrowdIntoTheChannel)
{
    const ob::SpaceInformationPtr si = channelProblem();
    WorkspaceMedialSampler medial(si.get());
    medial.setUniformProbability(0.0);  // passage samples only
    RetractionSampler retraction(si.get());
    const auto uniform = validStateSamplerAllocator("uniform")(si.get());
    const int n = test::scaled(200, 50);  // the counts below are shares of n
    int returnedMedial, returnedRetraction, returnedUniform;
    const int inMedial = channelSamples(si, medial, n, returnedMedial);
    const int inRetraction = channelSamples(si, retraction, n, returnedRetraction);
    const int inUniform = channelSamples(si, *uniform, n, returnedUniform);
    std::printf("lined up with the channel: workspace_medial %d of %d, retraction %d of %d, uniform %d of %d\n",
                inMedial, returnedMedial, inRetraction, returnedRetraction, inUniform, returnedUniform);
    // The channel is the only passage of the rod's size: most passage samples are lined up with it (in it, or in
    // front of it); such free states are a tiny part of the free space, which uniform sampling almost never hits.
    // sample() gives up after 2,000 draws of workspace points, of which about 0.3 % lie in the channel (the
    // space is 64 cubic units, the channel 0.2): a third of the calls or more return a state.
    EXPECT_GE(returnedMedial, n / 5);
    EXPECT_GE(inMedial, returnedMedial * 6 / 10);
    EXPECT_LE(inUniform, 4);
    // retraction turns colliding rods into line only where a draw starts across the channel: a few in 200 at most
    // (printed, not asserted: 0-4 depending on the random stream).
}
