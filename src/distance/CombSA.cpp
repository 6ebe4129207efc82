#include "meshgap/distance/CombSA.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "meshgap/Exception.h"
#include "meshgap/distance/HillClimb.h"
#include "meshgap/distance/MeshMoves.h"
#include "meshgap/distance/PairEvaluator.h"

namespace meshgap
{
    CombSA::CombSA(bool localSearch)
        : DistanceSolver(localSearch ? "comb-SA-wl" : "comb-SA-nl"), localSearch_(localSearch)
    {
        // Bad values throw std::invalid_argument, which ParamSet::setParam() turns into "false".
        params_.declareParam<double>(
            "boltzmann",
            [this](double k) { setChecked([&] { setBoltzmannConstant(k); }); },
            [this] { return getBoltzmannConstant(); });
        params_.declareParam<double>(
            "initial_temperature",
            [this](double t) { setChecked([&] { setInitialTemperature(t); }); },
            [this] { return getInitialTemperature(); });
    }

    void CombSA::setBoltzmannConstant(double k)
    {
        if (!(k > 0.0 && std::isfinite(k)))
            throw Exception(name_, "Boltzmann constant must be positive and finite, not " + std::to_string(k));
        boltzmann_ = k;
    }

    void CombSA::setInitialTemperature(double t)
    {
        if (!(t >= 0.0 && std::isfinite(t)))
            throw Exception(name_, "initial temperature must be finite and not negative, not " + std::to_string(t));
        initialTemperature_ = t;
    }

    // Cooling schedule. The paper (II-B.1) ties the temperature to the iteration number ("increase the iteration
    // number (in SA parlance: decrease the temperature)") and sets t_ini = G_max N_pop, "the total number of trials
    // the GA performs", so that the two algorithms are compared at equal budgets (IV). Both fit one schedule: one
    // unit of temperature per trial point, t_i = t_ini - (i - 1), ending when t would reach 0. (Read literally, step
    // 3 advances the iteration only on improvement; near a minimum improvements stop, the temperature would then
    // never fall and the run would never end, so every trial counts.)
    double CombSA::temperature(double initialTemperature, std::size_t i)
    {
        return initialTemperature - static_cast<double>(i - 1);
    }

    // Radius schedule. III-C.2 scales r_max down "as the iteration number increases (i.e., the temperature
    // decreases) using a Boltzmann type variation", with no formula. We take the Boltzmann factor exp(-E / t) with
    // E = t_ini, normalised to 1 at t = t_ini: r = r_max exp(1 - t_ini / t). It keeps most of r_max early (r_max/e at
    // half the run: the exploration the paper wants), then falls fast (5% at three quarters, 0.01% at nine tenths),
    // so the last part of the run makes one-edge moves around the current point.
    double CombSA::moveRadius(double maxRadius, double initialTemperature, double t)
    {
        if (!(t > 0.0))
            return 0.0;
        return maxRadius * std::exp(1.0 - initialTemperature / t);
    }

    void CombSA::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                       DistanceResult &result) const
    {
        const auto startTime = std::chrono::steady_clock::now();
        result = DistanceResult();
        checkRequest(a, b, request);

        const double kB = boltzmann_, tIni = initialTemperature_;
        const bool localSearch = localSearch_;
        const std::size_t cap = request.maxEvaluations;

        QueryRng rng(request.seed);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        PairEvaluator evaluator(a, b, X_AB);
        const MeshDistances &distancesA = a.distances(), &distancesB = b.distances();
        // The largest move is the mutation's r_max = max(D)/2 (III-B.3), shrunk by moveRadius() as t falls.
        const double maxRadiusA = 0.5 * distancesA.maxDistance(), maxRadiusB = 0.5 * distancesB.maxDistance();
        ThreadScratch<MoveScratch> lease;
        MoveScratch &scratch = lease.get();
        scratch.reserve(std::max(distancesA.graph().numNodes(), distancesB.graph().numNodes()));

        NodePair current;
        if (request.start)
            current = *request.start;
        else
        {
            current.a = std::uniform_int_distribution<std::uint32_t>(0, a.numNodes() - 1)(rng);
            current.b = std::uniform_int_distribution<std::uint32_t>(0, b.numNodes() - 1)(rng);
        }
        std::size_t localSteps = 0;
        double current2 = evaluator.d2(current);
        if (localSearch)
            localSteps += hillClimb(evaluator, current, current2, cap);
        NodePair best = current;
        double best2 = current2;
        std::size_t convergedAt = 0;
        if (request.recordHistory)
            result.history.push_back(std::sqrt(best2));

        std::size_t iteration = 0;
        for (;;)
        {
            const double t = temperature(tIni, iteration + 1);
            if (!(t > 0.0) || (cap != 0 && evaluator.evaluations() >= cap))
                break;
            ++iteration;

            // A new trial point: the random move of both nodes within the shrinking radius (III-C.2).
            NodePair trial;
            trial.a = randomMove(distancesA, current.a, moveRadius(maxRadiusA, tIni, t), rng, scratch);
            trial.b = randomMove(distancesB, current.b, moveRadius(maxRadiusB, tIni, t), rng, scratch);
            double trial2 = evaluator.d2(trial);
            if (localSearch)
                localSteps += hillClimb(evaluator, trial, trial2, cap);

            // Metropolis criterion, eq. 3. The draw is made only for worse points, so an improvement costs none.
            if (trial2 <= current2 || unit(rng) < std::exp((current2 - trial2) / (kB * t)))
            {
                current = trial;
                current2 = trial2;
            }
            if (current2 < best2)
            {
                best = current;
                best2 = current2;
                convergedAt = iteration;
            }
            if (request.recordHistory)
                result.history.push_back(std::sqrt(best2));
        }

        evaluator.fill(best, best2, result);
        result.localSteps = localSteps;
        result.iterations = iteration;
        result.convergedAt = convergedAt;
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
    }
}  // namespace meshgap
