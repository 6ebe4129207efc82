#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>
#include <string>

#include "makemap/MapScene.h"
#include "meshgap/AtomicFile.h"
#include "meshgap/Exception.h"
#include "meshgap/geometry/TriangleBvh.h"
#include "meshgap/mesh/MeshLoader.h"
#include "meshgap/mesh/MeshOperations.h"
#include "meshgap/scene/Pose.h"
#include "support/MeshWriter.h"

namespace meshgap
{
    namespace makemap
    {
        // ---------------------------------------------------------------------------------------------------------
        // Output
        // ---------------------------------------------------------------------------------------------------------

        namespace
        {
            std::string number(double x)
            {
                char buffer[64];
                std::snprintf(buffer, sizeof buffer, "%.17g", x);
                return buffer;
            }

            std::size_t closedEdgeFaults(const Mesh &m)
            {
                std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
                for (const Triangle &t : m.triangles)
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
                for (const Triangle &t : m.triangles)
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

            /** \brief Store B with the mean of its unique vertices at the origin; its poses (B's pose in A's frame)
                follow. */
            void centreB(Scene &s)
            {
                const Vector3d centre = vertexMean(s.b);
                transformMesh(s.b, pose(-centre));
                for (Eigen::Isometry3d &X : s.poses)
                    X = X * pose(centre);
                s.goal = s.goal * pose(centre);
                if (s.start)
                    *s.start = *s.start * pose(centre);
            }

            /** \brief An OMPL.app state as cfg keys: prefix.x ... prefix.axis.z (axis-angle). */
            void writeState(std::ostream &cfg, const std::string &prefix, const Eigen::Isometry3d &X)
            {
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
            }

            /** \brief The scene's OMPL.app problem (.cfg), its robot file already written in \e directory. */
            std::string problemText(const Scene &s, const std::filesystem::path &directory)
            {
                const Eigen::Isometry3d start = s.start ? *s.start : s.poses.front();
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
                // The .cfg holds OMPL.app states. OMPL.app shifts a robot by the mean of every vertex assimp returns
                // for the file (its per-face copies included), c, which is not B's origin: p = R (v - c) + x. So the
                // state that puts B where its pose X does is X * translate(c), read from the file just written with
                // meshgap's own loader.
                LoadReport robotReport;
                LoadOptions centre;
                centre.omplAppCenter = true;
                loadMesh((directory / (s.name + "_b.obj")).string(), &robotReport, centre);
                const Eigen::Isometry3d toState = pose(robotReport.omplAppCenter.value());
                writeState(cfg, "start", start * toState);
                writeState(cfg, "goal", s.goal * toState);
                const char *axes = "xyz";
                for (int k = 0; k < 3; ++k)
                    cfg << "volume.min." << axes[k] << " = " << number(std::floor(volume.min()[k] - margin)) << '\n';
                for (int k = 0; k < 3; ++k)
                    cfg << "volume.max." << axes[k] << " = " << number(std::ceil(volume.max()[k] + margin)) << '\n';
                // RRTConnect solves every map well within this (bench/clearance_table.sh).
                cfg << "\n[benchmark]\ntime_limit = 10\nmem_limit = 1000\nrun_count = 10\n";
                return cfg.str();
            }

            void describe(const char *label, const Mesh &m)
            {
                const Eigen::Vector3d extent = m.bounds().diagonal();
                std::printf("  %s: %zu nodes, %zu triangles, %zu components, %zu open edges, volume %.6g, "
                            "extent %.4g x %.4g x %.4g, edges %.4g mean %.4g longest\n",
                            label, m.vertices.size(), m.triangles.size(), countComponents(m), closedEdgeFaults(m),
                            signedVolume(m), extent.x(), extent.y(), extent.z(), meanEdge(m), longestEdge(m));
            }

            /** \brief The written scene, checked: A and B as exact bodies, and each named part of each with a BVH over
                its triangles (all vertices kept). */
            class SceneCheck
            {
            public:
                explicit SceneCheck(const Scene &s) : s_(s), bodyA_(exactBody(s.a)), bodyB_(exactBody(s.b))
                {
                    for (std::size_t i = 0; i < s.partsA.names.size(); ++i)
                        partMeshesA_.push_back(partMesh(s.a, s.partsA, i));
                    for (std::size_t j = 0; j < s.partsB.names.size(); ++j)
                        partMeshesB_.push_back(partMesh(s.b, s.partsB, j));
                    for (const Mesh &part : partMeshesA_)  // the trees point into partMeshesA_/B_, which stay put
                        partTreesA_.emplace_back(part);
                    for (const Mesh &part : partMeshesB_)
                        partTreesB_.emplace_back(part);
                }

                /** \brief B at pose X must be clear of A; report the closest parts. */
                void check(const std::string &label, const Eigen::Isometry3d &X) const
                {
                    const DistanceResult c = distanceAt(*bodyA_, *bodyB_, X);
                    if (!(c.distance > 0.0))
                        throw Exception(s_.name, label + ": B touches A");
                    std::printf("  %s: exact distance %.10g (A %s at %.4f %.4f %.4f, B %s), nearest nodes %.6g\n",
                                label.c_str(), c.distance, s_.partsA.names[s_.partsA.label[c.triangleA]].c_str(),
                                c.onA.x(), c.onA.y(), c.onA.z(), s_.partsB.names[s_.partsB.label[c.triangleB]].c_str(),
                                minVertexDistance(s_.a, posed(s_.b, X)));
                    if (s_.partsA.names.size() * s_.partsB.names.size() > 1)
                        reportPartPairs(X);
                }

                /** \brief Every pose clear of A; the first, the closest and the last reported (all of a few). */
                void checkPath() const
                {
                    const std::vector<Eigen::Isometry3d> &poses = s_.poses;
                    if (poses.size() <= 8)
                    {
                        for (std::size_t i = 0; i < poses.size(); ++i)
                            check("pose " + std::to_string(i + 1), poses[i]);
                        return;
                    }
                    std::size_t closest = 0;
                    double best = std::numeric_limits<double>::infinity(), worst = 0.0;
                    for (std::size_t i = 0; i < poses.size(); ++i)
                    {
                        const double d = distanceAt(*bodyA_, *bodyB_, poses[i]).distance;
                        if (!(d > 0.0))
                            throw Exception(s_.name, "pose " + std::to_string(i + 1) + ": B touches A");
                        worst = std::max(worst, d);
                        if (d < best)
                        {
                            best = d;
                            closest = i;
                        }
                    }
                    std::printf("  path of %zu poses: exact distance from %.10g (pose %zu) to %.10g\n", poses.size(),
                                best, closest + 1, worst);
                    check("pose 1", poses.front());
                    check("pose " + std::to_string(closest + 1), poses[closest]);
                    check("pose " + std::to_string(poses.size()), poses.back());
                }

            private:
                /** \brief Distance between each part of A and each of B (surface distance, 0 if they intersect): each
                    is (at least) one local minimum. A part without triangles is infinitely far. */
                void reportPartPairs(const Eigen::Isometry3d &X) const
                {
                    std::vector<std::pair<double, std::string>> pairs;
                    for (std::size_t i = 0; i < partTreesA_.size(); ++i)
                        for (std::size_t j = 0; j < partTreesB_.size(); ++j)
                        {
                            BvhDistanceResult r;
                            if (!partMeshesA_[i].triangles.empty() && !partMeshesB_[j].triangles.empty())
                                bvhDistance(partTreesA_[i], partTreesB_[j], X, std::numeric_limits<double>::infinity(),
                                            0.0, r);
                            pairs.emplace_back(r.distance, s_.partsA.names[i] + "-" + s_.partsB.names[j]);
                        }
                    std::sort(pairs.begin(), pairs.end());
                    std::printf("    closest part pairs (A-B):");
                    const std::size_t shown = std::min<std::size_t>(8, pairs.size());
                    for (std::size_t k = 0; k < shown; ++k)
                        std::printf(" %s %.4g%s", pairs[k].second.c_str(), pairs[k].first, k + 1 < shown ? "," : "\n");
                }

                const Scene &s_;
                BodyPtr bodyA_, bodyB_;
                std::vector<Mesh> partMeshesA_, partMeshesB_;
                std::vector<TriangleBvh> partTreesA_, partTreesB_;
            };
        }  // namespace

        void writeScene(Scene s, const std::filesystem::path &directory)
        {
            std::filesystem::create_directories(directory);
            centreB(s);
            s.a.source = s.name + "_a";
            s.b.source = s.name + "_b";
            writeObj(s.a, (directory / (s.name + "_a.obj")).string());
            writeObj(s.b, (directory / (s.name + "_b.obj")).string());
            std::string poses;
            for (const Eigen::Isometry3d &X : s.poses)
                poses += formatPose(X) + "\n";
            writeText(directory / (s.name + ".poses"), poses);
            writeText(directory / (s.name + ".cfg"), problemText(s, directory));

            // Report (and check) what was written.
            std::printf("%s (%s) -> %s\n", s.name.c_str(), s.units.c_str(), directory.string().c_str());
            describe("A", s.a);
            describe("B", s.b);
            const SceneCheck checks(s);
            checks.checkPath();
            if (s.start)
                checks.check("start", *s.start);
            checks.check("goal", s.goal);
        }
    }  // namespace makemap
}  // namespace meshgap
