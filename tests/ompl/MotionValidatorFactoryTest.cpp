// The motion validator factory: each name gives its validator's kind, for one rigid body and for a robot; an
// unknown name or a clearance validator on the fast checker throws, naming what was asked and what is valid.

#include <gtest/gtest.h>

#include <ompl/base/DiscreteMotionValidator.h>
#include <ompl/base/SpaceInformation.h>

#include "TestMeshes.h"
#include "TestSpaces.h"
#include "meshgap/Exception.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/RobotMotionValidator.h"
#include "meshgap/ompl/RobotStateSpace.h"
#include "meshgap/robot/RigidBodyRobot.h"
#include "robot/TestTree.h"

namespace ob = ompl::base;

namespace meshgap
{
    namespace
    {
        /** \brief The message of the meshgap::Exception \e f throws ("" when it throws none). */
        template <typename F>
        std::string thrown(F f)
        {
            try
            {
                f();
            }
            catch (const Exception &e)
            {
                return e.what();
            }
            return "";
        }

        ob::SpaceInformationPtr robotSpace(const RobotModel &robot)
        {
            ob::RealVectorBounds bounds(3);
            bounds.setLow(-1);
            bounds.setHigh(1);
            return std::make_shared<ob::SpaceInformation>(robotStateSpace(robot, bounds));
        }
    }  // namespace

    TEST(MotionValidatorFactory, NamesTheValidators)
    {
        EXPECT_EQ(motionValidatorNames(), (std::vector<std::string>{"discrete", "clearance"}));
        for (const std::string &name : motionValidatorNames())
            EXPECT_NO_THROW(checkMotionValidatorName(name));
    }

    TEST(MotionValidatorFactory, GivesEachKindForOneRigidBody)
    {
        const ScenePtr scene = Scene::fromMeshes(test::box(0.1, 0.1, 0.1), test::box(0.5, 0.5, 0.5));
        const auto si = std::make_shared<ob::SpaceInformation>(test::se3Space(4));
        const auto certified = std::make_shared<ClearanceChecker>(si, scene);
        const auto fast = std::make_shared<ClearanceChecker>(si, scene, ClearanceChecker::Mode::FAST);
        EXPECT_TRUE(std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(
            allocMotionValidator("discrete", si, certified)));
        EXPECT_TRUE(std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(allocMotionValidator("discrete", si, fast)));
        EXPECT_TRUE(std::dynamic_pointer_cast<ClearanceMotionValidator>(
            allocMotionValidator("clearance", si, certified)));
        const std::string error = thrown([&] { allocMotionValidator("clearance", si, fast, "--motion"); });
        EXPECT_NE(error.find("--motion"), std::string::npos) << error;
        EXPECT_NE(error.find("fast"), std::string::npos) << error;
    }

    TEST(MotionValidatorFactory, GivesEachKindForEveryKindOfRobot)
    {
        // A fixed-base tree with its payload, the same tree on a floating base, one rigid body as a robot: each has
        // certified motions and OMPL's discrete ones.
        UrdfOptions floating;
        floating.floatingBase = true;
        const RobotModelConstPtr robots[] = {
            test::treeWithPayload(), UrdfRobot::load(test::TREE_URDF, floating),
            std::make_shared<RigidBodyRobot>(Body::build(test::box(0.1, 0.1, 0.1)), RigidSpace::SE3)};
        for (const RobotModelConstPtr &robot : robots)
        {
            const auto scene = std::make_shared<RobotScene>(robot, test::postsAroundTree());
            const ob::SpaceInformationPtr si = robotSpace(*robot);
            EXPECT_TRUE(std::dynamic_pointer_cast<RobotMotionValidator>(allocMotionValidator("clearance", si, scene)));
            EXPECT_TRUE(std::dynamic_pointer_cast<ob::DiscreteMotionValidator>(
                allocMotionValidator("discrete", si, scene)));
        }
    }

    TEST(MotionValidatorFactory, AnUnknownNameThrowsNamingItAndTheValidNames)
    {
        const ScenePtr scene = Scene::fromMeshes(test::box(0.1, 0.1, 0.1), test::box(0.5, 0.5, 0.5));
        const auto si = std::make_shared<ob::SpaceInformation>(test::se3Space(4));
        const auto checker = std::make_shared<ClearanceChecker>(si, scene);
        const UrdfRobotPtr tree = test::treeWithPayload();
        const auto treeScene = std::make_shared<RobotScene>(tree, test::postsAroundTree());
        const ob::SpaceInformationPtr treeSi = robotSpace(*tree);
        for (const std::string &error :
             {thrown([&] { checkMotionValidatorName("sampled", "--motion"); }),
              thrown([&] { allocMotionValidator("sampled", si, checker, "--motion"); }),
              thrown([&] { allocMotionValidator("sampled", treeSi, treeScene, "--motion"); })})
        {
            EXPECT_NE(error.find("--motion"), std::string::npos) << error;
            EXPECT_NE(error.find("'sampled'"), std::string::npos) << error;
            EXPECT_NE(error.find("discrete, clearance"), std::string::npos) << error;
        }
    }
}  // namespace meshgap
