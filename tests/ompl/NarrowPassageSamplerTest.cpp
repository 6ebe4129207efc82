// The narrow-passage sampler returns only valid states (exact check), crowds them into a slot far more than
// uniform sampling does, and is selectable by name (unknown names list the valid ones), also from a cfg.

#include <gtest/gtest.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/NarrowPassageSampler.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/ompl/SamplerFactory.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;

namespace
{
    /** \brief A thick wall at x in [-0.5, 0.5] spanning the whole space but for a slot |y| < \e halfGap (default
        0.3), and a small box robot (half sizes 0.2 0.1 0.1) that fits through it only lying along x. */
    ob::SpaceInformationPtr slotProblem(double halfGap = 0.3)
    {
        const Mesh world =
            test::merged(test::transformed(test::box(0.5, 1.85, 3.0, 2), test::translation(0, halfGap + 1.85, 0)),
                         test::transformed(test::box(0.5, 1.85, 3.0, 2), test::translation(0, -halfGap - 1.85, 0)));
        auto space = test::se3Space(2);
        auto si = std::make_shared<ob::SpaceInformation>(space);
        si->setStateValidityChecker(
            std::make_shared<ClearanceChecker>(si, Scene::fromMeshes(test::box(0.2, 0.1, 0.1, 1), world)));
        si->setup();
        return si;
    }

    /** \brief Of \e n samples: how many lie in the slot (|x| < 0.5), after checking each is valid. */
    int inSlot(const ob::SpaceInformationPtr &si, ob::ValidStateSampler &sampler, int n)
    {
        const auto checker = std::static_pointer_cast<const ClearanceChecker>(si->getStateValidityChecker());
        ob::State *s = si->allocState();
        int count = 0, returned = 0;
        for (int i = 0; i < n; ++i)
        {
            if (!sampler.sample(s))
                continue;
            ++returned;
            EXPECT_TRUE(si->satisfiesBounds(s));
            EXPECT_FALSE(checker->scene().inCollision(poseFromState(*si->getStateSpace(), s))) << sampler.getName();
            count += std::abs(s->as<ob::SE3StateSpace::StateType>()->getX()) < 0.5;
        }
        EXPECT_GT(returned, n / 2) << sampler.getName();
        si->freeState(s);
        return count;
    }
}  // namespace

TEST(NarrowPassageSampler, ValidStatesCrowdedIntoTheSlot)
{
    const ob::SpaceInformationPtr si = slotProblem();
    NarrowPassageSampler narrow(si.get());
    const auto uniform = validStateSamplerAllocator("uniform")(si.get());
    const int n = 1000;
    const int narrowInSlot = inSlot(si, narrow, n), uniformInSlot = inSlot(si, *uniform, n);
    // The slot holds about 1.5 % of the valid states: uniform sampling puts a few there, the narrow-passage
    // sampler (pushing colliding samples out of the wall, then to the middle) many.
    EXPECT_GE(narrowInSlot, 2.5 * uniformInSlot + 20) << narrowInSlot << " vs " << uniformInSlot;
    std::printf("in the slot: narrow_passage %d, uniform %d of %d\n", narrowInSlot, uniformInSlot, n);
}

TEST(NarrowPassageSampler, SampleNearIsValidAndSucceedsWhereUniformGivesUp)
{
    // A slot barely wider than the robot (half gap 0.115 for its half width 0.1).
    const ob::SpaceInformationPtr si = slotProblem(0.115);
    const auto checker = std::static_pointer_cast<const ClearanceChecker>(si->getStateValidityChecker());
    NarrowPassageSampler narrow(si.get());
    const auto uniform = validStateSamplerAllocator("uniform")(si.get());
    ob::State *near = si->allocState(), *s = si->allocState();
    auto *se3 = near->as<ob::SE3StateSpace::StateType>();
    se3->rotation().setIdentity();
    const auto returned = [&](ob::ValidStateSampler &sampler, double distance, int n)
    {
        int count = 0;
        for (int i = 0; i < n; ++i)
            if (sampler.sampleNear(s, near, distance))
            {
                ++count;
                EXPECT_TRUE(si->satisfiesBounds(s)) << sampler.getName();
                EXPECT_FALSE(checker->scene().inCollision(poseFromState(*si->getStateSpace(), s))) << sampler.getName();
            }
        return count;
    };
    // From the slot's middle, within 0.3: some draws are free, most collide (a slot barely wider than the robot);
    // every state returned is valid by the exact test, pushed out or not.
    se3->setXYZ(0.0, 0.0, 0.0);
    ASSERT_FALSE(checker->scene().inCollision(poseFromState(*si->getStateSpace(), near)));
    const int inSlotNarrow = returned(narrow, 0.3, 100), inSlotUniform = returned(*uniform, 0.3, 100);
    std::printf("sampleNear from the slot: narrow_passage %d, uniform %d of 100\n", inSlotNarrow, inSlotUniform);
    // From inside the wall (x = 0, y = 1), within 0.05: every draw collides, so uniform sampling gives up each
    // time; the narrow-passage sampler pushes the last draw out of the wall (the nearest way out is along x, by
    // about 0.7), keeping y within the draw's 0.05 of the wall's state.
    se3->setXYZ(0.0, 1.0, 0.0);
    const int n = 50;
    EXPECT_EQ(returned(*uniform, 0.05, n), 0);
    int pushed = 0;
    for (int i = 0; i < n; ++i)
        if (narrow.sampleNear(s, near, 0.05))
        {
            ++pushed;
            const auto *p = s->as<ob::SE3StateSpace::StateType>();
            EXPECT_FALSE(checker->scene().inCollision(poseFromState(*si->getStateSpace(), s)));
            EXPECT_GT(std::abs(p->getX()), 0.5) << "out of the wall along x";
            EXPECT_NEAR(p->getY(), 1.0, 0.05 + 1e-9);
        }
    EXPECT_GE(pushed, n * 9 / 10);
    si->freeState(near);
    si->freeState(s);
}

TEST(NarrowPassageSampler, SelectableByNameFromTheCommandLineAndTheCfg)
{
    const ob::SpaceInformationPtr si = slotProblem();
    for (const std::string &name : validStateSamplerNames())
    {
        const ob::ValidStateSamplerPtr sampler = validStateSamplerAllocator(name)(si.get());
        ob::State *s = si->allocState();
        bool sampled = false;  // the bridge test may give up within its attempts: a few tries
        for (int attempt = 0; attempt < 20 && !sampled; ++attempt)
            sampled = sampler->sample(s);
        EXPECT_TRUE(sampled) << name;
        EXPECT_TRUE(si->isValid(s)) << name;
        si->freeState(s);
    }
    try
    {
        validStateSamplerAllocator("medial", "--sampler");
        ADD_FAILURE() << "no exception";
    }
    catch (const Exception &e)
    {
        const std::string what = e.what();
        EXPECT_NE(what.find("--sampler"), std::string::npos) << what;
        for (const char *name : {"uniform", "gaussian", "obstacle_based", "bridge_test", "max_clearance",
                                 "narrow_passage", "retraction", "workspace_medial"})
            EXPECT_NE(what.find(name), std::string::npos) << what;
    }

    // A cfg's [problem] sampler= key, as OMPL.app reads it.
    const fs::path dir = fs::temp_directory_path() / ("meshgap_sampler_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path map = fs::path(MESHGAP_SOURCE_DIR) / "maps" / "slotted_wall";
    std::string text;
    {
        std::ifstream in(map / "slotted_wall.cfg");
        for (std::string line; std::getline(in, line);)
        {
            if (line.rfind("robot", 0) == 0)
                line = "robot = " + (map / "slotted_wall_b.obj").string();
            else if (line.rfind("world", 0) == 0)
                line = "world = " + (map / "slotted_wall_a.obj").string() + "\nsampler = SAMPLER";
            text += line + "\n";
        }
    }
    for (const std::string &name : {std::string("narrow_passage"), std::string("bogus")})
    {
        std::string cfgText = text;
        cfgText.replace(cfgText.find("SAMPLER"), 7, name);
        const fs::path cfg = dir / (name + ".cfg");
        std::ofstream(cfg) << cfgText;
        if (name == "bogus")
        {
            try
            {
                setupProblem(readProblemConfig(cfg.string()), ClearanceChecker::Mode::CERTIFIED);
                ADD_FAILURE() << "no exception for sampler = bogus";
            }
            catch (const Exception &e)
            {
                EXPECT_NE(std::string(e.what()).find(cfg.string()), std::string::npos) << e.what();
                EXPECT_NE(std::string(e.what()).find("narrow_passage"), std::string::npos) << e.what();
            }
            continue;
        }
        const OmplProblem problem = setupProblem(readProblemConfig(cfg.string()), ClearanceChecker::Mode::CERTIFIED);
        EXPECT_EQ(problem.setup->getSpaceInformation()->allocValidStateSampler()->getName(), "narrow_passage");
    }
    fs::remove_all(dir);
}
