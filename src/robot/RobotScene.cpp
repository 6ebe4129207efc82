#include "meshgap/robot/RobotScene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>

#include "meshgap/Exception.h"

namespace meshgap
{
    namespace
    {
        std::atomic<std::uint64_t> nextRobotSceneId{1};

        /** \brief Empty \e result for a new query, keeping its vectors' memory. */
        void resetResult(RobotResult &result, std::size_t pairs, std::size_t links)
        {
            result.distance = std::numeric_limits<double>::infinity();
            result.selfPair = false;
            result.link = result.other = 0;
            result.onA.setZero();
            result.onB.setZero();
            result.inCollision = false;
            result.penetrationDepth = 0.0;
            result.certified = false;
            result.atLeast = false;
            result.pairsChecked = 0;
            result.pairs.resize(pairs);
            std::fill(result.pairs.begin(), result.pairs.end(), RobotPairAnswer());
            result.linkClearance.resize(links);
        }
    }  // namespace

    RobotScene::RobotScene(RobotModelConstPtr robot, std::vector<BodyConstPtr> obstacles,
                           const std::vector<LinkPair> &allowedObstacles)
        : robot_(std::move(robot)), obstacles_(std::move(obstacles)), id_(nextRobotSceneId++)
    {
        if (!robot_)
            throw Exception("RobotScene", "no robot");
        links_ = robot_->links();
        if (links_.empty())
            throw Exception("RobotScene", "the robot has no collision geometry (no link with a body, no payload): "
                                          "there is nothing to check");
        selfPairs_ = robot_->selfPairs();
        std::vector<std::vector<bool>> allowed(links_.size(), std::vector<bool>(obstacles_.size(), false));
        for (const auto &[link, obstacle] : allowedObstacles)
        {
            if (link >= links_.size() || obstacle >= obstacles_.size())
                throw Exception("RobotScene", "an allowed pair names link " + std::to_string(link) + " and obstacle " +
                                                  std::to_string(obstacle) + ", but there are " +
                                                  std::to_string(links_.size()) + " links and " +
                                                  std::to_string(obstacles_.size()) + " obstacles");
            allowed[link][obstacle] = true;
        }
        // One broad phase per distinct set of checked obstacles (one in all without an allowed collision matrix),
        // shared by the links' scenes.
        std::map<std::vector<bool>, std::size_t> sceneOf;
        for (std::size_t i = 0; i < links_.size(); ++i)
        {
            std::vector<BodyConstPtr> checked;
            linkObstacles_.emplace_back();
            for (std::size_t o = 0; o < obstacles_.size(); ++o)
                if (!allowed[i][o])
                {
                    checked.push_back(obstacles_[o]);
                    linkObstacles_.back().push_back(o);
                }
            const auto [same, isNew] = sceneOf.emplace(allowed[i], i);
            scenes_.push_back(isNew ? std::make_shared<Scene>(links_[i].body, std::move(checked)) :
                                      std::make_shared<Scene>(links_[i].body, *scenes_[same->second]));
        }
        buildVerdictBounds();
        for (const auto &[a, b] : selfPairs_)
            selfAncestor_.push_back(robot_->commonFrame(links_[a].frame, links_[b].frame));
        sweepOffset_.assign(1, 0);
        for (const std::vector<std::size_t> &checked : linkObstacles_)
        {
            std::size_t questions = 0;
            for (std::size_t o : checked)
                questions += std::max<std::size_t>(1, obstacles_[o]->primitives().size());
            sweepOffset_.push_back(sweepOffset_.back() + questions);
        }
        sweepOffset_.push_back(sweepOffset_.back() + selfPairs_.size());
    }

    void RobotScene::prepare(const double *state, std::size_t size, RobotWarmStart &warm) const
    {
        if (warm.scene != id_ || warm.links.size() != links_.size() || warm.self.size() != selfPairs_.size())
        {
            // First query with this warm start, or one made with another robot scene: nothing carries over.
            warm.links.assign(links_.size(), SceneWarmStart());
            warm.self.assign(selfPairs_.size(), ExactWarmStart());
            warm.obstaclePairs.assign(pairOffset_.back(), ExactWarmStart());
            warm.sweepAxes.assign(sweepOffset_.back(), Eigen::Vector3d::Zero());
            warm.valid = false;
            warm.scene = id_;
        }
        robot_->framePoses(state, size, warm.frames);
        warm.state.assign(state, state + size);
        warm.poses.resize(links_.size());
        for (std::size_t i = 0; i < links_.size(); ++i)
            warm.poses[i] = warm.frames[links_[i].frame] * links_[i].X_FL;
        placeBounds(warm);
    }

    void RobotScene::tabulateSelfPairs(const SelfPairTable::Options &options)
    {
        table_.reset();  // the table's own questions are asked without it
        table_ = std::make_shared<const SelfPairTable>(*this, options);
    }

    bool RobotScene::spheresApart(std::size_t p, const RobotWarmStart &warm, double bound, double &gap) const
    {
        const auto [a, b] = selfPairs_[p];
        const TriangleBvh::Node &ra = links_[a].body->bvh().nodes()[0], &rb = links_[b].body->bvh().nodes()[0];
        const double centres = (warm.centers[a] - warm.centers[b]).norm();
        // Padded against roundoff in the transforms (1e-9 of the sizes involved is far above it).
        gap = centres - ra.radius - rb.radius - 1e-9 * (centres + ra.radius + rb.radius) - 1e-300;
        return gap >= bound;
    }

    bool RobotScene::inCollision(const double *state, std::size_t size, RobotWarmStart &warm,
                                 bool selfCollision) const
    {
        prepare(state, size, warm);
        const std::size_t count = selfCollision ? numPairs() : links_.size();
        const std::size_t first = warm.valid && warm.pair < count ? warm.pair : count;
        auto collides = [&](std::size_t k)
        { return k < links_.size() ? linkCollides(k, warm) : selfVerdict(k - links_.size(), warm); };
        // The pair of the last answer first: along a run of states in collision it is the likeliest to hit.
        if (first < count && collides(first))
            return true;
        for (std::size_t k = 0; k < count; ++k)
            if (k != first && collides(k))
            {
                warm.valid = true;
                warm.pair = k;
                return true;
            }
        return false;
    }

    bool RobotScene::answerPair(std::size_t k, const RobotRequest &request, double bound, RobotWarmStart &warm,
                                RobotPairAnswer &answer, RobotResult &best, bool &complete) const
    {
        if (!(bound > 0.0))
        {
            // In collision, only a deeper collision can change the answer: the exact collision test first (a
            // bound near zero would prune nothing the test does not), then the signed distance of a colliding pair.
            const bool collides = k < links_.size() ? scenes_[k]->inCollision(warm.poses[k], warm.links[k])
                                                    : selfVerdict(k - links_.size(), warm);
            if (!collides)
            {
                ++best.pairsChecked;
                answer = {0.0, RobotPairAnswer::Status::AT_LEAST, 0};
                return false;
            }
            bound = request.upperBound;
        }
        return k < links_.size() ? answerLink(k, request, bound, warm, answer, best, complete)
                                 : answerSelf(k - links_.size(), request, bound, warm, answer, best, complete);
    }

    bool RobotScene::answerLink(std::size_t i, const RobotRequest &request, double bound, RobotWarmStart &warm,
                                RobotPairAnswer &answer, RobotResult &best, bool &complete) const
    {
        // The fields RobotRequest passes on (its seed, start, maxEvaluations, recordHistory and maxTests are ignored).
        SceneRequest sceneRequest;
        sceneRequest.stopBelow = request.stopBelow;
        sceneRequest.upperBound = bound;
        sceneRequest.computeDepth = request.computeDepth;
        sceneRequest.outerBoundFirst = request.outerBoundFirst;
        SceneResult s;
        scenes_[i]->distance(warm.poses[i], sceneRequest, warm.links[i], s);
        best.pairsChecked += s.pairsChecked > 0 ? 1 : 0;
        complete = complete && s.certified;
        const std::size_t obstacle = s.obstacle < linkObstacles_[i].size() ? linkObstacles_[i][s.obstacle] : 0;
        answer = {s.distance, s.atLeast ? RobotPairAnswer::Status::AT_LEAST : RobotPairAnswer::Status::EXACT,
                  obstacle};
        if (s.atLeast || !(s.distance < best.distance))
            return false;
        best.selfPair = false;
        best.link = i;
        best.other = obstacle;
        best.onA = s.onA;
        best.onB = s.onB;
        best.inCollision = s.inCollision;
        best.penetrationDepth = s.penetrationDepth;
        best.distance = s.distance;
        return true;
    }

    bool RobotScene::answerSelf(std::size_t p, const RobotRequest &request, double bound, RobotWarmStart &warm,
                                RobotPairAnswer &answer, RobotResult &best, bool &complete) const
    {
        const auto [a, b] = selfPairs_[p];
        double gap;
        if (spheresApart(p, warm, bound, gap))
        {
            answer = {gap, RobotPairAnswer::Status::AT_LEAST, 0};
            return false;
        }
        DistanceRequest pairRequest;  // as answerLink() passes them on
        pairRequest.stopBelow = request.stopBelow;
        pairRequest.upperBound = bound;
        pairRequest.computeDepth = request.computeDepth;
        pairRequest.outerBoundFirst = request.outerBoundFirst;
        DistanceResult r;
        refineExact(*links_[a].body, *links_[b].body, warm.poses[a].inverse() * warm.poses[b], r, pairRequest,
                    &warm.self[p]);
        ++best.pairsChecked;
        complete = complete && r.certified;
        if (!(r.distance < bound))  // nothing below the bound (refineExact's infinity)
        {
            answer = {bound, RobotPairAnswer::Status::AT_LEAST, 0};
            return false;
        }
        answer = {r.distance, RobotPairAnswer::Status::EXACT, 0};
        if (!(r.distance < best.distance))
            return false;
        best.selfPair = true;
        best.link = a;
        best.other = b;
        best.onA = warm.poses[a] * r.onA;  // refineExact's witnesses are in a's frame
        best.onB = warm.poses[a] * r.onB;
        best.inCollision = r.inCollision;
        best.penetrationDepth = r.penetrationDepth;
        best.distance = r.distance;
        return true;
    }

    // How a query is answered: the pairs are visited one by one, the last minimum's pair first (the warm start's),
    // then the links against the obstacles, then the self pairs. Without everyPair, each pair is bounded by the
    // best distance so far (pruned when it cannot be below it; once in collision, only collisions matter, so the
    // deepest penetration over every colliding pair is found, as Scene does over obstacles); with it, every pair
    // is answered to the caller's bound. stopBelow ends the walk at the first pair at or below it.
    void RobotScene::distance(const double *state, std::size_t size, const RobotRequest &request,
                              RobotWarmStart &warm, RobotResult &result) const
    {
        if (!(request.upperBound > 0.0))
            throw Exception("RobotScene", "the upper bound of a distance query must be positive");
        prepare(state, size, warm);
        resetResult(result, numPairs(), links_.size());
        const std::size_t count = request.selfCollision ? numPairs() : links_.size();
        const std::size_t first = warm.valid && warm.pair < count ? warm.pair : count;
        const bool mayStop = request.stopBelow >= 0.0;
        bool complete = true, found = false, bestCertified = false, stopped = false;
        std::size_t bestPair = count;
        auto bound = [&]
        {
            if (request.everyPair || !found)
                return request.upperBound;
            // In collision, only a deeper collision can change the answer (answerPair(): bound 0).
            return result.distance > 0.0 ? std::min(result.distance, request.upperBound) : 0.0;
        };
        for (std::size_t step = 0; step < count && !stopped; ++step)
        {
            // Step 0 visits the warm start's pair; the others follow in order.
            const std::size_t k = first == count ? step : step == 0 ? first : step <= first ? step - 1 : step;
            bool pairComplete = true;
            if (answerPair(k, request, bound(), warm, result.pairs[k], result, pairComplete))
            {
                found = true;
                bestPair = k;
                bestCertified = pairComplete;
            }
            complete = complete && pairComplete;
            stopped = mayStop && found && result.distance <= request.stopBelow;
            if (stopped && step + 1 < count)
                complete = false;  // pairs left unvisited might be closer
        }
        if (!found && request.upperBound < std::numeric_limits<double>::infinity())
        {
            result.distance = request.upperBound;
            result.atLeast = true;
        }
        result.certified = result.inCollision ? bestCertified : complete;
        if (found)
        {
            warm.valid = true;
            warm.pair = bestPair;
        }
        finish(result);
    }

    void RobotScene::distance(const std::vector<double> &state, const RobotRequest &request,
                              RobotResult &result) const
    {
        RobotWarmStart cold;
        distance(state.data(), state.size(), request, cold, result);
    }

    void RobotScene::place(const double *state, std::size_t size, RobotWarmStart &warm) const
    {
        prepare(state, size, warm);
    }

    bool RobotScene::pairBoundsApart(std::size_t k, double margin, const RobotWarmStart &warm) const
    {
        const double bound = margin * (1.0 + 1e-12) + 1e-300;  // as pairApart() asks it
        if (k < links_.size())
            return boundsApart(k, bound, warm);
        const std::size_t p = k - links_.size();
        double gap;
        const auto [a, b] = selfPairs_[p];
        return rigidClearance_[p] > bound || spheresApart(p, warm, bound, gap) ||
               boxGap(warm.boxes[a], warm.boxes[b]) > bound;
    }

    bool RobotScene::pairApart(std::size_t k, double margin, RobotWarmStart &warm, std::size_t budget,
                               bool *gaveUp) const
    {
        if (gaveUp)
            *gaveUp = false;
        if (pairBoundsApart(k, margin, warm))
            return true;  // boxes and spheres suffice: no traversal, no hull
        // Above margin, strictly: the question asked is "nothing at or below margin * (1 + 1e-12) + tiny".
        const double bound = margin * (1.0 + 1e-12) + 1e-300;
        if (k < links_.size())
        {
            SceneRequest request;
            request.upperBound = bound;
            request.stopBelow = bound;
            request.computeDepth = false;
            request.maxTests = budget;
            request.outerBoundFirst = true;
            SceneResult s;
            scenes_[k]->distance(warm.poses[k], request, warm.links[k], s);
            const bool apart = s.atLeast && !s.inCollision;
            if (apart && !s.certified && gaveUp)
                *gaveUp = true;
            return apart && s.certified;
        }
        const std::size_t p = k - links_.size();
        const auto [a, b] = selfPairs_[p];
        DistanceRequest request;
        request.upperBound = bound;
        request.stopBelow = bound;
        request.computeDepth = false;
        request.maxTests = budget;
        request.outerBoundFirst = true;
        DistanceResult r;
        refineExact(*links_[a].body, *links_[b].body, warm.poses[a].inverse() * warm.poses[b], r, request,
                    &warm.self[p]);
        const bool apart = !r.inCollision && !(r.distance < bound);
        if (apart && !r.certified && gaveUp)
            *gaveUp = true;
        return apart && r.certified;
    }

    bool RobotScene::pairCollides(std::size_t k, RobotWarmStart &warm) const
    {
        return k < links_.size() ? linkCollides(k, warm) : selfVerdict(k - links_.size(), warm);
    }

    void RobotScene::finish(RobotResult &result) const
    {
        for (std::size_t i = 0; i < links_.size(); ++i)
            result.linkClearance[i] = result.pairs[i].distance;
        for (std::size_t p = 0; p < selfPairs_.size(); ++p)
        {
            const RobotPairAnswer &answer = result.pairs[links_.size() + p];
            for (std::size_t i : {selfPairs_[p].first, selfPairs_[p].second})
                result.linkClearance[i] = std::min(result.linkClearance[i], answer.distance);
        }
    }
}  // namespace meshgap
