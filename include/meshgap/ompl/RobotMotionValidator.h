#ifndef MESHGAP_OMPL_ROBOT_MOTION_VALIDATOR_H
#define MESHGAP_OMPL_ROBOT_MOTION_VALIDATOR_H

#include <ompl/base/MotionValidator.h>

#include <utility>
#include <vector>

#include "meshgap/ompl/RobotChecker.h"
#include "meshgap/ompl/StatePool.h"
#include "meshgap/robot/MotionBound.h"

namespace meshgap
{
    /**
       @anchor mgRobotMotionValidator
       @par Short description
       A certified motion validator for robots of every kind (URDF trees with a fixed or floating base, one or
       several rigid bodies in SE(2) or SE(3)) in a space made by robotStateSpace(): a motion is valid when it is
       proven free. Each pair's signed distance is 1-Lipschitz in the displacement of its bodies, and MotionBound
       bounds that displacement along the motion by lambda, the sum of each moving frame's step times its lever
       (|dq_j| r_j for a joint, |dp| + theta r for a free body), which grows linearly along OMPL's interpolation
       (for two links, how far either moves in the frame of their nearest common ancestor,
       MotionBound::pairDisplacement(), so both bodies' bounds added for two bodies of several; a link's own bound
       for a link against the obstacles). So on a piece
       [t0, t1] of the motion every state is within (t1 - t0) lambda / 2 of the piece's middle state, and a pair
       that is more than that apart at the middle (RobotScene::pairApart(), a bounded question: nothing beyond the
       margin is looked at) is free on the whole piece. The margin is the least of that and the piece's own bound
       at its middle state (MotionBound::pieceBounds(): each joint's step times the distance of the link's box from
       that joint's axis there, not its farthest reach over every state; two to three times tighter on an arm; for
       a self pair, MotionBound::pairPieceBound(): the joints between the two links split where that bounds least,
       each part charged to the link that moves less about it, so that a base is not charged for its upper arm
       sweeping about the shoulder). A piece's bounds are computed for the links of its pending pairs only, and its
       ends are its parent's end and middle, placed once.
       A self pair of a scene whose self pairs are tabulated (RobotScene::tabulateSelfPairs()) is first looked up:
       when the numbers that move it stay, over the piece, within cells of joint space proven apart
       (SelfPairTable::apartAlong(): the piece's segment in those numbers covered by a box, or by boxes around its
       halves, down to 2^5 of them), it needs no other question on the piece or its halves.
       Before the middle state's meshes are asked, a pair that the boxes at the middle do not prove apart is asked
       about the piece as a whole (RobotScene::sweptApart()): each link's convex hull swept between its places at
       the piece's two ends, grown by how far its points may stray from those straight lines (MotionBound::bend():
       at most (t1 - t0)^2 / 8 times the bend, a bound that shrinks with the square of the piece's length where the
       middle state's margin shrinks with its length); a link that stays put in the sweep's frame over the motion
       (MotionBound::stays()) is placed once, not swept, and each question's GJK starts along the direction it
       ended on for the last piece (RobotWarmStart::sweepAxes). A
       question that costs more than a budget of box and triangle tests gives up, and the pair is asked again on
       both halves with half the margin (cheaper: a pair just beyond its margin is the costly kind to prove) and
       four times the budget, without a budget from the sixth time. Pieces are taken breadth first (halves of halves, as OMPL's
       discrete validator orders its states), each asking only the pairs its parent could not prove; a pair that
       collides at a middle state (RobotScene::pairCollides()) makes the motion invalid at once, and so does a
       piece 2^-30 of the motion long, or a 65,537th piece, still unproven (conservative). The end states are not
       tested apart: the pieces' proofs cover them (an end in collision leaves the pieces beside it unproven).
       @par External documentation
       F. Schwarzer, M. Saha, J.-C. Latombe, Adaptive dynamic collision checking for single and multiple
       articulated robots in complex environments, IEEE Transactions on Robotics 21(3), 2005.
    */
    class RobotMotionValidator : public ompl::base::MotionValidator
    {
    public:
        RobotMotionValidator(const ompl::base::SpaceInformationPtr &si, RobotSceneConstPtr scene,
                             const RobotModel &robot);

        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2) const override;
        /** \brief As checkMotion(s1, s2); on failure \e lastValid holds s1 and fraction 0 (no partial motion is
            claimed). */
        bool checkMotion(const ompl::base::State *s1, const ompl::base::State *s2,
                         std::pair<ompl::base::State *, double> &lastValid) const override;

    private:
        /** \brief Whether the motion from \e s1 to \e s2 is proven free, as described above. */
        bool proveFree(const ompl::base::State *s1, const ompl::base::State *s2) const;

        /** \brief Per pair (RobotScene's order), its two links' MotionBound::bend() over \e motion into \e bends
            (the second 0 for a link against the obstacles), and whether each stays put (MotionBound::stays()) into
            \e stays. */
        void pairBends(const MotionBound::Motion &motion, std::vector<double> &bends,
                       std::vector<unsigned char> &stays) const;

        /** \brief How far pair \e k's distance may change over a piece \e half of \e motion long (a fraction), from
            MotionBound::pieceBounds()' \e sums: a link's displacement, or a self pair's least split bound
            (MotionBound::pairPieceBound(), with the middle state's \e frames and link \e poses). */
        double pieceBound(std::size_t k, const std::vector<double> &sums, const MotionBound::Motion &motion,
                          double half, const std::vector<Eigen::Isometry3d> &frames,
                          const std::vector<Eigen::Isometry3d> &poses) const;

        RobotSceneConstPtr scene_;
        MotionBound bound_;
        /** \brief Per self pair, MotionBound::pairTerms(). */
        std::vector<std::pair<std::size_t, std::size_t>> pairTerms_;
        /** \brief Per state number: 1 for an angle interpolated along the shorter arc (an SO(2) space's). */
        std::vector<unsigned char> angles_;
        mutable StatePool states_;  ///< the working state of each thread checking a motion
    };
}  // namespace meshgap

#endif
