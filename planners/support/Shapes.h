#ifndef MESHGAP_PLANNERS_SUPPORT_SHAPES_H
#define MESHGAP_PLANNERS_SUPPORT_SHAPES_H

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "meshgap/mesh/Mesh.h"
#include "meshgap/mesh/MeshOperations.h"

namespace meshgap
{
    /** \brief The grid size at a point of the body frame: the longest triangle edge allowed there. It may vary over
        a body (the paper's hand is meshed at 3 mm near the fingertips and up to 30 mm on the back, Table IV). It
        must be positive and finite everywhere it is asked. */
    using SizingFunction = std::function<double(const Eigen::Vector3d &)>;

    /** \brief The same grid size \e h everywhere. */
    SizingFunction uniformSizing(double h);

    /** \brief A simple polygon in the plane, closed implicitly (the last point joins the first). */
    using Polygon2d = std::vector<Eigen::Vector2d>;

    /** \brief A closed polyhedron bounded by planar faces, each face an outer loop of corners and any number of hole
        loops: a boundary representation that mesh() turns into an evenly gridded triangle mesh.

        Every corner is stored once and faces refer to corners by index, so two faces that share an edge share its
        corners exactly; mesh() then subdivides each edge once and both faces use the same nodes, which makes the
        result watertight by construction (no welding by position). Loops are wound counter-clockwise seen from
        outside the solid (outer loop) and clockwise (holes), so every edge is used once in each direction; check()
        verifies this. */
    class Polyhedron
    {
    public:
        /** \brief Corner indices around a loop. */
        using Loop = std::vector<std::uint32_t>;

        /** \brief One planar face: loops[0] is the outer boundary, the others are holes. */
        struct Face
        {
            std::vector<Loop> loops;
        };

        /** \brief Add a corner and return its index. */
        std::uint32_t addCorner(const Eigen::Vector3d &p);

        /** \brief Add a face with outer loop \e outer (counter-clockwise seen from outside); returns its index. */
        std::size_t addFace(Loop outer);

        /** \brief Add a hole loop (clockwise seen from outside) to face \e face. */
        void addHole(std::size_t face, Loop hole);

        /** \brief Raise a prism on face \e face: the polygon \e base (3D points on the face, inside it and clear of
            its holes; either winding) becomes a hole of the face, with side walls and a top face \e height along the
            face's outward normal. A negative height sinks a blind pocket instead (a peg or an alignment hole).
            Returns the index of the top (or pocket bottom) face. */
        std::size_t addBoss(std::size_t face, const std::vector<Eigen::Vector3d> &base, double height);

        /** \brief Outward unit normal of a face (Newell's method on its outer loop). */
        Eigen::Vector3d faceNormal(std::size_t face) const;

        /** \brief Enclosed volume (positive when the loops are wound outward). */
        double volume() const;

        /** \brief Reverse every loop (turns an inward-wound polyhedron outward). */
        void reverse();

        /** \brief Move every corner by \e X. */
        void transform(const Eigen::Isometry3d &X);

        /** \brief Throws meshgap::Exception unless every face has an outer loop of at least three corners, every
            index is valid and every edge is used exactly once in each direction (closed and consistently wound). */
        void check() const;

        /** \brief Triangulate every face with edges no longer than \e sizing (within rounding): each polyhedron edge
            is split into equal parts (graded when the sizing varies), each face is triangulated (ear clipping,
            Delaunay edge flips, longest-edge-propagation bisection and Laplacian smoothing of the inner nodes). The
            result is closed, consistently wound, and outward when volume() > 0. \e name becomes Mesh::source. */
        Mesh mesh(const SizingFunction &sizing, const std::string &name) const;

        const std::vector<Eigen::Vector3d> &corners() const
        {
            return corners_;
        }
        const std::vector<Face> &faces() const
        {
            return faces_;
        }

    private:
        std::vector<Eigen::Vector3d> corners_;
        std::vector<Face> faces_;
    };

    /** \brief The prism of \e outer minus \e holes (polygons in the x-y plane, either winding) from z = 0 to
        z = \e height. Face 0 is the bottom, face 1 the top, then one side face per polygon edge (outer loop first,
        then each hole, in order). */
    Polyhedron prismPolyhedron(const Polygon2d &outer, const std::vector<Polygon2d> &holes, double height);

    /** \brief Revolve a profile polyline of (r, z) points about the z axis, the circle linearised with \e segments
        sides. The first and last points must lie on the axis (r = 0), the others off it (r > 0), so the solid is
        closed and of genus 0. A horizontal profile segment becomes one flat face (disk or annulus); the others
        become \e segments planar trapezoids (triangles where they meet the axis). */
    Polyhedron revolutionPolyhedron(const std::vector<Eigen::Vector2d> &profile, unsigned int segments);

    /** \brief A rounded tube of radius \e radius along the polyline \e path: a prism of \e segments sides per path
        segment, mitred at the bends, closed by polyhedral hemispheres of \e capRings rings. Bends must be less than
        120 degrees and segments longer than the mitre needs. A bent finger is one such tube. */
    Polyhedron tubePolyhedron(const std::vector<Eigen::Vector3d> &path, double radius, unsigned int segments,
                              unsigned int capRings);

    /** \brief Box [-sx/2, sx/2] x [-sy/2, sy/2] x [-sz/2, sz/2] at grid size \e h. */
    Mesh makeBox(const Eigen::Vector3d &size, double h);

    /** \brief prismPolyhedron(outer, holes, height) at grid size \e h. */
    Mesh makeExtrusion(const Polygon2d &outer, const std::vector<Polygon2d> &holes, double height, double h);

    /** \brief revolutionPolyhedron(profile, segments) at grid size \e h. */
    Mesh makeRevolution(const std::vector<Eigen::Vector2d> &profile, unsigned int segments, double h);

    /** \brief A capsule (rounded cylinder) of radius \e radius between points \e a and \e b at grid size \e h. */
    Mesh makeCapsule(const Eigen::Vector3d &a, const Eigen::Vector3d &b, double radius, unsigned int segments,
                     unsigned int capRings, double h);

    /** \brief tubePolyhedron(path, radius, segments, capRings) at grid size \e sizing. */
    Mesh makeTube(const std::vector<Eigen::Vector3d> &path, double radius, unsigned int segments,
                  unsigned int capRings, const SizingFunction &sizing);

    /** \brief Regular polygon of \e sides corners on a circle of radius \e circumradius, counter-clockwise, the
        first corner at angle \e phase (radians). */
    Polygon2d regularPolygon(const Eigen::Vector2d &centre, double circumradius, unsigned int sides,
                             double phase = 0.0);

    /** \brief Signed area of a polygon (positive when counter-clockwise). */
    double polygonArea(const Polygon2d &polygon);
}  // namespace meshgap

#endif
