#ifndef MESHGAP_ROBOT_SELF_PAIR_TABLE_H
#define MESHGAP_ROBOT_SELF_PAIR_TABLE_H

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshgap/ClassForward.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(SelfPairTable);
    class RobotScene;
    class MotionBound;

    /** \brief Where in joint space two links of a robot are proven apart, for the self pairs whose relative pose
        is a function of one or two state numbers (a base and the upper arm two joints up, a forearm and the wrist
        two joints down): a grid over those numbers' range whose cells are each proven free as a whole, once per
        robot. A state check of such a pair is then one look-up (apartAt()), and a piece of motion whose numbers
        stay within proven cells needs no question about the pair (apartAlong()).

        A cell is proven as a piece of motion is (RobotMotionValidator): the pair is more than a margin apart at
        the cell's centre (RobotScene::pairApart(), certified), the margin bounding how far either link moves
        relative to the other while the numbers stray within the cell (MotionBound::pairPieceBound() over the
        motion between two opposite corners: every bound of MotionBound grows with each number's step alone, so
        the motion from the centre's mirror image to any state of the cell, no longer in any number, is bounded by
        it). A cell not proven is halved in every number and its parts asked, down to a finest cell; an unproven
        cell claims nothing. The pairs are shared out between the machine's cores while building.

        A number of a joint with limits is tabulated over them; a continuous joint's angle over [-pi, pi), the
        cells wrapping around. A state outside the range (beyond roundoff) gets no claim. Pairs moved by a free
        frame, by more than two numbers, or by a number without limits other than an angle are not tabulated, nor
        is any pair of a robot MotionBound does not take (a frame moving free below a moving one).
        Immutable once built; thread-safe; look-ups allocate nothing. */
    class SelfPairTable
    {
    public:
        struct Options
        {
            /** \brief Cells per number at the coarsest level. */
            unsigned int rootCells{8};
            /** \brief How many times a cell may be halved: the finest cell is the range over rootCells *
                2^levels. */
            unsigned int levels{5};
        };

        /** \brief Tabulate the self pairs of \e scene (RobotScene::selfPairs() order); its obstacles play no part. */
        SelfPairTable(const RobotScene &scene, const Options &options);
        explicit SelfPairTable(const RobotScene &scene) : SelfPairTable(scene, Options()) {}

        /** \brief Number of self pairs (tabulated or not). */
        std::size_t numPairs() const { return pairs_.size(); }
        /** \brief Whether self pair \e p has a grid. */
        bool tabulated(std::size_t p) const { return pairs_[p].dims > 0; }
        /** \brief True when self pair \e p is proven apart at \e state (a state of the robot, its numbers;
            false: no claim). */
        bool apartAt(std::size_t p, const double *state) const;
        /** \brief True when self pair \e p is proven apart at every state middle + t step, |t| <= \e half (both
            indexed by state number; an angle's step along the circle, signed): the box around the segment (with
            \e splits 0, that box alone), or else each half of the segment in the same way, at most \e splits times
            deep. */
        bool apartAlong(std::size_t p, const double *middle, const double *step, double half,
                        unsigned int splits) const;
        /** \brief The fraction of self pair \e p's range proven apart (0 for a pair not tabulated). */
        double provenFraction(std::size_t p) const;
        /** \brief How many cells were asked about while building, over every pair. */
        std::size_t questions() const { return questions_; }

    private:
        /** \brief One pair's grid: its numbers (dims of them, 0: not tabulated), each one's range and cells, and the
            summed counts of the cells not proven ((cells[0] + 1) x (cells[1] + 1), row by the first number). */
        struct Grid
        {
            int dims{0};
            std::size_t numbers[2]{0, 0};
            bool arc[2]{false, false};
            double lower[2]{0.0, 0.0}, width[2]{0.0, 0.0};  ///< the range's start, one cell's width
            std::size_t cells[2]{1, 1};
            std::vector<std::uint32_t> sums;
        };

        /** \brief Prove the cells of self pair \e p of \e scene into \e g (its numbers and ranges set), from cells
            \e root finest cells wide; returns how many questions it asked. */
        static std::size_t tabulate(const RobotScene &scene, const MotionBound &bound, std::size_t p,
                                    std::size_t root, Grid &g);
        /** \brief The cells of grid \e g that the numbers within [from, to] of dimension \e d cover, as at most two
            runs of indices ([first[i], last[i]], i < runs; an angle's may wrap around); false when the range leaves
            the grid's. */
        static bool cover(const Grid &g, int d, double from, double to, std::size_t first[2], std::size_t last[2],
                          int &runs);
        /** \brief How many cells of \e g are not proven in the index box [i0, i1] x [j0, j1]. */
        static std::uint32_t unproven(const Grid &g, std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1);
        /** \brief apartAlong() for grid \e g, the segment's middle and step in its numbers. */
        static bool provenAlong(const Grid &g, const double middle[2], const double step[2], double half,
                                unsigned int splits);
        /** \brief True when every cell of \e g that the box of numbers [from[d], to[d]] covers is proven. */
        static bool provenOver(const Grid &g, const double from[2], const double to[2]);

        std::vector<Grid> pairs_;
        std::size_t questions_{0};
    };
}  // namespace meshgap

#endif
