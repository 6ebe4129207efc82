#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "meshgap/Exception.h"
#include "meshgap/scene/Pose.h"

using namespace meshgap;

TEST(Pose, QuaternionIsScalarLast)
{
    // 90 degrees about z: (qx qy qz qw) = (0 0 sin45 cos45); it maps x to y.
    const Eigen::Isometry3d X = parsePose("1 2 3 0 0 0.70710678118654752 0.70710678118654752", "test");
    EXPECT_TRUE((X * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 3, 3), 1e-12));
    EXPECT_TRUE(parsePose(formatPose(X), "again").isApprox(X, 1e-15));
}

TEST(Pose, RejectsBadText)
{
    for (const char *bad : {"1 2 3 0 0 0", "1 2 3 0 0 0 1 5", "1 2 x 0 0 0 1", "1 2 3 0 0 0 nan", "1 2 3 0 0 0 0",
                            "1 2 3 0 0 0 2", "1 2 3 0 0 0 1e"})
        EXPECT_THROW(parsePose(bad, "here"), Exception) << bad;
}

TEST(Pose, ReadPosesNamesFileAndLine)
{
    const std::string path = (std::filesystem::temp_directory_path() / "meshgap_pose_test.path").string();
    {
        std::ofstream out(path);
        out << "# comment\n0 0 0 0 0 0 1\n\n1 1 1 0 0 0 1\n1 1 1 0 0 0\n";
    }
    try
    {
        readPoses(path);
        FAIL();
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find(path + ":5"), std::string::npos) << e.what();
    }
    {
        std::ofstream out(path);
        out << "0 0 0 0 0 0 1\n1 1 1 0 0 0 1\n";
    }
    EXPECT_EQ(readPoses(path).size(), 2u);
    std::filesystem::remove(path);
}

TEST(Pose, AxisAngle)
{
    const Eigen::Isometry3d X = poseFromAxisAngle(Eigen::Vector3d(0, 0, 1), M_PI / 2, Eigen::Vector3d(0, 0, 2));
    EXPECT_TRUE((X * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(0, 1, 1), 1e-12));
}
