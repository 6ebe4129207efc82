// The one strict number parser, list splitter and name joiner (meshgap/Text.h), against std::strtod and hand cases.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"

using namespace meshgap;

TEST(Text, ParseNumberTakesWholeNumbersOnly)
{
    for (const char *text : {"0", "-1.5", "+2", "1e3", "1E-3", ".5", "5.", "0x1p3", "inf", "-inf", "nan"})
    {
        double x = 0.0;
        ASSERT_TRUE(parseNumber(text, x)) << text;
        const double oracle = std::strtod(text, nullptr);
        EXPECT_TRUE(x == oracle || (std::isnan(x) && std::isnan(oracle))) << text;
    }
    for (const char *text : {"", " 1", "1 ", "1.5x", "x", "1,5", "--1", "1e", "1e400", "-1e400"})
    {
        double x = 42.0;
        EXPECT_FALSE(parseNumber(text, x)) << "'" << text << "'";
        EXPECT_EQ(x, 42.0) << "a refused text leaves the value alone: '" << text << "'";
    }
}

TEST(Text, ParseFiniteNumberNamesTheTextAndWhatWasExpected)
{
    EXPECT_EQ(parseFiniteNumber("2.5", "here"), 2.5);
    for (const char *text : {"inf", "nan", "abc", ""})
    {
        try
        {
            parseFiniteNumber(text, "f.cfg:3", "x y theta");
            ADD_FAILURE() << text;
        }
        catch (const Exception &e)
        {
            EXPECT_EQ(std::string(e.what()), "f.cfg:3: '" + std::string(text) + "' is not a finite number (expected x y theta)");
        }
    }
}

TEST(Text, ParseUnsignedTakesDigitsThatFit)
{
    unsigned long n = 0;
    EXPECT_TRUE(parseUnsigned("0", n));
    EXPECT_EQ(n, 0u);
    EXPECT_TRUE(parseUnsigned("4096", n));
    EXPECT_EQ(n, 4096u);
    const std::string max = std::to_string(std::numeric_limits<unsigned long>::max());
    EXPECT_TRUE(parseUnsigned(max, n));
    EXPECT_EQ(n, std::numeric_limits<unsigned long>::max());
    for (const std::string &text : std::vector<std::string>{"", "-1", "+1", "1.0", "1e3", " 1", "12x", max + "0"})
        EXPECT_FALSE(parseUnsigned(text, n)) << "'" << text << "'";
}

TEST(Text, SplitListTrimsAndDropsEmptyItems)
{
    EXPECT_EQ(splitList("a,b,c"), (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(splitList(" a , b ,, c ,"), (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(splitList(""), std::vector<std::string>{});
    EXPECT_EQ(splitList(" , ,"), std::vector<std::string>{});
    EXPECT_EQ(splitList("comb-GA-wl"), std::vector<std::string>{"comb-GA-wl"});
}

TEST(Text, JoinNamesIsTheInverseOfSplitList)
{
    const std::vector<std::string> names = {"rrtconnect", "rrtstar", "prm"};
    EXPECT_EQ(joinNames(names), "rrtconnect, rrtstar, prm");
    EXPECT_EQ(splitList(joinNames(names)), names);
    EXPECT_EQ(joinNames({}), "");
    EXPECT_EQ(joinNames({"one"}), "one");
}

TEST(Text, ExcerptKeepsShortTextAndShortensLongTextAtBothEnds)
{
    EXPECT_EQ(excerpt("abc"), "abc");
    EXPECT_EQ(quote("abc"), "'abc'");
    EXPECT_EQ(quote(""), "''");
    const std::string limit(MAX_QUOTED, 'x');
    EXPECT_EQ(excerpt(limit), limit);
    const std::string path = "/" + std::string(5000, 'd') + "/mesh.obj";
    const std::string shown = excerpt(path);
    EXPECT_EQ(shown, "/" + std::string(149, 'd') + "..." + std::string(41, 'd') + "/mesh.obj (5010 characters)");
    EXPECT_EQ(quote(path),
              "'/" + std::string(149, 'd') + "..." + std::string(41, 'd') + "/mesh.obj' (5010 characters)");
    EXPECT_EQ(excerpt(std::string(1000, 'a'), 8), "aaaaaa...aa (1000 characters)");
    // Cut between UTF-8 characters, never inside one ("é" is two bytes).
    std::string accents;
    for (int k = 0; k < 200; ++k)
        accents += "\xc3\xa9";
    const std::string cut = excerpt(accents);
    EXPECT_EQ(cut, accents.substr(0, 150) + "..." + accents.substr(400 - 50) + " (400 characters)");
    const std::string odd = "x" + accents;  // every character boundary shifted by one byte
    EXPECT_EQ(excerpt(odd), odd.substr(0, 149) + "..." + odd.substr(401 - 50) + " (401 characters)");
}

TEST(Text, AnExceptionKeepsTheBeginningAndEndOfAnOverlongMessage)
{
    const std::string where = "scene.yaml:3";
    const std::string what = "unknown name '" + std::string(1000000, 'n') + "' (valid: a, b)";
    const std::string message = Exception(where, what).what();
    EXPECT_LE(message.size(), MAX_MESSAGE + 40);
    EXPECT_EQ(message.rfind(where + ": unknown name 'nnn", 0), 0u);
    EXPECT_NE(message.find("' (valid: a, b) (" + std::to_string(where.size() + 2 + what.size()) + " characters)"),
              std::string::npos);
    const std::string shortWhat = "a value is not a number";
    EXPECT_EQ(std::string(Exception(where, shortWhat).what()), where + ": " + shortWhat);
}
