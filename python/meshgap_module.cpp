// The Python module `meshgap`: a thin pybind11 layer over meshgap's public C++ API (DESIGN.md, "Second wave"):
// scenes from OMPL.app .cfg problems or meshes (files or (V, F) numpy arrays), batched distance and collision
// queries over (N, 7) SE(3) or (N, 3) SE(2) pose arrays (distanceBatch(), the GIL released), robots of many bodies
// (RobotScene: a URDF arm among obstacles, batches of (N, dof) states, robotDistanceBatch()), and planning: plan()
// makes meshgap_plan's run (support/PlanRun.h), its keywords the flags of support/PlanOptions.h's table, so the two
// cannot drift apart. meshgap::Exception becomes FileNotFoundError for a missing file and ValueError otherwise, with
// the CLI's one-line message.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <optional>
#include <sstream>
#include <type_traits>
#include <variant>

#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/robot/RobotBatch.h"
#include "meshgap/robot/MoveItScene.h"
#include "meshgap/robot/RobotProblem.h"
#include "meshgap/robot/RobotScene.h"
#include "meshgap/robot/Srdf.h"
#include "meshgap/robot/UrdfRobot.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/SceneBatch.h"
#include "support/DenseClearance.h"
#include "support/PlanOptions.h"
#include "support/PlanReport.h"
#include "support/PlanRun.h"
#include "support/MoveItOptions.h"
#include "support/ControlRun.h"
#include "meshgap/ompl/RobotStateSpace.h"

namespace py = pybind11;
using namespace meshgap;
using meshgap::cli::PlanOption;
using meshgap::cli::PlanOptionKind;
using meshgap::cli::PlanOptions;
using meshgap::cli::PlanRun;
using meshgap::cli::checkPlanOptions;
using meshgap::cli::planKeyword;
using meshgap::cli::planOptionTable;
using meshgap::cli::setUpPlan;
using meshgap::cli::solvePlan;
using meshgap::cli::writePlanFiles;

namespace
{
    /** \brief A scene and, when it came from a .cfg, the problem it came from. */
    struct PyScene
    {
        ScenePtr scene;
        std::optional<ProblemConfig> config;
    };

    std::string shapeText(const py::array &a)
    {
        std::string s = "(";
        for (py::ssize_t k = 0; k < a.ndim(); ++k)
            s += (k ? ", " : "") + std::to_string(a.shape(k));
        return s + (a.ndim() == 1 ? ",)" : ")");
    }

    std::string typeName(const py::handle &h)
    {
        return py::str(py::type::handle_of(h).attr("__name__"));
    }

    std::string pathArg(const py::handle &h, const std::string &what)
    {
        if (!py::isinstance<py::str>(h) && !py::hasattr(h, "__fspath__"))
            throw Exception(what, "expected a file path (str or os.PathLike), got " +
                                      std::string(py::str(py::type::handle_of(h).attr("__name__"))));
        return py::module_::import("os").attr("fspath")(h).cast<std::string>();
    }

    /** \brief \e h as a 2-D float64 array with \e columns columns (any strides), or a ValueError naming \e what. */
    py::array_t<double> doubleArray(const py::handle &h, const std::string &what, const std::string &expected)
    {
        if (!py::isinstance<py::array>(h))
            throw Exception(what, "expected a numpy array " + expected + ", got " +
                                      std::string(py::str(py::type::handle_of(h).attr("__name__"))));
        const py::array a = py::reinterpret_borrow<py::array>(h);
        if (!a.dtype().is(py::dtype::of<double>()))
            throw Exception(what, "dtype " + std::string(py::str(a.dtype())) + ", expected float64 (convert with "
                                  ".astype(numpy.float64))");
        return py::reinterpret_borrow<py::array_t<double>>(h);
    }

    /** \brief Room for \e rows elements in \e v, or a MemoryError naming \e what and how many \e rows (a broadcast
        view may name more rows than memory holds). */
    template <typename T>
    void reserveRows(std::vector<T> &v, py::ssize_t rows, const std::string &what, const std::string &unit)
    {
        try
        {
            v.reserve(static_cast<std::size_t>(rows));
        }
        catch (const std::exception &)  // std::bad_alloc, or std::length_error past max_size()
        {
            std::ostringstream text;
            text << what << ": cannot allocate " << std::setprecision(3) << double(rows) * double(sizeof(T)) / 1e9
                 << " GB for " << rows << " " << unit;
            PyErr_SetString(PyExc_MemoryError, text.str().c_str());
            throw py::error_already_set();
        }
    }

    /** \brief \e h (a numpy array, or what numpy.asarray takes: nested lists, a trimesh TrackedArray) as an array of
        shape (rows, 3): of real numbers (any float or integer dtype) for vertices, of integers for \e indices; or one
        ValueError naming \e what. */
    py::array meshRowsArg(const py::handle &h, const std::string &what, bool indices)
    {
        const char *expected = indices ? "an integer array of shape (m, 3)" : "an array of shape (n, 3)";
        py::array a;
        try
        {
            a = py::module_::import("numpy").attr("asarray")(h);
        }
        catch (py::error_already_set &e)
        {
            if (e.matches(PyExc_MemoryError))
                throw;
            throw Exception(what, std::string("expected ") + expected + ", got " + typeName(h));
        }
        const char kind = a.dtype().kind();
        if (indices ? kind != 'i' && kind != 'u' : kind != 'f' && kind != 'i' && kind != 'u')
            throw Exception(what, "dtype " + std::string(py::str(a.dtype())) +
                                      (indices ? ", expected an integer type" : ", expected real numbers"));
        if (a.ndim() != 2 || a.shape(1) != 3)
            throw Exception(what, std::string("expected shape ") + (indices ? "(m, 3)" : "(n, 3)") + ", got " +
                                      shapeText(a));
        return a;
    }

    /** \brief A mesh from a file path, from a (V, F) pair, or from an object with .vertices and .faces (a
        trimesh.Trimesh): V of shape (n, 3), real numbers of any float or integer dtype (taken as float64), F of
        shape (m, 3), integers, vertex indices. Cleaned as loadMesh() cleans a file's mesh (welded, degenerate
        triangles dropped). */
    Mesh meshArg(const py::handle &h, const std::string &what)
    {
        const bool file = py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__");
        const bool arrays = py::isinstance<py::tuple>(h) || py::isinstance<py::list>(h);
        const bool meshLike = !file && !arrays && py::hasattr(h, "vertices") && py::hasattr(h, "faces");
        if (!arrays && !meshLike)
        {
            const std::string path = pathArg(h, what);
            py::gil_scoped_release release;
            return loadMesh(path);
        }
        if (arrays && py::len(h) != 2)
            throw Exception(what, "expected a file path or a (V, F) pair of arrays (or a mesh with .vertices and "
                                  ".faces), got a sequence of " + std::to_string(py::len(h)));
        const py::object Vo = meshLike ? h.attr("vertices") : py::reinterpret_borrow<py::object>(h[py::int_(0)]);
        const py::object Fo = meshLike ? h.attr("faces") : py::reinterpret_borrow<py::object>(h[py::int_(1)]);
        const std::string vName = what + (meshLike ? ".vertices" : " V"), fName = what + (meshLike ? ".faces" : " F");
        const py::array_t<double, py::array::forcecast> V(meshRowsArg(Vo, vName, false));
        const py::array Fa = meshRowsArg(Fo, fName, true);
        const auto F = py::array_t<std::int64_t, py::array::forcecast>(Fa);
        Mesh mesh;
        mesh.source = what;
        reserveRows(mesh.vertices, V.shape(0), vName, "vertices");
        reserveRows(mesh.triangles, F.shape(0), fName, "triangles");
        const auto v = V.unchecked<2>();
        for (py::ssize_t i = 0; i < v.shape(0); ++i)
            mesh.vertices.emplace_back(v(i, 0), v(i, 1), v(i, 2));
        const auto f = F.unchecked<2>();
        for (py::ssize_t i = 0; i < f.shape(0); ++i)
        {
            Triangle t;
            for (int k = 0; k < 3; ++k)
            {
                if (f(i, k) < 0 || f(i, k) >= v.shape(0))
                    throw Exception(fName, "row " + std::to_string(i) + ": vertex index " +
                                                     std::to_string(f(i, k)) + " is out of range [0, " +
                                                     std::to_string(v.shape(0)) + ")");
                t[k] = static_cast<std::uint32_t>(f(i, k));
            }
            mesh.triangles.push_back(t);
        }
        mesh.validate();
        cleanMesh(mesh);
        if (mesh.triangles.empty())
            throw Exception(what, "no triangles left once degenerate ones are dropped");
        warnIfNotClosed(what, countEdges(mesh));
        return mesh;
    }

    /** \brief (N, 7) x y z qx qy qz qw (the quaternion normalised; its norm must be within 1e-3 of 1, as in a
        .path file) or (N, 3) x y theta (the robot in the plane z = 0, yawed by theta, as OMPL.app's SE(2)). */
    std::vector<Eigen::Isometry3d> posesArg(const py::handle &h)
    {
        const std::string expected = "of shape (N, 7) (x y z qx qy qz qw) or (N, 3) (x y theta)";
        const py::array_t<double> a = doubleArray(h, "poses", expected);
        if (a.ndim() != 2 || (a.shape(1) != 7 && a.shape(1) != 3))
            throw Exception("poses", "expected an array " + expected + ", got shape " + shapeText(a));
        const auto p = a.unchecked<2>();
        const bool planar = a.shape(1) == 3;
        std::vector<Eigen::Isometry3d> poses;
        reserveRows(poses, a.shape(0), "poses", "poses");
        poses.resize(static_cast<std::size_t>(a.shape(0)));
        for (py::ssize_t i = 0; i < p.shape(0); ++i)
        {
            const std::string where = "poses[" + std::to_string(i) + "]";
            for (py::ssize_t k = 0; k < p.shape(1); ++k)
                if (!std::isfinite(p(i, k)))
                    throw Exception(where, "pose has a NaN or infinite number");
            Eigen::Isometry3d &X = poses[static_cast<std::size_t>(i)];
            X.setIdentity();
            if (planar)
            {
                X.linear() = Eigen::AngleAxisd(p(i, 2), Eigen::Vector3d::UnitZ()).toRotationMatrix();
                X.translation() = Eigen::Vector3d(p(i, 0), p(i, 1), 0.0);
                continue;
            }
            Eigen::Quaterniond q(p(i, 6), p(i, 3), p(i, 4), p(i, 5));
            const double norm = q.norm();
            if (std::abs(norm - 1.0) > 1e-3)
                throw Exception(where, "quaternion (qx qy qz qw) is not of unit length (norm " + std::to_string(norm) +
                                           ")");
            q.normalize();
            X.linear() = q.toRotationMatrix();
            X.translation() = Eigen::Vector3d(p(i, 0), p(i, 1), p(i, 2));
        }
        return poses;
    }

    unsigned threadsArg(int threads)
    {
        if (threads < 1)
            throw Exception("threads", "must be at least 1, not " + std::to_string(threads));
        return static_cast<unsigned>(threads);
    }

    /** \brief A pose as x y z qx qy qz qw, or x y theta when \e planar. */
    py::array_t<double> poseArray(const std::vector<Eigen::Isometry3d> &poses, bool planar)
    {
        const py::ssize_t n = static_cast<py::ssize_t>(poses.size()), cols = planar ? 3 : 7;
        py::array_t<double> out({n, cols});
        auto o = out.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < n; ++i)
        {
            const Eigen::Isometry3d &X = poses[static_cast<std::size_t>(i)];
            if (planar)
            {
                o(i, 0) = X.translation().x();
                o(i, 1) = X.translation().y();
                o(i, 2) = std::atan2(X.linear()(1, 0), X.linear()(0, 0));
                continue;
            }
            const Eigen::Quaterniond q(X.linear());
            const double v[7] = {X.translation().x(), X.translation().y(), X.translation().z(), q.x(), q.y(), q.z(),
                                 q.w()};
            for (int k = 0; k < 7; ++k)
                o(i, k) = v[k];
        }
        return out;
    }

    py::dict distance(const PyScene &self, const py::handle &posesObject, bool exact, bool warm, int threads,
                      bool withDepth)
    {
        const std::vector<Eigen::Isometry3d> poses = posesArg(posesObject);
        const unsigned t = threadsArg(threads);
        SceneRequest request;
        request.exact = exact;
        request.computeDepth = withDepth;
        std::vector<SceneResult> results;
        {
            py::gil_scoped_release release;
            distanceBatch(*self.scene, poses, request, warm, t, results);
        }
        const py::ssize_t n = static_cast<py::ssize_t>(results.size());
        py::array_t<double> distance(n), onA({n, py::ssize_t(3)}), onB({n, py::ssize_t(3)}),
            depth(n);
        py::array_t<std::int64_t> obstacle(n);
        py::array_t<bool> inCollision(n), certified(n), openBody(n);
        auto d = distance.mutable_unchecked<1>();
        auto r = onA.mutable_unchecked<2>();
        auto o = onB.mutable_unchecked<2>();
        auto ob = obstacle.mutable_unchecked<1>();
        auto c = inCollision.mutable_unchecked<1>();
        auto cert = certified.mutable_unchecked<1>();
        auto open = openBody.mutable_unchecked<1>();
        for (py::ssize_t i = 0; i < n; ++i)
        {
            const SceneResult &s = results[static_cast<std::size_t>(i)];
            d(i) = s.distance;
            for (int k = 0; k < 3; ++k)
            {
                r(i, k) = s.onA[k];
                o(i, k) = s.onB[k];
            }
            ob(i) = static_cast<std::int64_t>(s.obstacle);
            c(i) = s.inCollision;
            cert(i) = s.certified;
            open(i) = s.openBody;
        }
        py::dict out;
        out["distance"] = distance;
        out["on_a"] = onA;
        out["on_b"] = onB;
        out["obstacle"] = obstacle;
        out["in_collision"] = inCollision;
        out["certified"] = certified;
        out["open_body"] = openBody;
        return out;
    }

    py::array_t<bool> inCollisionPoses(const PyScene &self, const py::handle &posesObject, int threads)
    {
        const std::vector<Eigen::Isometry3d> poses = posesArg(posesObject);
        const unsigned t = threadsArg(threads);
        std::vector<char> results;
        {
            py::gil_scoped_release release;
            inCollisionBatch(*self.scene, poses, t, results);
        }
        py::array_t<bool> out(static_cast<py::ssize_t>(results.size()));
        auto o = out.mutable_unchecked<1>();
        for (py::ssize_t i = 0; i < o.shape(0); ++i)
            o(i) = results[static_cast<std::size_t>(i)] != 0;
        return out;
    }

    /** \brief Scene.bounds: the cfg's volume as bounds per pose number, or None. */
    py::object sceneBounds(const PyScene &s)
    {
        if (!s.config || !s.config->volume)
            return py::none();
        const Eigen::AlignedBox3d &v = *s.config->volume;
        const bool planar = s.config->planar;
        py::array_t<double> out({py::ssize_t(planar ? 3 : 7), py::ssize_t(2)});
        for (py::ssize_t k = 0; k < (planar ? 2 : 3); ++k)
        {
            out.mutable_at(k, 0) = v.min()[k];
            out.mutable_at(k, 1) = v.max()[k];
        }
        for (py::ssize_t k = planar ? 2 : 3; k < out.shape(0); ++k)
        {
            out.mutable_at(k, 0) = planar ? -M_PI : -1.0;
            out.mutable_at(k, 1) = planar ? M_PI : 1.0;
        }
        return std::move(out);
    }

    PyScene sceneFromCfg(const py::handle &pathObject)
    {
        const std::string path = pathArg(pathObject, "cfg");
        PyScene s;
        py::gil_scoped_release release;
        const Problem problem = readProblem(path);
        if (!problem.rigidBody)
            throw Exception(path, "a robot problem (robot.urdf, or robot.1 and more bodies): open it with "
                                  "meshgap.RobotScene.from_cfg");
        const ProblemConfig &config = *problem.rigidBody;
        s.scene = Scene::fromMeshes(loadRobotMesh(config.robot, config.planar), loadMesh(config.world));
        s.config = config;
        return s;
    }

    PyScene sceneFromMeshes(const py::handle &robot, const py::handle &world)
    {
        const Mesh r = meshArg(robot, "robot"), w = meshArg(world, "world");
        PyScene s;
        py::gil_scoped_release release;
        s.scene = Scene::fromMeshes(r, w);
        return s;
    }

    py::tuple meshArrays(const Mesh &mesh)
    {
        py::array_t<double> V({py::ssize_t(mesh.vertices.size()), py::ssize_t(3)});
        py::array_t<std::int64_t> F({py::ssize_t(mesh.triangles.size()), py::ssize_t(3)});
        auto v = V.mutable_unchecked<2>();
        auto f = F.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < v.shape(0); ++i)
            for (int k = 0; k < 3; ++k)
                v(i, k) = mesh.vertices[static_cast<std::size_t>(i)][k];
        for (py::ssize_t i = 0; i < f.shape(0); ++i)
            for (int k = 0; k < 3; ++k)
                f(i, k) = mesh.triangles[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
        return py::make_tuple(V, F);
    }

    /** \brief A surface's EdgeReport as {"boundary_edges": ..., "non_manifold_edges": ...}. */
    py::dict edgesDict(const EdgeReport &edges)
    {
        py::dict d;
        d["boundary_edges"] = edges.boundaryEdges;
        d["non_manifold_edges"] = edges.nonManifoldEdges;
        return d;
    }

    /** \brief The states of \e path as an (M, n) array of the robot's \e n state numbers (robotStateToVector(); a
        single body's pose x y z qx qy qz qw, or x y theta in SE(2)). */
    py::array_t<double> stateRows(const ompl::geometric::PathGeometric &path, std::size_t n)
    {
        py::array_t<double> rows({static_cast<py::ssize_t>(path.getStateCount()), static_cast<py::ssize_t>(n)});
        auto view = rows.mutable_unchecked<2>();
        std::vector<double> q;
        for (std::size_t i = 0; i < path.getStateCount(); ++i)
        {
            robotStateToVector(*path.getSpaceInformation()->getStateSpace(), path.getState(i), q);
            for (std::size_t k = 0; k < n; ++k)
                view(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = q[k];
        }
        return rows;
    }

    /** \brief The dense path of plan()'s summary: its states (as poses), arc_length, clearance, in_collision. */
    py::dict denseDict(const DenseClearance &d, std::size_t n)
    {
        py::dict dd;
        dd["poses"] = stateRows(d.path, n);
        dd["arc_length"] = py::array_t<double>(py::ssize_t(d.arcLength.size()), d.arcLength.data());
        dd["clearance"] = py::array_t<double>(py::ssize_t(d.clearance.size()), d.clearance.data());
        py::array_t<bool> collide(py::ssize_t(d.inCollision.size()));
        for (std::size_t i = 0; i < d.inCollision.size(); ++i)
            collide.mutable_at(py::ssize_t(i)) = d.inCollision[i] != 0;
        dd["in_collision"] = collide;
        return dd;
    }

    /** \brief plan()'s planner parameters as text, as --param NAME=VALUE gives them (a bool as 1 or 0). */
    std::vector<std::pair<std::string, std::string>> paramTexts(const py::handle &paramsObject)
    {
        if (!py::isinstance<py::dict>(paramsObject))
            throw Exception("params", "expected a dict of the planner's parameters, got " + typeName(paramsObject));
        std::vector<std::pair<std::string, std::string>> params;
        for (const auto &[name, value] : py::reinterpret_borrow<py::dict>(paramsObject))
            params.emplace_back(py::str(name).cast<std::string>(),
                                py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "1" : "0") :
                                                                    py::str(value).cast<std::string>());
        return params;
    }

    /** \brief An index (a Python int of any size, or what has __index__) into \e size items, or one ValueError
        naming \e what, the index and the range. */
    std::size_t indexArg(const py::handle &h, std::size_t size, const std::string &what)
    {
        if (py::isinstance<py::bool_>(h) || !PyIndex_Check(h.ptr()))
            throw Exception(what, "expected an int index, got " + typeName(h));
        const py::int_ value = py::reinterpret_steal<py::int_>(PyNumber_Index(h.ptr()));
        if (!value)
            throw py::error_already_set();
        if (value < py::int_(0) || value >= py::int_(size))
            throw Exception(what, "index " + py::str(py::handle(value)).cast<std::string>() + " is out of range [0, " +
                                      std::to_string(size) + ")");
        return value.cast<std::size_t>();
    }

    /** \brief A non-negative integer keyword that fits 32 bits. */
    unsigned countArg(const py::handle &h, const std::string &keyword)
    {
        if (py::isinstance<py::bool_>(h) || !PyIndex_Check(h.ptr()))
            throw Exception(keyword, "expected an int, got " + typeName(h));
        const py::int_ value = py::reinterpret_steal<py::int_>(PyNumber_Index(h.ptr()));
        if (value < py::int_(0) || value > py::int_(std::numeric_limits<std::uint32_t>::max()))
            throw Exception(keyword, py::str(py::handle(value)).cast<std::string>() + " is out of range [0, 2^32)");
        return value.cast<unsigned>();
    }

    /** \brief The value of one keyword of plan(), as support/PlanOptions.h's table row \e row says, into \e o. */
    void setKeyword(PlanOptions &o, const PlanOption &row, const py::handle &value)
    {
        const std::string keyword = planKeyword(row.name);
        std::visit(
            [&](auto field)
            {
                using T = std::remove_reference_t<decltype(o.*field)>;
                if constexpr (std::is_same_v<T, std::string>)
                {
                    if (row.kind == PlanOptionKind::FILE)
                        o.*field = pathArg(value, keyword);
                    else if (py::isinstance<py::str>(value))
                        o.*field = value.cast<std::string>();
                    else
                        throw Exception(keyword, "expected a str, got " + typeName(value));
                }
                else if constexpr (std::is_same_v<T, double>)
                {
                    if (py::isinstance<py::bool_>(value) || !(PyFloat_Check(value.ptr()) || PyIndex_Check(value.ptr())))
                        throw Exception(keyword, "expected a number, got " + typeName(value));
                    o.*field = value.cast<double>();
                }
                else if constexpr (std::is_same_v<T, unsigned>)
                    o.*field = countArg(value, keyword);
                else if constexpr (std::is_same_v<T, bool>)
                {
                    if (!py::isinstance<py::bool_>(value))
                        throw Exception(keyword, "expected a bool, got " + typeName(value));
                    o.*field = value.cast<bool>();
                }
                else
                {
                    const bool list = py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value);
                    const py::sequence items = list ? py::reinterpret_borrow<py::sequence>(value) :
                                                      py::sequence(py::make_tuple(value));
                    for (const py::handle item : items)
                        if (!py::isinstance<py::str>(item))
                            throw Exception(keyword, "expected a str or a list of str, got " + typeName(item));
                    o.*field = items.cast<T>();
                }
            },
            row.field);
        o.given.insert(row.name);
    }

    /** \brief plan()'s keywords: meshgap_plan's flags (dashes as underscores), then those of Python only. */
    std::vector<std::string> planKeywords()
    {
        std::vector<std::string> keywords;
        for (const PlanOption &row : planOptionTable())
            keywords.push_back(planKeyword(row.name));
        keywords.push_back("params");
        return keywords;
    }

    /** \brief plan()'s keyword arguments into \e o: each checked against the table (an unknown one is a
        TypeError listing the valid ones), None leaving the default. */
    void planOptionsFromKeywords(PlanOptions &o, const py::kwargs &kwargs)
    {
        for (const auto &[key, value] : kwargs)
        {
            const std::string keyword = py::str(key).cast<std::string>();
            const auto &table = planOptionTable();
            const auto row = std::find_if(table.begin(), table.end(), [&keyword](const PlanOption &r)
                                          { return planKeyword(r.name) == keyword; });
            if (row == table.end() && keyword != "params" && keyword != "mode")
                throw py::type_error("plan() got an unexpected keyword argument '" + keyword +
                                     "'; valid: " + joinNames(planKeywords()));
            if (value.is_none())
                continue;
            if (keyword == "mode")  // the old spelling, as meshgap_plan refuses --mode
                throw Exception("mode", "renamed: use checker='certified' or checker='fast'");
            if (keyword == "params")
            {
                // PLANNER.NAME, as --param spells it (the planner checked as meshgap_plan checks it), or NAME.
                for (const auto &[name, text] : paramTexts(value))
                {
                    if (name.find('.') != std::string::npos)
                        o.params.push_back(name + "=" + text);
                    else
                        o.plannerParams.emplace_back(name, text);
                }
            }
            else
                setKeyword(o, *row, value);
        }
    }

    /** \brief OMPL's seed: OMPL logs an error when the seed is set again in one process, yet it does restart its
        seed generator: the same seed gives the same path (tested). Keep that message out of a notebook. */
    void setSeedQuietly(std::uint32_t seed)
    {
        const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
        ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
        ompl::RNG::setSeed(seed);
        ompl::msg::setLogLevel(level);
    }

    /** \brief OMPL's log level for a while (plan(quiet=False) shows OMPL's messages, as meshgap_plan does). */
    class LogLevelScope
    {
    public:
        explicit LogLevelScope(bool quiet) : level_(ompl::msg::getLogLevel())
        {
            if (!quiet)
                ompl::msg::setLogLevel(ompl::msg::LOG_INFO);
        }
        ~LogLevelScope() { ompl::msg::setLogLevel(level_); }

    private:
        ompl::msg::LogLevel level_;
    };

    /** \brief plan()'s summary dict: meshgap_plan's fields, its summary text, and the dense path. */
    py::dict summaryDict(const PlanRun &p, const PlanOptions &o)
    {
        py::dict summary;
        summary["problem"] = p.checks->settings().name;
        summary["robot"] = p.scene->robot().description();
        summary["planar"] = p.checks->settings().planar;
        summary["planner"] = o.planner;
        summary["objective"] = p.objective;
        summary["checker"] = o.checker;
        summary["motion"] = p.motion;
        summary["status"] = p.status.asString();
        summary["solved"] = p.havePath;
        summary["exact"] = p.exact;
        summary["planning_time"] = p.setup->getLastPlanComputationTime();
        if (const std::optional<CheckerStats> stats = p.checks->stats())
        {
            summary["validity_calls"] = stats->validityCalls;
            summary["clearance_calls"] = stats->clearanceCalls;
            summary["query_time"] = stats->seconds;
        }
        summary["text"] = p.summary;
        if (p.dense)
        {
            ompl::geometric::PathGeometric &path = p.setup->getSolutionPath();
            summary["states"] = path.getStateCount();
            summary["length"] = path.length();
            summary["cost"] = path.cost(p.setup->getOptimizationObjective()).value();
            summary["min_clearance"] = p.dense->minClearance;
            summary["min_clearance_arc_length"] = p.dense->arcLength[p.dense->argmin];
            summary["limiting_pair"] = pairText(*p.scene, p.dense->worst);
            summary["dense_path_free"] = p.dense->collisions == 0;
            summary["dense"] = denseDict(*p.dense, p.scene->robot().dimension());
        }
        if (p.before)
        {
            summary["min_clearance_before"] = p.before->minClearance;
            summary["limiting_pair_before"] = pairText(*p.scene, p.before->worst);
            summary["optimize_failed"] = p.optimizeFailed;
        }
        return summary;
    }

    /** \brief plan() on a control problem (support/ControlRun.h, meshgap_plan's run): the path's states one
        propagation step apart as an (M, n) array of the model's state numbers (the rows --out writes), and the
        summary dict (meshgap_plan's fields, its summary text). */
    py::tuple planControl(const PlanOptions &o, ProblemConfig config)
    {
        std::unique_ptr<meshgap::cli::ControlPlanRun> run;
        {
            py::gil_scoped_release release;
            const LogLevelScope logLevel(o.quiet);
            setSeedQuietly(o.seed);
            run = meshgap::cli::setUpControlPlan(o, std::move(config));
            meshgap::cli::solveControlPlan(*run, o);
            std::ostringstream log;
            meshgap::cli::writeControlPlanFiles(*run, o, log);
        }
        const auto width = static_cast<py::ssize_t>(
            ompl::base::ScopedState<>(run->problem.setup->getStateSpace()).reals().size());
        py::array_t<double> path({static_cast<py::ssize_t>(run->states.size()), width});
        auto view = path.mutable_unchecked<2>();
        for (std::size_t i = 0; i < run->states.size(); ++i)
            for (py::ssize_t k = 0; k < width; ++k)
                view(static_cast<py::ssize_t>(i), k) = run->states[i][static_cast<std::size_t>(k)];
        const CheckerStats stats = run->problem.checker->stats();
        py::dict summary;
        summary["problem"] = run->config.name;
        summary["control"] = run->config.control;
        summary["planner"] = run->planner;
        summary["checker"] = o.checker;
        summary["status"] = run->status.asString();
        summary["solved"] = run->havePath;
        summary["exact"] = run->exact;
        summary["planning_time"] = run->problem.setup->getLastPlanComputationTime();
        summary["validity_calls"] = stats.validityCalls;
        summary["query_time"] = stats.seconds;
        summary["text"] = run->summary;
        if (run->havePath)
        {
            summary["states"] = run->states.size();
            summary["duration"] = run->duration;
            summary["goal_distance"] = run->goalDistance;
            summary["min_clearance"] = run->minClearance;
        }
        return py::make_tuple(path, summary);
    }

    /** \brief meshgap_plan's run (support/PlanRun.h) with the keywords as its flags; returns the path's states and
        the summary dict. */
    py::tuple plan(const py::handle &cfgObject, const py::kwargs &kwargs)
    {
        PlanOptions o;
        o.keywords = true;
        o.quiet = true;  // plan() returns its summary: no progress line unless quiet=False
        o.cfg = pathArg(cfgObject, "cfg");
        planOptionsFromKeywords(o, kwargs);
        Problem problem;
        {
            py::gil_scoped_release release;
            const LogLevelScope logLevel(o.quiet);  // a robot's meshes load here: their warnings follow quiet
            problem = meshgap::cli::readToolProblem(o.cfg, o.moveit);
        }
        if (meshgap::cli::isControlProblem(problem))
        {
            checkPlanOptions(o);
            return planControl(o, std::move(*problem.rigidBody));
        }
        std::unique_ptr<PlanRun> p;
        {
            py::gil_scoped_release release;
            const LogLevelScope logLevel(o.quiet);
            checkPlanOptions(o);
            setSeedQuietly(o.seed);
            p = setUpPlan(o, std::move(problem));
            solvePlan(*p, o);
            std::ostringstream log;  // meshgap_plan's "path written ..." lines: the caller knows what it asked for
            writePlanFiles(*p, o, log);
        }
        const ompl::geometric::PathGeometric none(p->setup->getSpaceInformation());
        const ompl::geometric::PathGeometric &path = p->havePath ? p->setup->getSolutionPath() : none;
        return py::make_tuple(stateRows(path, p->scene->robot().dimension()), summaryDict(*p, o));
    }

    /** \brief plan()'s docstring: what it returns, then every keyword with its flag's help. */
    std::string planDoc()
    {
        std::string doc =
            "plan(cfg, **keywords): plan for a problem file (an OMPL.app .cfg: one body, a URDF arm with its payload, "
            "several bodies) as meshgap_plan does, the same run for every kind. Returns (path, summary): the "
            "solution's states as an (M, n) array of the problem's state numbers (a single body's pose: n = 7, x y z "
            "qx qy qz qw, or 3, x y theta; a robot's, as RobotScene.state_names; empty when none was found), the "
            "numbers --out writes, and a dict: problem, robot (what plans: 'one body in SE(3)', \"URDF 'arm', 4 "
            "joints\", ...), planar, planner, objective, checker, motion, status, solved, exact, planning_time, the "
            "checker's validity_calls, clearance_calls and query_time (a single body's, which counts them), 'text': "
            "meshgap_plan's summary; with a path, states, length, cost, min_clearance over the dense path, "
            "min_clearance_arc_length and limiting_pair (where and which pair attains it), dense_path_free and "
            "'dense': the dense path's poses (its states, as the path's rows), arc_length, clearance, in_collision; "
            "with optimize, min_clearance_before and limiting_pair_before (the planner's path) and optimize_failed. A "
            "control problem (a 'control' key: kinematic_car, dynamic_car, blimp, quadrotor) is planned with OMPL's "
            "control planners as meshgap_plan plans it: the path is an (M, n) array of the model's state numbers one "
            "propagation step apart (the rows meshgap_plan --out writes) and the dict has problem, control, planner, "
            "checker, status, solved, exact, planning_time, validity_calls, query_time, text and, with a path, "
            "states, duration, goal_distance and min_clearance (certified, over those states).\n\nKeywords: "
            "meshgap_plan's flags, '-' written '_' "
            "(None keeps the default; files as str or os.PathLike; param a list of str):\n";
        for (const PlanOption &row : planOptionTable())
            if (row.name != "cfg")
                doc += "  " + planKeyword(row.name) + ": " + row.help +
                       (row.name == "quiet" ? "; True by default here (False: the progress line and OMPL's messages "
                                              "on stderr)\n" :
                                              "\n");
        doc += "  params: a dict of the planner's parameters, NAME: VALUE or PLANNER.NAME: VALUE (a bool as 1 or 0), "
               "as param PLANNER.NAME=VALUE\n"
               "The old mode= is refused (checker=).";
        return doc;
    }

    /** \brief A robot of many bodies among obstacles (RobotScene) and, when it came from a problem file, the
        problem's start and goal states. */
    struct PyRobotScene
    {
        RobotModelPtr model;
        RobotSceneConstPtr scene;
        std::string name;
        std::vector<std::string> stateNames;  ///< what each number of a state is
        std::optional<std::vector<double>> start, goal;
    };

    /** \brief The names of a robot's state numbers (RobotModel::stateName()): "shoulder", a planar joint's
        "base.x", a floating base's "base.qw", a rigid body's "robot.theta". */
    std::vector<std::string> stateNamesOf(const RobotModel &robot)
    {
        std::vector<std::string> names;
        for (std::size_t i = 0; i < robot.dimension(); ++i)
            names.push_back(robot.stateName(i));
        return names;
    }

    /** \brief A package search path: a str of folders joined by ':' (ROS_PACKAGE_PATH's form), an os.PathLike, or
        a sequence of either; None: empty. */
    std::vector<std::string> packagePathArg(const py::handle &h)
    {
        std::vector<std::string> folders;
        if (h.is_none())
            return folders;
        if (py::isinstance<py::str>(h) || py::hasattr(h, "__fspath__"))
        {
            std::stringstream text(pathArg(h, "package_path"));
            for (std::string folder; std::getline(text, folder, ':');)
                if (!folder.empty())
                    folders.push_back(folder);
            return folders;
        }
        if (!py::isinstance<py::sequence>(h))
            throw Exception("package_path", "expected a str of folders joined by ':' or a list of folders, got " +
                                                typeName(h));
        for (const py::handle &item : py::reinterpret_borrow<py::sequence>(h))
            folders.push_back(pathArg(item, "package_path"));
        return folders;
    }

    /** \brief x y z qx qy qz qw (a sequence of 7 finite numbers, the quaternion of unit length within 1e-3) as a
        pose. */
    Eigen::Isometry3d pose7Arg(const py::handle &h, const std::string &what)
    {
        std::vector<double> v;
        try
        {
            v = h.cast<std::vector<double>>();
        }
        catch (const py::cast_error &)
        {
            throw Exception(what, "expected 7 numbers x y z qx qy qz qw, got " + typeName(h));
        }
        if (v.size() != 7)
            throw Exception(what, "expected 7 numbers x y z qx qy qz qw, got " + std::to_string(v.size()));
        for (double x : v)
            if (!std::isfinite(x))
                throw Exception(what, "pose has a NaN or infinite number");
        Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
        if (std::abs(q.norm() - 1.0) > 1e-3)
            throw Exception(what, "quaternion (qx qy qz qw) is not of unit length (norm " + std::to_string(q.norm()) +
                                      ")");
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = q.normalized().toRotationMatrix();
        X.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        return X;
    }

    /** \brief attach=: None, one (mesh, link, pose) triple or a list of them; each payload is named "payload"
        (one) or "payload1", "payload2", ... (several), in the order given. */
    void attachArg(RobotModel &robot, const py::handle &h)
    {
        if (h.is_none())
            return;
        std::vector<py::handle> items;
        const bool one = py::isinstance<py::tuple>(h) && py::len(h) == 3 && py::isinstance<py::str>(h[py::int_(1)]);
        if (one)
            items.push_back(h);
        else if (py::isinstance<py::list>(h) || py::isinstance<py::tuple>(h))
            for (const py::handle &item : py::reinterpret_borrow<py::sequence>(h))
                items.push_back(item);
        else
            throw Exception("attach", "expected a (mesh, link, pose) triple or a list of them, got " + typeName(h));
        for (std::size_t k = 0; k < items.size(); ++k)
        {
            const std::string what = one ? "attach" : "attach[" + std::to_string(k) + "]";
            if (!py::isinstance<py::tuple>(items[k]) || py::len(items[k]) != 3)
                throw Exception(what, "expected a (mesh, link, pose) triple: a mesh file or (V, F), a link name and "
                                      "x y z qx qy qz qw");
            const py::tuple t = py::reinterpret_borrow<py::tuple>(items[k]);
            if (!py::isinstance<py::str>(t[1]))
                throw Exception(what, "the link must be a str (a link's name), got " + typeName(t[1]));
            Mesh mesh = meshArg(t[0], what + " mesh");
            const Eigen::Isometry3d X = pose7Arg(t[2], what + " pose");
            robot.attach(one || items.size() == 1 ? "payload" : "payload" + std::to_string(k + 1), std::move(mesh),
                         t[1].cast<std::string>(), X);
        }
    }

    /** \brief The world's bodies: a mesh (file or (V, F)) split into its connected parts, one obstacle each; None:
        no obstacles. */
    std::vector<BodyConstPtr> worldArg(const py::handle &h)
    {
        std::vector<BodyConstPtr> obstacles;
        if (h.is_none())
            return obstacles;
        const Mesh world = meshArg(h, "world");
        py::gil_scoped_release release;
        for (Mesh &part : splitComponents(world))
            obstacles.push_back(Body::build(std::move(part)));
        return obstacles;
    }

    PyRobotScene robotSceneFromUrdf(const py::handle &urdf, const py::handle &world, const py::handle &srdf,
                                    const py::handle &packagePath, const py::handle &attach, bool floatingBase)
    {
        UrdfOptions options;
        options.packagePath = packagePathArg(packagePath);
        options.floatingBase = floatingBase;
        const std::string path = pathArg(urdf, "urdf");
        const std::string srdfPath = srdf.is_none() ? std::string() : pathArg(srdf, "srdf");
        for (const std::string &file : {path, srdfPath})
            if (std::error_code error; !file.empty() && !std::filesystem::exists(file, error))
                throw Exception(excerpt(file),  // FileNotFoundError, as for a mesh
                                error ? "cannot be read (" + error.message() + ")" : "no such file");
        UrdfRobotPtr robot;
        {
            py::gil_scoped_release release;
            robot = UrdfRobot::load(path, options);
            if (!srdfPath.empty())
                readSrdf(*robot, srdfPath);
        }
        attachArg(*robot, attach);
        PyRobotScene s;
        s.stateNames = stateNamesOf(*robot);
        s.name = robot->name();
        s.model = robot;
        std::vector<BodyConstPtr> obstacles = worldArg(world);
        s.scene = std::make_shared<RobotScene>(robot, std::move(obstacles));
        return s;
    }

    /** \brief The Python scene of a robot problem read by \e read (with the GIL released): its robot among its
        world, honouring its allowed pairs, its start and goal, its state names. */
    template <typename Read>
    PyRobotScene robotSceneOf(Read read)
    {
        PyRobotScene s;
        {
            py::gil_scoped_release release;
            const RobotProblem problem = read();
            s.model = problem.robot;
            s.scene = planningScene(problem);
            s.name = problem.name;
            s.start = problem.start;
            s.goal = problem.goal;
        }
        s.stateNames = stateNamesOf(*s.model);
        return s;
    }

    /** \brief A URDF robot (and its SRDF) in a MoveIt planning scene, with a motion plan request's start and goal
        (MoveItScene.h). */
    PyRobotScene robotSceneFromMoveIt(const py::handle &urdf, const py::handle &srdf, const py::handle &scene,
                                      const py::handle &request, const py::handle &packagePath)
    {
        MoveItFiles files;
        files.urdf = pathArg(urdf, "urdf");
        files.srdf = srdf.is_none() ? std::string() : pathArg(srdf, "srdf");
        files.scene = scene.is_none() ? std::string() : pathArg(scene, "scene");
        files.request = request.is_none() ? std::string() : pathArg(request, "request");
        files.packagePath = packagePathArg(packagePath);
        return robotSceneOf([&files] { return readMoveItProblem(files); });
    }

    /** \brief A problem file of any kind (readAnyRobotProblem(): a single body is a robot of one link): its robot
        among its world, its start and goal. */
    PyRobotScene robotSceneFromCfg(const py::handle &pathObject)
    {
        const std::string path = pathArg(pathObject, "cfg");
        return robotSceneOf(
            [&path]
            {
                if (std::error_code error; !std::filesystem::exists(path, error))
                    throw Exception(excerpt(path),
                                    error ? "cannot be read (" + error.message() + ")" : "no such file");
                return readAnyRobotProblem(path);
            });
    }

    /** \brief \e h as (N, dof) float64 numbers, C-contiguous (a copy when it is not), every number finite; or one
        ValueError naming the problem. */
    py::array_t<double, py::array::c_style> statesArg(const PyRobotScene &self, const py::handle &h)
    {
        const std::size_t dof = self.scene->robot().dimension();
        std::string expected = "of shape (N, " + std::to_string(dof) + ") (one state per row:";
        for (const std::string &n : self.stateNames)
            expected += " " + n;
        expected += ")";
        const py::array_t<double> a = doubleArray(h, "states", expected);
        if (a.ndim() != 2 || a.shape(1) != static_cast<py::ssize_t>(dof))
            throw Exception("states", "expected an array " + expected + ", got shape " + shapeText(a));
        // Not ensure(): it returns a null array, the error cleared, when the copy cannot be made (a broadcast view
        // of many rows); the constructor raises numpy's MemoryError naming the shape.
        const py::array_t<double, py::array::c_style | py::array::forcecast> s(a);
        const auto v = s.unchecked<2>();
        for (py::ssize_t i = 0; i < v.shape(0); ++i)
            for (py::ssize_t k = 0; k < v.shape(1); ++k)
                if (!std::isfinite(v(i, k)))
                    throw Exception("states[" + std::to_string(i) + "]", "state has a NaN or infinite number (" +
                                                                             self.stateNames[std::size_t(k)] + ")");
        return s;
    }

    /** \brief The per-state arrays of robotDistance() filled from \e results. */
    py::dict robotResultDict(const PyRobotScene &self, const std::vector<RobotResult> &results, bool everyPair)
    {
        const py::ssize_t n = py::ssize_t(results.size()), links = py::ssize_t(self.scene->links().size());
        const py::ssize_t self_ = py::ssize_t(self.scene->selfPairs().size());
        py::array_t<double> distance(n), onA({n, py::ssize_t(3)}), onB({n, py::ssize_t(3)});
        py::array_t<double> clearance({n, links}), linkObstacles({n, links}), selfPairs({n, self_});
        py::array_t<std::int64_t> link(n), obstacle(n), otherLink(n);
        py::array_t<bool> selfPair(n), inCollision(n), certified(n);
        for (py::ssize_t i = 0; i < n; ++i)
        {
            const RobotResult &r = results[std::size_t(i)];
            const bool none = !r.selfPair && r.atLeast;  // no pair below the bound: no attaining pair
            distance.mutable_at(i) = r.distance;
            selfPair.mutable_at(i) = r.selfPair;
            link.mutable_at(i) = none ? -1 : std::int64_t(r.link);
            obstacle.mutable_at(i) = r.selfPair || none ? -1 : std::int64_t(r.other);
            otherLink.mutable_at(i) = r.selfPair ? std::int64_t(r.other) : -1;
            inCollision.mutable_at(i) = r.inCollision;
            certified.mutable_at(i) = r.certified;
            for (py::ssize_t k = 0; k < 3; ++k)
            {
                onA.mutable_at(i, k) = r.onA[k];
                onB.mutable_at(i, k) = r.onB[k];
            }
            for (py::ssize_t k = 0; everyPair && k < links; ++k)
            {
                clearance.mutable_at(i, k) = r.linkClearance[std::size_t(k)];
                linkObstacles.mutable_at(i, k) = r.pairs[std::size_t(k)].distance;
            }
            for (py::ssize_t k = 0; everyPair && k < self_; ++k)
                selfPairs.mutable_at(i, k) = r.pairs[std::size_t(links + k)].distance;
        }
        py::dict out;
        out["distance"] = distance;
        out["in_collision"] = inCollision;
        out["certified"] = certified;
        out["self_pair"] = selfPair;
        out["link"] = link;
        out["obstacle"] = obstacle;
        out["other_link"] = otherLink;
        out["on_a"] = onA;
        out["on_b"] = onB;
        if (everyPair)
        {
            out["link_clearance"] = clearance;
            out["link_obstacle_distance"] = linkObstacles;
            out["self_pair_distance"] = selfPairs;
        }
        return out;
    }

    py::dict robotDistance(const PyRobotScene &self, const py::handle &statesObject, int threads, bool everyPair,
                           bool selfCollision)
    {
        const auto states = statesArg(self, statesObject);
        const unsigned t = threadsArg(threads);
        RobotRequest request;
        request.everyPair = everyPair;
        request.selfCollision = selfCollision;
        std::vector<RobotResult> results;
        {
            py::gil_scoped_release release;
            robotDistanceBatch(*self.scene, states.data(), std::size_t(states.shape(0)), request, t, results);
        }
        return robotResultDict(self, results, everyPair);
    }

    py::array_t<bool> robotInCollision(const PyRobotScene &self, const py::handle &statesObject, int threads,
                                       bool selfCollision)
    {
        const auto states = statesArg(self, statesObject);
        const unsigned t = threadsArg(threads);
        std::vector<char> results;
        {
            py::gil_scoped_release release;
            robotInCollisionBatch(*self.scene, states.data(), std::size_t(states.shape(0)), selfCollision, t, results);
        }
        py::array_t<bool> out(py::ssize_t(results.size()));
        for (std::size_t i = 0; i < results.size(); ++i)
            out.mutable_at(py::ssize_t(i)) = results[i] != 0;
        return out;
    }

    /** \brief Every link body's world pose at every state, (N, links, 4, 4). */
    py::array_t<double> robotLinkPoses(const PyRobotScene &self, const py::handle &statesObject)
    {
        const auto states = statesArg(self, statesObject);
        const RobotModel &robot = self.scene->robot();
        const py::ssize_t n = states.shape(0), links = py::ssize_t(self.scene->links().size());
        py::array_t<double> out({n, links, py::ssize_t(4), py::ssize_t(4)});
        std::vector<Eigen::Isometry3d> frames;
        for (py::ssize_t i = 0; i < n; ++i)
        {
            robot.framePoses(states.data(i, 0), robot.dimension(), frames);
            for (py::ssize_t k = 0; k < links; ++k)
            {
                const RobotLink &link = self.scene->links()[std::size_t(k)];
                const Eigen::Matrix4d X = (frames[link.frame] * link.X_FL).matrix();
                for (py::ssize_t r = 0; r < 4; ++r)
                    for (py::ssize_t c = 0; c < 4; ++c)
                        out.mutable_at(i, k, r, c) = X(r, c);
            }
        }
        return out;
    }

    std::size_t linkIndexArg(const PyRobotScene &self, const py::handle &h)
    {
        const std::vector<RobotLink> &links = self.scene->links();
        if (py::isinstance<py::str>(h))
        {
            const std::string name = h.cast<std::string>();
            for (std::size_t i = 0; i < links.size(); ++i)
                if (links[i].name == name)
                    return i;
            throw Exception("link", "no link named " + quote(name));
        }
        if (py::isinstance<py::bool_>(h) || !PyIndex_Check(h.ptr()))
            throw Exception("link", "expected a link's name (str) or index (int), got " + typeName(h));
        return indexArg(h, links.size(), "link");
    }

    /** \brief Every state number's bounds, (dof, 2): its limits (a URDF joint's; -inf, inf for a continuous joint,
        positions and angles), -1, 1 for a quaternion's numbers (a floating base's or joint's, a rigid body's). */
    py::array_t<double> robotBounds(const PyRobotScene &self)
    {
        const RobotModel &robot = self.scene->robot();
        const std::size_t dof = robot.dimension();
        py::array_t<double> out({py::ssize_t(dof), py::ssize_t(2)});
        std::vector<bool> quaternion(dof, false);
        for (const StateBlock &block : robot.stateBlocks())
            if (block.space == JointSpace::SE3)
                for (std::size_t k = 3; k < 7; ++k)
                    quaternion[block.first + k] = true;
        for (std::size_t k = 0; k < dof; ++k)
        {
            out.mutable_at(py::ssize_t(k), 0) = quaternion[k] ? -1.0 : robot.stateLower(k);
            out.mutable_at(py::ssize_t(k), 1) = quaternion[k] ? 1.0 : robot.stateUpper(k);
        }
        return out;
    }

    py::object stateOrNone(const std::optional<std::vector<double>> &state)
    {
        if (!state)
            return py::none();
        return py::array_t<double>(py::ssize_t(state->size()), state->data());
    }

    void addRobotScene(py::module_ &m)
    {
        py::class_<PyRobotScene>(
            m, "RobotScene",
            "A robot of many bodies (a URDF arm, links checked against the obstacles and against each other) among "
            "obstacles. RobotScene.from_urdf(urdf, world=..., ...) builds one; a state is a row of numbers: a "
            "floating base's pose (x y z qx qy qz qw) if any, then the URDF's movable joints' values in its order "
            "(a planar joint's x y theta, a floating joint's x y z qx qy qz qw; state_names).")
            .def_static("from_cfg", &robotSceneFromCfg, py::arg("path"),
                        "A robot problem file (robot.urdf = FILE with robot.srdf, robot.package_path, world, attach, "
                        "start.joints and goal.joints; or several bodies robot.1 = FILE, ...), or a single-body "
                        "OMPL.app file (robot = FILE: a robot of one link named 'robot', its state the pose, x y "
                        "theta or x y z qx qy qz qw): its robot among its world; start and goal its states. As "
                        "the planning tools do, the self pairs that one or two joints move are tabulated "
                        "(SelfPairTable: a fraction of a second for an arm).")
            .def_static("from_moveit", &robotSceneFromMoveIt, py::arg("urdf"), py::arg("srdf") = py::none(),
                        py::arg("scene") = py::none(), py::kw_only(), py::arg("request") = py::none(),
                        py::arg("package_path") = py::none(),
                        "A URDF robot (srdf: its disable_collisions pairs allowed) in a MoveIt planning scene YAML "
                        "(moveit_msgs/PlanningScene: its collision objects the obstacles, its allowed collision "
                        "matrix honoured, its robot state the start), and a motion plan request YAML "
                        "(moveit_msgs/MotionPlanRequest: start state, goal joint constraints). MotionBenchMaker's "
                        "problems read as shipped. Self pairs tabulated as from_cfg's.")
            .def_static("from_urdf", &robotSceneFromUrdf, py::arg("urdf"), py::kw_only(),
                        py::arg("world") = py::none(), py::arg("srdf") = py::none(),
                        py::arg("package_path") = py::none(), py::arg("attach") = py::none(),
                        py::arg("floating_base") = false,
                        "A URDF robot among the parts of world (a mesh file or (V, F), split into its connected "
                        "parts, one obstacle each; None: no obstacles). srdf: its disable_collisions pairs are not "
                        "checked (links joined by a joint never are). package_path: folders that hold the packages "
                        "package:// URIs name, a str joined by ':' or a list (default ROS_PACKAGE_PATH; the URDF's "
                        "folder and its parents are searched after). attach: a (mesh, link, pose) triple or a list of "
                        "them, a payload fixed to the link at pose x y z qx qy qz qw, named 'payload' ('payload1', "
                        "'payload2', ... for several). floating_base: the root link moves free in SE(3), its pose the "
                        "state's first 7 numbers.")
            .def("distance", &robotDistance, py::arg("states"), py::kw_only(), py::arg("threads") = 1,
                 py::arg("every_pair") = true, py::arg("self_collision") = true,
                 "Whole-robot minimum signed distance (negative in collision) at every state of an (N, dimension) "
                 "float64 array, exact and certified. Returns a dict of arrays: distance (N,), in_collision (N,), "
                 "certified (N,); the pair that attains it: self_pair (N,) (two links, else a link against an "
                 "obstacle), link (N,) (index in link_names), obstacle (N,) (-1 for a self pair), other_link (N,) "
                 "(-1 for an obstacle); on_a and on_b (N, 3) witness points (world frame), on the link and on the "
                 "obstacle or other link; and with "
                 "every_pair (default): link_clearance (N, links) (each link's distance from everything it is "
                 "checked against), link_obstacle_distance (N, links) (each link against the obstacles) and "
                 "self_pair_distance (N, len(self_pairs)). every_pair=False: the minimum alone, cheaper (pairs "
                 "pruned). self_collision=False: links against the obstacles only. threads: split the states over "
                 "this many threads (identical answers). The GIL is released while it runs.")
            .def("in_collision", &robotInCollision, py::arg("states"), py::kw_only(), py::arg("threads") = 1,
                 py::arg("self_collision") = true, "Exact collision test at every state; a bool array (N,).")
            .def("link_poses", &robotLinkPoses, py::arg("states"),
                 "Every link's world pose (the frame its mesh is in) at every state: an (N, links, 4, 4) array.")
            .def("link_mesh",
                 [](const PyRobotScene &s, const py::handle &link)
                 { return meshArrays(s.scene->links()[linkIndexArg(s, link)].body->surface()); },
                 py::arg("link"), "(V, F) of a link's surface (by name or index) in its own frame (link_poses)")
            .def("obstacle_mesh",
                 [](const PyRobotScene &s, const py::handle &index)
                 {
                     const std::size_t i = indexArg(index, s.scene->obstacles().size(), "obstacle_mesh");
                     return meshArrays(s.scene->obstacles()[i]->surface());
                 },
                 py::arg("index"), "(V, F) of obstacle index's surface, world frame")
            .def_property_readonly("dimension", [](const PyRobotScene &s) { return s.scene->robot().dimension(); },
                                   "numbers in a state")
            .def_property_readonly("state_names", [](const PyRobotScene &s) { return s.stateNames; },
                                   "what each number of a state is (joint names; base.x ... for a floating base)")
            .def_property_readonly("bounds", &robotBounds,
                                   "(dimension, 2) lower and upper bound of each state number (joint limits)")
            .def_property_readonly("link_names",
                                   [](const PyRobotScene &s)
                                   {
                                       std::vector<std::string> names;
                                       for (const RobotLink &l : s.scene->links())
                                           names.push_back(l.name);
                                       return names;
                                   })
            .def_property_readonly("self_pairs",
                                   [](const PyRobotScene &s)
                                   {
                                       std::vector<std::pair<std::string, std::string>> pairs;
                                       for (const LinkPair &p : s.scene->selfPairs())
                                           pairs.emplace_back(s.scene->links()[p.first].name,
                                                              s.scene->links()[p.second].name);
                                       return pairs;
                                   },
                                   "the link pairs checked against each other (names), self_pair_distance's columns")
            .def_property_readonly("obstacles", [](const PyRobotScene &s) { return s.scene->obstacles().size(); })
            .def_property_readonly("name", [](const PyRobotScene &s) { return s.name; })
            .def_property_readonly("start", [](const PyRobotScene &s) { return stateOrNone(s.start); },
                                   "the problem's start state, None without a problem file")
            .def_property_readonly("goal", [](const PyRobotScene &s) { return stateOrNone(s.goal); },
                                   "the problem's goal state, None without a problem file")
            .def("__repr__",
                 [](const PyRobotScene &s)
                 {
                     return "<meshgap.RobotScene " + s.name + ": " + std::to_string(s.scene->links().size()) +
                            " links, " + std::to_string(s.scene->robot().dimension()) + " state numbers, " +
                            std::to_string(s.scene->selfPairs().size()) + " self pairs, " +
                            std::to_string(s.scene->obstacles().size()) + " obstacles>";
                 });
    }
}  // namespace

PYBIND11_MODULE(_meshgap, m)
{
    m.doc() = "meshgap: exact minimum distance between concave triangle meshes, batched over poses, and planning "
              "with certified clearance (OMPL)";
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

    py::register_exception_translator([](std::exception_ptr p) {
        try
        {
            if (p)
                std::rethrow_exception(p);
        }
        catch (const Exception &e)
        {
            // The file-naming errors of the loaders: "FILE: no such file" (readProblemConfig, loadMesh) and
            // "FILE:LINE: robot mesh 'PATH' does not exist" (a cfg naming a missing mesh).
            const std::string what = e.what();
            const auto endsWith = [&what](const char *tail) {
                const std::size_t n = std::strlen(tail);
                return what.size() >= n && what.compare(what.size() - n, n, tail) == 0;
            };
            // A message may quote bytes of a binary file that are not UTF-8: those become \x escapes.
            PyObject *message = PyUnicode_DecodeUTF8(what.data(), static_cast<Py_ssize_t>(what.size()),
                                                     "backslashreplace");
            PyErr_SetObject(endsWith(": no such file") || endsWith("' does not exist") ? PyExc_FileNotFoundError :
                                                                                        PyExc_ValueError,
                            message);
            Py_XDECREF(message);
        }
    });

    py::class_<PyScene>(m, "Scene",
                        "A robot among obstacles. Scene(robot, world): each a mesh file (OBJ, STL, PLY, COLLADA, ...) "
                        "or a (V, F) pair of arrays (V (n, 3) real numbers, any float or integer dtype, taken as float64; "
                        "F (m, 3) integers) or a mesh with .vertices and .faces (trimesh.Trimesh); the robot in its own "
                        "frame, the world split into its connected parts, one obstacle each. Scene.from_cfg(path): "
                        "an OMPL.app problem, the robot centred as OMPL.app does, so a pose is the robot's state (a "
                        "robot problem file, robot.urdf or robot.1 and more bodies, is refused with a ValueError "
                        "naming meshgap.RobotScene.from_cfg, which reads those).")
        .def(py::init(&sceneFromMeshes), py::arg("robot"), py::arg("world"))
        .def_static("from_cfg", &sceneFromCfg, py::arg("path"))
        .def("distance", &distance, py::arg("poses"), py::kw_only(), py::arg("exact") = true,
             py::arg("warm") = true, py::arg("threads") = 1, py::arg("depth") = true,
             "Minimum distance at every pose of an (N, 7) (x y z qx qy qz qw) or (N, 3) (x y theta) float64 array. "
             "Returns a dict of arrays: distance (N,) (signed: negative in collision), on_a and on_b (N, 3) "
             "witness points (world frame) on the robot and on the obstacle, obstacle (N,), in_collision (N,), "
             "certified (N,), open_body (N,) "
             "(the robot or that obstacle is not a closed surface: it has no inside, so nothing counts as inside "
             "it; see open_obstacles). exact: the "
             "certified surface distance. exact=False (fast mode) is never dearer than the exact query: the paper's "
             "node-level search from scratch (comb-GA-wl) costs 1.4 to 140 times it per pose and seconds on a body's "
             "first use (bench/fast_vs_exact.py), so fast mode falls back to the exact query and gives its answer, "
             "certified (SceneRequest::fallBack; C++ keeps the node-level solvers for the paper's benches). "
             "warm: carry a warm "
             "start from pose to pose (exact: each thread across its blocks of 256 poses, the answers being the cold "
             "ones bit for bit; fast: afresh at each block). threads: split the blocks over this many threads "
             "(identical answers). depth: in collision, the penetration depth as a negative distance (else the "
             "verdict alone, cheaper: distance -2.2e-308, a zero below zero, as FCL answers 0, and the first "
             "colliding obstacle met). The GIL is released while it runs.")
        .def("in_collision", &inCollisionPoses, py::arg("poses"), py::kw_only(), py::arg("threads") = 1,
             "Exact collision test at every pose; a bool array (N,).")
        .def("__repr__",
             [](const PyScene &s) {
                 std::size_t world = 0;
                 for (const BodyConstPtr &b : s.scene->obstacles())
                     world += b->surface().triangles.size();
                 return "<meshgap.Scene" + (s.config ? " " + s.config->name : std::string()) + ": robot " +
                        std::to_string(s.scene->robot().surface().triangles.size()) + " triangles, " +
                        std::to_string(s.scene->obstacles().size()) + " obstacles (" + std::to_string(world) +
                        " triangles)>";
             })
        .def_property_readonly("obstacles", [](const PyScene &s) { return s.scene->obstacles().size(); })
        .def_property_readonly("robot_triangles",
                               [](const PyScene &s) { return s.scene->robot().surface().triangles.size(); })
        .def_property_readonly("world_triangles",
                               [](const PyScene &s) {
                                   std::size_t n = 0;
                                   for (const BodyConstPtr &b : s.scene->obstacles())
                                       n += b->surface().triangles.size();
                                   return n;
                               })
        .def_property_readonly("robot_edges", [](const PyScene &s) { return edgesDict(s.scene->robot().edges()); },
                               "the robot's boundary_edges (used by one triangle) and non_manifold_edges (by three "
                               "or more), a dict; both 0 for a closed surface")
        .def_property_readonly("world_edges",
                               [](const PyScene &s) {
                                   EdgeReport total;
                                   for (const BodyConstPtr &b : s.scene->obstacles())
                                   {
                                       total.boundaryEdges += b->edges().boundaryEdges;
                                       total.nonManifoldEdges += b->edges().nonManifoldEdges;
                                   }
                                   return edgesDict(total);
                               },
                               "robot_edges summed over the world's parts (obstacles)")
        .def_property_readonly("open_obstacles",
                               [](const PyScene &s) {
                                   std::vector<std::size_t> open;
                                   for (std::size_t i = 0; i < s.scene->obstacles().size(); ++i)
                                       if (!s.scene->obstacles()[i]->isClosed())
                                           open.push_back(i);
                                   return open;
                               },
                               "indices of the obstacles that are not closed surfaces (no inside)")
        .def_property_readonly("robot_mesh", [](const PyScene &s) { return meshArrays(s.scene->robot().surface()); },
                               "(V, F) of the robot's surface in its own frame")
        .def("obstacle_mesh",
             [](const PyScene &s, const py::handle &index) {
                 const std::size_t i = indexArg(index, s.scene->obstacles().size(), "obstacle_mesh");
                 return meshArrays(s.scene->obstacles()[i]->surface());
             },
             py::arg("index"), "(V, F) of obstacle index's surface, world frame")
        .def_property_readonly("planar",
                               [](const PyScene &s) { return s.config ? s.config->planar : false; },
                               "True for a planar (SE(2)) .cfg problem")
        .def_property_readonly("bounds", &sceneBounds,
                               "(7, 2) or (3, 2) lower and upper bound of each pose number (as RobotScene.bounds): "
                               "x y z from the cfg's volume, -1 1 for qx qy qz qw; planar: x y, and -pi pi for "
                               "theta. None without a cfg or a volume in it")
        .def_property_readonly("start",
                               [](const PyScene &s) -> py::object {
                                   if (!s.config)
                                       return py::none();
                                   return poseArray({s.config->start}, s.config->planar)[py::int_(0)];
                               },
                               "the cfg's start state (x y z qx qy qz qw, or x y theta), None without a cfg")
        .def_property_readonly("goal", [](const PyScene &s) -> py::object {
            if (!s.config || !s.config->goal)
                return py::none();
            return poseArray({*s.config->goal}, s.config->planar)[py::int_(0)];
        });

    addRobotScene(m);

    m.def("load_mesh", [](const py::handle &path) { return meshArrays(meshArg(path, "path")); }, py::arg("path"),
          "Load a mesh file as meshgap does (welded, cleaned): a (V, F) pair of numpy arrays.");
    m.def("plan", &plan, py::arg("cfg"), planDoc().c_str());
    m.attr("PLAN_KEYWORDS") = py::tuple(py::cast(planKeywords()));  // plan()'s keywords, cfg first
    m.attr("SCENE_BATCH_BLOCK") = SCENE_BATCH_BLOCK;
    m.attr("REPORT_AVAILABLE") = planReportAvailable();  // three.js was found at build time: plan(report=...) works
}
