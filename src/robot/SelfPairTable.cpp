#include "meshgap/robot/SelfPairTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

#include "meshgap/Exception.h"
#include "meshgap/robot/MotionBound.h"
#include "meshgap/robot/RobotScene.h"

namespace meshgap
{
    namespace
    {
        constexpr double TWO_PI = 2.0 * M_PI;
        /** \brief A number this far beyond its range (relative to the larger of 1 and the limit) is taken as at the
            limit: the roundoff of an interpolation between two states there (RobotModel::checkState()'s slack). A
            cell is proven over half-widths padded by more (CELL_PAD), so such a state still lies in it. */
        constexpr double RANGE_SLACK = 1e-9;
        constexpr double CELL_PAD = 1e-7;

        /** \brief A state of \e robot inside its limits: each number at the middle of its limits (0 without), an
            SE(3) rotation the identity. Only the tabulated numbers are changed from it; the others do not move the
            pair. */
        std::vector<double> restingState(const RobotModel &robot)
        {
            std::vector<double> state(robot.dimension(), 0.0);
            for (std::size_t v = 0; v < state.size(); ++v)
            {
                const double lo = robot.stateLower(v), hi = robot.stateUpper(v);
                if (std::isfinite(lo) && std::isfinite(hi))
                    state[v] = 0.5 * (lo + hi);
                else if (std::isfinite(lo))
                    state[v] = lo;
                else if (std::isfinite(hi))
                    state[v] = hi;
            }
            for (const StateBlock &block : robot.stateBlocks())
                if (block.space == JointSpace::SE3)
                {
                    for (std::size_t i = 3; i < 6; ++i)
                        state[block.first + i] = 0.0;
                    state[block.first + 6] = 1.0;
                }
            return state;
        }
    }  // namespace

    SelfPairTable::SelfPairTable(const RobotScene &scene, const Options &options)
    {
        if (options.rootCells < 4 || options.rootCells > 64 || options.levels > 8)
            throw Exception("SelfPairTable", "rootCells must be within [4, 64] and levels at most 8, not " +
                                                 std::to_string(options.rootCells) + " and " +
                                                 std::to_string(options.levels));
        const RobotModel &robot = scene.robot();
        pairs_.resize(scene.selfPairs().size());
        std::unique_ptr<const MotionBound> bounds;
        try
        {
            bounds = std::make_unique<const MotionBound>(robot);
        }
        catch (const Exception &)
        {
            return;  // a frame moving free below a moving one: no motion bound (as the validator has none), no table
        }
        const MotionBound &bound = *bounds;
        std::vector<std::size_t> numbers, todo;
        std::vector<unsigned char> arcs;
        for (std::size_t p = 0; p < pairs_.size(); ++p)
        {
            const auto [a, b] = scene.selfPairs()[p];
            if (!bound.pairNumbers(a, b, numbers, arcs) || numbers.empty() || numbers.size() > 2)
                continue;
            Grid &g = pairs_[p];
            bool ranged = true;
            for (std::size_t d = 0; d < numbers.size(); ++d)
            {
                const std::size_t v = numbers[d];
                g.numbers[d] = v;
                g.arc[d] = arcs[d] != 0;
                g.cells[d] = std::size_t(options.rootCells) << options.levels;
                const double from = g.arc[d] ? -M_PI : robot.stateLower(v);
                const double to = g.arc[d] ? M_PI : robot.stateUpper(v);
                ranged = ranged && std::isfinite(from) && std::isfinite(to) && to > from;
                g.lower[d] = from;
                g.width[d] = (to - from) / double(g.cells[d]);
            }
            g.dims = ranged ? int(numbers.size()) : 0;
            if (g.dims > 0)
                todo.push_back(p);
        }
        // The pairs shared out between threads (each asks the scene's const questions with its own warm start).
        std::atomic<std::size_t> next{0}, questions{0};
        std::exception_ptr failure;
        std::mutex failed;
        auto work = [&]
        {
            try
            {
                for (std::size_t t = next++; t < todo.size(); t = next++)
                    questions += tabulate(scene, bound, todo[t], std::size_t(1) << options.levels, pairs_[todo[t]]);
            }
            catch (...)
            {
                const std::lock_guard<std::mutex> lock(failed);
                failure = std::current_exception();
                next = todo.size();
            }
        };
        const std::size_t threads =
            std::min<std::size_t>(todo.size(), std::max(1u, std::thread::hardware_concurrency()));
        std::vector<std::thread> pool;
        for (std::size_t t = 1; t < threads; ++t)
            pool.emplace_back(work);
        work();
        for (std::thread &t : pool)
            t.join();
        if (failure)
            std::rethrow_exception(failure);
        questions_ = questions;
    }

    std::size_t SelfPairTable::tabulate(const RobotScene &scene, const MotionBound &bound, std::size_t p,
                                        std::size_t root, Grid &g)
    {
        const auto [a, b] = scene.selfPairs()[p];
        const std::vector<double> rest = restingState(scene.robot());
        std::vector<double> state, lo, hi, sums;
        std::vector<unsigned char> only(scene.links().size(), 0);
        only[a] = only[b] = 1;
        MotionBound::Motion motion;
        RobotWarmStart warm;
        const std::pair<std::size_t, std::size_t> terms = bound.pairTerms(a, b);
        const std::size_t n0 = g.cells[0], n1 = g.cells[1], step1 = g.dims == 2 ? root : 1;
        std::vector<unsigned char> open(n0 * n1, 1);
        std::vector<std::size_t> todo;  // cells to ask, depth first: (i, j, size) in finest cells, three numbers each
        for (std::size_t i = 0; i < n0; i += root)
            for (std::size_t j = 0; j < n1; j += step1)
                todo.insert(todo.end(), {i, j, root});
        std::size_t questions = 0;
        while (!todo.empty())
        {
            const std::size_t size = todo.back(), j = todo[todo.size() - 2], i = todo[todo.size() - 3];
            todo.resize(todo.size() - 3);
            const std::size_t at[2] = {i, j};
            state = lo = hi = rest;
            for (int d = 0; d < g.dims; ++d)
            {
                const double half = 0.5 * double(size) * g.width[d];
                const double centre = g.lower[d] + double(at[d]) * g.width[d] + half;
                const double padded = half * (1.0 + CELL_PAD) + CELL_PAD * std::max(1.0, std::abs(centre));
                state[g.numbers[d]] = centre;
                lo[g.numbers[d]] = centre - padded;
                hi[g.numbers[d]] = centre + padded;
            }
            // How far the two links may move relative to each other within the cell: over the motion between two
            // opposite corners, from the centre (a piece of half 0.5 about it).
            bound.motion(lo, hi, motion);
            scene.place(state.data(), state.size(), warm);
            bound.pieceBounds(motion, warm.frames, warm.poses, 0.5, sums, &only);
            const double margin = std::min(0.5 * bound.pairDisplacement(a, b, lo, hi),
                                           bound.pairPieceBound(a, b, terms, sums, motion, 0.5, warm.frames,
                                                                warm.poses));
            ++questions;
            if (scene.pairApart(scene.links().size() + p, margin, warm))
            {
                const std::size_t i1 = std::min(i + size, n0), j1 = std::min(j + (g.dims == 2 ? size : 1), n1);
                for (std::size_t x = i; x < i1; ++x)
                    std::fill(open.begin() + x * n1 + j, open.begin() + x * n1 + j1, 0);
                continue;
            }
            if (size == 1)
                continue;
            const std::size_t h = size / 2;
            todo.insert(todo.end(), {i, j, h, i + h, j, h});
            if (g.dims == 2)
                todo.insert(todo.end(), {i, j + h, h, i + h, j + h, h});
        }
        g.sums.assign((n0 + 1) * (n1 + 1), 0);
        for (std::size_t x = 0; x < n0; ++x)
            for (std::size_t y = 0; y < n1; ++y)
                g.sums[(x + 1) * (n1 + 1) + y + 1] = open[x * n1 + y] + g.sums[x * (n1 + 1) + y + 1] +
                                                     g.sums[(x + 1) * (n1 + 1) + y] - g.sums[x * (n1 + 1) + y];
        return questions;
    }

    std::uint32_t SelfPairTable::unproven(const Grid &g, std::size_t i0, std::size_t i1, std::size_t j0,
                                          std::size_t j1)
    {
        const std::size_t w = g.cells[1] + 1;
        return g.sums[(i1 + 1) * w + j1 + 1] - g.sums[i0 * w + j1 + 1] - g.sums[(i1 + 1) * w + j0] +
               g.sums[i0 * w + j0];
    }

    bool SelfPairTable::cover(const Grid &g, int d, double from, double to, std::size_t first[2],
                              std::size_t last[2], int &runs)
    {
        const double n = double(g.cells[d]);
        if (!(from <= to))
            return false;  // NaN
        if (g.arc[d])
        {
            if (to - from >= TWO_PI)
            {
                runs = 1;
                first[0] = 0;
                last[0] = g.cells[d] - 1;
                return true;
            }
            const double start = from - TWO_PI * std::floor((from + M_PI) / TWO_PI);  // in [-pi, pi)
            const double x0 = std::floor((start + M_PI) / g.width[d]);
            const double x1 = std::floor((start + (to - from) + M_PI) / g.width[d]);
            const std::size_t i0 = std::size_t(std::clamp(x0, 0.0, n - 1.0));
            const std::size_t i1 = std::size_t(std::clamp(x1, 0.0, 2.0 * n - 1.0));
            if (i1 < g.cells[d])
            {
                runs = 1;
                first[0] = i0;
                last[0] = i1;
                return true;
            }
            runs = 2;
            first[0] = i0;
            last[0] = g.cells[d] - 1;
            first[1] = 0;
            last[1] = std::min(i1 - g.cells[d], g.cells[d] - 1);
            return true;
        }
        const double upper = g.lower[d] + n * g.width[d];
        const double slack = RANGE_SLACK * std::max({1.0, std::abs(g.lower[d]), std::abs(upper)});
        if (from < g.lower[d] - slack || to > upper + slack)
            return false;
        runs = 1;
        first[0] = std::size_t(std::clamp(std::floor((from - g.lower[d]) / g.width[d]), 0.0, n - 1.0));
        last[0] = std::size_t(std::clamp(std::floor((to - g.lower[d]) / g.width[d]), 0.0, n - 1.0));
        return true;
    }

    bool SelfPairTable::provenOver(const Grid &g, const double from[2], const double to[2])
    {
        std::size_t first[2][2], last[2][2];
        int runs[2] = {1, 1};
        first[1][0] = last[1][0] = 0;
        for (int d = 0; d < g.dims; ++d)
            if (!cover(g, d, from[d], to[d], first[d], last[d], runs[d]))
                return false;
        for (int r = 0; r < runs[0]; ++r)
            for (int s = 0; s < runs[1]; ++s)
                if (unproven(g, first[0][r], last[0][r], first[1][s], last[1][s]) != 0)
                    return false;
        return true;
    }

    bool SelfPairTable::apartAt(std::size_t p, const double *state) const
    {
        const Grid &g = pairs_[p];
        if (g.dims == 0)
            return false;
        double from[2] = {0.0, 0.0};
        for (int d = 0; d < g.dims; ++d)
            from[d] = state[g.numbers[d]];
        return provenOver(g, from, from);
    }

    bool SelfPairTable::provenAlong(const Grid &g, const double middle[2], const double step[2], double half,
                                    unsigned int splits)
    {
        double from[2] = {0.0, 0.0}, to[2] = {0.0, 0.0};
        for (int d = 0; d < g.dims; ++d)
        {
            // Padded against roundoff in the interpolation that places the segment's states.
            const double reach = std::abs(half * step[d]) * (1.0 + 1e-9) + 1e-12 * (1.0 + std::abs(middle[d]));
            from[d] = middle[d] - reach;
            to[d] = middle[d] + reach;
        }
        if (provenOver(g, from, to))
            return true;
        if (splits == 0)
            return false;
        double m0[2] = {0.0, 0.0}, m1[2] = {0.0, 0.0};
        for (int d = 0; d < g.dims; ++d)
        {
            m0[d] = middle[d] - 0.5 * half * step[d];
            m1[d] = middle[d] + 0.5 * half * step[d];
        }
        return provenAlong(g, m0, step, 0.5 * half, splits - 1) && provenAlong(g, m1, step, 0.5 * half, splits - 1);
    }

    bool SelfPairTable::apartAlong(std::size_t p, const double *middle, const double *step, double half,
                                   unsigned int splits) const
    {
        const Grid &g = pairs_[p];
        if (g.dims == 0)
            return false;
        double m[2] = {0.0, 0.0}, s[2] = {0.0, 0.0};
        for (int d = 0; d < g.dims; ++d)
        {
            m[d] = middle[g.numbers[d]];
            s[d] = step[g.numbers[d]];
        }
        return provenAlong(g, m, s, half, splits);
    }

    double SelfPairTable::provenFraction(std::size_t p) const
    {
        const Grid &g = pairs_[p];
        if (g.dims == 0)
            return 0.0;
        const double cells = double(g.cells[0] * g.cells[1]);
        return 1.0 - double(unproven(g, 0, g.cells[0] - 1, 0, g.cells[1] - 1)) / cells;
    }
}  // namespace meshgap
