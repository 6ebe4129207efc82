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
        // Twisted, in its own units: a stress scene for the exact layer, not from the paper. A long, thin
        // flat strip (section 1.5 x 0.4) wound as a helix, three turns (a coil spring of flat wire), screws through a
        // helical channel of the same pitch (five turns, a hollow coil whose bore is the strip's section grown by the
        // play on every side). Both are concave, twisted everywhere and made of long thin triangles (slivers, 15 degrees
        // of arc long). The motion is a screw about z that the channel maps onto itself, so inside it the strip keeps
        // about its play on every side (less the chords' sagitta), the whole way.
        constexpr double TWIST_RADIUS = 12.0;       // the strip's mid radius about z
        constexpr double TWIST_WIDTH = 1.5;         // radial width: r in [11.25, 12.75]
        constexpr double TWIST_THICKNESS = 0.4;     // along z
        constexpr double TWIST_PITCH = 8.0;         // rise per turn (strip and channel)
        constexpr double TWIST_PLAY = 0.3;          // the channel's bore: the strip's section grown by this on each side
        constexpr double TWIST_WALL = 1.0;          // the channel's wall thickness
        constexpr double TWIST_STEP_DEGREES = 15.0;  // stations of both sweeps (the same angles, so faces line up)
        constexpr int TWIST_STRIP_TURNS = 3, TWIST_CHANNEL_TURNS = 5;
        constexpr double TWIST_APPROACH_DEGREES = 15.0;  // the strip's end this far before the channel at the start
        constexpr double TWIST_POSE_STEP_DEGREES = 3.75;  // the screw turned this much between two .poses lines

        /** \brief The solid swept by the section \e outer (minus \e hole, if not empty), drawn in the (r, z) half-plane
            (r > 0), along the screw about z that turns by theta and rises by pitch * theta / (2 PI), from \e from to
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
                                                                    q.y() + pitch * theta / (2.0 * PI))));
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

        /** \brief The screw about z by \e theta radians (the rise of TWIST_PITCH per turn). */
        Eigen::Isometry3d twistScrew(double theta)
        {
            return pose(Vector3d(0.0, 0.0, TWIST_PITCH * theta / (2.0 * PI)),
                        rotation(Vector3d::UnitZ(), theta * 180.0 / PI));
        }

        Scene twistedScene()
        {
            Scene s;
            s.name = "twisted";
            s.units = "units";
            const double r0 = TWIST_RADIUS - 0.5 * TWIST_WIDTH, r1 = TWIST_RADIUS + 0.5 * TWIST_WIDTH, h = 0.5 * TWIST_THICKNESS;
            const double huge = 1e3;  // sizing above every edge: the sweeps' triangles are kept as they are (slivers)
            const unsigned int stripSteps =
                static_cast<unsigned int>(std::lround(360.0 * TWIST_STRIP_TURNS / TWIST_STEP_DEGREES));
            const unsigned int channelSteps =
                static_cast<unsigned int>(std::lround(360.0 * TWIST_CHANNEL_TURNS / TWIST_STEP_DEGREES));
            const double stripEnd = 2.0 * PI * TWIST_STRIP_TURNS, channelEnd = 2.0 * PI * TWIST_CHANNEL_TURNS;
            s.b = helicalSweep(sectionRectangle(r0, r1, h), {}, 0.0, stripEnd, stripSteps, TWIST_PITCH)
                      .mesh(meshgap::uniformSizing(huge), "twisted strip");
            const double bore = TWIST_PLAY, wall = TWIST_PLAY + TWIST_WALL;
            s.a = helicalSweep(sectionRectangle(r0 - wall, r1 + wall, h + wall),
                               sectionRectangle(r0 - bore, r1 + bore, h + bore), 0.0, channelEnd, channelSteps, TWIST_PITCH)
                      .mesh(meshgap::uniformSizing(huge), "twisted channel");
            // The path: the screw from the strip's end TWIST_APPROACH_DEGREES before the channel's mouth to its start
            // as far beyond the channel's far end; the strip occupies the screw angles [u, u + stripEnd].
            const double approach = radians(TWIST_APPROACH_DEGREES);
            const double u0 = -stripEnd - approach, u1 = channelEnd + approach;
            const int count = static_cast<int>(std::lround((u1 - u0) / radians(TWIST_POSE_STEP_DEGREES)));
            for (int k = 0; k <= count; ++k)
                s.poses.push_back(twistScrew(u0 + (u1 - u0) * k / count));
            s.goal = s.poses.back();
            s.partsA = partsByRuns({{"channel", 0}}, s.a.triangles.size());
            s.partsB = partsByRuns({{"strip", 0}}, s.b.triangles.size());
            return s;
        }
    }  // namespace makemap
}  // namespace meshgap
