#ifndef MESHGAP_TESTS_FCL_ORACLE_H
#define MESHGAP_TESTS_FCL_ORACLE_H

// FCL 0.7 as the oracle for exact mesh distance and collision (BVHModel<OBBRSS>, as OMPL.app uses it).
#ifdef MESHGAP_HAVE_FCL
#include <fcl/fcl.h>
#include <memory>

#include "meshgap/mesh/Mesh.h"

namespace meshgap
{
    namespace test
    {
        using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

        inline std::shared_ptr<FclModel> fclModel(const Mesh &m)
        {
            auto model = std::make_shared<FclModel>();
            std::vector<fcl::Vector3d> points(m.vertices.begin(), m.vertices.end());
            std::vector<fcl::Triangle> triangles;
            for (const Triangle &t : m.triangles)
                triangles.emplace_back(t[0], t[1], t[2]);
            model->beginModel();
            model->addSubModel(points, triangles);
            model->endModel();
            model->computeLocalAABB();
            return model;
        }

        /** \brief Exact distance between A (identity) and B at X_AB; 0 or less when they collide. (FCL's geometry
            overloads: a CollisionObject would recompute the model's local box over every vertex at each call.) */
        inline double fclDistance(const std::shared_ptr<FclModel> &a, const std::shared_ptr<FclModel> &b,
                                  const Eigen::Isometry3d &X_AB)
        {
            fcl::DistanceRequestd request(true);
            fcl::DistanceResultd result;
            fcl::distance(a.get(), fcl::Transform3d::Identity(), b.get(), fcl::Transform3d(X_AB.matrix()), request,
                          result);
            return result.min_distance;
        }

        inline bool fclCollide(const std::shared_ptr<FclModel> &a, const std::shared_ptr<FclModel> &b,
                               const Eigen::Isometry3d &X_AB)
        {
            fcl::CollisionRequestd request;
            fcl::CollisionResultd result;
            fcl::collide(a.get(), fcl::Transform3d::Identity(), b.get(), fcl::Transform3d(X_AB.matrix()), request,
                         result);
            return result.isCollision();
        }
    }  // namespace test
}  // namespace meshgap
#endif

#endif
