#ifndef MESHGAP_PLANNERS_FCL_ROBOT_SCENE_H
#define MESHGAP_PLANNERS_FCL_ROBOT_SCENE_H

// FCL 0.7 as MoveIt's collision_detection_fcl uses it, on a RobotScene: the peer of meshgap's whole-robot queries.
// Header-only (every planners/*.cpp is an executable); needs MESHGAP_HAVE_FCL and the fcl target.

#ifdef MESHGAP_HAVE_FCL
#include <algorithm>
#include <fcl/fcl.h>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "meshgap/mesh/Mesh.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    /** \brief An FCL BVHModel<OBBRSS> of a mesh, in the mesh's own frame (as OMPL.app and MoveIt give FCL a mesh). */
    inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fclModelOf(const Mesh &mesh)
    {
        auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
        const std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
        std::vector<fcl::Triangle> triangles;
        triangles.reserve(mesh.triangles.size());
        for (const Triangle &t : mesh.triangles)
            triangles.emplace_back(t[0], t[1], t[2]);
        model->beginModel(static_cast<int>(triangles.size()), static_cast<int>(points.size()));
        model->addSubModel(points, triangles);
        model->endModel();
        model->computeLocalAABB();
        return model;
    }

    /** \brief FCL's geometry for one primitive solid, as MoveIt gives it to FCL: fcl::Box, fcl::Sphere,
        fcl::Cylinder, fcl::Cone (in the solid's own frame). */
    inline std::shared_ptr<fcl::CollisionGeometryd> fclSolidOf(const Primitive &p)
    {
        switch (p.kind)
        {
            case Primitive::Kind::BOX:
                return std::make_shared<fcl::Boxd>(p.size.x(), p.size.y(), p.size.z());
            case Primitive::Kind::SPHERE:
                return std::make_shared<fcl::Sphered>(p.size.x());
            case Primitive::Kind::CYLINDER:
                return std::make_shared<fcl::Cylinderd>(p.size.x(), p.size.y());
            case Primitive::Kind::CONE:
                return std::make_shared<fcl::Coned>(p.size.x(), p.size.y());
            case Primitive::Kind::CAPSULE:
                return std::make_shared<fcl::Capsuled>(p.size.x(), p.size.y());
        }
        return nullptr;
    }

    /**
       @anchor mgFclRobotScene
       @par Short description
       Whole-robot collision and minimum distance by FCL, the way MoveIt's collision_detection_fcl answers them: the
       obstacles in one broad-phase manager (fcl::DynamicAABBTreeCollisionManager) built once, the robot's links in
       another, updated to the link poses of each query; the robot's manager against the obstacles' for the links
       against the world, the robot's manager against itself for the self pairs (a robot of one FCL object, a single
       rigid body, is put to the obstacles' manager directly: nothing to update, no self pair), each pair the
       manager's broad phase passes put to FCL's narrow phase only when the scene checks it
       (RobotScene::linkObstacles() and selfPairs() play MoveIt's allowed collision matrix). inCollision() stops at the first contact; distance() keeps the
       least distance, each manager pruning the pairs whose boxes are farther apart than it.

       Shapes as MoveIt gives them to FCL: a body built from primitive solids (Body::primitives(): a URDF link of
       boxes, cylinders and spheres, a MoveIt scene's primitive) is one FCL object per solid, fcl::Box,
       fcl::Cylinder, fcl::Sphere or fcl::Cone, the true shape; any other body is one BVHModel<OBBRSS> of its
       surface. meshgap's exact queries answer those solids as the shapes they are too (refineExact(), 5), so the
       two answer the same shapes (FCL's GJK to its tolerance). With \e primitives false every body is the
       BVHModel of its surface: the same triangles as meshgap's.

       Thread-safe: the obstacles' manager is only read by queries; each query borrows a robot manager of its own
       from a pool (one per thread that queries at once), so threads never share one.
    */
    class FclRobotScene
    {
    public:
        explicit FclRobotScene(RobotSceneConstPtr scene, bool primitives = true) : scene_(std::move(scene))
        {
            const std::size_t links = scene_->links().size(), obstacles = scene_->obstacles().size();
            tags_.reserve(links + obstacles);
            for (std::size_t i = 0; i < links; ++i)
                tags_.push_back({true, i});
            for (std::size_t o = 0; o < obstacles; ++o)
                tags_.push_back({false, o});
            for (std::size_t i = 0; i < links; ++i)
                addParts(*scene_->links()[i].body, primitives, &tags_[i], links_, linkParts_);
            std::vector<Eigen::Isometry3d> ignored;
            for (std::size_t o = 0; o < obstacles; ++o)
                addParts(*scene_->obstacles()[o], primitives, &tags_[links + o], obstacles_, ignored);
            for (std::size_t k = 0; k < obstacles_.size(); ++k)
            {
                obstacles_[k]->setTransform(ignored[k]);  // obstacles are in the world frame
                obstacles_[k]->computeAABB();
            }
            std::vector<fcl::CollisionObjectd *> world;
            for (const auto &object : obstacles_)
                world.push_back(object.get());
            world_.registerObjects(world);
            world_.setup();
            // Which pairs count: link i against obstacle o, links i and j (i < j).
            linkObstacle_.assign(links * obstacles, 0);
            for (std::size_t i = 0; i < links; ++i)
                for (std::size_t o : scene_->linkObstacles(i))
                    linkObstacle_[i * obstacles + o] = 1;
            selfPair_.assign(links * links, 0);
            for (const LinkPair &p : scene_->selfPairs())
                selfPair_[p.first * links + p.second] = selfPair_[p.second * links + p.first] = 1;
        }

        FclRobotScene(const FclRobotScene &) = delete;
        FclRobotScene &operator=(const FclRobotScene &) = delete;

        const RobotScene &scene() const { return *scene_; }
        /** \brief FCL objects: the links' (at least one per link) and the obstacles'. */
        std::size_t numLinkObjects() const { return links_.size(); }
        std::size_t numObstacleObjects() const { return obstacles_.size(); }

        /** \brief True when some pair the scene checks is in contact with the links at \e X (every link's world
            pose, RobotModel::linkPoses()); the links against the obstacles first, then the self pairs, stopping
            at the first contact. */
        bool inCollision(const std::vector<Eigen::Isometry3d> &X) const
        {
            Lease robot(*this, X);
            CollideData data{this, false};
            if (robot->objects.size() == 1)  // one object: straight into the obstacles' manager, no self pair
                world_.collide(robot->objects[0].get(), &data, &FclRobotScene::collideCallback);
            else
            {
                world_.collide(&robot->manager, &data, &FclRobotScene::collideCallback);
                if (!data.hit)
                    robot->manager.collide(&data, &FclRobotScene::collideCallback);
            }
            return data.hit;
        }

        /** \brief The least distance over the pairs the scene checks with the links at \e X, at least 0 (0 in
            collision, as FCL's distance answers it); +infinity when the scene checks no pair. With \e below, the
            least distance when it is less than \e below, else \e below: the managers prune the pairs whose boxes
            are \e below apart or more, and FCL's traversal of a pair the nodes that are (the least over many states
            at the price of the states that come near it). */
        double distance(const std::vector<Eigen::Isometry3d> &X,
                        double below = std::numeric_limits<double>::infinity()) const
        {
            Lease robot(*this, X);
            DistanceData data{this, below};
            if (robot->objects.size() == 1)
                world_.distance(robot->objects[0].get(), &data, &FclRobotScene::distanceCallback);
            else
            {
                world_.distance(&robot->manager, &data, &FclRobotScene::distanceCallback);
                if (data.least > 0.0)
                    robot->manager.distance(&data, &FclRobotScene::distanceCallback);
            }
            return data.least;
        }

    private:
        /** \brief What an FCL object is part of: link \e index (robot) or obstacle \e index. */
        struct Tag
        {
            bool robot;
            std::size_t index;
        };

        /** \brief A robot manager and its objects, used by one query at a time. */
        struct Robot
        {
            std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
            fcl::DynamicAABBTreeCollisionManagerd manager;
        };

        /** \brief A robot manager borrowed from the pool for one query, its objects placed at the link poses. */
        class Lease
        {
        public:
            Lease(const FclRobotScene &owner, const std::vector<Eigen::Isometry3d> &X)
              : owner_(owner), robot_(owner.acquire())
            {
                for (std::size_t k = 0; k < robot_->objects.size(); ++k)
                {
                    fcl::CollisionObjectd &object = *robot_->objects[k];
                    object.setTransform(X[static_cast<const Tag *>(object.getUserData())->index] *
                                        owner.linkParts_[k]);
                    object.computeAABB();
                }
                if (robot_->objects.size() > 1)  // one object is put to the obstacles' manager directly
                    robot_->manager.update();
            }
            ~Lease() { owner_.release(std::move(robot_)); }
            Lease(const Lease &) = delete;
            Lease &operator=(const Lease &) = delete;
            Robot *operator->() const { return robot_.get(); }

        private:
            const FclRobotScene &owner_;
            std::unique_ptr<Robot> robot_;
        };

        struct CollideData
        {
            const FclRobotScene *owner;
            bool hit;
        };

        struct DistanceData
        {
            const FclRobotScene *owner;
            double least;
        };

        /** \brief One FCL object per primitive solid of \e body (when \e primitives and it has them), else one of
            its surface; each object's pose in the body frame into \e poses. */
        static void addParts(const Body &body, bool primitives, Tag *tag,
                             std::vector<std::unique_ptr<fcl::CollisionObjectd>> &objects,
                             std::vector<Eigen::Isometry3d> &poses)
        {
            auto add = [&](const std::shared_ptr<fcl::CollisionGeometryd> &geometry, const Eigen::Isometry3d &X)
            {
                objects.push_back(std::make_unique<fcl::CollisionObjectd>(geometry));  // computes its local box
                objects.back()->setUserData(tag);
                poses.push_back(X);
            };
            if (primitives && !body.primitives().empty())
                for (const Primitive &p : body.primitives())
                    add(fclSolidOf(p), p.pose);
            else
                add(fclModelOf(body.surface()), Eigen::Isometry3d::Identity());
        }

        /** \brief True when the scene checks the pair of \e a and \e b (a link against an obstacle not allowed with
            it, two links of a self pair; never two parts of one link). */
        bool checks(const Tag &a, const Tag &b) const
        {
            const std::size_t obstacles = scene_->obstacles().size(), links = scene_->links().size();
            if (a.robot && b.robot)
                return selfPair_[a.index * links + b.index] != 0;
            if (a.robot != b.robot)
            {
                const Tag &link = a.robot ? a : b, &obstacle = a.robot ? b : a;
                return linkObstacle_[link.index * obstacles + obstacle.index] != 0;
            }
            return false;
        }

        /** \brief Puts a pair in one order whatever the order the managers meet it in (the obstacle first, else the
            link of lower index), so that FCL's answer, which depends on the order by its rounding (and its GJK's
            tolerance on primitive solids), is the same from any tree and thread. */
        static void order(fcl::CollisionObjectd *&a, fcl::CollisionObjectd *&b)
        {
            const Tag &ta = *static_cast<const Tag *>(a->getUserData());
            const Tag &tb = *static_cast<const Tag *>(b->getUserData());
            if (ta.robot && (!tb.robot || tb.index < ta.index))
                std::swap(a, b);
        }

        static bool collideCallback(fcl::CollisionObjectd *a, fcl::CollisionObjectd *b, void *cdata)
        {
            auto &data = *static_cast<CollideData *>(cdata);
            if (data.hit)
                return true;
            if (!data.owner->checks(*static_cast<const Tag *>(a->getUserData()),
                                    *static_cast<const Tag *>(b->getUserData())))
                return false;
            order(a, b);
            const fcl::CollisionRequestd request;  // one contact is enough
            fcl::CollisionResultd result;
            fcl::collide(a, b, request, result);
            data.hit = result.isCollision();
            return data.hit;
        }

        static bool distanceCallback(fcl::CollisionObjectd *a, fcl::CollisionObjectd *b, void *cdata, double &dist)
        {
            auto &data = *static_cast<DistanceData *>(cdata);
            if (data.owner->checks(*static_cast<const Tag *>(a->getUserData()),
                                   *static_cast<const Tag *>(b->getUserData())))
            {
                order(a, b);
                const fcl::DistanceRequestd request;
                fcl::DistanceResultd result;
                result.min_distance = data.least;  // FCL's traversal keeps only what is nearer
                fcl::distance(a, b, request, result);
                data.least = std::min(data.least, std::max(0.0, result.min_distance));
            }
            dist = data.least;  // the manager prunes the pairs whose boxes are farther apart
            return data.least <= 0.0;
        }

        std::unique_ptr<Robot> acquire() const
        {
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                if (!idle_.empty())
                {
                    std::unique_ptr<Robot> robot = std::move(idle_.back());
                    idle_.pop_back();
                    return robot;
                }
            }
            auto robot = std::make_unique<Robot>();
            std::vector<fcl::CollisionObjectd *> registered;
            for (const auto &prototype : links_)
            {
                // A copy keeps the geometry's local box as computed once (no write to the shared geometry).
                robot->objects.push_back(std::make_unique<fcl::CollisionObjectd>(*prototype));
                registered.push_back(robot->objects.back().get());
            }
            // Two rebalancing passes after each update rather than FCL's ten: fewer instructions a query on both
            // the four-joint arm and the UR5 (measured: 0 passes lose on the UR5's 18 links, 10 on both).
            robot->manager.tree_incremental_balance_pass = 2;
            robot->manager.registerObjects(registered);
            robot->manager.setup();
            return robot;
        }

        void release(std::unique_ptr<Robot> robot) const
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            idle_.push_back(std::move(robot));
        }

        RobotSceneConstPtr scene_;
        std::vector<Tag> tags_;  ///< links', then obstacles'; each FCL object points at its own
        std::vector<std::unique_ptr<fcl::CollisionObjectd>> links_, obstacles_;
        std::vector<Eigen::Isometry3d> linkParts_;  ///< per link object, its pose in the link's frame
        fcl::DynamicAABBTreeCollisionManagerd world_;
        std::vector<char> linkObstacle_, selfPair_;
        mutable std::mutex mutex_;
        mutable std::vector<std::unique_ptr<Robot>> idle_;
    };
}  // namespace meshgap
#endif

#endif
