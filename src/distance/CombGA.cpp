#include "meshgap/distance/CombGA.h"

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
    namespace
    {
        struct Individual
        {
            NodePair pair;
            double d2;
        };

        /** \brief An offspring, and whether it is a new trial point (to evaluate) or a copy of a known one. */
        struct Offspring
        {
            Individual x;
            bool fresh;
        };

        /** \brief Fitness for selection; larger is better. We minimise d^2, so SUS needs a transform; the paper does
            not give one. We take Goldberg's (1989) transform for minimisation, f_i = C_max - d^2_i with C_max the
            worst d^2 of the current population:
            - it is invariant to the scene's units (every d^2 times c gives every f times c, which SUS ignores) and
              needs no epsilon for touching pairs (d^2 = 0);
            - its pressure is moderate: the worst individual is never picked, the others in proportion to how much
              better than the worst they are. The population still collapses onto one pair within a few generations
              (mesh mating draws near the fitter parent), and what slows that collapse is what finds the global
              minimum. Measured on bumpy spheres like CombSolversTest's (20 seeds x 8 poses; icospheres of 642 nodes
              with bumps of 30% at frequency 16, 2562 nodes with the same, 2562 nodes with 20% at 24), comb-GA-wl
              found the enumeration minimum in 160, 148 and 155 of 160 runs with this transform, against 158, 134 and
              131 with the inverse 1 / (d^2 + eps) (a pair at half the distance is four times as fit: faster
              collapse) and 158, 143 and 139 with linear ranking.
            A population of equal d^2 (all f = 0) is selected uniformly. */
        void maxMinusFitness(const std::vector<Individual> &population, std::vector<double> &fitness)
        {
            double worst = 0.0;
            for (const Individual &x : population)
                worst = std::max(worst, x.d2);
            fitness.resize(population.size());
            for (std::size_t i = 0; i < population.size(); ++i)
                fitness[i] = worst - population[i].d2;
        }

        /** \brief Stochastic Universal Sampling (Baker 1987): \e count equally spaced pointers, the first uniform in
            [0, total / count), over the wheel of cumulative fitness; individual i is picked once per pointer that
            falls in its slot. The picks come in population order. A degenerate wheel (total not positive and
            finite) counts as equal fitness. */
        void stochasticUniversalSampling(std::vector<double> &fitness, std::size_t count, QueryRng &rng,
                                         std::vector<std::size_t> &picks)
        {
            picks.clear();
            double total = 0.0;
            for (double f : fitness)
                total += f;
            if (!(total > 0.0) || !std::isfinite(total))
            {
                std::fill(fitness.begin(), fitness.end(), 1.0);
                total = static_cast<double>(fitness.size());
            }
            const double step = total / static_cast<double>(count);
            const double first = std::uniform_real_distribution<double>(0.0, step)(rng);
            std::size_t i = 0;
            double slotEnd = fitness[0];
            for (std::size_t k = 0; k < count; ++k)
            {
                const double pointer = first + static_cast<double>(k) * step;
                while (pointer >= slotEnd && i + 1 < fitness.size())
                    slotEnd += fitness[++i];
                picks.push_back(i);
            }
        }

        /** \brief The per-query arrays of solve(), kept per thread (ThreadScratch). */
        struct Scratch
        {
            std::vector<Individual> population;
            std::vector<double> fitness;
            std::vector<std::size_t> picks;
            std::vector<Offspring> offspring;
            std::vector<std::pair<double, std::uint32_t>> clusterGaps;  ///< (signed sphere gap, i * |B's| + j)
            MoveScratch moves;
        };

        /** \brief The settings of one query, read once (a query sees one consistent set even if params change). */
        struct Settings
        {
            std::size_t populationSize;
            unsigned int maxGenerations;
            double mutationRate, crossoverRate;
            bool localSearch;
            std::size_t stallGenerations;
            CombGA::Seeding seeding;
            std::size_t restartStall;
            std::size_t cap;  ///< the request's evaluation cap (0: none)
        };

        /** \brief One comb-GA query: the population, the best pair so far, and the steps of a generation. */
        class GaRun
        {
        public:
            GaRun(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                  const Settings &settings, Scratch &work, DistanceResult &result)
                : a_(a),
                  b_(b),
                  X_AB_(X_AB),
                  request_(request),
                  s_(settings),
                  rng_(request.seed),
                  evaluator_(a, b, X_AB),
                  distancesA_(a.distances()),
                  distancesB_(b.distances()),
                  radiusA_(0.5 * distancesA_.maxDistance()),
                  radiusB_(0.5 * distancesB_.maxDistance()),
                  work_(work),
                  population_(work.population),
                  offspring_(work.offspring),
                  scratch_(work.moves),
                  result_(result)
            {
                scratch_.reserve(std::max(distancesA_.graph().numNodes(), distancesB_.graph().numNodes()));
            }

            /** \brief The whole search; the best pair found goes into the result. */
            void run()
            {
                seedClusters();
                seedRandom();
                bool stopped = !evaluatePopulation(0, false);
                record();
                offspring_.clear();
                offspring_.reserve(s_.populationSize);
                std::size_t generation = 0, lastRestart = 0;
                bool converged = false;
                while (!stopped && !converged && generation < s_.maxGenerations)
                {
                    ++generation;
                    select();
                    mate();
                    mutate();
                    stopped = !evaluateOffspring(generation);
                    record();
                    if (stopped)
                        break;
                    keepElite();
                    // Restart (optional, see setRestartStall()): no better pair for restartStall generations since
                    // the last improvement or restart: every member but the best drawn again.
                    if (s_.restartStall != 0 && generation - std::max(convergedAt_, lastRestart) >= s_.restartStall &&
                        generation < s_.maxGenerations)
                    {
                        lastRestart = generation;
                        if (!evaluatePopulation(generation, true))
                            break;
                    }
                    // Convergence (optional, see setStallGenerations()): no better pair for stallGenerations
                    // generations.
                    converged = s_.stallGenerations != 0 && generation - convergedAt_ >= s_.stallGenerations;
                }
                evaluator_.fill(best_.pair, best_.d2, result_);
                result_.localSteps = localSteps_;
                result_.iterations = generation;
                result_.convergedAt = convergedAt_;
            }

        private:
            /** \brief A new trial point: d^2, then (wl) the hill climb whose result replaces it. False when the cap is
                reached. */
            bool evaluate(Individual &x, std::size_t generation)
            {
                if (s_.cap != 0 && evaluator_.evaluations() >= s_.cap)
                    return false;
                x.d2 = evaluator_.d2(x.pair);
                if (s_.localSearch)
                    localSteps_ += hillClimb(evaluator_, x.pair, x.d2, s_.cap);
                if (x.d2 < best_.d2)
                {
                    best_ = x;
                    convergedAt_ = generation;
                }
                return true;
            }

            void record()
            {
                if (request_.recordHistory)
                    result_.history.push_back(std::sqrt(best_.d2));
            }

            /** \brief A node pair drawn uniformly from A x B. */
            NodePair randomPair()
            {
                std::uniform_int_distribution<std::uint32_t> nodeA(0, a_.numNodes() - 1), nodeB(0, b_.numNodes() - 1);
                return NodePair{nodeA(rng_), nodeB(rng_)};
            }

            /** \brief Initial population, cluster members (Seeding CLUSTERS: all, MIXED: every other): the nearest
                cluster pairs by signed sphere gap, nearest first, one member each (cycling if there are fewer
                cluster pairs than members), a random node of each cluster. */
            void seedClusters()
            {
                population_.assign(s_.populationSize, Individual());
                if (s_.seeding == CombGA::Seeding::RANDOM)
                    return;
                const auto &ca = a_.clusters(), &cb = b_.clusters();
                const Eigen::Matrix3d R = X_AB_.linear();
                const Eigen::Vector3d t = X_AB_.translation();
                auto &gaps = work_.clusterGaps;
                gaps.clear();
                for (std::uint32_t j = 0; j < cb.size(); ++j)
                {
                    const Eigen::Vector3d c = R * cb[j].center + t;
                    for (std::uint32_t i = 0; i < ca.size(); ++i)
                        gaps.emplace_back((ca[i].center - c).norm() - ca[i].radius - cb[j].radius,
                                          i * static_cast<std::uint32_t>(cb.size()) + j);
                }
                const bool clustersOnly = s_.seeding == CombGA::Seeding::CLUSTERS;
                const std::size_t clusterMembers = clustersOnly ? s_.populationSize : (s_.populationSize + 1) / 2;
                const std::size_t kept = std::min(gaps.size(), clusterMembers);
                std::partial_sort(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(kept), gaps.end());
                const auto &orderA = a_.clusterOrder(), &orderB = b_.clusterOrder();
                for (std::size_t k = 0; k < clusterMembers; ++k)
                {
                    const std::uint32_t key = gaps[k % kept].second;
                    const NodeCluster &A = ca[key / cb.size()], &B = cb[key % cb.size()];
                    const std::uint32_t ka = std::uniform_int_distribution<std::uint32_t>(A.begin, A.end - 1)(rng_);
                    const std::uint32_t kb = std::uniform_int_distribution<std::uint32_t>(B.begin, B.end - 1)(rng_);
                    // Mixed: cluster members at the even places, random ones at the odd.
                    population_[clustersOnly ? k : 2 * k].pair = NodePair{orderA[ka], orderB[kb]};
                }
            }

            /** \brief Random members (the paper's draw, in its order: the warm start takes the first place without a
                draw). */
            void seedRandom()
            {
                for (std::size_t i = 0; i < s_.populationSize; ++i)
                    if (i == 0 && request_.start)
                        population_[0].pair = *request_.start;
                    else if (s_.seeding == CombGA::Seeding::RANDOM ||
                             (s_.seeding == CombGA::Seeding::MIXED && i % 2 == 1))
                        population_[i].pair = randomPair();
            }

            /** \brief Selection: SUS, then a shuffle, since SUS returns its picks in population order and consecutive
                picks would otherwise mate with their neighbours in the array. */
            void select()
            {
                maxMinusFitness(population_, work_.fitness);
                stochasticUniversalSampling(work_.fitness, s_.populationSize, rng_, work_.picks);
                std::shuffle(work_.picks.begin(), work_.picks.end(), rng_);
            }

            /** \brief Mating: each pair of parents gives two offspring, mesh mated with probability p_x (both drawn
                independently by the rule of eq. 5, centred on the fitter parent), copies of the parents otherwise. */
            void mate()
            {
                const std::vector<std::size_t> &picks = work_.picks;
                std::uniform_real_distribution<double> unit(0.0, 1.0);  // a local: its bounds fold into the code
                offspring_.clear();
                for (std::size_t k = 0; k + 1 < s_.populationSize; k += 2)
                {
                    const Individual &p1 = population_[picks[k]], &p2 = population_[picks[k + 1]];
                    if (unit(rng_) < s_.crossoverRate)
                    {
                        const Individual &fitter = p1.d2 <= p2.d2 ? p1 : p2, &other = p1.d2 <= p2.d2 ? p2 : p1;
                        for (int child = 0; child < 2; ++child)
                        {
                            const Offspring o = meshMated(fitter, other);
                            offspring_.push_back(o);
                        }
                    }
                    else
                    {
                        offspring_.push_back({p1, false});
                        offspring_.push_back({p2, false});
                    }
                }
                if (s_.populationSize % 2 == 1)  // the odd one out passes on unmated
                    offspring_.push_back({population_[picks.back()], false});
            }

            /** \brief One mesh-mated child of \e fitter and \e other. */
            Offspring meshMated(const Individual &fitter, const Individual &other)
            {
                Offspring o{{NodePair(), 0.0}, true};
                o.x.pair.a = meshMate(distancesA_, fitter.pair.a, other.pair.a, fitter.d2, other.d2, rng_, scratch_);
                o.x.pair.b = meshMate(distancesB_, fitter.pair.b, other.pair.b, fitter.d2, other.d2, rng_, scratch_);
                // An offspring equal to a parent is no new trial point: it keeps the parent's known d^2.
                for (const Individual *parent : {&fitter, &other})
                    if (o.fresh && o.x.pair == parent->pair)
                    {
                        o.x.d2 = parent->d2;
                        o.fresh = false;
                    }
                return o;
            }

            /** \brief Mutation: the random move, per gene, with probability p_m, within r_max = max(D)/2. */
            void mutate()
            {
                std::uniform_real_distribution<double> unit(0.0, 1.0);
                for (Offspring &o : offspring_)
                {
                    if (unit(rng_) < s_.mutationRate)
                    {
                        o.x.pair.a = randomMove(distancesA_, o.x.pair.a, radiusA_, rng_, scratch_);
                        o.fresh = true;
                    }
                    if (unit(rng_) < s_.mutationRate)
                    {
                        o.x.pair.b = randomMove(distancesB_, o.x.pair.b, radiusB_, rng_, scratch_);
                        o.fresh = true;
                    }
                }
            }

            /** \brief Evaluation of the new trial points (hill-climbed first for -wl); false at the cap. */
            bool evaluateOffspring(std::size_t generation)
            {
                for (Offspring &o : offspring_)
                    if (o.fresh && !evaluate(o.x, generation))
                        return false;
                return true;
            }

            /** \brief Elitism: the best pair ever seen replaces the worst offspring unless it is already among them;
                the offspring become the population. */
            void keepElite()
            {
                const bool bestPresent = std::any_of(offspring_.begin(), offspring_.end(),
                                                     [&](const Offspring &o) { return o.x.pair == best_.pair; });
                if (!bestPresent)
                    std::max_element(offspring_.begin(), offspring_.end(),
                                     [](const Offspring &p, const Offspring &q) { return p.x.d2 < q.x.d2; })
                        ->x = best_;
                for (std::size_t i = 0; i < s_.populationSize; ++i)
                    population_[i] = offspring_[i].x;
            }

            /** \brief Evaluate the population in order; with \e redraw (a restart), every member but one copy of the
                best is first drawn again uniformly at random. False when the cap is reached. */
            bool evaluatePopulation(std::size_t generation, bool redraw)
            {
                bool bestKept = !redraw;  // one copy of the best stays (a collapsed population is all copies)
                for (std::size_t i = 0; i < s_.populationSize; ++i)
                {
                    if (redraw)
                    {
                        if (!bestKept && population_[i].pair == best_.pair)
                        {
                            bestKept = true;
                            continue;
                        }
                        population_[i].pair = randomPair();
                    }
                    if (!evaluate(population_[i], generation))
                        return false;
                }
                return true;
            }

            const Body &a_, &b_;
            const Eigen::Isometry3d &X_AB_;
            const DistanceRequest &request_;
            const Settings s_;  // by value: read in the hot loops without an indirection
            QueryRng rng_;
            PairEvaluator evaluator_;
            const MeshDistances &distancesA_, &distancesB_;
            /** \brief The mutation radius, fixed at max(D)/2 (III-B.3: "In the present case r_max was fixed to
                max(D)/2"). */
            const double radiusA_, radiusB_;
            Scratch &work_;
            std::vector<Individual> &population_;
            std::vector<Offspring> &offspring_;
            MoveScratch &scratch_;
            DistanceResult &result_;
            Individual best_{NodePair(), std::numeric_limits<double>::infinity()};
            std::size_t convergedAt_{0}, localSteps_{0};
        };
    }  // namespace

    CombGA::CombGA(bool localSearch)
        : DistanceSolver(localSearch ? "comb-GA-wl" : "comb-GA-nl"), localSearch_(localSearch)
    {
        // Bad values throw std::invalid_argument, which ParamSet::setParam() turns into "false".
        params_.declareParam<int>(
            "population",
            [this](int n) { setChecked([&] { setPopulationSize(static_cast<unsigned int>(std::max(n, 0))); }); },
            [this] { return static_cast<int>(getPopulationSize()); });
        params_.declareParam<int>(
            "generations",
            [this](int g)
            {
                if (g < 0)
                    throw std::invalid_argument("generations must not be negative");
                setGenerations(static_cast<unsigned int>(g));
            },
            [this] { return static_cast<int>(getGenerations()); });
        params_.declareParam<double>(
            "mutation_rate",
            [this](double p) { setChecked([&] { setMutationRate(p); }); },
            [this] { return getMutationRate(); });
        params_.declareParam<double>(
            "crossover_rate",
            [this](double p) { setChecked([&] { setCrossoverRate(p); }); },
            [this] { return getCrossoverRate(); });
        params_.declareParam<int>(
            "stall_generations",
            [this](int g)
            {
                if (g < 0)
                    throw std::invalid_argument("stall_generations must not be negative");
                setStallGenerations(static_cast<unsigned int>(g));
            },
            [this] { return static_cast<int>(getStallGenerations()); });
        params_.declareParam<std::string>(
            "seeding",
            [this](const std::string &s)
            {
                if (s == "random")
                    setSeeding(Seeding::RANDOM);
                else if (s == "clusters")
                    setSeeding(Seeding::CLUSTERS);
                else if (s == "mixed")
                    setSeeding(Seeding::MIXED);
                else
                    throw std::invalid_argument("seeding must be random, clusters or mixed");
            },
            [this]
            {
                const Seeding s = getSeeding();
                return std::string(s == Seeding::CLUSTERS ? "clusters" : s == Seeding::MIXED ? "mixed" : "random");
            });
        params_.declareParam<int>(
            "restart_stall",
            [this](int g)
            {
                if (g < 0)
                    throw std::invalid_argument("restart_stall must not be negative");
                setRestartStall(static_cast<unsigned int>(g));
            },
            [this] { return static_cast<int>(getRestartStall()); });
    }

    void CombGA::setPopulationSize(unsigned int n)
    {
        if (n < 2)
            throw Exception(name_, "population must be at least 2, not " + std::to_string(n));
        population_ = n;
    }

    void CombGA::setMutationRate(double p)
    {
        if (!(p >= 0.0 && p <= 1.0))
            throw Exception(name_, "mutation rate must lie in [0, 1], not " + std::to_string(p));
        mutationRate_ = p;
    }

    void CombGA::setCrossoverRate(double p)
    {
        if (!(p >= 0.0 && p <= 1.0))
            throw Exception(name_, "crossover rate must lie in [0, 1], not " + std::to_string(p));
        crossoverRate_ = p;
    }

    void CombGA::solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                       DistanceResult &result) const
    {
        const auto startTime = std::chrono::steady_clock::now();
        result = DistanceResult();
        checkRequest(a, b, request);
        const Settings settings{population_,       generations_, mutationRate_, crossoverRate_,        localSearch_,
                                stallGenerations_, seeding_,     restartStall_, request.maxEvaluations};
        ThreadScratch<Scratch> lease;
        GaRun(a, b, X_AB, request, settings, lease.get(), result).run();
        result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - startTime).count();
    }
}  // namespace meshgap
