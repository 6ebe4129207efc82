// The Python module `meshgap`: a thin pybind11 layer over meshgap's public C++ API (DESIGN.md, "Second wave"):
// scenes from OMPL.app .cfg problems or meshes (files or (V, F) numpy arrays), batched distance and collision
// queries over (N, 7) SE(3) or (N, 3) SE(2) pose arrays (distanceBatch(), the GIL released), and planning
// (setupProblem(), the planner factory, the dense clearance meshgap_plan prints). meshgap::Exception becomes
// FileNotFoundError for a missing file and ValueError otherwise, with the CLI's one-line message.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <optional>
#include <sstream>

#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/ompl/ClearanceMotionValidator.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/ProblemSetup.h"
#include "meshgap/scene/ProblemConfig.h"
#include "meshgap/scene/RobotMesh.h"
#include "meshgap/scene/SceneBatch.h"
#include "support/DenseClearance.h"
#include "support/PlanReport.h"

namespace py = pybind11;
using namespace meshgap;

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

    /** \brief A mesh from a file path, or from a (V, F) pair: V an (n, 3) float64 array, F an (m, 3) integer
        array of vertex indices. Cleaned as loadMesh() cleans a file's mesh (welded, degenerate triangles dropped). */
    Mesh meshArg(const py::handle &h, const std::string &what)
    {
        if (!py::isinstance<py::tuple>(h) && !py::isinstance<py::list>(h))
        {
            const std::string path = pathArg(h, what);
            py::gil_scoped_release release;
            return loadMesh(path);
        }
        const py::sequence seq = py::reinterpret_borrow<py::sequence>(h);
        if (seq.size() != 2)
            throw Exception(what, "expected a file path or a (V, F) pair of arrays, got a sequence of " +
                                      std::to_string(seq.size()));
        const py::array_t<double> V = doubleArray(seq[0], what + " V", "of shape (n, 3)");
        if (V.ndim() != 2 || V.shape(1) != 3)
            throw Exception(what + " V", "expected shape (n, 3), got " + shapeText(V));
        if (!py::isinstance<py::array>(seq[1]))
            throw Exception(what + " F", "expected a numpy integer array of shape (m, 3)");
        const py::array Fa = py::reinterpret_borrow<py::array>(seq[1]);
        const char kind = Fa.dtype().kind();
        if (kind != 'i' && kind != 'u')
            throw Exception(what + " F", "dtype " + std::string(py::str(Fa.dtype())) + ", expected an integer type");
        if (Fa.ndim() != 2 || Fa.shape(1) != 3)
            throw Exception(what + " F", "expected shape (m, 3), got " + shapeText(Fa));
        const auto F = py::array_t<std::int64_t, py::array::forcecast>(Fa);
        Mesh mesh;
        mesh.source = what;
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
                    throw Exception(what + " F", "row " + std::to_string(i) + ": vertex index " +
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
        std::vector<Eigen::Isometry3d> poses(static_cast<std::size_t>(a.shape(0)));
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

    py::dict distance(const PyScene &self, const py::handle &posesObject, bool exact, bool warm, int threads)
    {
        const std::vector<Eigen::Isometry3d> poses = posesArg(posesObject);
        const unsigned t = threadsArg(threads);
        SceneRequest request;
        request.exact = exact;
        std::vector<SceneResult> results;
        {
            py::gil_scoped_release release;
            distanceBatch(*self.scene, poses, request, warm, t, results);
        }
        const py::ssize_t n = static_cast<py::ssize_t>(results.size());
        py::array_t<double> distance(n), onRobot({n, py::ssize_t(3)}), onObstacle({n, py::ssize_t(3)}),
            depth(n);
        py::array_t<std::int64_t> obstacle(n);
        py::array_t<bool> inCollision(n), certified(n), openBody(n);
        auto d = distance.mutable_unchecked<1>();
        auto r = onRobot.mutable_unchecked<2>();
        auto o = onObstacle.mutable_unchecked<2>();
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
                r(i, k) = s.onRobot[k];
                o(i, k) = s.onObstacle[k];
            }
            ob(i) = static_cast<std::int64_t>(s.obstacle);
            c(i) = s.inCollision;
            cert(i) = s.certified;
            open(i) = s.openBody;
        }
        py::dict out;
        out["distance"] = distance;
        out["on_robot"] = onRobot;
        out["on_obstacle"] = onObstacle;
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

    PyScene sceneFromCfg(const py::handle &pathObject)
    {
        const std::string path = pathArg(pathObject, "cfg");
        PyScene s;
        py::gil_scoped_release release;
        const ProblemConfig config = readProblemConfig(path);
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

    /** \brief plan()'s arguments checked as meshgap_plan checks its flags (the old mode= refused). */
    void checkPlanArguments(const std::string &checker, const std::string &motion, double time, unsigned dense,
                            const py::object &modeObject)
    {
        if (!modeObject.is_none())  // the old spelling, as meshgap_plan refuses --mode
            throw Exception("mode", "renamed: use checker='certified' or checker='fast'");
        if (checker != "certified" && checker != "fast")
            throw Exception("checker", "'" + checker + "' is not certified or fast");
        if (motion != "discrete" && motion != "clearance")
            throw Exception("motion", "'" + motion + "' is not discrete or clearance");
        if (motion == "clearance" && checker != "certified")
            throw Exception("motion", "clearance needs checker certified (it steps by exact clearance)");
        if (!(time > 0.0) || !std::isfinite(time))
            throw Exception("time", "must be positive and finite");
        if (dense < 1)
            throw Exception("dense", "must be at least 1");
    }

    /** \brief The dense path of plan()'s summary: poses, arc_length, clearance, in_collision. */
    py::dict denseDict(const DenseClearance &d, const std::vector<Eigen::Isometry3d> &denseStates, bool planar)
    {
        py::dict dd;
        dd["poses"] = poseArray(denseStates, planar);
        dd["arc_length"] = py::array_t<double>(py::ssize_t(d.arcLength.size()), d.arcLength.data());
        dd["clearance"] = py::array_t<double>(py::ssize_t(d.clearance.size()), d.clearance.data());
        py::array_t<bool> collide(py::ssize_t(d.inCollision.size()));
        for (std::size_t i = 0; i < d.inCollision.size(); ++i)
            collide.mutable_at(py::ssize_t(i)) = d.inCollision[i] != 0;
        dd["in_collision"] = collide;
        return dd;
    }

    /** \brief plan()'s planner parameters as text, as --param NAME=VALUE gives them (a bool as 1 or 0). */
    std::vector<std::pair<std::string, std::string>> paramTexts(const py::dict &paramsObject)
    {
        std::vector<std::pair<std::string, std::string>> params;
        for (const auto &[name, value] : paramsObject)
            params.emplace_back(py::str(name).cast<std::string>(),
                                py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "1" : "0") :
                                                                    py::str(value).cast<std::string>());
        return params;
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

    /** \brief plan()'s HTML report with meshgap_plan's rows, and the dense path \e d when there is one. */
    void writeReport(const std::string &file, const OmplProblem &problem, const ProblemConfig &config,
                     const DenseClearance *d, const std::string &planner, const std::string &clearanceMode,
                     const std::string &status)
    {
        const std::vector<std::pair<std::string, std::string>> rows = {
            {"problem", config.name + (config.planar ? " (SE(2))" : " (SE(3))")},
            {"planner", planner},
            {"objective", problem.objective},
            {"clearance mode", clearanceMode},
            {"status", status},
            {"planning time", std::to_string(problem.setup->getLastPlanComputationTime()) + " s"}};
        writePlanReport(*problem.scene, d ? reportFromDense(*d, rows) : reportWithoutPath(config, rows), file);
    }

    /** \brief meshgap_plan's steps through the same library calls: the problem, the planner with its parameters,
        solve, then the dense clearance (support/DenseClearance.h); the summary with meshgap_plan's fields. */
    py::tuple plan(const py::handle &cfgObject, const std::string &planner, const std::string &objective, double time,
                   std::uint32_t seed, const std::string &checker, const std::string &motion, unsigned dense,
                   const py::dict &paramsObject, const py::object &reportObject, const py::object &modeObject)
    {
        namespace ob = ompl::base;
        const std::string cfg = pathArg(cfgObject, "cfg");
        const std::string reportFile = reportObject.is_none() ? std::string() : pathArg(reportObject, "report");
        checkPlanArguments(checker, motion, time, dense, modeObject);
        const std::vector<std::pair<std::string, std::string>> params = paramTexts(paramsObject);

        py::gil_scoped_release release;
        setSeedQuietly(seed);
        const ProblemConfig config = readProblemConfig(cfg);
        OmplProblem problem = setupProblem(
            config, checker == "certified" ? ClearanceChecker::Mode::CERTIFIED : ClearanceChecker::Mode::FAST,
            objective);
        const ob::SpaceInformationPtr si = problem.setup->getSpaceInformation();
        if (motion == "clearance")
            si->setMotionValidator(std::make_shared<ClearanceMotionValidator>(si, problem.checker));
        const ob::PlannerPtr plannerPtr = allocPlanner(planner, si);
        for (const auto &[name, value] : params)
            setPlannerParam(*plannerPtr, name, value, "params");
        problem.setup->setPlanner(plannerPtr);
        problem.setup->setup();
        const ob::PlannerStatus status = problem.setup->solve(time);
        const bool exact = status == ob::PlannerStatus::EXACT_SOLUTION;
        const bool havePath = problem.setup->haveSolutionPath() &&
                              (exact || status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
        const CheckerStats stats = problem.checker->stats();
        std::unique_ptr<DenseClearance> d;
        std::vector<Eigen::Isometry3d> states, denseStates;
        double length = 0.0, cost = 0.0;
        if (havePath)
        {
            ompl::geometric::PathGeometric &path = problem.setup->getSolutionPath();
            d = std::make_unique<DenseClearance>(denseClearance(path, *problem.scene, dense));
            for (const ob::State *s : path.getStates())
                states.push_back(poseFromState(*si->getStateSpace(), s));
            for (const ob::State *s : d->path.getStates())
                denseStates.push_back(poseFromState(*si->getStateSpace(), s));
            length = path.length();
            cost = path.cost(problem.setup->getOptimizationObjective()).value();
        }
        if (!reportFile.empty())
            writeReport(reportFile, problem, config, d.get(), planner, checker + ", motion " + motion,
                        status.asString());

        py::gil_scoped_acquire acquire;
        py::dict summary;
        summary["problem"] = config.name;
        summary["planar"] = config.planar;
        summary["planner"] = planner;
        summary["objective"] = problem.objective;
        summary["checker"] = checker;
        summary["motion"] = motion;
        summary["status"] = status.asString();
        summary["solved"] = havePath;
        summary["exact"] = exact;
        summary["planning_time"] = problem.setup->getLastPlanComputationTime();
        summary["validity_calls"] = stats.validityCalls;
        summary["clearance_calls"] = stats.clearanceCalls;
        summary["query_time"] = stats.seconds;
        if (d)
        {
            summary["states"] = states.size();
            summary["length"] = length;
            summary["cost"] = cost;
            summary["min_clearance"] = d->minClearance;
            summary["min_clearance_arc_length"] = d->arcLength[d->argmin];
            summary["dense_path_free"] = d->collisions == 0;
            summary["dense"] = denseDict(*d, denseStates, config.planar);
        }
        return py::make_tuple(poseArray(states, config.planar), summary);
    }
}  // namespace

PYBIND11_MODULE(meshgap, m)
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
                        "or a (V, F) pair of numpy arrays (V float64 (n, 3), F integer (m, 3)); the robot in its own "
                        "frame, the world split into its connected parts, one obstacle each. Scene.from_cfg(path): "
                        "an OMPL.app problem, the robot centred as OMPL.app does, so a pose is the robot's state.")
        .def(py::init(&sceneFromMeshes), py::arg("robot"), py::arg("world"))
        .def_static("from_cfg", &sceneFromCfg, py::arg("path"))
        .def("distance", &distance, py::arg("poses"), py::kw_only(), py::arg("exact") = true,
             py::arg("warm") = true, py::arg("threads") = 1,
             "Minimum distance at every pose of an (N, 7) (x y z qx qy qz qw) or (N, 3) (x y theta) float64 array. "
             "Returns a dict of arrays: distance (N,) (signed: negative in collision), on_robot and on_obstacle "
             "(N, 3) witness points (world frame), obstacle (N,), in_collision (N,), certified (N,), open_body (N,) "
             "(the robot or that obstacle is not a closed surface: it has no inside, so nothing counts as inside "
             "it; see open_obstacles). exact: the "
             "certified surface distance (else the paper's node distance; collision still exact). warm: carry a warm "
             "start from pose to pose (exact: each thread across its blocks of 256 poses, the answers being the cold "
             "ones bit for bit; fast: afresh at each block). threads: split the blocks over this many threads "
             "(identical answers). The GIL is released while it runs.")
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
             [](const PyScene &s, std::size_t i) {
                 if (i >= s.scene->obstacles().size())
                     throw Exception("obstacle_mesh", "index " + std::to_string(i) + " is out of range [0, " +
                                                          std::to_string(s.scene->obstacles().size()) + ")");
                 return meshArrays(s.scene->obstacles()[i]->surface());
             },
             py::arg("index"), "(V, F) of obstacle index's surface, world frame")
        .def_property_readonly("planar",
                               [](const PyScene &s) { return s.config ? s.config->planar : false; },
                               "True for a planar (SE(2)) .cfg problem")
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

    m.def("load_mesh", [](const py::handle &path) { return meshArrays(meshArg(path, "path")); }, py::arg("path"),
          "Load a mesh file as meshgap does (welded, cleaned): a (V, F) pair of numpy arrays.");
    m.def("plan", &plan, py::arg("cfg"), py::kw_only(), py::arg("planner") = "rrtconnect", py::arg("objective") = "",
          py::arg("time") = 10.0, py::arg("seed") = 1, py::arg("checker") = "certified", py::arg("motion") = "discrete",
          py::arg("dense") = 4, py::arg("params") = py::dict(), py::arg("report") = py::none(),
          py::arg("mode") = py::none(),
          "Plan for an OMPL.app .cfg problem as meshgap_plan does. Returns (path, summary): the solution's states "
          "as an (M, 7) or (M, 3) array (empty when none was found) and a dict (problem, planner, objective, status, "
          "solved, exact, planning_time, length, cost, min_clearance over the dense path, dense_path_free, and "
          "'dense': the dense path's poses, arc_length, clearance, in_collision). checker: certified or fast, as "
          "meshgap_plan's --checker (the old mode= is refused). report: also write the HTML plan report there.");
    m.attr("SCENE_BATCH_BLOCK") = SCENE_BATCH_BLOCK;
    m.attr("REPORT_AVAILABLE") = planReportAvailable();  // three.js was found at build time: plan(report=...) works
}
