// meshgap_makemap: writes the paper's three test scenes (Carretero & Nahon, Section IV) as meshes, poses and
// OMPL.app problem files:
//
//   battery_fixture  ORU battery (B) near an insertion pose on its fixture (A), two poses (cm, Table II)
//   hand_bowl        a hand (B) whose middle fingertip is about to touch a bowl's rim (A) (mm, Table IV)
//   handshake        two hands about to shake, B's thumb tip nearest to A's index tip (mm)
//
// and two scenes that are not from the paper:
//
//   slotted_wall     a C-shaped payload (B) to pass through a wall (A) by a narrow slot (short, little clearance)
//                    or a wide one off to the side (long, four times the play): a length/clearance trade-off
//   twisted          a stress scene for the exact layer: a thin helical strip (B, three turns of long thin
//                    triangles) screwed through a helical channel of the same pitch (A) with 0.3 of play on every
//                    side; its .poses are the whole screw motion, a collision-free path close to A all the way
//
// Each body is built from planar-faced polyhedra (planners/support/Shapes.h) gridded at the paper's grid sizes. Each
// pose is designed by hand and then slid along one direction until the exact (triangle-triangle) distance between
// the meshes equals the paper's "exact" minimum distance for that example (Tables III, V, VI). Each scene's .cfg is
// also a planning problem that forces a clearance trade-off (its straight line from start to goal runs into A; see
// maps/README.md); battery_fixture and hand_bowl start from poses of their own, not the paper's.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "CliMain.h"
#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/geometry/Body.h"
#include "meshgap/mesh/Mesh.h"
#include "meshgap/mesh/MeshLoader.h"
#include "support/MeshWriter.h"
#include "support/Shapes.h"

namespace po = boost::program_options;

namespace
{
    using meshgap::Mesh;
    using meshgap::Polygon2d;
    using meshgap::Polyhedron;
    using Eigen::Vector2d;
    using Eigen::Vector3d;

    constexpr double pi = 3.14159265358979323846;

    double radians(double degrees)
    {
        return degrees * pi / 180.0;
    }

    // ---------------------------------------------------------------------------------------------------------
    // Exact distance between two triangle meshes: the library's exact layer (ExactSolver, bvhDistance).
    // ---------------------------------------------------------------------------------------------------------

    Mesh posed(const Mesh &body, const Eigen::Isometry3d &X)
    {
        Mesh m = body;
        meshgap::transformMesh(m, X);
        return m;
    }

    /** \brief A mesh as a body for exact queries: its surface kept as it is (no refinement), so triangle indices
        in a DistanceResult are the mesh's own. */
    meshgap::BodyPtr exactBody(const Mesh &mesh)
    {
        meshgap::BodyOptions options;
        options.gridSize = 0.0;
        return meshgap::Body::build(mesh, options);
    }

    /** \brief Exact distance between A and B placed at X (B's pose in A's frame): closest triangles and witness
        points (in A's frame), distance 0 when they intersect or one lies inside the other. */
    meshgap::DistanceResult distanceAt(const meshgap::Body &a, const meshgap::Body &b, const Eigen::Isometry3d &X)
    {
        meshgap::DistanceResult result;
        meshgap::ExactSolver().solve(a, b, X, meshgap::DistanceRequest(), result);
        return result;
    }

    /** \brief Slide B from pose X along the unit direction w until its exact distance to A is \e gap. Moving B by
        delta changes the distance by at most |delta|, so each step of (distance - gap) along w never overshoots;
        the iteration converges when w has a component along the separating direction. */
    Eigen::Isometry3d placeAtGap(const meshgap::Body &a, const meshgap::Body &b, Eigen::Isometry3d X, const Vector3d &w,
                                 double gap, const std::string &what)
    {
        for (int step = 0; step < 20000; ++step)
        {
            const meshgap::DistanceResult r = distanceAt(a, b, X);
            if (r.inCollision || r.distance == 0.0)
                throw meshgap::Exception(what, "the designed pose already intersects the fixed body");
            if (std::abs(r.distance - gap) <= 1e-12 * (1.0 + gap))
                return X;
            X.pretranslate((r.distance - gap) * w);
        }
        throw meshgap::Exception(what, "placing at the target gap did not converge");
    }

    // ---------------------------------------------------------------------------------------------------------
    // Bodies
    // ---------------------------------------------------------------------------------------------------------

    /** \brief Index of the face of p with outward normal n whose plane passes through point q. */
    std::size_t findFace(const Polyhedron &p, const Vector3d &n, const Vector3d &q)
    {
        for (std::size_t f = 0; f < p.faces().size(); ++f)
            if (p.faceNormal(f).dot(n) > 1.0 - 1e-9 &&
                std::abs((p.corners()[p.faces()[f].loops[0][0]] - q).dot(n)) < 1e-9)
                return f;
        throw meshgap::Exception("meshgap_makemap", "internal error: no face found for a feature");
    }

    /** \brief A hexagon ("round, linearised with 6 sides") on the plane x = x0, centred at (y, z), a corner
        pointing along +y. */
    std::vector<Vector3d> hexagonOnX(double x0, double y, double z, double circumradius)
    {
        std::vector<Vector3d> points;
        for (const Vector2d &q : meshgap::regularPolygon({y, z}, circumradius, 6))
            points.emplace_back(x0, q.x(), q.y());
        return points;
    }

    // Battery and fixture, in cm (Table II: 92 x 74 x 31 and 62 x 86 x 99).
    // The paper's "grid size" g is read as the spacing of a square grid cut into right triangles: edges g and
    // g * sqrt(2). So bodies are meshed with edges at most sqrt(2) g (they then average about g).
    const double sqrt2 = std::sqrt(2.0);
    double batteryGrid = 5.0 * sqrt2;           // Table II's 0.05 m = 5 cm (see maps/README.md); --battery-grid
    constexpr double holeRadius = 3.0;          // alignment holes: hexagons of circumradius 3, 12 deep
    constexpr double holeDepth = 12.0;
    constexpr double pegRadius = 2.5;           // pegs: hexagons of circumradius 2.5, 10 long
    constexpr double pegLength = 10.0;
    constexpr double shelfTop = 6.0;            // the battery sits on the fixture's shelf
    const Vector2d pegAt[2] = {{-24.0, 24.0}, {24.0, 72.0}};  // (y, z) of the pegs on the fixture plate

    /** \brief Battery (body frame): box x in [0, 31] (x = 0 the back face, towards the fixture), y in [-37, 37],
        z in [0, 92], with two blind hexagonal alignment holes in the back face. */
    Mesh battery()
    {
        Polyhedron p = meshgap::prismPolyhedron({{0.0, -37.0}, {31.0, -37.0}, {31.0, 37.0}, {0.0, 37.0}}, {}, 92.0);
        const std::size_t back = findFace(p, -Vector3d::UnitX(), Vector3d::Zero());
        for (const Vector2d &peg : pegAt)
            p.addBoss(back, hexagonOnX(0.0, peg.x(), peg.y() - shelfTop, holeRadius), -holeDepth);
        return p.mesh(meshgap::uniformSizing(batteryGrid), "battery");
    }

    /** \brief Fixture (world frame): an L bracket, back plate x in [-8, 0], z in [0, 99] and shelf x in [-8, 54],
        z in [0, 6], y in [-43, 43], with a lip along the shelf's front edge (x in [48, 54], up to z = 14); two
        hexagonal pegs on the plate's front face (x = 0) and two guide rails on the shelf either side of the
        battery. */
    Mesh fixture()
    {
        Polyhedron p = meshgap::prismPolyhedron(
            {{-8.0, 0.0}, {54.0, 0.0}, {54.0, 14.0}, {48.0, 14.0}, {48.0, shelfTop}, {0.0, shelfTop}, {0.0, 99.0},
             {-8.0, 99.0}},
            {}, 86.0);
        // Profile drawn in (x, z), extruded along -y: (X, Y, Z) -> (X, 43 - Z, Y).
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;
        X.translation() = Vector3d(0.0, 43.0, 0.0);
        p.transform(X);
        const std::size_t plate = findFace(p, Vector3d::UnitX(), Vector3d::Zero());
        for (const Vector2d &peg : pegAt)
            p.addBoss(plate, hexagonOnX(0.0, peg.x(), peg.y(), pegRadius), pegLength);
        const std::size_t shelf = findFace(p, Vector3d::UnitZ(), Vector3d(0.0, 0.0, shelfTop));
        for (double side : {-1.0, 1.0})
        {
            const double y0 = side * 38.5, y1 = side * 42.0;
            p.addBoss(shelf, {{10.0, y0, shelfTop}, {44.0, y0, shelfTop}, {44.0, y1, shelfTop}, {10.0, y1, shelfTop}},
                      6.0);
        }
        return p.mesh(meshgap::uniformSizing(batteryGrid), "fixture");
    }

    // Hand and bowl, in mm (Table IV: hand 130 x 185 x 90, grid 3 to 30; bowl 300 x 60, grid 10, 36 segments).

    // Hand grid (before the sqrt(2)): 3 mm within 6 mm of a fingertip, growing slowly along the fingers (by
    // handGrading per mm) and fast (0.35 per mm more) beyond 70 mm from the nearest tip, up to 30 mm on the back.
    constexpr double handGrading = 0.055;

    struct Finger
    {
        std::string name;
        Vector3d base;                  // knuckle, inside the palm
        std::array<double, 3> lengths;  // phalanges
        std::array<double, 3> flex;     // bend at each joint towards the palm (degrees), cumulative
        double splay;                   // sideways angle (degrees, + towards the little finger)
        double radius;
    };

    struct Hand
    {
        Mesh mesh;
        std::vector<std::pair<std::string, Vector3d>> tips;    // fingertip points (body frame)
        std::vector<std::pair<std::string, std::size_t>> parts;  // part name, first triangle
    };

    /** \brief A right hand (body frame): back of the hand towards +z, palm towards -z, fingers along +y, thumb on
        the -x side, wrist at y = 0. Palm slab plus five bent fingers, each one closed shell (six components that
        overlap where the fingers enter the palm). Grid 3 mm at the fingertips growing to 30 mm away from them. */
    Hand hand()
    {
        const std::vector<Finger> fingers = {
            {"index", {-29.0, 84.0, 1.0}, {47.0, 28.0, 21.0}, {18.0, 32.0, 20.0}, -6.0, 9.0},
            {"middle", {-8.0, 88.0, 1.0}, {54.0, 32.0, 24.0}, {14.0, 30.0, 18.0}, 0.0, 9.5},
            {"ring", {13.0, 86.0, 1.0}, {48.0, 29.0, 21.0}, {18.0, 32.0, 20.0}, 5.0, 9.0},
            {"little", {32.0, 80.0, 1.0}, {38.0, 23.0, 19.0}, {22.0, 34.0, 20.0}, 11.0, 8.0},
        };
        std::vector<std::pair<std::string, std::vector<Vector3d>>> paths;
        std::vector<double> radii;
        for (const Finger &f : fingers)
        {
            const Vector3d forward(std::sin(radians(f.splay)), std::cos(radians(f.splay)), 0.0);
            std::vector<Vector3d> path{f.base};
            double bend = 0.0;
            for (int k = 0; k < 3; ++k)
            {
                bend += radians(f.flex[k]);
                path.push_back(path.back() + f.lengths[k] * (std::cos(bend) * forward - std::sin(bend) *
                                                                                            Vector3d::UnitZ()));
            }
            paths.emplace_back(f.name, path);
            radii.push_back(f.radius);
        }
        // Thumb: from the base of the palm's thumb side outwards, forwards and under the palm.
        paths.emplace_back("thumb", std::vector<Vector3d>{{-30.0, 22.0, -2.0},
                                                          {-60.0, 46.0, -20.0},
                                                          {-71.0, 72.0, -36.0},
                                                          {-70.0, 92.0, -57.0}});
        radii.push_back(10.5);

        Hand result;
        for (std::size_t i = 0; i < paths.size(); ++i)
        {
            const auto &path = paths[i].second;
            const Vector3d tangent = (path.back() - path[path.size() - 2]).normalized();
            result.tips.emplace_back(paths[i].first, path.back() + radii[i] * tangent);
        }
        std::vector<Vector3d> tipPoints;
        for (const auto &tip : result.tips)
            tipPoints.push_back(tip.second);
        const meshgap::SizingFunction sizing = [tipPoints](const Vector3d &p) {
            double d = std::numeric_limits<double>::infinity();
            for (const Vector3d &t : tipPoints)
                d = std::min(d, (p - t).norm());
            return sqrt2 *
                   std::min(30.0, 3.0 + handGrading * std::max(0.0, d - 6.0) + 0.35 * std::max(0.0, d - 70.0));
        };
        std::vector<Mesh> parts;
        Polyhedron palm = meshgap::prismPolyhedron({{-38.0, 0.0},
                                                    {36.0, 0.0},
                                                    {45.0, 18.0},
                                                    {46.0, 78.0},
                                                    {40.0, 92.0},
                                                    {-36.0, 97.0},
                                                    {-45.0, 86.0},
                                                    {-47.0, 30.0}},
                                                   {}, 34.0);
        Eigen::Isometry3d down = Eigen::Isometry3d::Identity();
        down.translation().z() = -17.0;
        palm.transform(down);
        result.parts.emplace_back("palm", 0);
        parts.push_back(palm.mesh(sizing, "hand palm"));
        std::size_t triangles = parts.back().triangles.size();
        for (std::size_t i = 0; i < paths.size(); ++i)
        {
            result.parts.emplace_back(paths[i].first, triangles);
            parts.push_back(meshgap::tubePolyhedron(paths[i].second, radii[i], 12, 4)
                                .mesh(sizing, "hand " + paths[i].first));
            triangles += parts.back().triangles.size();
        }
        result.mesh = meshgap::mergeMeshes(parts, "hand");
        return result;
    }

    constexpr double bowlGrid = 11.6;  // grid giving Table IV's node count (see maps/README.md)

    /** \brief Bowl (body frame): outer diameter 300, height 60, wall 6, rim at z = 60, foot on z = 0; the circle
        linearised with 36 segments, grid 10. */
    Mesh bowl()
    {
        std::vector<Vector2d> profile{{0.0, 0.0}, {80.0, 0.0}};
        const int wall = 12;
        for (int k = 1; k <= wall; ++k)  // outer wall: quarter ellipse from (80, 0) to (150, 60)
        {
            const double t = 0.5 * pi * k / wall;
            profile.emplace_back(80.0 + 70.0 * std::sin(t), 60.0 * (1.0 - std::cos(t)));
        }
        for (int k = wall; k >= 0; --k)  // inner wall: from (144, 60) down to (80, 6)
        {
            const double t = 0.5 * pi * k / wall;
            profile.emplace_back(80.0 + 64.0 * std::sin(t), 6.0 + 54.0 * (1.0 - std::cos(t)));
        }
        profile.emplace_back(0.0, 6.0);
        return meshgap::revolutionPolyhedron(profile, 36).mesh(meshgap::uniformSizing(bowlGrid), "bowl");
    }

    // ---------------------------------------------------------------------------------------------------------
    // Scenes
    // ---------------------------------------------------------------------------------------------------------

    struct Parts
    {
        std::vector<std::string> names;
        std::vector<std::size_t> label;  // per triangle, an index into names
    };

    struct Scene
    {
        std::string name, units, description;
        Mesh a, b;                               // A in the world frame; B in its body frame (not yet centred)
        std::vector<Eigen::Isometry3d> poses;    // B's body frame in A's frame
        std::optional<Eigen::Isometry3d> start;  // the planning problem's start; unset: the first pose
        Eigen::Isometry3d goal;                  // a pose clear of A (for the planning problem)
        Parts partsA, partsB;                    // named groups of triangles (for the report)
        std::optional<Eigen::AlignedBox3d> volume;  // the cfg's state volume; unset: a box around everything
    };

    Eigen::Isometry3d pose(const Vector3d &translation, const Eigen::Matrix3d &rotation = Eigen::Matrix3d::Identity())
    {
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() = rotation;
        X.translation() = translation;
        return X;
    }

    Eigen::Matrix3d rotation(const Vector3d &axis, double degrees)
    {
        return Eigen::AngleAxisd(radians(degrees), axis.normalized()).toRotationMatrix();
    }

    /** \brief The triangles of one part (all vertices kept). */
    Mesh partMesh(const Mesh &m, const Parts &parts, std::size_t i)
    {
        Mesh part = m;
        part.triangles.clear();
        for (std::size_t t = 0; t < m.triangles.size(); ++t)
            if (parts.label[t] == i)
                part.triangles.push_back(m.triangles[t]);
        return part;
    }

    /** \brief Parts of a body whose triangles come in consecutive runs (name, first triangle). */
    Parts partsByRuns(const std::vector<std::pair<std::string, std::size_t>> &runs, std::size_t triangles)
    {
        Parts parts;
        parts.label.assign(triangles, 0);
        for (std::size_t i = 0; i < runs.size(); ++i)
        {
            parts.names.push_back(runs[i].first);
            for (std::size_t t = runs[i].second; t < triangles; ++t)
                parts.label[t] = i;
        }
        return parts;
    }

    /** \brief Parts of a body told apart by where each triangle's centroid is. */
    Parts partsByPlace(const Mesh &m, std::vector<std::string> names,
                       const std::function<std::size_t(const Vector3d &)> &classify)
    {
        Parts parts;
        parts.names = std::move(names);
        for (const meshgap::Triangle &t : m.triangles)
            parts.label.push_back(classify((m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0));
        return parts;
    }

    Scene batteryFixture()
    {
        Scene s;
        s.name = "battery_fixture";
        s.units = "cm";
        s.a = fixture();
        s.b = battery();
        const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
        // Position 1: battery 4 cm off the plate (pegs 6 cm into the holes), 0.3 cm above the shelf, rolled 0.1
        // degrees; slid sideways (-y) until a peg is 0.0747 from its hole's wall (Table III, exact).
        const Eigen::Isometry3d p1 =
            pose(Vector3d(4.0, 0.0, shelfTop + 0.3), rotation(Vector3d::UnitX(), 0.1));
        s.poses.push_back(placeAtGap(*bodyA, *bodyB, p1, -Vector3d::UnitY(), 0.0747, "battery_fixture position 1"));
        // Position 2: 2.5 cm off the plate, yawed 0.3 degrees, 0.25 above the shelf; slid +y to 0.0987.
        const Eigen::Isometry3d p2 =
            pose(Vector3d(2.5, 0.0, shelfTop + 0.25), rotation(Vector3d::UnitZ(), 0.3));
        s.poses.push_back(placeAtGap(*bodyA, *bodyB, p2, Vector3d::UnitY(), 0.0987, "battery_fixture position 2"));
        // The planning problem does not start at position 1: with the pegs 6 into the holes and 0.07 of play, the
        // way out is a passage that sampling does not find. It starts just before insertion instead: the battery
        // centred between the rails, 1.5 above the shelf, its back face 1.5 in front of the peg tips (then lowered
        // 1.5 and pushed in, the holes would take the pegs), so the shelf, both rails and both peg tips are all
        // 1.5 away. The goal is in front of the shelf's lip at the same height: the battery has to be lifted over
        // the lip (6.5 higher at least). The shortest way skims the lip; one that keeps 1.5 goes higher.
        s.start = pose(Vector3d(pegLength + 1.5, 0.0, shelfTop + 1.5));
        s.goal = pose(Vector3d(61.0, 0.0, shelfTop + 1.5));
        auto near = [](double x, double y) { return std::abs(x - y) < 1e-9; };
        auto nearAxis = [](const Vector3d &c, const Vector2d &axis, double radius) {
            return (Vector2d(c.y(), c.z()) - axis).norm() <= radius + 1e-9;
        };
        const std::vector<std::string> partNamesA = {"peg1", "peg2", "plate", "shelf", "rails", "lip", "other"};
        s.partsA = partsByPlace(s.a, partNamesA, [&](const Vector3d &c) {
            for (std::size_t i = 0; i < 2; ++i)
                if (c.x() > 1e-9 && c.x() <= pegLength + 1e-9 && nearAxis(c, pegAt[i], pegRadius))
                    return i;
            if (near(c.x(), 0.0))
                return std::size_t(2);
            if (near(c.z(), shelfTop))
                return std::size_t(3);
            if (c.z() > shelfTop + 1e-9 && std::abs(c.y()) >= 38.5 - 1e-9 && c.x() > 1e-9 && c.x() <= 44.0 + 1e-9)
                return std::size_t(4);
            if (c.x() >= 48.0 - 1e-9)
                return std::size_t(5);
            return std::size_t(6);
        });
        s.partsB = partsByPlace(s.b, {"hole1", "hole2", "back", "bottom", "other"}, [&](const Vector3d &c) {
            for (std::size_t i = 0; i < 2; ++i)
                if (c.x() > 1e-9 && c.x() <= holeDepth + 1e-9 &&
                    nearAxis(c, pegAt[i] - Vector2d(0.0, shelfTop), holeRadius))
                    return i;
            if (near(c.x(), 0.0))
                return std::size_t(2);
            if (near(c.z(), 0.0))
                return std::size_t(3);
            return std::size_t(4);
        });
        return s;
    }

    Scene handBowl()
    {
        Scene s;
        s.name = "hand_bowl";
        s.units = "mm";
        s.a = bowl();
        Hand h = hand();
        s.b = h.mesh;
        const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
        // Hand over the rim at +x, fingers pointing at the bowl's axis (-x), palm down; tilted so the middle
        // fingertip hangs lowest, then lowered until it is 4.7527 from the rim (Table V, exact).
        const Eigen::Matrix3d R = rotation(Vector3d::UnitZ(), 90.0) * rotation(Vector3d::UnitX(), -8.0);
        Vector3d middleTip = Vector3d::Zero();
        for (const auto &tip : h.tips)
            if (tip.first == "middle")
                middleTip = tip.second;
        const Vector3d start = Vector3d(147.0, 4.0, 60.0 + 20.0) - R * middleTip;  // between rim nodes
        s.poses.push_back(placeAtGap(*bodyA, *bodyB, pose(start, R), -Vector3d::UnitZ(), 4.7527, "hand_bowl"));
        // Planning: from beside the bowl, below its rim (the pose moved 40 down and out along +x until the hand is
        // 25 from the bowl's outer wall; 4.75 would bound every path's minimum clearance), into the bowl: the hand
        // moved over the bowl's middle and lowered into it, its fingertips above the floor (27.2 from the bowl).
        // The straight line runs through the wall; the shortest way over the rim skims it, one that keeps 25 lifts
        // the hand well above the rim first.
        s.start = placeAtGap(*bodyA, *bodyB, pose(s.poses.front().translation() + Vector3d(60.0, 0.0, -40.0), R),
                             -Vector3d::UnitX(), 25.0, "hand_bowl start");
        s.goal = pose(s.poses.front().translation() + Vector3d(-240.0, 0.0, -30.0), R);
        s.partsA = partsByRuns({{"bowl", 0}}, s.a.triangles.size());
        s.partsB = partsByRuns(h.parts, s.b.triangles.size());
        return s;
    }

    Scene handshake()
    {
        Scene s;
        s.name = "handshake";
        s.units = "mm";
        Hand h = hand();
        // A: right hand, fingers along +y, palm facing -x, thumb up (body z -> world x, body x -> world -z).
        Eigen::Matrix3d RA;
        RA << 0, 0, 1, 0, 1, 0, -1, 0, 0;
        s.a = posed(h.mesh, pose(Vector3d::Zero(), RA));
        s.b = h.mesh;
        // B: the other person's right hand, turned half about the vertical to face A, a little higher and tilted.
        const Eigen::Matrix3d RB = rotation(Vector3d::UnitY(), 25.0) * rotation(Vector3d::UnitZ(), 180.0) * RA;
        Vector3d indexA = Vector3d::Zero(), thumbB = Vector3d::Zero();
        for (const auto &tip : h.tips)
        {
            if (tip.first == "index")
                indexA = RA * tip.second;
            if (tip.first == "thumb")
                thumbB = RB * tip.second;
        }
        // B's thumb tip placed beside and above A's index tip, then slid along that offset to 18.95 (Table VI).
        const Vector3d offset = Vector3d(-0.8, 0.45, 0.3).normalized();
        const Vector3d start = indexA + 45.0 * offset - thumbB;
        const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
        s.poses.push_back(placeAtGap(*bodyA, *bodyB, pose(start, RB), -offset, 18.95, "handshake"));
        // Goal: B on the far side of A (behind the back of A's hand), same orientation. The straight line runs
        // through A, so a path goes round A's fingers, thumb or wrist: the shortest way skims A, one that keeps
        // the start's 18.95 swings wide.
        s.goal = pose(s.poses.front().translation() + Vector3d(300.0, 0.0, 0.0), RB);
        s.partsA = partsByRuns(h.parts, s.a.triangles.size());
        s.partsB = partsByRuns(h.parts, s.b.triangles.size());
        return s;
    }


    // Slotted wall, in its own units: a wall with a narrow slot (short route, little play) and a wide slot off to
    // one side (long route, four times the play), and a C-shaped payload that fits through either slot only lying
    // nearly flat. Not from the paper: a planning problem that forces a trade-off between length and clearance.
    constexpr double wallThickness = 10.0;                // x in [-5, 5]
    constexpr double wallWidth = 200.0;                   // y in [-100, 100]
    constexpr double wallHeight = 150.0;                  // z in [0, 150]
    constexpr double slotLength = 40.0;                   // both slots, along y
    constexpr double slotZ = 75.0;                        // both slots' mid-height
    constexpr double payloadThickness = 8.0;              // the C part's extrusion
    constexpr double narrowSlot = payloadThickness + 5.0; // 5 of play in total, centred at y = 0
    constexpr double wideSlot = payloadThickness + 20.0;  // 20 of play (4x), centred at y = 55
    constexpr double wideSlotY = 55.0;
    constexpr double wallGrid = 9.0;
    constexpr double payloadGrid = 2.5;

    /** \brief Wall (world frame): x in [-5, 5], y in [-100, 100], z in [0, 150], with two horizontal rectangular
        through slots of length 40 (along y) at z = 75: 13 high at y = 0 and 28 high at y = 55. */
    Mesh slottedWall()
    {
        auto slot = [](double y, double height) {
            return Polygon2d{{y - 0.5 * slotLength, slotZ - 0.5 * height},
                             {y + 0.5 * slotLength, slotZ - 0.5 * height},
                             {y + 0.5 * slotLength, slotZ + 0.5 * height},
                             {y - 0.5 * slotLength, slotZ + 0.5 * height}};
        };
        // Profile drawn in (y, z), extruded along x: (X, Y, Z) -> (Z - 5, X, Y).
        Polyhedron p = meshgap::prismPolyhedron({{-0.5 * wallWidth, 0.0},
                                                 {0.5 * wallWidth, 0.0},
                                                 {0.5 * wallWidth, wallHeight},
                                                 {-0.5 * wallWidth, wallHeight}},
                                                {slot(0.0, narrowSlot), slot(wideSlotY, wideSlot)}, wallThickness);
        Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
        X.linear() << 0, 0, 1, 1, 0, 0, 0, 1, 0;
        X.translation() = Vector3d(-0.5 * wallThickness, 0.0, 0.0);
        p.transform(X);
        return p.mesh(meshgap::uniformSizing(wallGrid), "slotted wall");
    }

    /** \brief Payload (body frame): a C, x in [0, 20], y in [0, 30], arms 6 thick opening towards +x, extruded
        8 along z. */
    Mesh payload()
    {
        return meshgap::prismPolyhedron({{0.0, 0.0},
                                         {20.0, 0.0},
                                         {20.0, 6.0},
                                         {6.0, 6.0},
                                         {6.0, 24.0},
                                         {20.0, 24.0},
                                         {20.0, 30.0},
                                         {0.0, 30.0}},
                                        {}, payloadThickness)
            .mesh(meshgap::uniformSizing(payloadGrid), "payload");
    }

    Scene slottedWallScene()
    {
        Scene s;
        s.name = "slotted_wall";
        s.units = "units";
        s.a = slottedWall();
        s.b = payload();
        const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
        // Start: in front of the wall (-x), standing on edge (rolled 90 degrees about x: 20 along x, 8 along y, 30
        // along z), which fits neither slot; slid towards the wall until 5 from it. Goal: the same on the far
        // side, 6 from the wall.
        const Eigen::Matrix3d R = rotation(Vector3d::UnitX(), 90.0);
        const Vector3d centre(10.0, 15.0, 0.5 * payloadThickness);  // the C's bounding-box centre (body frame)
        s.poses.push_back(placeAtGap(*bodyA, *bodyB, pose(Vector3d(-40.0, -10.0, 70.0) - R * centre, R),
                                     Vector3d::UnitX(), 5.0, "slotted_wall start"));
        s.goal = placeAtGap(*bodyA, *bodyB, pose(Vector3d(40.0, -10.0, 70.0) - R * centre, R), -Vector3d::UnitX(), 6.0,
                            "slotted_wall goal");
        // The state volume keeps B's origin (its vertex mean, near the C's middle; no point of the C is more than 20
        // from it) at least 25 inside the wall's sides, top and bottom, so the only ways across are the slots.
        s.volume = Eigen::AlignedBox3d(Vector3d(-45.0, -75.0, 25.0), Vector3d(45.0, 75.0, 125.0));
        s.partsA = partsByPlace(s.a, {"narrow slot", "wide slot", "wall"}, [](const Vector3d &c) {
            const bool inFace = std::abs(c.x()) < 0.5 * wallThickness - 1e-9;
            if (inFace && std::abs(c.y()) <= 0.5 * slotLength + 1e-9 &&
                std::abs(c.z() - slotZ) <= 0.5 * narrowSlot + 1e-9)
                return std::size_t(0);
            if (inFace && std::abs(c.y() - wideSlotY) <= 0.5 * slotLength + 1e-9 &&
                std::abs(c.z() - slotZ) <= 0.5 * wideSlot + 1e-9)
                return std::size_t(1);
            return std::size_t(2);
        });
        s.partsB = partsByRuns({{"payload", 0}}, s.b.triangles.size());
        return s;
    }

    // Twisted, in its own units: a stress scene for the exact layer (issue 13), not from the paper. A long, thin
    // flat strip (section 1.5 x 0.4) wound as a helix, three turns (a coil spring of flat wire), screws through a
    // helical channel of the same pitch (five turns, a hollow coil whose bore is the strip's section grown by the
    // play on every side). Both are concave, twisted everywhere and made of long thin triangles (slivers, 15 degrees
    // of arc long). The motion is a screw about z that the channel maps onto itself, so inside it the strip keeps
    // about its play on every side (less the chords' sagitta), the whole way.
    constexpr double twistRadius = 12.0;       // the strip's mid radius about z
    constexpr double twistWidth = 1.5;         // radial width: r in [11.25, 12.75]
    constexpr double twistThickness = 0.4;     // along z
    constexpr double twistPitch = 8.0;         // rise per turn (strip and channel)
    constexpr double twistPlay = 0.3;          // the channel's bore: the strip's section grown by this on each side
    constexpr double twistWall = 1.0;          // the channel's wall thickness
    constexpr double twistStepDegrees = 15.0;  // stations of both sweeps (the same angles, so faces line up)
    constexpr int twistStripTurns = 3, twistChannelTurns = 5;
    constexpr double twistApproachDegrees = 15.0;  // the strip's end this far before the channel at the start
    constexpr double twistPoseStepDegrees = 3.75;  // the screw turned this much between two .poses lines

    /** \brief The solid swept by the section \e outer (minus \e hole, if not empty), drawn in the (r, z) half-plane
        (r > 0), along the screw about z that turns by theta and rises by pitch * theta / (2 pi), from \e from to
        \e to (radians) in \e steps stations. The section is planar at every station (a meridian half-plane), so
        each end is one planar face (with a hole); between stations each side quad is split into two triangles
        (a helicoid is not planar). Wound outward. */
    Polyhedron helicalSweep(Polygon2d outer, Polygon2d hole, double from, double to, unsigned int steps, double pitch)
    {
        if (meshgap::polygonArea(outer) < 0.0)
            std::reverse(outer.begin(), outer.end());
        if (!hole.empty() && meshgap::polygonArea(hole) > 0.0)
            std::reverse(hole.begin(), hole.end());
        std::vector<Polygon2d> loops{outer};
        if (!hole.empty())
            loops.push_back(hole);
        Polyhedron p;
        // id[k][l][i]: corner i of loop l at station k.
        std::vector<std::vector<Polyhedron::Loop>> id(steps + 1);
        for (unsigned int k = 0; k <= steps; ++k)
        {
            const double theta = from + (to - from) * k / steps;
            for (const Polygon2d &loop : loops)
            {
                id[k].emplace_back();
                for (const Vector2d &q : loop)
                    id[k].back().push_back(p.addCorner(Vector3d(q.x() * std::cos(theta), q.x() * std::sin(theta),
                                                                q.y() + pitch * theta / (2.0 * pi))));
            }
        }
        for (unsigned int k = 0; k < steps; ++k)
            for (std::size_t l = 0; l < loops.size(); ++l)
                for (std::size_t i = 0; i < loops[l].size(); ++i)
                {
                    const std::size_t j = (i + 1) % loops[l].size();
                    const std::uint32_t a = id[k][l][i], b = id[k][l][j], c = id[k + 1][l][j], d = id[k + 1][l][i];
                    p.addFace({a, b, c});
                    p.addFace({a, c, d});
                }
        auto reversed = [](Polyhedron::Loop loop) {
            std::reverse(loop.begin(), loop.end());
            return loop;
        };
        const std::size_t first = p.addFace(reversed(id[0][0])), last = p.addFace(id[steps][0]);
        for (std::size_t l = 1; l < loops.size(); ++l)
        {
            p.addHole(first, reversed(id[0][l]));
            p.addHole(last, id[steps][l]);
        }
        p.check();
        if (p.volume() < 0.0)
            p.reverse();
        return p;
    }

    /** \brief An axis-aligned rectangle in the (r, z) half-plane: r in [r0, r1], z in [-h, h]. */
    Polygon2d sectionRectangle(double r0, double r1, double h)
    {
        return {{r0, -h}, {r1, -h}, {r1, h}, {r0, h}};
    }

    /** \brief The screw about z by \e theta radians (the rise of twistPitch per turn). */
    Eigen::Isometry3d twistScrew(double theta)
    {
        return pose(Vector3d(0.0, 0.0, twistPitch * theta / (2.0 * pi)),
                    rotation(Vector3d::UnitZ(), theta * 180.0 / pi));
    }

    Scene twistedScene()
    {
        Scene s;
        s.name = "twisted";
        s.units = "units";
        const double r0 = twistRadius - 0.5 * twistWidth, r1 = twistRadius + 0.5 * twistWidth, h = 0.5 * twistThickness;
        const double huge = 1e3;  // sizing above every edge: the sweeps' triangles are kept as they are (slivers)
        const unsigned int stripSteps =
            static_cast<unsigned int>(std::lround(360.0 * twistStripTurns / twistStepDegrees));
        const unsigned int channelSteps =
            static_cast<unsigned int>(std::lround(360.0 * twistChannelTurns / twistStepDegrees));
        const double stripEnd = 2.0 * pi * twistStripTurns, channelEnd = 2.0 * pi * twistChannelTurns;
        s.b = helicalSweep(sectionRectangle(r0, r1, h), {}, 0.0, stripEnd, stripSteps, twistPitch)
                  .mesh(meshgap::uniformSizing(huge), "twisted strip");
        const double bore = twistPlay, wall = twistPlay + twistWall;
        s.a = helicalSweep(sectionRectangle(r0 - wall, r1 + wall, h + wall),
                           sectionRectangle(r0 - bore, r1 + bore, h + bore), 0.0, channelEnd, channelSteps, twistPitch)
                  .mesh(meshgap::uniformSizing(huge), "twisted channel");
        // The path: the screw from the strip's end twistApproachDegrees before the channel's mouth to its start
        // as far beyond the channel's far end; the strip occupies the screw angles [u, u + stripEnd].
        const double approach = radians(twistApproachDegrees);
        const double u0 = -stripEnd - approach, u1 = channelEnd + approach;
        const int count = static_cast<int>(std::lround((u1 - u0) / radians(twistPoseStepDegrees)));
        for (int k = 0; k <= count; ++k)
            s.poses.push_back(twistScrew(u0 + (u1 - u0) * k / count));
        s.goal = s.poses.back();
        s.partsA = partsByRuns({{"channel", 0}}, s.a.triangles.size());
        s.partsB = partsByRuns({{"strip", 0}}, s.b.triangles.size());
        return s;
    }

    // ---------------------------------------------------------------------------------------------------------
    // Output
    // ---------------------------------------------------------------------------------------------------------

    std::string number(double x)
    {
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, "%.17g", x);
        return buffer;
    }

    void writeText(const std::filesystem::path &path, const std::string &text)
    {
        meshgap::writeStreamAtomically(path.string(), [&](std::ostream &out) { out << text; });
    }

    std::size_t closedEdgeFaults(const Mesh &m)
    {
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (const meshgap::Triangle &t : m.triangles)
            for (int k = 0; k < 3; ++k)
                ++uses[std::minmax(t[k], t[(k + 1) % 3])];
        std::size_t faults = 0;
        for (const auto &entry : uses)
            faults += entry.second != 2;
        return faults;
    }

    double meanEdge(const Mesh &m)
    {
        double sum = 0.0;
        for (const meshgap::Triangle &t : m.triangles)
            for (int k = 0; k < 3; ++k)
                sum += (m.vertices[t[k]] - m.vertices[t[(k + 1) % 3]]).norm();
        return m.triangles.empty() ? 0.0 : sum / (3.0 * static_cast<double>(m.triangles.size()));
    }

    double minVertexDistance(const Mesh &a, const Mesh &b)
    {
        double best = std::numeric_limits<double>::infinity();
        for (const Vector3d &p : a.vertices)
            for (const Vector3d &q : b.vertices)
                best = std::min(best, (p - q).squaredNorm());
        return std::sqrt(best);
    }

    void writeScene(Scene s, const std::filesystem::path &directory)
    {
        std::filesystem::create_directories(directory);
        // B is stored with the mean of its unique vertices at the origin; the .poses file holds B's pose in A's frame.
        const Vector3d centre = meshgap::vertexMean(s.b);
        meshgap::transformMesh(s.b, pose(-centre));
        for (Eigen::Isometry3d &X : s.poses)
            X = X * pose(centre);
        s.goal = s.goal * pose(centre);
        if (s.start)
            *s.start = *s.start * pose(centre);
        const Eigen::Isometry3d start = s.start ? *s.start : s.poses.front();
        s.a.source = s.name + "_a";
        s.b.source = s.name + "_b";
        meshgap::writeObj(s.a, (directory / (s.name + "_a.obj")).string());
        meshgap::writeObj(s.b, (directory / (s.name + "_b.obj")).string());

        std::ostringstream poses;
        for (const Eigen::Isometry3d &X : s.poses)
        {
            const Eigen::Quaterniond q(X.linear());
            poses << number(X.translation().x()) << ' ' << number(X.translation().y()) << ' '
                  << number(X.translation().z()) << ' ' << number(q.x()) << ' ' << number(q.y()) << ' '
                  << number(q.z()) << ' ' << number(q.w()) << '\n';
        }
        writeText(directory / (s.name + ".poses"), poses.str());

        Eigen::AlignedBox3d volume = s.a.bounds();
        volume.extend(s.poses.front().translation());
        volume.extend(start.translation());
        volume.extend(s.goal.translation());
        double margin = 0.25 * volume.diagonal().norm();
        if (s.volume)
        {
            volume = *s.volume;
            margin = 0.0;
        }
        std::ostringstream cfg;
        cfg << "[problem]\nname = " << s.name << "\nrobot = " << s.name << "_b.obj\nworld = " << s.name
            << "_a.obj\n";
        auto state = [&cfg](const std::string &prefix, const Eigen::Isometry3d &X) {
            Eigen::AngleAxisd aa(X.linear());
            Vector3d axis = aa.axis();
            if (aa.angle() == 0.0)
                axis = Vector3d::UnitZ();
            cfg << prefix << ".x = " << number(X.translation().x()) << '\n'
                << prefix << ".y = " << number(X.translation().y()) << '\n'
                << prefix << ".z = " << number(X.translation().z()) << '\n'
                << prefix << ".theta = " << number(aa.angle()) << '\n'
                << prefix << ".axis.x = " << number(axis.x()) << '\n'
                << prefix << ".axis.y = " << number(axis.y()) << '\n'
                << prefix << ".axis.z = " << number(axis.z()) << '\n';
        };
        // The .cfg holds OMPL.app states. OMPL.app shifts a robot by the mean of every vertex assimp returns for the
        // file (its per-face copies included), c, which is not B's origin: p = R (v - c) + x. So the state that puts
        // B where its pose X does is X * translate(c), read from the file just written with meshgap's own loader.
        meshgap::LoadReport robotReport;
        meshgap::loadMesh((directory / (s.name + "_b.obj")).string(), &robotReport);
        const Eigen::Isometry3d toState = pose(robotReport.omplAppCenter);
        state("start", start * toState);
        state("goal", s.goal * toState);
        const char *axes = "xyz";
        for (int k = 0; k < 3; ++k)
            cfg << "volume.min." << axes[k] << " = " << number(std::floor(volume.min()[k] - margin)) << '\n';
        for (int k = 0; k < 3; ++k)
            cfg << "volume.max." << axes[k] << " = " << number(std::ceil(volume.max()[k] + margin)) << '\n';
        // RRTConnect solves every map well within this (bench/clearance_table.sh).
        cfg << "\n[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n";
        writeText(directory / (s.name + ".cfg"), cfg.str());

        // Report (and check) what was written.
        auto describe = [](const char *label, const Mesh &m) {
            const Eigen::Vector3d extent = m.bounds().diagonal();
            std::printf("  %s: %zu nodes, %zu triangles, %zu components, %zu open edges, volume %.6g, "
                        "extent %.4g x %.4g x %.4g, edges %.4g mean %.4g longest\n",
                        label, m.vertices.size(), m.triangles.size(), meshgap::countComponents(m),
                        closedEdgeFaults(m), meshgap::signedVolume(m), extent.x(), extent.y(), extent.z(),
                        meanEdge(m), meshgap::longestEdge(m));
        };
        std::printf("%s (%s) -> %s\n", s.name.c_str(), s.units.c_str(), directory.string().c_str());
        describe("A", s.a);
        describe("B", s.b);
        const meshgap::BodyPtr bodyA = exactBody(s.a), bodyB = exactBody(s.b);
        // Each part of A and of B as a mesh of its own (all vertices kept) with a BVH over its triangles.
        std::vector<Mesh> partMeshesA, partMeshesB;
        for (std::size_t i = 0; i < s.partsA.names.size(); ++i)
            partMeshesA.push_back(partMesh(s.a, s.partsA, i));
        for (std::size_t j = 0; j < s.partsB.names.size(); ++j)
            partMeshesB.push_back(partMesh(s.b, s.partsB, j));
        std::vector<meshgap::TriangleBvh> partTreesA, partTreesB;  // point into partMeshesA/B, which stay put
        for (const Mesh &part : partMeshesA)
            partTreesA.emplace_back(part);
        for (const Mesh &part : partMeshesB)
            partTreesB.emplace_back(part);
        auto check = [&](const char *label, const Eigen::Isometry3d &X) {
            const meshgap::DistanceResult c = distanceAt(*bodyA, *bodyB, X);
            if (!(c.distance > 0.0))
                throw meshgap::Exception(s.name, std::string(label) + ": B touches A");
            std::printf("  %s: exact distance %.10g (A %s at %.4f %.4f %.4f, B %s), nearest nodes %.6g\n", label,
                        c.distance, s.partsA.names[s.partsA.label[c.triangleA]].c_str(), c.onA.x(), c.onA.y(),
                        c.onA.z(), s.partsB.names[s.partsB.label[c.triangleB]].c_str(),
                        minVertexDistance(s.a, posed(s.b, X)));
            if (s.partsA.names.size() * s.partsB.names.size() == 1)
                return;
            // Distance between each part of A and each of B (surface distance, 0 if they intersect): each is (at
            // least) one local minimum. A part without triangles is infinitely far.
            std::vector<std::pair<double, std::string>> pairs;
            for (std::size_t i = 0; i < partTreesA.size(); ++i)
                for (std::size_t j = 0; j < partTreesB.size(); ++j)
                {
                    meshgap::BvhDistanceResult r;
                    if (!partMeshesA[i].triangles.empty() && !partMeshesB[j].triangles.empty())
                        meshgap::bvhDistance(partTreesA[i], partTreesB[j], X,
                                             std::numeric_limits<double>::infinity(), 0.0, r);
                    pairs.emplace_back(r.distance, s.partsA.names[i] + "-" + s.partsB.names[j]);
                }
            std::sort(pairs.begin(), pairs.end());
            std::printf("    closest part pairs (A-B):");
            const std::size_t shown = std::min<std::size_t>(8, pairs.size());
            for (std::size_t k = 0; k < shown; ++k)
                std::printf(" %s %.4g%s", pairs[k].second.c_str(), pairs[k].first, k + 1 < shown ? "," : "\n");
        };
        if (s.poses.size() <= 8)
            for (std::size_t i = 0; i < s.poses.size(); ++i)
                check(("pose " + std::to_string(i + 1)).c_str(), s.poses[i]);
        else
        {
            // A path: every pose must be clear of A; the first, the closest and the last are reported.
            std::size_t closest = 0;
            double best = std::numeric_limits<double>::infinity(), worst = 0.0;
            for (std::size_t i = 0; i < s.poses.size(); ++i)
            {
                const double d = distanceAt(*bodyA, *bodyB, s.poses[i]).distance;
                if (!(d > 0.0))
                    throw meshgap::Exception(s.name, "pose " + std::to_string(i + 1) + ": B touches A");
                worst = std::max(worst, d);
                if (d < best)
                {
                    best = d;
                    closest = i;
                }
            }
            std::printf("  path of %zu poses: exact distance from %.10g (pose %zu) to %.10g\n", s.poses.size(), best,
                        closest + 1, worst);
            check("pose 1", s.poses.front());
            check(("pose " + std::to_string(closest + 1)).c_str(), s.poses[closest]);
            check(("pose " + std::to_string(s.poses.size())).c_str(), s.poses.back());
        }
        if (s.start)
            check("start", *s.start);
        check("goal", s.goal);
    }
}  // namespace

int main(int argc, char **argv)
{
    return meshgap::cli::runMain(argc, argv, [](int ac, char **av) {
        const std::vector<std::pair<std::string, std::function<Scene()>>> scenes = {
            {"battery_fixture", batteryFixture}, {"hand_bowl", handBowl}, {"handshake", handshake},
            {"slotted_wall", slottedWallScene}, {"twisted", twistedScene}};
        po::options_description options("meshgap_makemap: write the paper's test scenes (meshes, poses, OMPL.app "
                                        "problems)");
        std::string out, which;
        options.add_options()("help,h", "show this help")(
            "out", po::value<std::string>(&out)->required(), "output directory (one sub-directory per scene)")(
            "scene", po::value<std::string>(&which)->default_value("all"),
            "battery_fixture, hand_bowl, handshake, slotted_wall, twisted or all")(
            "battery-grid", po::value<double>(&batteryGrid),
            "largest edge of the battery and fixture meshes in cm (default 5 sqrt 2, Table II's grid; a larger value "
            "gives coarse meshes for adaptive node sizing to refine)");
        po::variables_map vm;
        if (!meshgap::cli::parseCommandLine(ac, av, options, vm))
            return 0;
        std::string names;
        bool found = false;
        for (const auto &scene : scenes)
        {
            names += (names.empty() ? "" : ", ") + scene.first;
            found = found || scene.first == which;
        }
        if (which != "all" && !found)
            throw meshgap::Exception("--scene", "unknown scene '" + which + "' (valid: " + names + ", all)");
        for (const auto &scene : scenes)
            if (which == "all" || which == scene.first)
                writeScene(scene.second(), std::filesystem::path(out) / scene.first);
        return 0;
    });
}
