// Which certificate a query starts from (SceneWarmStart::choose()), and what that costs on the streams planners,
// samplers and data-labelling users make: a path, unrelated random poses, the two mixed, and two paths in two
// regions queried in turn. Cost is counted as work (box-pair and triangle tests, SceneResult), never as time, so the
// verdicts do not depend on the machine; the answers are checked against the cold query's, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>

#include "TestMeshes.h"
#include "TestNote.h"
#include "TestScale.h"
#include "meshgap/scene/Scene.h"

using namespace meshgap;

namespace
{
    Eigen::Isometry3d warmPose(double x, double y, double z, double angle = 0.0,
                               const Eigen::Vector3d &axis = Eigen::Vector3d::UnitZ())
    {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.translation() = Eigen::Vector3d(x, y, z);
        X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
        return X;
    }

    /** \brief An L-shaped robot (two boxes) among a dozen boxes and spheres in a 12-wide volume. */
    ScenePtr clutter()
    {
        const Mesh robot = test::merged(test::box(0.8, 0.15, 0.2, 2),
                                        test::transformed(test::box(0.15, 0.6, 0.2, 2), warmPose(0.65, 0.45, 0)));
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-5.0, 5.0), s(0.3, 1.0);
        Mesh world = test::icosphere(1.0, 2);
        for (int i = 0; i < 11; ++i)
        {
            const Mesh part = i % 2 ? test::box(s(rng), s(rng), s(rng), 2) : test::icosphere(s(rng), 2);
            world = test::merged(world, test::transformed(part, warmPose(u(rng), u(rng), u(rng), u(rng),
                                                                         Eigen::Vector3d(u(rng), u(rng), 1.0))));
        }
        BodyOptions options;
        options.gridSize = 0.3;
        return Scene::fromMeshes(robot, world, options);
    }

    Eigen::Isometry3d randomPose(std::mt19937 &rng)
    {
        std::uniform_real_distribution<double> u(-6.0, 6.0);
        std::normal_distribution<double> g;
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
        X.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
        return X;
    }

    /** \brief A motion through the clutter: \e steps + 1 poses from \e from to \e to (slerp for the rotation). */
    std::vector<Eigen::Isometry3d> line(const Eigen::Isometry3d &from, const Eigen::Isometry3d &to, std::size_t steps)
    {
        const Eigen::Quaterniond q0(from.linear()), q1(to.linear());
        std::vector<Eigen::Isometry3d> out;
        for (std::size_t i = 0; i <= steps; ++i)
        {
            const double f = static_cast<double>(i) / static_cast<double>(steps);
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() = q0.slerp(f, q1).toRotationMatrix();
            X.translation() = (1.0 - f) * from.translation() + f * to.translation();
            out.push_back(X);
        }
        return out;
    }

    struct StreamCost
    {
        std::vector<double> warm, cold;  ///< work per query
        SceneWarmStart start;
        explicit StreamCost(std::size_t capacity) : start(capacity) {}
    };

    double percentile(std::vector<double> v, double p)
    {
        std::sort(v.begin(), v.end());
        return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
    }

    double total(const std::vector<double> &v)
    {
        double t = 0.0;
        for (double x : v)
            t += x;
        return t;
    }

    /** \brief Every pose of \e poses asked warm (one warm start of \e capacity certificates carried along) and cold;
        the answers must agree bit for bit (verdict, signed distance, witnesses), and the work of each is kept. */
    StreamCost streamCostRun(const Scene &scene, const std::vector<Eigen::Isometry3d> &poses, std::size_t capacity)
    {
        StreamCost cost(capacity);
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            SceneResult w, c;
            scene.distance(poses[i], SceneRequest(), cost.start, w);
            scene.distance(poses[i], SceneRequest(), c);
            EXPECT_EQ(w.inCollision, c.inCollision) << "pose " << i;
            EXPECT_EQ(w.distance, c.distance) << "pose " << i;
            EXPECT_EQ(w.onA, c.onA) << "pose " << i;
            cost.warm.push_back(static_cast<double>(w.boxTests + w.triangleTests));
            cost.cold.push_back(static_cast<double>(c.boxTests + c.triangleTests));
        }
        return cost;
    }

    void note(std::ostream &out, const char *stream, std::size_t capacity, const StreamCost &c)
    {
        out << "[ warm     ] " << stream << ", " << capacity << " certificate(s): work p50 warm "
                     << percentile(c.warm, 0.5) << " / cold " << percentile(c.cold, 0.5) << ", p99 "
                     << percentile(c.warm, 0.99) << " / " << percentile(c.cold, 0.99) << ", total "
                     << total(c.warm) / total(c.cold) << " of cold; carried " << c.start.carried << ", written "
                     << c.start.written << ", cold " << c.start.cold << "\n";
    }

    /** \brief The robot's bounding sphere, as Scene passes it to choose(). */
    double robotRadius(const Scene &scene) { return scene.robot().bvh().nodes()[0].radius; }
}  // namespace

TEST(SceneWarmStart, ChoosesTheNearestCertificateByTheMotionBound)
{
    // A robot sphere of radius 1 about its origin: the motion bound of a pure translation is its length, so
    // COHERENCE radii is the line between carried and unrelated.
    const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    const double near = 0.9 * SceneWarmStart::COHERENCE, far = 1.5 * SceneWarmStart::COHERENCE;
    SceneWarmStart warm(2);
    using Use = SceneWarmStart::Use;
    auto at = [](double x, double y) { return warmPose(x, y, 0.0); };
    EXPECT_EQ(warm.choose(at(0, 0), centre, 1.0), Use::COLD);  // nothing known: cold, and nothing written
    EXPECT_EQ(warm.choose(at(near, 0), centre, 1.0), Use::WRITE);  // near the last pose: a run starts
    warm.stamp(at(near, 0));
    EXPECT_EQ(warm.choose(at(2 * near, 0), centre, 1.0), Use::CARRY);
    warm.stamp(at(2 * near, 0));
    EXPECT_EQ(warm.choose(at(10, 0), centre, 1.0), Use::COLD);  // a jump: unrelated, cold
    EXPECT_EQ(warm.choose(at(10 + near, 0), centre, 1.0), Use::WRITE);  // a second region: a second certificate
    warm.stamp(at(10 + near, 0));
    // Back to the first region: its certificate is chosen (swapped into use), then the second again.
    EXPECT_EQ(warm.choose(at(2 * near, near), centre, 1.0), Use::CARRY);
    EXPECT_TRUE(warm.pose.isApprox(at(2 * near, 0)));
    warm.stamp(at(2 * near, near));
    EXPECT_EQ(warm.choose(at(10 + near, near / 2), centre, 1.0), Use::CARRY);
    EXPECT_TRUE(warm.pose.isApprox(at(10 + near, 0)));
    warm.stamp(at(10 + near, near / 2));
    // A rotation counts by the distance it moves the sphere's points: a quarter turn moves them sqrt(2) radii.
    EXPECT_EQ(warm.choose(warmPose(10 + near, near / 2, 0, M_PI / 2), centre, 1.0), Use::COLD);
    // A third region with capacity 2: the least recently used certificate (the first region's) goes.
    EXPECT_EQ(warm.choose(at(-10, 0), centre, 1.0), Use::COLD);
    EXPECT_EQ(warm.choose(at(-10, far - near), centre, 1.0), Use::WRITE);
    warm.stamp(at(-10, far - near));
    EXPECT_EQ(warm.choose(at(2 * near, near), centre, 1.0), Use::COLD);
    EXPECT_EQ(warm.choose(at(10 + near, near), centre, 1.0), Use::CARRY);
    EXPECT_EQ(warm.carried, 4u);
    EXPECT_EQ(warm.written, 3u);
    EXPECT_EQ(warm.cold, 5u);
}

TEST(SceneWarmStart, NeverCostsMoreThanColdOnUnrelatedPosesAndPaysAlongPaths)
{
    const ScenePtr scene = clutter();
    // Under test::scale() < 1 a share of each stream: its first poses, at the same steps (what is carried along a
    // stream depends on its steps, not on its length), and one motion of the three.
    const auto share = [](std::size_t n) { return static_cast<std::size_t>(test::scaled(static_cast<int>(n), 200)); };
    std::mt19937 rng(11);
    std::vector<Eigen::Isometry3d> random;
    for (int i = 0; i < 300; ++i)
        random.push_back(randomPose(rng));
    // Paths: three motions across the clutter, steps of about 0.02 (a planner's motion checks).
    std::vector<Eigen::Isometry3d> path;
    for (int i = 0; i < test::scaled(3); ++i)
    {
        const auto segment = line(randomPose(rng), randomPose(rng), 400);
        path.insert(path.end(), segment.begin(), segment.end());
    }
    // Mixed: a path state, then an unrelated one, in turn (a sampler's draws between a motion's checks).
    std::vector<Eigen::Isometry3d> mixed;
    for (std::size_t i = 0; i < 400; ++i)
    {
        mixed.push_back(path[i]);
        mixed.push_back(random[i % random.size()]);
    }
    // Alternating: two motions in two regions, queried in turn (RRTConnect's two trees).
    std::vector<Eigen::Isometry3d> alternating;
    const auto first = line(warmPose(-5, -4, -3, 0.2), warmPose(-2, -1, -3, 1.0), 300),
               second = line(warmPose(4, 3, 2, -0.5), warmPose(1, 4, 3, 0.3), 300);
    for (std::size_t i = 0; i < first.size(); ++i)
    {
        alternating.push_back(first[i]);
        alternating.push_back(second[i]);
    }
    for (std::vector<Eigen::Isometry3d> *stream : {&random, &mixed, &alternating})
        stream->resize(share(stream->size()));

    std::ostringstream notes;
    for (std::size_t capacity : {1u, 4u})
    {
        const StreamCost r = streamCostRun(*scene, random, capacity), p = streamCostRun(*scene, path, capacity),
                         m = streamCostRun(*scene, mixed, capacity), a = streamCostRun(*scene, alternating, capacity);
        note(notes, "random", capacity, r);
        note(notes, "path", capacity, p);
        note(notes, "mixed", capacity, m);
        note(notes, "alternating", capacity, a);
        // Never hurts: on every stream the warm p99 and total work stay within 10% of cold's.
        for (const StreamCost *c : {&r, &p, &m, &a})
        {
            EXPECT_LE(percentile(c->warm, 0.99), 1.1 * percentile(c->cold, 0.99));
            EXPECT_LE(total(c->warm), 1.1 * total(c->cold));
        }
        // Unrelated poses are answered cold: the same work.
        EXPECT_GE(r.start.cold, random.size() * 9 / 10);
        // Along a path it pays.
        EXPECT_LT(total(p.warm), 0.6 * total(p.cold));
        EXPECT_GE(p.start.carried, path.size() * 9 / 10);
        if (capacity > 1)
        {
            // One certificate per region: the alternating stream is carried as a path is, and pays as much.
            EXPECT_GE(a.start.carried, alternating.size() * 9 / 10);
            EXPECT_LT(total(a.warm), 0.6 * total(a.cold));
            EXPECT_GE(m.start.carried, mixed.size() / 2 * 9 / 10);  // every path state but the first
        }
    }
    EXPECT_GT(robotRadius(*scene), 0.5);
    test::Note() << notes.str();
}
