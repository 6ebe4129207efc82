#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <functional>
#include <limits>
#include <random>

#include "TestMeshes.h"
#include "meshgap/Exception.h"
#include "meshgap/FlatIndexSet.h"

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

    /** \brief cleanMesh() as its documentation says, in O(n^2): each vertex welded to the first vertex at an equal
        position (==), a triangle dropped if two of its welded corners are one vertex or twice its area is at most
        1e-12 times its longest edge squared (collinear within rounding), or if an earlier kept triangle has the same
        three vertices; then the vertices no kept triangle uses dropped, the rest kept in order. */
    CleanReport bruteForceClean(Mesh &m)
    {
        CleanReport report;
        const std::size_t n = m.vertices.size();
        std::vector<std::uint32_t> weldTo(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            weldTo[i] = static_cast<std::uint32_t>(i);
            for (std::size_t j = 0; j < i; ++j)
                if (m.vertices[j] == m.vertices[i])
                {
                    weldTo[i] = static_cast<std::uint32_t>(j);
                    break;
                }
        }
        std::vector<Triangle> kept;
        for (Triangle t : m.triangles)
        {
            for (std::uint32_t &index : t)
                index = weldTo[index];
            const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
            const double longest2 = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
            if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || (b - a).cross(c - a).norm() <= 1e-12 * longest2)
            {
                ++report.degenerate;
                continue;
            }
            bool repeated = false;
            for (const Triangle &k : kept)
            {
                Triangle x = k, y = t;
                std::sort(x.begin(), x.end());
                std::sort(y.begin(), y.end());
                repeated = repeated || x == y;
            }
            if (repeated)
            {
                ++report.duplicates;
                continue;
            }
            kept.push_back(t);
        }
        std::vector<bool> used(n, false);
        for (const Triangle &t : kept)
            for (std::uint32_t index : t)
                used[index] = true;
        std::vector<std::uint32_t> newIndex(n, UINT32_MAX);
        std::vector<Eigen::Vector3d> vertices;
        for (std::size_t i = 0; i < n; ++i)
        {
            if (used[i])
            {
                newIndex[i] = static_cast<std::uint32_t>(vertices.size());
                vertices.push_back(m.vertices[i]);
            }
            else if (weldTo[i] == i)
                ++report.unused;
        }
        for (Triangle &t : kept)
            for (std::uint32_t &index : t)
                index = newIndex[index];
        m.vertices = vertices;
        m.triangles = kept;
        return report;
    }

    /** \brief cleanMesh() of \e input equals bruteForceClean(): the vertices bit for bit (so a -0 kept where the
        first of its position has one), the triangles and the report. */
    void expectCleanEqualsBruteForce(const Mesh &input, const std::string &what)
    {
        Mesh fast = input, slow = input;
        const CleanReport got = cleanMesh(fast), want = bruteForceClean(slow);
        EXPECT_EQ(got.degenerate, want.degenerate) << what;
        EXPECT_EQ(got.duplicates, want.duplicates) << what;
        EXPECT_EQ(got.unused, want.unused) << what;
        ASSERT_EQ(fast.vertices.size(), slow.vertices.size()) << what;
        for (std::size_t i = 0; i < fast.vertices.size(); ++i)
            EXPECT_EQ(std::memcmp(fast.vertices[i].data(), slow.vertices[i].data(), 3 * sizeof(double)), 0)
                << what << ": vertex " << i << " (" << fast.vertices[i].transpose() << ") against ("
                << slow.vertices[i].transpose() << ")";
        EXPECT_EQ(fast.triangles, slow.triangles) << what;
    }

    /** \brief Triangles over \e m's vertices, at random: \e count of them, with repeated corners, repeats of
        earlier triangles in either winding, and collinear corners where the vertices allow. */
    void addRandomTriangles(Mesh &m, std::size_t count, std::mt19937 &rng)
    {
        std::uniform_int_distribution<std::uint32_t> vertex(0, static_cast<std::uint32_t>(m.vertices.size() - 1));
        std::uniform_int_distribution<int> kind(0, 9);
        for (std::size_t i = 0; i < count; ++i)
        {
            Triangle t{vertex(rng), vertex(rng), vertex(rng)};
            const int k = kind(rng);
            if (k == 0)
                t[2] = t[0];  // a repeated corner
            else if (k <= 2 && !m.triangles.empty())
            {
                t = m.triangles[std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng)];
                std::swap(t[0], t[k]);  // a repeat, the other winding (k = 1, 2)
            }
            else if (k == 3 && !m.triangles.empty())
                t = m.triangles[std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng)];
            m.triangles.push_back(t);
        }
    }

    /** \brief The component of each vertex by breadth-first search over the triangle edges, numbered in order of
        each component's first vertex. */
    std::vector<std::uint32_t> componentsByBreadthFirstSearch(const Mesh &m, std::uint32_t &count)
    {
        std::vector<std::vector<std::uint32_t>> neighbours(m.vertices.size());
        for (const Triangle &t : m.triangles)
            for (int k = 0; k < 3; ++k)
            {
                neighbours[t[k]].push_back(t[(k + 1) % 3]);
                neighbours[t[(k + 1) % 3]].push_back(t[k]);
            }
        std::vector<std::uint32_t> label(m.vertices.size(), UINT32_MAX);
        count = 0;
        for (std::uint32_t start = 0; start < m.vertices.size(); ++start)
        {
            if (label[start] != UINT32_MAX)
                continue;
            std::deque<std::uint32_t> queue{start};
            label[start] = count;
            while (!queue.empty())
            {
                const std::uint32_t v = queue.front();
                queue.pop_front();
                for (std::uint32_t w : neighbours[v])
                    if (label[w] == UINT32_MAX)
                    {
                        label[w] = count;
                        queue.push_back(w);
                    }
            }
            ++count;
        }
        return label;
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

TEST(Mesh, CleanEqualsBruteForceOnRandomSoups)
{
    for (unsigned seed = 1; seed <= 40; ++seed)
    {
        std::mt19937 rng(seed);
        // Positions from a small pool (each used many times, as a flat-shaded file repeats them), on a coarse
        // lattice so that some triples are collinear, and zeros of either sign.
        const int pool = 4 + static_cast<int>(seed % 7) * 6;
        std::uniform_int_distribution<int> lattice(-2, 2), pick(0, pool - 1);
        std::vector<Eigen::Vector3d> positions;
        for (int i = 0; i < pool; ++i)
            positions.emplace_back(0.5 * lattice(rng), 0.5 * lattice(rng), 0.25 * lattice(rng));
        Mesh m;
        m.source = "soup";
        const int vertices = 3 * pool + static_cast<int>(seed % 5) * 17;
        for (int i = 0; i < vertices; ++i)
        {
            Eigen::Vector3d p = positions[pick(rng)];
            for (int k = 0; k < 3; ++k)
                if (p[k] == 0.0 && rng() % 2 == 0)
                    p[k] = -0.0;
            m.vertices.push_back(p);
        }
        addRandomTriangles(m, 2 * vertices, rng);
        expectCleanEqualsBruteForce(m, "seed " + std::to_string(seed));
    }
}

TEST(Mesh, CleanEqualsBruteForceOnAdversarialInputs)
{
    std::mt19937 rng(7);
    std::vector<std::vector<Eigen::Vector3d>> cases;
    // Every sign of zero in every coordinate: one position.
    {
        std::vector<Eigen::Vector3d> v;
        for (int signs = 7; signs >= 0; --signs)
            v.emplace_back(signs & 1 ? -0.0 : 0.0, signs & 2 ? -0.0 : 0.0, signs & 4 ? -0.0 : 0.0);
        v.emplace_back(1, 0, 0);
        v.emplace_back(0, 1, 0);
        v.emplace_back(-0.0, 1, 0);
        cases.push_back(v);
    }
    // The coordinates' permutations and sign flips (equal under a hash that adds or xors the coordinates).
    {
        std::vector<Eigen::Vector3d> v;
        const double a = 0.1, b = 2.5, c = -7.0;
        for (int r = 0; r < 2; ++r)
            for (const Eigen::Vector3d &p : {Eigen::Vector3d(a, b, c), Eigen::Vector3d(b, c, a),
                                             Eigen::Vector3d(c, a, b), Eigen::Vector3d(b, a, c),
                                             Eigen::Vector3d(a, c, b), Eigen::Vector3d(c, b, a)})
            {
                v.push_back(p);
                v.push_back(-p);
                v.emplace_back(-p.x(), p.y(), p.z());
            }
        cases.push_back(v);
    }
    // Neighbours one unit in the last place apart, repeated: distinct positions that differ in one low bit.
    {
        std::vector<Eigen::Vector3d> v;
        double x = 1.0;
        for (int i = 0; i < 40; ++i, x = std::nextafter(x, 2.0))
            v.emplace_back(x, i % 2 == 0 ? 1.0 : std::nextafter(1.0, 0.0), 3.0);
        for (int i = 0; i < 40; ++i)
            v.push_back(v[static_cast<std::size_t>(rng() % 40)]);
        cases.push_back(v);
    }
    // Powers of two and values sharing their low bits (a table indexed by the bits' low end collides on them),
    // the smallest and largest magnitudes, denormals.
    {
        std::vector<Eigen::Vector3d> v;
        for (int e = -60; e <= 60; e += 3)
            v.emplace_back(std::ldexp(1.0, e), std::ldexp(1.0, -e), std::ldexp(3.0, e));
        v.emplace_back(std::numeric_limits<double>::denorm_min(), 0.0, 1.0);
        v.emplace_back(-std::numeric_limits<double>::denorm_min(), -0.0, 1.0);
        v.emplace_back(1e12, -1e12, std::numeric_limits<double>::min());
        const std::size_t distinct = v.size();
        for (std::size_t i = 0; i < 2 * distinct; ++i)
            v.push_back(v[rng() % distinct]);
        cases.push_back(v);
    }
    // Many vertices, all at few positions: long runs of equal keys.
    {
        std::vector<Eigen::Vector3d> v;
        for (int i = 0; i < 600; ++i)
            v.emplace_back(i % 3, (i / 3) % 2, -0.0);
        cases.push_back(v);
    }
    for (std::size_t c = 0; c < cases.size(); ++c)
    {
        Mesh m;
        m.source = "adversarial";
        m.vertices = cases[c];
        // Every index used at least once, then random triangles (repeats, repeated corners) over them.
        for (std::uint32_t i = 0; i + 2 < m.vertices.size(); i += 3)
            m.triangles.push_back({i, i + 1, i + 2});
        addRandomTriangles(m, 3 * m.vertices.size(), rng);
        expectCleanEqualsBruteForce(m, "case " + std::to_string(c));
    }
}

TEST(Mesh, FlatIndexSetKeepsTheFirstOfEqualKeysWhateverTheHashCollisions)
{
    // Keys 0..n-1 with n / 3 distinct values; hashes from one for all (every probe reads every slot, equal tags) to
    // few slots with distinct tags, and tags in the last slot (probes wrap around). The answer must be the first index of each value, as a linear search finds it.
    const std::size_t n = 300;
    std::vector<int> keys(n);
    std::mt19937 rng(3);
    for (int &k : keys)
        k = static_cast<int>(rng() % (n / 3));
    std::vector<std::uint32_t> first(n);
    for (std::size_t i = 0; i < n; ++i)
        first[i] = static_cast<std::uint32_t>(std::find(keys.begin(), keys.end(), keys[i]) - keys.begin());
    const std::vector<std::function<std::uint64_t(int)>> hashes = {
        [](int) { return std::uint64_t(0); },
        [](int k) { return std::uint64_t(k % 5) << 32; },
        [](int k) { return std::uint64_t(k % 4) * 16; },
        [](int k) { return ~std::uint64_t(0) - std::uint64_t(k); },
        [](int k) { return std::uint64_t(k % 7) << 61; }};
    for (std::size_t h = 0; h < hashes.size(); ++h)
    {
        FlatIndexSet set(h % 2 == 0 ? n : 0);  // sized for all, or doubling from 16 slots
        for (std::size_t i = 0; i < n; ++i)
            EXPECT_EQ(set.findOrInsert(hashes[h](keys[i]), static_cast<std::uint32_t>(i),
                                       [&](std::uint32_t j) { return keys[j] == keys[i]; }),
                      first[i])
                << "hash " << h << ", key " << i;
    }
}

TEST(Mesh, ComponentLabelsEqualABreadthFirstSearch)
{
    for (unsigned seed = 1; seed <= 30; ++seed)
    {
        std::mt19937 rng(seed);
        Mesh m;
        m.source = "random";
        const std::uint32_t n = 5 + seed * 7;
        for (std::uint32_t i = 0; i < n; ++i)
            m.vertices.emplace_back(i, 0, 0);
        // Few triangles over many vertices: many components, some vertices in none.
        std::uniform_int_distribution<std::uint32_t> vertex(0, n - 1);
        for (std::uint32_t t = 0; t < n / 3 + seed % 4; ++t)
            m.triangles.push_back({vertex(rng), vertex(rng), vertex(rng)});
        std::uint32_t count = 0, want = 0;
        const std::vector<std::uint32_t> label = labelComponents(m, count);
        EXPECT_EQ(label, componentsByBreadthFirstSearch(m, want)) << "seed " << seed;
        EXPECT_EQ(count, want) << "seed " << seed;
        EXPECT_EQ(countComponents(m), want) << "seed " << seed;
    }
}
