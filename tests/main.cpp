#include <gtest/gtest.h>
#include <ompl/util/Console.h>

int main(int argc, char **argv)
{
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
