#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "meshgap/Exception.h"

using namespace meshgap;

namespace
{
    // A unit square as two triangles whose corners are stored per face (as STL and flat-shaded DAE files do).
    Mesh soupSquare()
    {
        Mesh m;
        m.source = "soup";
        m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        m.triangles = {{0, 1, 2}, {3, 4, 5}};
        return m;
    }
}  // namespace

TEST(Mesh, CleanWeldsRepeatedCornersIntoOneComponent)
{
    Mesh m = soupSquare();
    EXPECT_EQ(countComponents(m), 2u);
    const CleanReport report = cleanMesh(m);
    EXPECT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.triangles.size(), 2u);
    EXPECT_EQ(countComponents(m), 1u);
    EXPECT_EQ(report.degenerate, 0u);
    EXPECT_EQ(report.duplicates, 0u);
}

TEST(Mesh, CleanDropsDegenerateAndDuplicatedTriangles)
{
    Mesh m = test::box(1, 1, 1, 1);
    const std::size_t faces = m.triangles.size();
    m.triangles.push_back({0, 0, 1});                                              // repeated index
    m.vertices.push_back((m.vertices[0] + m.vertices[1]) / 2);                     // collinear with 0 and 1
    m.triangles.push_back({0, 1, static_cast<std::uint32_t>(m.vertices.size() - 1)});
    m.triangles.push_back({m.triangles[0][2], m.triangles[0][1], m.triangles[0][0]});  // same face, other winding
    const CleanReport report = cleanMesh(m);
    EXPECT_EQ(report.degenerate, 2u);
    EXPECT_EQ(report.duplicates, 1u);
    EXPECT_EQ(report.unused, 1u);
    EXPECT_EQ(m.triangles.size(), faces);
    EXPECT_EQ(m.vertices.size(), 8u);
}

TEST(Mesh, ValidateNamesTheProblem)
{
    Mesh m = test::box(1, 1, 1, 1);
    m.source = "thing.obj";
    EXPECT_NO_THROW(m.validate());
    Mesh nan = m;
    nan.vertices[3].y() = std::nan("");
    try
    {
        nan.validate();
        FAIL() << "NaN accepted";
    }
    catch (const Exception &e)
    {
        EXPECT_NE(std::string(e.what()).find("thing.obj"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos);
    }
    Mesh index = m;
    index.triangles[2][1] = 99;
    EXPECT_THROW(index.validate(), Exception);
    Mesh empty = m;
    empty.triangles.clear();
    EXPECT_THROW(empty.validate(), Exception);
}

TEST(Mesh, BoundsSizeAndLongestEdge)
{
    const Mesh m = test::box(1, 2, 3, 1);
    EXPECT_DOUBLE_EQ(m.size(), std::sqrt(4.0 + 16.0 + 36.0));
    // The longest edge of the 1x1-grid box is a diagonal of its largest face (4 x 6).
    EXPECT_DOUBLE_EQ(longestEdge(m), std::sqrt(16.0 + 36.0));
}
