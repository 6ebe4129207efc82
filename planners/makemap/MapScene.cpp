#include "makemap/MapScene.h"

#include <cmath>

#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/distance/ExactDistance.h"
#include "meshgap/mesh/MeshOperations.h"

namespace meshgap
{
    namespace makemap
    {
        Eigen::Isometry3d pose(const Vector3d &translation, const Eigen::Matrix3d &rotation)
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

        // ---------------------------------------------------------------------------------------------------------
        // Exact distance between two triangle meshes: the library's exact layer (ExactSolver, bvhDistance).
        // ---------------------------------------------------------------------------------------------------------

        Mesh posed(const Mesh &body, const Eigen::Isometry3d &X)
        {
            Mesh m = body;
            meshgap::transformMesh(m, X);
            return m;
        }

        Mesh boxBetween(const Vector3d &lo, const Vector3d &hi, double h)
        {
            return posed(makeBox(hi - lo, h), pose(0.5 * (lo + hi)));
        }

        void writeText(const std::filesystem::path &path, const std::string &text)
        {
            writeStreamAtomically(path.string(), [&text](std::ostream &out) { out << text; });
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
    }  // namespace makemap
}  // namespace meshgap
