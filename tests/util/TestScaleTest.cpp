// The share of random cases the heavy randomized tests check (tests/TestScale.h): all of them unless
// MESHGAP_TEST_SCALE says less, never fewer than a test's own least, and a clear error for a value that is not a
// share.

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include "TestScale.h"

namespace
{
    /** \brief Sets MESHGAP_TEST_SCALE (or unsets it, for nullptr) for its lifetime, then puts back what was there. */
    class ScaleSetting
    {
    public:
        explicit ScaleSetting(const char *value)
        {
            if (const char *old = std::getenv("MESHGAP_TEST_SCALE"))
                old_ = old;
            if (value)
                ::setenv("MESHGAP_TEST_SCALE", value, 1);
            else
                ::unsetenv("MESHGAP_TEST_SCALE");
        }
        ScaleSetting(const ScaleSetting &) = delete;
        ScaleSetting &operator=(const ScaleSetting &) = delete;
        ~ScaleSetting()
        {
            if (old_)
                ::setenv("MESHGAP_TEST_SCALE", old_->c_str(), 1);
            else
                ::unsetenv("MESHGAP_TEST_SCALE");
        }

    private:
        std::optional<std::string> old_;
    };
}  // namespace

TEST(TestScale, FullCountsUnlessTheVariableSaysLess)
{
    {
        const ScaleSetting unset(nullptr);
        EXPECT_EQ(meshgap::test::scale(), 1.0);
        EXPECT_EQ(meshgap::test::scaled(300), 300);
        EXPECT_EQ(meshgap::test::scaledAtMost(300, 20), 300);  // the cap only under a smaller scale
        EXPECT_EQ(meshgap::test::stride(), 1);
    }
    {
        const ScaleSetting fifth("0.2");
        EXPECT_EQ(meshgap::test::scaled(300), 60);
        EXPECT_EQ(meshgap::test::scaled(3), 1);           // rounded up: never none
        EXPECT_EQ(meshgap::test::scaled(300, 100), 100);  // a test's own least
        EXPECT_EQ(meshgap::test::scaled(50, 100), 50);    // and never more than the full count
        EXPECT_EQ(meshgap::test::scaledAtMost(300, 20), 20);
        EXPECT_EQ(meshgap::test::scaledAtMost(300, 80), 60);     // a cap above the share changes nothing
        EXPECT_EQ(meshgap::test::scaledAtMost(300, 20, 30), 30);  // nor below the test's own least
        EXPECT_EQ(meshgap::test::stride(), 5);
    }
    for (const char *bad : {"0", "-0.5", "1.5", "fifth", "0.2x", "nan"})
    {
        const ScaleSetting setting(bad);
        try
        {
            meshgap::test::scale();
            ADD_FAILURE() << "MESHGAP_TEST_SCALE=" << bad << " accepted";
        }
        catch (const std::invalid_argument &e)
        {
            EXPECT_NE(std::string(e.what()).find(std::string("MESHGAP_TEST_SCALE='") + bad + "'"), std::string::npos)
                << e.what();
        }
    }
}
