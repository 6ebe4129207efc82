// Planar (SE(2)) problems as OMPL.app's 2D cfgs give them: read, set up in an SE2StateSpace with the robot in the
// plane z = 0, planned with RRTConnect, and every state of the densely interpolated path free by FCL; the clearance
// motion validator bounds the SE(2) sweep (never accepts a motion that collides, dense check at 1/1000).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/RandomNumbers.h>

#include "FclOracle.h"
#include "TestMeshes.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "support/MeshWriter.h"

using namespace meshgap;
namespace fs = std::filesystem;
namespace ob = ompl::base;

namespace
{
    /** \brief A wall with a 1.0 wide gap at x = 0 (two boxes, z in [0, 1]) and a 1.2 x 0.4 box robot lying at
        z in [0, 1] (not centred in z: OMPL.app does not shift a planar robot in z). The robot starts and ends
        across the gap with its long side along y, so it must turn to pass. */
    class PlanarProblem : public ::testing::Test
    {
    protected:
        void SetUp() override
        {
            dir_ = fs::temp_directory_path() / ("meshgap_planar_" + std::to_string(::getpid()));
            fs::create_directories(dir_);
            world_ = test::merged(test::transformed(test::box(0.3, 2.25, 0.5, 1), test::translation(0, 2.75, 0.5)),
                                  test::transformed(test::box(0.3, 2.25, 0.5, 1), test::translation(0, -2.75, 0.5)));
            robotFile_ = test::transformed(test::box(0.6, 0.2, 0.5, 1), test::translation(0.25, 0.1, 0.5));
            writeObj(world_, (dir_ / "wall.obj").string());
            writeObj(robotFile_, (dir_ / "bar.obj").string());
            cfg_ = (dir_ / "gap.cfg").string();
            std::ofstream(cfg_) << "[problem]\nname = gap\nrobot = bar.obj\nworld = wall.obj\n"
                                   "start.x = -3\nstart.y = 0.5\nstart.theta = 1.5707963267948966\n"
                                   "goal.x = 3\ngoal.y = -0.5\ngoal.theta = -1.5707963267948966\n"
                                   "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n"
                                   "[planner]\nrrtconnect=\n";
            // The robot as OMPL.app's 2D problems place it, built here: shifted by its centre's x and y only.
            LoadReport report;
            LoadOptions centre;
            centre.omplAppCenter = true;
            Mesh robot = loadMesh((dir_ / "bar.obj").string(), &report, centre);
            const Eigen::Vector3d c = report.omplAppCenter.value();
            for (Eigen::Vector3d &v : robot.vertices)
                v -= Eigen::Vector3d(c.x(), c.y(), 0.0);
            fclWorld_ = test::fclModel(world_);
            fclRobot_ = test::fclModel(robot);
        }
        void TearDown() override { fs::remove_all(dir_); }

        /** \brief The robot pose of an SE(2) state, written out here (not poseFromState()). */
        static Eigen::Isometry3d pose(const ob::State *s)
        {
            const auto *se2 = s->as<ob::SE2StateSpace::StateType>();
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = Eigen::AngleAxisd(se2->getYaw(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
            X.translation() = Eigen::Vector3d(se2->getX(), se2->getY(), 0.0);
            return X;
        }

        fs::path dir_;
        std::string cfg_;
        Mesh world_, robotFile_;
        std::shared_ptr<test::FclModel> fclWorld_, fclRobot_;
    };
}  // namespace

TEST_F(PlanarProblem, SetsUpAnSe2SpaceWithTheRobotInThePlane)
{
    const ProblemConfig config = readProblemConfig(cfg_);
    ASSERT_TRUE(config.planar);
    const OmplProblem problem = setupProblem(config, ClearanceChecker::Mode::CERTIFIED);
    const auto &space = *problem.setup->getStateSpace();
    EXPECT_EQ(space.getType(), ob::STATE_SPACE_SE2);
    const auto bounds = space.as<ob::SE2StateSpace>()->getBounds();
    EXPECT_EQ(bounds.low, std::vector<double>({-5, -5}));
    EXPECT_EQ(bounds.high, std::vector<double>({5, 5}));
    // Not shifted in z: the robot's vertices keep the file's z range [0, 1].
    double zlo = 1e9, zhi = -1e9;
    for (const Eigen::Vector3d &v : problem.scene->robot().surface().vertices)
    {
        zlo = std::min(zlo, v.z());
        zhi = std::max(zhi, v.z());
    }
    EXPECT_DOUBLE_EQ(zlo, 0.0);
    EXPECT_DOUBLE_EQ(zhi, 1.0);
    const auto *start = problem.setup->getProblemDefinition()->getStartState(0)->as<ob::SE2StateSpace::StateType>();
    EXPECT_DOUBLE_EQ(start->getX(), -3.0);
    EXPECT_DOUBLE_EQ(start->getY(), 0.5);
    EXPECT_NEAR(start->getYaw(), M_PI / 2, 1e-12);
}

#ifdef MESHGAP_HAVE_FCL
TEST_F(PlanarProblem, RrtConnectPathIsFreeByFclAtEveryDenseState)
{
    for (const char *motion : {"discrete", "clearance"})
    {
        ompl::RNG::setSeed(5);
        OmplProblem problem = setupProblem(readProblemConfig(cfg_), ClearanceChecker::Mode::CERTIFIED);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        if (std::string(motion) == "clearance")
            si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si, problem.checker));
        problem.setup->setPlanner(std::make_shared<ompl::geometric::RRTConnect>(si));
        // solve() returns at the first solution (well under a second here); the limit is for sanitizer builds.
        ASSERT_EQ(problem.setup->solve(120.0), ob::PlannerStatus::EXACT_SOLUTION) << motion;
        ompl::geometric::PathGeometric path = problem.setup->getSolutionPath();
        path.interpolate(2000);
        bool turned = false;
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            const Eigen::Isometry3d X = pose(path.getState(i));
            ASSERT_FALSE(test::fclCollide(fclWorld_, fclRobot_, X)) << motion << " state " << i;
            // Crossing the wall (|x| < 0.3) is only possible with the long side turned towards x.
            if (std::abs(X.translation().x()) < 0.05)
                turned = turned || std::abs(std::cos(path.getState(i)->as<ob::SE2StateSpace::StateType>()->getYaw())) > 0.5;
        }
        EXPECT_TRUE(turned) << motion;
    }
}

TEST_F(PlanarProblem, ClearanceMotionValidatorNeverAcceptsACollidingSe2Motion)
{
    OmplProblem problem = setupProblem(readProblemConfig(cfg_), ClearanceChecker::Mode::CERTIFIED);
    const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
    si->setup();
    ClearanceMotionValidator validator(si, problem.checker);
    ompl::RNG::setSeed(13);
    ob::ScopedState<ob::SE2StateSpace> s1(si->getStateSpace()), s2(si->getStateSpace()), s(si->getStateSpace());
    int motions = 0, accepted = 0, colliding = 0;
    while (motions < 600)
    {
        s1.random();
        if (!problem.checker->isValid(s1.get()))
            continue;
        s2.random();
        if (motions % 3 != 0)
            si->getStateSpace()->interpolate(s1.get(), s2.get(), 0.2, s2.get());
        ++motions;
        bool collides = false;
        for (int k = 0; k <= 1000 && !collides; ++k)
        {
            si->getStateSpace()->interpolate(s1.get(), s2.get(), k / 1000.0, s.get());
            collides = test::fclCollide(fclWorld_, fclRobot_, pose(s.get()));
        }
        colliding += collides;
        const bool ok = validator.checkMotion(s1.get(), s2.get());
        accepted += ok;
        ASSERT_FALSE(ok && collides) << "accepted a colliding motion";
    }
    EXPECT_GT(colliding, 100);
    EXPECT_GT(accepted, 100);
}
#endif
