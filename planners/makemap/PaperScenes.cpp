// The paper's three test scenes (Carretero & Nahon, Section IV): battery and fixture (cm, Table II), hand and
// bowl (mm, Table IV), two hands about to shake (mm).

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "makemap/MapScene.h"
#include "meshgap/Exception.h"
#include "meshgap/mesh/MeshOperations.h"
#include "support/Shapes.h"

namespace meshgap
{
    namespace makemap
    {
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
        constexpr double HOLE_RADIUS = 3.0;          // alignment holes: hexagons of circumradius 3, 12 deep
        constexpr double HOLE_DEPTH = 12.0;
        constexpr double PEG_RADIUS = 2.5;           // pegs: hexagons of circumradius 2.5, 10 long
        constexpr double PEG_LENGTH = 10.0;
        constexpr double SHELF_TOP = 6.0;            // the battery sits on the fixture's shelf
        const Vector2d pegAt[2] = {{-24.0, 24.0}, {24.0, 72.0}};  // (y, z) of the pegs on the fixture plate

        /** \brief Battery (body frame): box x in [0, 31] (x = 0 the back face, towards the fixture), y in [-37, 37],
            z in [0, 92], with two blind hexagonal alignment holes in the back face. */
        Mesh battery()
        {
            Polyhedron p = meshgap::prismPolyhedron({{0.0, -37.0}, {31.0, -37.0}, {31.0, 37.0}, {0.0, 37.0}}, {}, 92.0);
            const std::size_t back = findFace(p, -Vector3d::UnitX(), Vector3d::Zero());
            for (const Vector2d &peg : pegAt)
                p.addBoss(back, hexagonOnX(0.0, peg.x(), peg.y() - SHELF_TOP, HOLE_RADIUS), -HOLE_DEPTH);
            return p.mesh(meshgap::uniformSizing(batteryGrid), "battery");
        }

        /** \brief Fixture (world frame): an L bracket, back plate x in [-8, 0], z in [0, 99] and shelf x in [-8, 54],
            z in [0, 6], y in [-43, 43], with a lip along the shelf's front edge (x in [48, 54], up to z = 14); two
            hexagonal pegs on the plate's front face (x = 0) and two guide rails on the shelf either side of the
            battery. */
        Mesh fixture()
        {
            Polyhedron p = meshgap::prismPolyhedron(
                {{-8.0, 0.0}, {54.0, 0.0}, {54.0, 14.0}, {48.0, 14.0}, {48.0, SHELF_TOP}, {0.0, SHELF_TOP}, {0.0, 99.0},
                 {-8.0, 99.0}},
                {}, 86.0);
            // Profile drawn in (x, z), extruded along -y: (X, Y, Z) -> (X, 43 - Z, Y).
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            X.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;
            X.translation() = Vector3d(0.0, 43.0, 0.0);
            p.transform(X);
            const std::size_t plate = findFace(p, Vector3d::UnitX(), Vector3d::Zero());
            for (const Vector2d &peg : pegAt)
                p.addBoss(plate, hexagonOnX(0.0, peg.x(), peg.y(), PEG_RADIUS), PEG_LENGTH);
            const std::size_t shelf = findFace(p, Vector3d::UnitZ(), Vector3d(0.0, 0.0, SHELF_TOP));
            for (double side : {-1.0, 1.0})
            {
                const double y0 = side * 38.5, y1 = side * 42.0;
                p.addBoss(shelf, {{10.0, y0, SHELF_TOP}, {44.0, y0, SHELF_TOP}, {44.0, y1, SHELF_TOP}, {10.0, y1, SHELF_TOP}},
                          6.0);
            }
            return p.mesh(meshgap::uniformSizing(batteryGrid), "fixture");
        }

        // Hand and bowl, in mm (Table IV: hand 130 x 185 x 90, grid 3 to 30; bowl 300 x 60, grid 10, 36 segments).

        // Hand grid (before the sqrt(2)): 3 mm within 6 mm of a fingertip, growing slowly along the fingers (by
        // HAND_GRADING per mm) and fast (0.35 per mm more) beyond 70 mm from the nearest tip, up to 30 mm on the back.
        constexpr double HAND_GRADING = 0.055;

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
                       std::min(30.0, 3.0 + HAND_GRADING * std::max(0.0, d - 6.0) + 0.35 * std::max(0.0, d - 70.0));
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

        constexpr double BOWL_GRID = 11.6;  // grid giving Table IV's node count (see maps/README.md)

        /** \brief Bowl (body frame): outer diameter 300, height 60, wall 6, rim at z = 60, foot on z = 0; the circle
            linearised with 36 segments, grid 10. */
        Mesh bowl()
        {
            std::vector<Vector2d> profile{{0.0, 0.0}, {80.0, 0.0}};
            const int wall = 12;
            for (int k = 1; k <= wall; ++k)  // outer wall: quarter ellipse from (80, 0) to (150, 60)
            {
                const double t = 0.5 * PI * k / wall;
                profile.emplace_back(80.0 + 70.0 * std::sin(t), 60.0 * (1.0 - std::cos(t)));
            }
            for (int k = wall; k >= 0; --k)  // inner wall: from (144, 60) down to (80, 6)
            {
                const double t = 0.5 * PI * k / wall;
                profile.emplace_back(80.0 + 64.0 * std::sin(t), 6.0 + 54.0 * (1.0 - std::cos(t)));
            }
            profile.emplace_back(0.0, 6.0);
            return meshgap::revolutionPolyhedron(profile, 36).mesh(meshgap::uniformSizing(BOWL_GRID), "bowl");
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
                pose(Vector3d(4.0, 0.0, SHELF_TOP + 0.3), rotation(Vector3d::UnitX(), 0.1));
            s.poses.push_back(placeAtGap(*bodyA, *bodyB, p1, -Vector3d::UnitY(), 0.0747, "battery_fixture position 1"));
            // Position 2: 2.5 cm off the plate, yawed 0.3 degrees, 0.25 above the shelf; slid +y to 0.0987.
            const Eigen::Isometry3d p2 =
                pose(Vector3d(2.5, 0.0, SHELF_TOP + 0.25), rotation(Vector3d::UnitZ(), 0.3));
            s.poses.push_back(placeAtGap(*bodyA, *bodyB, p2, Vector3d::UnitY(), 0.0987, "battery_fixture position 2"));
            // The planning problem does not start at position 1: with the pegs 6 into the holes and 0.07 of play, the
            // way out is a passage that sampling does not find. It starts just before insertion instead: the battery
            // centred between the rails, 1.5 above the shelf, its back face 1.5 in front of the peg tips (then lowered
            // 1.5 and pushed in, the holes would take the pegs), so the shelf, both rails and both peg tips are all
            // 1.5 away. The goal is in front of the shelf's lip at the same height: the battery has to be lifted over
            // the lip (6.5 higher at least). The shortest way skims the lip; one that keeps 1.5 goes higher.
            s.start = pose(Vector3d(PEG_LENGTH + 1.5, 0.0, SHELF_TOP + 1.5));
            s.goal = pose(Vector3d(61.0, 0.0, SHELF_TOP + 1.5));
            auto near = [](double x, double y) { return std::abs(x - y) < 1e-9; };
            auto nearAxis = [](const Vector3d &c, const Vector2d &axis, double radius) {
                return (Vector2d(c.y(), c.z()) - axis).norm() <= radius + 1e-9;
            };
            const std::vector<std::string> partNamesA = {"peg1", "peg2", "plate", "shelf", "rails", "lip", "other"};
            s.partsA = partsByPlace(s.a, partNamesA, [&](const Vector3d &c) {
                for (std::size_t i = 0; i < 2; ++i)
                    if (c.x() > 1e-9 && c.x() <= PEG_LENGTH + 1e-9 && nearAxis(c, pegAt[i], PEG_RADIUS))
                        return i;
                if (near(c.x(), 0.0))
                    return std::size_t(2);
                if (near(c.z(), SHELF_TOP))
                    return std::size_t(3);
                if (c.z() > SHELF_TOP + 1e-9 && std::abs(c.y()) >= 38.5 - 1e-9 && c.x() > 1e-9 && c.x() <= 44.0 + 1e-9)
                    return std::size_t(4);
                if (c.x() >= 48.0 - 1e-9)
                    return std::size_t(5);
                return std::size_t(6);
            });
            s.partsB = partsByPlace(s.b, {"hole1", "hole2", "back", "bottom", "other"}, [&](const Vector3d &c) {
                for (std::size_t i = 0; i < 2; ++i)
                    if (c.x() > 1e-9 && c.x() <= HOLE_DEPTH + 1e-9 &&
                        nearAxis(c, pegAt[i] - Vector2d(0.0, SHELF_TOP), HOLE_RADIUS))
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


    }  // namespace makemap
}  // namespace meshgap
