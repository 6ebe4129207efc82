#ifndef MESHGAP_FUZZ_FUZZ_TARGETS_H
#define MESHGAP_FUZZ_FUZZ_TARGETS_H

// The bodies of the libFuzzer targets in fuzz/, as plain functions so that tests/fuzz/FuzzRegressionTest.cpp replays
// the seed corpora and every crash input through exactly the same code in each test run.
//
// Contract checked by every target: bad input ends in a meshgap::Exception and nothing else (no crash, no UB under
// the sanitizers, no other exception type, no hang: sizes are bounded so one input takes milliseconds); input that
// is accepted gives an answer satisfying the invariants below. A broken invariant prints a line and throws
// Violation, which is not a meshgap::Exception: it escapes, so libFuzzer reports a crash (std::terminate -> abort)
// and the regression test a failure.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ompl/util/Console.h>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/distance/SolverFactory.h"
#include "meshgap/geometry/TriangleDistance.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/Mesh.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/scene/Pose.h"
#include "meshgap/scene/ProblemConfig.h"

namespace meshgap
{
    namespace fuzz
    {
        /** \brief An invariant the library broke on a fuzz input. */
        class Violation : public std::logic_error
        {
        public:
            using std::logic_error::logic_error;
        };

        [[noreturn]] inline void violation(const std::string &what)
        {
            std::fprintf(stderr, "meshgap fuzz: invariant violated: %s\n", what.c_str());
            std::fflush(stderr);
            throw Violation(what);
        }

        inline void check(bool ok, const std::string &what)
        {
            if (!ok)
                violation(what);
        }

        /** \brief What a target did with an input. */
        enum class Outcome
        {
            Rejected,  ///< a meshgap::Exception (bad input, said so)
            Accepted   ///< read and computed; every invariant held
        };

        /** \brief OMPL's console silenced for one input (the library warns about dropped triangles and such). */
        class QuietLog
        {
        public:
            QuietLog() : saved_(ompl::msg::getLogLevel()) { ompl::msg::setLogLevel(ompl::msg::LOG_NONE); }
            ~QuietLog() { ompl::msg::setLogLevel(saved_); }
            QuietLog(const QuietLog &) = delete;
            QuietLog &operator=(const QuietLog &) = delete;

        private:
            ompl::msg::LogLevel saved_;
        };

        /** \brief The fuzz bytes, consumed front to back; 0 once exhausted (so every input decodes to something). */
        class Bytes
        {
        public:
            Bytes(const std::uint8_t *data, std::size_t size) : p_(data), end_(data + size) {}
            std::uint8_t u8() { return p_ < end_ ? *p_++ : 0; }
            std::int8_t s8() { return static_cast<std::int8_t>(u8()); }
            double f64()
            {
                std::uint64_t bits = 0;
                for (int k = 0; k < 8; ++k)
                    bits = (bits << 8) | u8();
                double x;
                std::memcpy(&x, &bits, sizeof x);
                return x;
            }
            std::string rest() { return std::string(reinterpret_cast<const char *>(p_), reinterpret_cast<const char *>(end_)); }

        private:
            const std::uint8_t *p_, *end_;
        };

        /** \brief A coordinate: mostly a grid value (k/16 in [-7, 7], so coincident, collinear and coplanar corners are
            common), sometimes a hostile one (signed zero, denormal, huge, NaN, infinity, raw bits). */
        inline double coordinate(Bytes &in)
        {
            const std::uint8_t b = in.u8();
            if (b < 224)
                return (double(b) - 112.0) / 16.0;
            constexpr double inf = std::numeric_limits<double>::infinity();
            switch (b - 224)
            {
                case 0: return -0.0;
                case 1: return 1e-300;
                case 2: return -1e-300;
                case 3: return std::numeric_limits<double>::denorm_min();
                case 4: return 1e300;
                case 5: return -1e300;
                case 6: return std::numeric_limits<double>::max();
                case 7: return -std::numeric_limits<double>::max();
                case 8: return std::numeric_limits<double>::quiet_NaN();
                case 9: return inf;
                case 10: return -inf;
                case 11: return 1e-9;
                case 12: return 1.0 + std::numeric_limits<double>::epsilon();
                case 13: return 1e8;
                case 14: return 1.0 / 3.0;
                case 15: return 0.1;
                default: return in.f64();
            }
        }

        inline bool isRotation(const Eigen::Matrix3d &R)
        {
            return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-9 &&
                   R.determinant() > 0.0;
        }

        inline bool isPose(const Eigen::Isometry3d &X)
        {
            return X.translation().allFinite() && isRotation(X.linear());
        }

        /** \brief A folder of this process for files the readers need (/dev/shm when there is one), removed at exit.
            Holds robot.obj and world.obj, so .cfg inputs can name existing meshes. */
        inline const std::filesystem::path &scratchDir()
        {
            namespace fs = std::filesystem;
            static const fs::path dir = [] {
                std::error_code ec;
                const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
                const fs::path d = base / ("meshgap-fuzz-" + std::to_string(::getpid()));
                fs::create_directories(d);
                for (const char *name : {"robot.obj", "world.obj"})
                    std::ofstream(d / name) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
                std::atexit([] {
                    std::error_code ignored;
                    fs::remove_all(scratchDir(), ignored);
                });
                return d;
            }();
            return dir;
        }

        inline std::string writeScratch(const std::string &name, const std::string &bytes)
        {
            const std::string path = (scratchDir() / name).string();
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
            return path;
        }

        /** \brief What every cleaned mesh must be: indices in range, no repeated corner, no duplicated triangle,
            every vertex used, all coordinates finite. */
        inline void checkCleanMesh(const Mesh &mesh, const std::string &what)
        {
            std::vector<char> used(mesh.vertices.size(), 0);
            std::vector<Triangle> sorted;
            for (const Triangle &t : mesh.triangles)
            {
                for (std::uint32_t i : t)
                {
                    check(i < mesh.vertices.size(), what + ": index out of range after cleaning");
                    used[i] = 1;
                }
                check(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], what + ": repeated corner after cleaning");
                Triangle key = t;
                std::sort(key.begin(), key.end());
                sorted.push_back(key);
            }
            std::sort(sorted.begin(), sorted.end());
            check(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(),
                  what + ": duplicated triangle after cleaning");
            for (std::size_t i = 0; i < used.size(); ++i)
                check(used[i] && mesh.vertices[i].allFinite(), what + ": unused or non-finite vertex after cleaning");
        }

        /** \brief cleanMesh() keeps the input's triangles (as positions, in order and winding) minus the dropped ones. */
        inline void checkCleaning(const Mesh &before, const Mesh &after, const CleanReport &report)
        {
            checkCleanMesh(after, "cleanMesh");
            check(report.degenerate + report.duplicates + after.triangles.size() == before.triangles.size(),
                  "cleanMesh: kept + dropped != input triangles");
            std::size_t j = 0;
            for (const Triangle &t : after.triangles)
            {
                auto same = [&](const Triangle &s) {
                    for (int k = 0; k < 3; ++k)
                        if (!(before.vertices[s[k]] == after.vertices[t[k]]))
                            return false;
                    return true;
                };
                while (j < before.triangles.size() && !same(before.triangles[j]))
                    ++j;
                check(j < before.triangles.size(), "cleanMesh: a kept triangle is not an input triangle, in order");
                ++j;
            }
        }

        /** \brief Body invariants: refinement reached the grid size, node maps and the surface graph are
            consistent, and (for small bodies) the mesh distances are a metric along real paths. */
        inline void checkBody(const Body &body)
        {
            const Mesh &m = body.mesh();
            checkCleanMesh(body.surface(), "Body::surface");
            check(body.numNodes() == m.vertices.size() && body.graph().numNodes() == body.numNodes(),
                  "Body: node counts differ");
            for (const Triangle &t : m.triangles)
                for (std::uint32_t i : t)
                    check(i < m.vertices.size(), "refineMesh: index out of range");
            for (const Eigen::Vector3d &v : m.vertices)
                check(v.allFinite(), "refineMesh: non-finite node");
            if (body.gridSize() > 0.0)
                check(body.refinement().longestEdge <= body.gridSize() * (1.0 + 1e-9),
                      "refineMesh: an edge is longer than the grid size");
            for (std::uint32_t i = 0; i < body.numNodes(); ++i)
            {
                check(body.beginNodeTriangles(i) != body.endNodeTriangles(i), "Body: a node lies on no triangle");
                for (const std::uint32_t *t = body.beginNodeTriangles(i); t != body.endNodeTriangles(i); ++t)
                    check(*t < body.surface().triangles.size(), "Body: node triangle out of range");
            }
            const SurfaceGraph &g = body.graph();
            for (std::size_t k = 0; k < g.neighbours().size(); ++k)
                check(g.neighbours()[k] < g.numNodes() && g.lengths()[k] >= 0.0, "SurfaceGraph: bad edge");
            check(g.numComponents() == countComponents(m), "SurfaceGraph: component count differs from the mesh's");

            // Mesh distances: the dense table only for small bodies (Dijkstra from every node is slow under the
            // sanitizers), the on-demand searches otherwise.
            if (body.distances().isDense() && body.numNodes() > 64)
                return;
            const MeshDistances &D = body.distances();
            std::vector<std::uint32_t> path;
            const std::uint32_t n = body.numNodes();
            for (std::uint32_t u = 0; u < std::min<std::uint32_t>(n, 4); ++u)
                for (std::uint32_t v = 0; v < n; ++v)
                {
                    const double d = D.distance(u, v);
                    check(!std::isnan(d) && d >= 0.0 && (u != v || d == 0.0), "MeshDistances: bad distance");
                    const bool connected = g.component(u) == g.component(v);
                    check(connected || d == std::numeric_limits<double>::infinity(),
                          "MeshDistances: finite distance between components");
                    D.path(u, v, path);
                    if (!connected)
                    {
                        check(path.empty(), "MeshDistances: a path between components");
                        continue;
                    }
                    check(!path.empty() && path.front() == u && path.back() == v, "MeshDistances: path ends wrong");
                    double length = 0.0;
                    for (std::size_t k = 0; k + 1 < path.size(); ++k)
                    {
                        const std::uint32_t *b = g.beginNeighbours(path[k]), *e = g.endNeighbours(path[k]);
                        check(std::find(b, e, path[k + 1]) != e, "MeshDistances: path steps off the mesh edges");
                        length += (m.vertices[path[k]] - m.vertices[path[k + 1]]).norm();
                    }
                    if (std::isfinite(d))
                        check(std::abs(length - d) <= 1e-9 * (1.0 + d), "MeshDistances: path length != distance");
                }
        }

        /** \brief Grid size for a fuzzed body: the library default, none, or a fraction of the longest edge or of
            the body's size (never below 1/9 of either, so refinement stays small). */
        inline double gridSize(std::uint8_t choice, const Mesh &mesh)
        {
            switch (choice % 4)
            {
                case 0: return -1.0;
                case 1: return 0.0;
                case 2: return longestEdge(mesh) / (1 + (choice >> 2) % 8);
                default: return mesh.size() / (2 + (choice >> 2) % 8);
            }
        }

        /** \brief Raw vertices and triangles -> validate, cleanMesh, validate, Body (refinement, BVH, surface
            graph, mesh distances). Up to 24 vertices and 24 triangles, indices may be out of range. */
        inline Outcome mesh(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            Bytes in(data, size);
            const std::uint8_t options = in.u8();
            const std::size_t nv = 1 + in.u8() % 24, nt = in.u8() % 25;
            Mesh m;
            m.source = "fuzz-mesh";
            for (std::size_t i = 0; i < nv; ++i)
            {
                const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
                m.vertices.emplace_back(x, y, z);
            }
            for (std::size_t t = 0; t < nt; ++t)
            {
                Triangle tri;
                for (std::uint32_t &i : tri)
                {
                    const std::uint8_t b = in.u8();
                    i = b == 255 ? UINT32_MAX : static_cast<std::uint32_t>(b % (nv + 2));
                }
                m.triangles.push_back(tri);
            }
            try
            {
                m.validate();
                const Mesh before = m;
                const CleanReport report = cleanMesh(m);
                checkCleaning(before, m, report);
                m.validate();  // throws if every triangle was dropped
                BodyOptions o;
                o.gridSize = gridSize(options, m);
                o.distances.threads = 1;
                if (options & 0x80)
                    o.distances.memoryBudgetBytes = 0;  // on-demand searches
                else
                    o.distances.memoryBudgetBytes = MeshDistances::denseTableBytes(64);
                checkBody(*Body::build(m, o));
                return Outcome::Accepted;
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
        }

        /** \brief The bytes after the first as a file with extension obj, stl or ply (chosen by the first byte, as is
            whether OMPL.app's centre is asked for) through loadMesh() (assimp, then our welding and cleaning). */
        inline Outcome loader(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            static const char *const extensions[] = {"obj", "stl", "ply"};
            const std::string ext = extensions[size > 0 ? data[0] % 3 : 0];
            const std::string path = writeScratch(
                "input." + ext, size > 0 ? std::string(reinterpret_cast<const char *>(data) + 1, size - 1) : "");
            try
            {
                LoadReport report;
                LoadOptions options;
                options.omplAppCenter = size > 0 && (data[0] / 3) % 2 == 1;
                const Mesh m = loadMesh(path, &report, options);
                m.validate();
                check(report.omplAppCenter.has_value() == options.omplAppCenter,
                      "loadMesh: the centre is there exactly when asked for");
                checkCleanMesh(m, "loadMesh");
                check(!m.triangles.empty(), "loadMesh: returned no triangles");
                check(report.clean.degenerate + report.clean.duplicates + m.triangles.size() == report.rawTriangles,
                      "loadMesh: kept + dropped != triangles read");
                check(report.components == countComponents(m), "loadMesh: component count");
                return Outcome::Accepted;
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
        }

        /** \brief The bytes as a .cfg (in a folder that holds robot.obj and world.obj) through readProblemConfig(). */
        inline Outcome config(const std::uint8_t *data, std::size_t size)
        {
            const std::string path =
                writeScratch("problem.cfg", std::string(reinterpret_cast<const char *>(data), size));
            try
            {
                const ProblemConfig c = readProblemConfig(path);
                check(isPose(c.start), "readProblemConfig: start is not a finite rigid pose");
                check(!c.goal || isPose(*c.goal), "readProblemConfig: goal is not a finite rigid pose");
                check(!c.volume || (c.volume->min().allFinite() && c.volume->max().allFinite() &&
                                    (c.volume->min().array() <= c.volume->max().array()).all()),
                      "readProblemConfig: bad volume");
                check(std::filesystem::exists(c.robot) && std::filesystem::exists(c.world),
                      "readProblemConfig: a mesh path that does not exist");
                check(!c.objectiveThreshold || std::isfinite(*c.objectiveThreshold),
                      "readProblemConfig: non-finite objective.threshold");
                return Outcome::Accepted;
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
        }

        inline void checkParsedPose(const Eigen::Isometry3d &X, const std::string &what)
        {
            check(isPose(X), what + ": not a finite rigid pose");
            const Eigen::Isometry3d again = parsePose(formatPose(X), "formatPose");  // must not throw
            const double scale = 1.0 + X.translation().cwiseAbs().maxCoeff();
            check((again.matrix() - X.matrix()).cwiseAbs().maxCoeff() <= 1e-12 * scale,
                  what + ": formatPose/parsePose does not round-trip");
        }

        /** \brief First byte even: the rest as one line through parsePose(); odd: as a .path file through
            readPoses(). Accepted poses must be rigid and survive formatPose() -> parsePose(). */
        inline Outcome pose(const std::uint8_t *data, std::size_t size)
        {
            Bytes in(data, size);
            const bool file = in.u8() % 2 == 1;
            const std::string text = in.rest();
            try
            {
                if (!file)
                    checkParsedPose(parsePose(text, "fuzz-pose"), "parsePose");
                else
                    for (const Eigen::Isometry3d &X : readPoses(writeScratch("poses.path", text)))
                        checkParsedPose(X, "readPoses");
                return Outcome::Accepted;
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
        }

        /** \brief A small body for the distance target: a triangle soup, a (perturbed) tetrahedron or octahedron
            (closed), or two tetrahedra (closed, two components). Coordinates on a 1/32 grid in [-4, 4). */
        inline Mesh smallMesh(Bytes &in, const std::string &name)
        {
            auto c = [&in] { return (double(in.u8()) - 128.0) / 32.0; };
            auto tetra = [&](Mesh &m) {
                const auto o = static_cast<std::uint32_t>(m.vertices.size());
                for (int k = 0; k < 4; ++k)
                {
                    const double x = c(), y = c(), z = c();
                    m.vertices.emplace_back(x, y, z);
                }
                m.triangles.insert(m.triangles.end(), {Triangle{o, o + 2, o + 1}, Triangle{o, o + 1, o + 3},
                                                       Triangle{o, o + 3, o + 2}, Triangle{o + 1, o + 2, o + 3}});
            };
            Mesh m;
            m.source = name;
            switch (in.u8() % 4)
            {
                case 0:
                {
                    const std::size_t nv = 3 + in.u8() % 6, nt = 1 + in.u8() % 8;
                    for (std::size_t i = 0; i < nv; ++i)
                    {
                        const double x = c(), y = c(), z = c();
                        m.vertices.emplace_back(x, y, z);
                    }
                    for (std::size_t t = 0; t < nt; ++t)
                    {
                        Triangle tri;
                        for (std::uint32_t &i : tri)
                            i = static_cast<std::uint32_t>(in.u8() % nv);
                        m.triangles.push_back(tri);
                    }
                    break;
                }
                case 1:
                    tetra(m);
                    break;
                case 2:
                {
                    const double r = 0.25 + in.u8() / 64.0;
                    Eigen::Vector3d centre;  // one statement per byte: argument order is unspecified
                    for (int k = 0; k < 3; ++k)
                        centre[k] = c();
                    const Eigen::Vector3d axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
                    for (const Eigen::Vector3d &a : axes)
                    {
                        Eigen::Vector3d jitter;
                        for (int k = 0; k < 3; ++k)
                            jitter[k] = in.s8();
                        m.vertices.push_back(centre + r * a + jitter / 256.0);
                    }
                    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
                    break;
                }
                default:
                    tetra(m);
                    tetra(m);
                    break;
            }
            return m;
        }

        /** \brief Winding number of the closed surface \e m around \e p (solid angles, Van Oosterom and Strackee). */
        inline double windingNumber(const Mesh &m, const Eigen::Vector3d &p)
        {
            double total = 0.0;
            for (const Triangle &f : m.triangles)
            {
                const Eigen::Vector3d a = m.vertices[f[0]] - p, b = m.vertices[f[1]] - p, c = m.vertices[f[2]] - p;
                const double la = a.norm(), lb = b.norm(), lc = c.norm();
                total += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
            }
            return std::abs(total) / (4.0 * M_PI);
        }

        /** \brief Largest winding number of \e inner's vertices (carried by \e X into the frame of \e outer) about
            the closed body \e outer; 0 if \e outer is open. */
        inline double deepestVertex(const Body &outer, const Body &inner, const Eigen::Isometry3d &X)
        {
            double w = 0.0;
            if (outer.isClosed())
                for (const Eigen::Vector3d &v : inner.surface().vertices)
                    w = std::max(w, windingNumber(outer.surface(), X * v));
            return w;
        }

        /** \brief Two small bodies and a pose from the bytes; the answers of "enumeration", "exact" (cold and warm),
            refineExact() and "comb-GA-wl" against brute force over all node pairs and all triangle pairs:
            enumeration equals the brute-force node minimum; exact is never above it; exact is never "free" when
            a triangle pair intersects or a vertex of one body lies inside the other (winding number > 0.6), and
            when free equals the brute-force triangle minimum; comb-GA-wl is never below exact. */
        inline Outcome distance(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            Bytes in(data, size);
            const std::uint8_t options = in.u8();
            Mesh ma = smallMesh(in, "fuzz-A"), mb = smallMesh(in, "fuzz-B");
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            {
                const double tx = (double(in.u8()) - 128.0) / 32.0, ty = (double(in.u8()) - 128.0) / 32.0,
                             tz = (double(in.u8()) - 128.0) / 32.0;
                X.translation() = Eigen::Vector3d(tx, ty, tz);
                const double qx = in.s8(), qy = in.s8(), qz = in.s8(), qw = in.s8();
                Eigen::Quaterniond q(qw, qx, qy, qz);
                if (q.norm() > 0.0)
                    X.linear() = q.normalized().toRotationMatrix();
            }
            const std::uint64_t seed = in.u8();
            BodyPtr a, b;
            try
            {
                ma.validate();
                mb.validate();
                cleanMesh(ma);
                cleanMesh(mb);
                ma.validate();
                mb.validate();
                BodyOptions oa, ob;
                oa.gridSize = (options & 1) ? ma.size() / 4 : 0.0;
                ob.gridSize = (options & 2) ? mb.size() / 4 : 0.0;
                oa.distances.threads = ob.distances.threads = 1;
                a = Body::build(ma, oa);
                b = Body::build(mb, ob);
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;  // all triangles degenerate
            }
            const double tol = 1e-9 * (1.0 + a->surface().size() + b->surface().size() + X.translation().norm());
            const Eigen::Matrix3d R = X.linear();
            const Eigen::Vector3d t = X.translation();

            // Brute force over node pairs and over surface triangle pairs (B's corners placed as R v + t).
            double nodeMin = std::numeric_limits<double>::infinity();
            for (std::uint32_t i = 0; i < a->numNodes(); ++i)
                for (std::uint32_t j = 0; j < b->numNodes(); ++j)
                    nodeMin = std::min(nodeMin, (a->node(i) - (R * b->node(j) + t)).norm());
            double triangleMin = std::numeric_limits<double>::infinity();
            bool touching = false;
            const Mesh &sa = a->surface(), &sb = b->surface();
            for (const Triangle &fa : sa.triangles)
                for (const Triangle &fb : sb.triangles)
                {
                    const Eigen::Vector3d b0 = R * sb.vertices[fb[0]] + t, b1 = R * sb.vertices[fb[1]] + t,
                                          b2 = R * sb.vertices[fb[2]] + t;
                    const Eigen::Vector3d &a0 = sa.vertices[fa[0]], &a1 = sa.vertices[fa[1]], &a2 = sa.vertices[fa[2]];
                    touching = touching || trianglesIntersect(a0, a1, a2, b0, b1, b2);
                    Eigen::Vector3d p, q;
                    triangleMin = std::min(triangleMin, triangleDistance(a0, a1, a2, b0, b1, b2, p, q));
                }
            const double deepest = std::max(deepestVertex(*a, *b, X), deepestVertex(*b, *a, X.inverse()));
            const bool mustCollide = touching || deepest > 0.6;
            const bool mustBeFree = !touching && deepest < 0.4;

            DistanceRequest request;
            request.seed = seed;
            DistanceResult e, x, g, warm, hinted;
            try
            {
                allocSolver("enumeration")->solve(*a, *b, X, request, e);
                allocSolver("exact")->solve(*a, *b, X, request, x);
                DistanceRequest capped = request;
                capped.maxEvaluations = 1000;
                allocSolver("comb-GA-wl")->solve(*a, *b, X, capped, g);
                warm = g;
                refineExact(*a, *b, X, warm);
                DistanceRequest started = request;
                started.start = g.nodes;
                allocSolver("exact")->solve(*a, *b, X, started, hinted);
            }
            catch (const Exception &error)
            {
                violation(std::string("a solver rejected two valid bodies: ") + error.what());
            }
            const std::string at = " (enumeration " + std::to_string(e.distance) + ", exact " +
                                   std::to_string(x.distance) + ", GA " + std::to_string(g.distance) + ", triangles " +
                                   std::to_string(triangleMin) + ", nodes " + std::to_string(nodeMin) + ")";
            check(e.nodeOptimal && std::abs(e.distance - nodeMin) <= tol, "enumeration != brute-force node minimum" + at);
            check(std::isfinite(x.distance) && x.certified, "exact: not a certified distance" + at);
            check(x.distance <= e.distance + tol, "exact above the node minimum" + at);
            check(!mustCollide || x.inCollision, "exact says free, brute force says collision" + at);
            check(!x.inCollision || !mustBeFree, "exact says collision, brute force says free" + at);
            // In collision the distance is 0 or, with a penetration depth, negative; outside it is >= 0.
            check(x.inCollision ? x.distance <= 0.0 : x.distance >= 0.0,
                  "exact: the sign of the distance and the collision flag disagree" + at);
            check(x.inCollision || std::abs(x.distance - triangleMin) <= tol,
                  "exact != brute-force triangle minimum" + at);
            check(inCollision(*a, *b, X) == x.inCollision, "inCollision() disagrees with the exact solver" + at);
            check(g.distance >= x.distance - tol && g.distance >= e.distance - tol, "comb-GA-wl below exact" + at);
            for (const DistanceResult *r : {&warm, &hinted})
                check(std::abs(r->distance - x.distance) <= tol && r->inCollision == x.inCollision && r->certified,
                      "warm exact query differs from the cold one" + at);
            return Outcome::Accepted;
        }

        /** \brief The robot every robot fixture folder holds as arm.urdf: revolute, continuous, fixed and mimic
            prismatic joints, a box, a mesh found through package://pkg/, a visual-only cylinder and a frame without
            geometry ("hand"). Its state: yaw, elbow. */
        inline const char *fixtureUrdf()
        {
            return R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <collision><origin xyz="0 0 0.05" rpy="0 0 0"/><geometry><box size="0.2 0.2 0.1"/></geometry></collision>
  </link>
  <link name="upper">
    <collision><origin xyz="0.25 0 0" rpy="0 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision>
  </link>
  <link name="fore">
    <collision><geometry><mesh filename="package://pkg/meshes/cube.obj" scale="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="hand"/>
  <link name="finger">
    <visual><geometry><cylinder radius="0.01" length="0.05"/></geometry></visual>
  </link>
  <joint name="yaw" type="revolute">
    <origin xyz="0 0 0.2" rpy="0 0 0"/><parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/>
  </joint>
  <joint name="elbow" type="continuous">
    <origin xyz="0.5 0 0" rpy="0 0 0"/><parent link="upper"/><child link="fore"/><axis xyz="0 1 0"/>
  </joint>
  <joint name="wrist" type="fixed">
    <origin xyz="0.4 0 0" rpy="0 0 0"/><parent link="fore"/><child link="hand"/>
  </joint>
  <joint name="slide" type="prismatic">
    <parent link="hand"/><child link="finger"/><axis xyz="1 0 0"/>
    <limit lower="-0.1" upper="0.1" effort="1" velocity="1"/><mimic joint="yaw" multiplier="0.01" offset="0"/>
  </joint>
</robot>
)";
        }

        inline std::string writeFile(const std::filesystem::path &path, const std::string &bytes)
        {
            std::ofstream out(path, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
            return path.string();
        }

        /** \brief A folder \e name in scratchDir() (one per target, so that no target reads another's input) that
            holds arm.urdf (fixtureUrdf()), arm.srdf, robot.obj and world.obj (tetrahedra) and the package
            pkg/meshes/cube.obj. */
        inline std::filesystem::path robotFolder(const std::string &name)
        {
            namespace fs = std::filesystem;
            const fs::path dir = scratchDir() / name;
            if (fs::exists(dir / "arm.urdf"))
                return dir;
            fs::create_directories(dir / "pkg" / "meshes");
            const std::string tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
            writeFile(dir / "robot.obj", tetra);
            writeFile(dir / "world.obj", "v 2 2 2\nv 3 2 2\nv 2 3 2\nv 2 2 3\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
            writeFile(dir / "pkg" / "meshes" / "cube.obj",
                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
                      "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n");
            writeFile(dir / "arm.srdf", "<robot name=\"arm\"><disable_collisions link1=\"base\" link2=\"fore\" "
                                        "reason=\"Never\"/></robot>\n");
            writeFile(dir / "arm.urdf", fixtureUrdf());
            return dir;
        }

        /** \brief Bodies without refinement and with a small mesh-distance table: reading is what is fuzzed. */
        inline BodyOptions robotBodyOptions()
        {
            BodyOptions o;
            o.gridSize = 0.0;
            o.distances.threads = 1;
            o.distances.memoryBudgetBytes = MeshDistances::denseTableBytes(64);
            return o;
        }

        /** \brief Every frame and link pose of \e robot at \e state is a finite rigid pose. */
        inline void checkPosesAt(const RobotModel &robot, const std::vector<double> &state, const std::string &what)
        {
            std::vector<Eigen::Isometry3d> frames, links;
            try
            {
                robot.linkPoses(state.data(), state.size(), frames, links);
            }
            catch (const Exception &error)
            {
                violation(what + ": a valid state is refused: " + error.what());
            }
            for (const Eigen::Isometry3d &X : frames)
                check(isPose(X), what + ": a frame pose is not a finite rigid pose");
            for (const Eigen::Isometry3d &X : links)
                check(isPose(X), what + ": a link pose is not a finite rigid pose");
        }

        /** \brief What every robot model must be: frames a forest in order with unique names, links in existing
            frames with unique names, finite surfaces and rigid offsets, self pairs in order and not allowed. */
        inline void checkRobotModel(const RobotModel &robot, const std::string &what)
        {
            const std::vector<RobotFrame> &frames = robot.frames();
            for (std::size_t f = 0; f < frames.size(); ++f)
                check(robot.findFrame(frames[f].name) == f &&
                          (frames[f].parent == RobotModel::NONE || frames[f].parent < f),
                      what + ": frame '" + frames[f].name + "': duplicated name or parent after it");
            const std::vector<RobotLink> &links = robot.links();
            for (std::size_t l = 0; l < links.size(); ++l)
            {
                const RobotLink &link = links[l];
                check(robot.findLink(link.name) == l && link.frame < frames.size() && link.body && isPose(link.X_FL),
                      what + ": link '" + link.name + "': duplicated name, bad frame, no body or a bad offset");
                check(!link.body->surface().triangles.empty(), what + ": link '" + link.name + "' has no triangles");
                for (const Eigen::Vector3d &v : link.body->surface().vertices)
                    check(v.allFinite(), what + ": link '" + link.name + "' has a non-finite vertex");
            }
            LinkPair last{0, 0};
            bool first = true;
            for (const LinkPair &p : robot.selfPairs())
            {
                check(p.first < p.second && p.second < links.size() && !robot.isAllowed(p.first, p.second) &&
                          (first || last < p),
                      what + ": selfPairs() out of order, out of range or allowed");
                last = p;
                first = false;
            }
        }

        /** \brief A state of \e robot: the floating base at the origin, each joint at 0 moved into its limits. */
        inline std::vector<double> referenceState(const UrdfRobot &robot)
        {
            std::vector<double> q(robot.dimension(), 0.0);
            if (robot.floatingBase())
                q[6] = 1.0;
            for (std::size_t k = 0; k < robot.variables().size(); ++k)
            {
                const UrdfJoint &j = robot.joints()[robot.variables()[k]];
                q[robot.jointOffset() + k] = j.joint->neutral(robot.jointOffset() + k - j.variable);
            }
            return q;
        }

        /** \brief A UrdfRobot's joints: one per frame but the root, parent before child, rigid origins, unit axes,
            ordered limits; movable joints are the state's variables in order, mimic joints follow a movable one;
            every frame is a finite rigid pose at the reference state. */
        inline void checkUrdfRobot(const UrdfRobot &robot, const std::string &what)
        {
            checkRobotModel(robot, what);
            const std::vector<UrdfJoint> &joints = robot.joints();
            check(!robot.frames().empty() && robot.frames()[0].parent == RobotModel::NONE &&
                      joints.size() + 1 == robot.frames().size(),
                  what + ": not one joint for every frame but the root");
            for (std::size_t k = 0; k < joints.size(); ++k)
            {
                const UrdfJoint &j = joints[k];
                const std::string at = what + ": joint '" + j.name + "'";
                check(j.child == k + 1 && j.parent == robot.frames()[j.child].parent, at + ": frames out of order");
                check(isPose(j.origin), at + ": its origin is not a finite rigid pose");
                check(j.axis.allFinite() && std::abs(j.axis.norm() - 1.0) < 1e-12, at + ": axis not of unit length");
                for (std::size_t v = 0; v < j.joint->size(); ++v)
                    check(!(j.joint->lower(v) > j.joint->upper(v)) && !std::isnan(j.joint->lower(v)) &&
                              !std::isnan(j.joint->upper(v)),
                          at + ": limits");
                const bool fixed = j.joint->size() == 0;
                if (fixed || j.mimics != RobotModel::NONE)
                {
                    check(j.variable == RobotModel::NONE, at + ": a fixed or mimic joint has a variable");
                    check(fixed || (j.mimics < joints.size() && joints[j.mimics].variable != RobotModel::NONE &&
                                    std::isfinite(j.multiplier) && std::isfinite(j.offset)),
                          at + ": mimics no movable joint, or by a non-finite map");
                }
                else
                    check(j.variable != RobotModel::NONE, at + ": a movable joint without a variable");
            }
            check(robot.jointOffset() + robot.variables().size() == robot.dimension(), what + ": dimension");
            for (std::size_t i = 0; i < robot.variables().size(); ++i)
                check(robot.variables()[i] < joints.size() &&
                          joints[robot.variables()[i]].variable <= robot.jointOffset() + i &&
                          robot.jointOffset() + i < joints[robot.variables()[i]].variable +
                                                        joints[robot.variables()[i]].joint->size(),
                      what + ": variables() and the joints' variable disagree");
            checkPosesAt(robot, referenceState(robot), what);
        }

        /** \brief First byte: options (bit 0 a floating base, then facets for cylinders and spheres); the rest as a
            URDF, beside arm.urdf, robot.obj and package pkg (robotFolder()), through UrdfRobot::load(). */
        inline Outcome urdf(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            Bytes in(data, size);
            const std::uint8_t options = in.u8();
            const std::filesystem::path dir = robotFolder("urdf");
            const std::string path = writeFile(dir / "input.urdf", in.rest());
            UrdfOptions o;
            o.packagePath = {dir.string()};
            o.floatingBase = options & 1;
            o.segments = 3 + (options >> 1) % 6;
            o.body = robotBodyOptions();
            try
            {
                checkUrdfRobot(*UrdfRobot::load(path, o), "UrdfRobot::load");
                return Outcome::Accepted;
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
        }

        /** \brief The bytes as an SRDF through readSrdf() on a copy of arm.urdf with a payload on "hand": an
            accepted SRDF names only links and frames the robot has, allows every pair it names and nothing else. */
        inline Outcome srdf(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            const std::filesystem::path dir = robotFolder("srdf");
            static const UrdfRobotPtr base = [&dir] {
                UrdfOptions o;
                o.packagePath = {dir.string()};
                o.body = robotBodyOptions();
                UrdfRobotPtr r = UrdfRobot::load((dir / "arm.urdf").string(), o);
                r->attach("payload", loadMesh((dir / "robot.obj").string()), "hand", Eigen::Isometry3d::Identity(),
                          o.body);
                return r;
            }();
            UrdfRobot robot(*base);
            const std::string path =
                writeFile(dir / "input.srdf", std::string(reinterpret_cast<const char *>(data), size));
            try
            {
                readSrdf(robot, path);
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
            checkUrdfRobot(robot, "readSrdf");
            check(robot.links().size() == base->links().size() && robot.frames().size() == base->frames().size(),
                  "readSrdf: links or frames changed");
            // The links a name stands for: the link of that name, else every link but a payload in the frame of
            // that name (RobotModel::allowCollision()).
            auto linksOf = [&robot](const std::string &name) {
                const std::size_t link = robot.findLink(name), frame = robot.findFrame(name);
                std::vector<std::size_t> found;
                for (std::size_t l = 0; l < robot.links().size(); ++l)
                    if (link != RobotModel::NONE ? l == link
                                                 : robot.links()[l].frame == frame && !robot.links()[l].payload)
                        found.push_back(l);
                return found;
            };
            std::vector<std::vector<bool>> listed(robot.links().size(), std::vector<bool>(robot.links().size()));
            try
            {
                for (const SrdfDisabledPair &pair : readSrdfDisabledCollisions(path))
                {
                    for (const std::string &name : {pair.link1, pair.link2})
                        check(robot.findLink(name) != RobotModel::NONE || robot.findFrame(name) != RobotModel::NONE,
                              "readSrdf: accepted an unknown link '" + name + "'");
                    for (std::size_t a : linksOf(pair.link1))
                        for (std::size_t b : linksOf(pair.link2))
                        {
                            check(robot.isAllowed(a, b), "readSrdf: a disabled pair is still checked");
                            listed[a][b] = listed[b][a] = true;
                        }
                }
            }
            catch (const Exception &error)
            {
                violation(std::string("readSrdfDisabledCollisions refuses what readSrdf accepted: ") + error.what());
            }
            for (std::size_t a = 0; a < robot.links().size(); ++a)
                for (std::size_t b = a + 1; b < robot.links().size(); ++b)
                    check(robot.isAllowed(a, b) == (base->isAllowed(a, b) || listed[a][b]),
                          "readSrdf: allowed a pair the SRDF does not name");
            return Outcome::Accepted;
        }

        /** \brief The start and goal of \e p: of the robot's dimension, finite, inside the joint limits (a
            UrdfRobot's), with finite rigid poses. */
        inline void checkProblemStates(const RobotProblem &p, const std::string &what)
        {
            std::vector<const std::vector<double> *> states{&p.start};
            if (p.goal)
                states.push_back(&*p.goal);
            for (const std::vector<double> *q : states)
            {
                check(q->size() == p.robot->dimension(), what + ": a state of the wrong dimension");
                for (std::size_t i = 0; i < q->size(); ++i)
                {
                    check(std::isfinite((*q)[i]), what + ": a non-finite state number");
                    check(p.robot->stateLower(i) <= (*q)[i] && (*q)[i] <= p.robot->stateUpper(i),
                          what + ": a state outside a joint's limits");
                }
                checkPosesAt(*p.robot, *q, what);
            }
        }

        /** \brief The bytes as a robot problem (.cfg) beside arm.urdf, arm.srdf, robot.obj, world.obj and package
            pkg (robotFolder()) through readRobotProblem(). An accepted problem has a robot, states of its dimension
            inside the joint limits whose poses are finite and rigid, obstacles, a finite ordered volume. */
        inline Outcome robotProblem(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            const std::filesystem::path dir = robotFolder("robot_problem");
            const std::string path =
                writeFile(dir / "problem.cfg", std::string(reinterpret_cast<const char *>(data), size));
            RobotProblem p;
            try
            {
                p = readRobotProblem(path, robotBodyOptions());
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
            const std::string what = "readRobotProblem";
            check(p.robot != nullptr && !p.obstacles.empty(), what + ": no robot or no obstacles");
            for (const BodyConstPtr &b : p.obstacles)
                check(b && !b->surface().triangles.empty(), what + ": an empty obstacle");
            const auto *urdfRobot = dynamic_cast<const UrdfRobot *>(p.robot.get());
            check(p.urdf == (urdfRobot != nullptr), what + ": urdf flag and robot kind disagree");
            if (urdfRobot)
                checkUrdfRobot(*urdfRobot, what);
            else
                checkRobotModel(*p.robot, what);
            checkProblemStates(p, what);
            check(!p.volume || (p.volume->min().allFinite() && p.volume->max().allFinite() &&
                                (p.volume->min().array() <= p.volume->max().array()).all()),
                  what + ": bad volume");
            check(!p.objectiveThreshold || std::isfinite(*p.objectiveThreshold), what + ": non-finite threshold");
            check(std::filesystem::exists(p.world), what + ": the world file does not exist");
            return Outcome::Accepted;
        }

        /** \brief The bytes as both the moveit_msgs/PlanningScene and the moveit_msgs/MotionPlanRequest (YAML; a
            scene's keys and a request's do not overlap, so one input may hold either or both) of the fixture robot
            with its SRDF (robotFolder(); meshes by file name or through package pkg) through readMoveItProblem().
            An accepted problem has the fixture's robot (its links and frames), a start and a goal (when given) of
            its dimension inside the joint limits with finite rigid poses, one named obstacle per body, each
            non-empty and finite, and (link, obstacle) allowed pairs in range, sorted and unique. */
        inline Outcome moveit(const std::uint8_t *data, std::size_t size)
        {
            QuietLog quiet;
            const std::filesystem::path dir = robotFolder("moveit");
            static const UrdfRobotConstPtr robot = [&dir] {
                MoveItFiles f;
                f.urdf = (dir / "arm.urdf").string();
                f.srdf = (dir / "arm.srdf").string();
                f.packagePath = {dir.string()};
                return readMoveItRobot(f, robotBodyOptions());
            }();
            MoveItFiles files;
            files.robot = robot;
            files.packagePath = {dir.string()};
            files.segments = 6;
            files.scene = files.request =
                writeFile(dir / "input.yaml", std::string(reinterpret_cast<const char *>(data), size));
            RobotProblem p;
            try
            {
                p = readMoveItProblem(files, robotBodyOptions());
            }
            catch (const Exception &)
            {
                return Outcome::Rejected;
            }
            const std::string what = "readMoveItProblem";
            const auto *urdfRobot = dynamic_cast<const UrdfRobot *>(p.robot.get());
            check(p.urdf && urdfRobot != nullptr, what + ": not a UrdfRobot");
            check(urdfRobot->links().size() == robot->links().size() &&
                      urdfRobot->frames().size() == robot->frames().size(),
                  what + ": links or frames changed");
            checkUrdfRobot(*urdfRobot, what);
            checkProblemStates(p, what);
            check(p.obstacleNames.size() == p.obstacles.size(), what + ": not one name per obstacle");
            for (const BodyConstPtr &b : p.obstacles)
            {
                check(b && !b->surface().triangles.empty(), what + ": an empty obstacle");
                for (const Eigen::Vector3d &v : b->surface().vertices)
                    check(v.allFinite(), what + ": an obstacle has a non-finite vertex");
            }
            for (std::size_t k = 0; k < p.allowedObstacles.size(); ++k)
            {
                const LinkPair &pair = p.allowedObstacles[k];
                check(pair.first < urdfRobot->links().size() && pair.second < p.obstacles.size() &&
                          (k == 0 || p.allowedObstacles[k - 1] < pair),
                      what + ": allowed (link, obstacle) pairs out of range, out of order or repeated");
            }
            return Outcome::Accepted;
        }

        /** \brief The targets by name (the stem of fuzz/<name>.cpp and of the corpus folders). */
        struct Target
        {
            const char *name;
            Outcome (*run)(const std::uint8_t *, std::size_t);
        };
        inline const std::vector<Target> &targets()
        {
            static const std::vector<Target> all = {
                {"mesh", &mesh},         {"loader", &loader}, {"config", &config},
                {"pose", &pose},         {"distance", &distance}, {"urdf", &urdf},
                {"srdf", &srdf},         {"robot_problem", &robotProblem}, {"moveit", &moveit}};
            return all;
        }
    }  // namespace fuzz
}  // namespace meshgap

#endif
