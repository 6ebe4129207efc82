#ifndef MESHGAP_DISTANCE_COMB_GA_H
#define MESHGAP_DISTANCE_COMB_GA_H

#include "meshgap/distance/DistanceSolver.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(CombGA);

    /**
       @anchor mgCombGA
       @par Short description
       The paper's comb-GA: a genetic algorithm over node pairs (one node per body). The population (Table I: 50) is
       drawn at random from the request's seed, with DistanceRequest::start as one member when given (warm start,
       III-D). Each generation: Stochastic Universal Sampling on the fitness "worst d^2 of the population minus d^2"
       (see CombGA.cpp for the choice); parents paired at random; mesh mating with probability crossover_rate (per
       body: a node on the shortest mesh path between the parents' nodes, within the radius of eq. 5 of the fitter
       parent, see meshMate()); the random move along a mesh path within max(D)/2 as the mutation of each gene with
       probability mutation_rate (randomMove()). The best pair ever seen is kept and put back into every new
       population (elitism). It runs \e generations generations (Table I: G_max = 50), the hard cap.

       Convergence: the paper stops at G_max "or when convergence is detected" without a test, and reports comb-GA-wl
       still improving at generation 40. The population collapses onto one pair within about ten generations, but the
       runs that go on from there (mutation, then mating of the mutants with the best) are the ones that find the
       global minimum on hard cases: on bumpy spheres of 2562 nodes (CombSolversTest's, subdivided once more), stopping
       at collapse lost 12 to 30% of the successes, and stopping after 10 or 20 generations without improvement up to
       5%. So by default only G_max stops the search; "stall_generations" (setStallGenerations()) trades robustness for
       cost.

       Initial population ("seeding", setSeeding()): Seeding::RANDOM, the paper's and the default, draws node pairs
       uniformly from A x B. Seeding::CLUSTERS (our variant, off by default) draws them from the region pairs nearest
       each other: the bodies' node clusters (Body::clusters(), bounding spheres of at most 32 nodes, the leaves that
       enumeration prunes with) are paired, the pairs ranked by their signed sphere gap (centre distance minus both
       radii, as enumeration orders them), and member k of the population is a random node of each cluster of the
       k-th nearest cluster pair; the search from there is the paper's. It costs the clusters' pair count in sphere
       gaps (not node evaluations, and not counted as such). Seeding::MIXED draws half the population that way and
       half at random. setRestartStall() re-draws a stalled population at random, keeping the best (a restart with
       the remaining generations). Both measured in bench/paper/README.md ("Variants"); both off by default.

       "comb-GA-wl" hill-climbs (hillClimb(), III-E) every new trial point before it enters the population, and the
       improved pair replaces it (Lamarckian evolution: the paper's memetic variant); "comb-GA-nl" does not.

       Cost: DistanceResult::evaluations counts every d^2 (those of the hill climbs included); an offspring identical
       to a parent (no mating, or a draw of the parent's own nodes, and no mutation) is no new trial point and keeps
       its parent's d^2 without a new evaluation, so once the population has collapsed a generation costs little
       more than its mutants. iterations counts generations; convergedAt is the generation at which the final best was
       first found (0: the initial population).
       history[0] is the initial population's best distance and history[g] the best after generation g.

       DistanceRequest::maxEvaluations is a hard cap: the search stops before the evaluation that would exceed it.
       @par External documentation
       The paper in shared/paper, Sections II-B.2 and III-A, III-B, III-D, III-E; parameters: Table I.
       J. E. Baker, Reducing bias and inefficiency in the selection algorithm, Proc. 2nd Int. Conf. on Genetic
       Algorithms, 1987 (Stochastic Universal Sampling).
    */
    class CombGA : public DistanceSolver
    {
    public:
        /** \brief Table I: population size N_pop. */
        static constexpr unsigned int DEFAULT_POPULATION = 50;
        /** \brief Table I: maximum number of generations G_max. */
        static constexpr unsigned int DEFAULT_GENERATIONS = 50;
        /** \brief Table I: probability of mutation p_m, per gene (per body node of an individual). */
        static constexpr double DEFAULT_MUTATION_RATE = 0.02;
        /** \brief Table I: probability of crossover (mesh mating) p_x, per pair of parents. */
        static constexpr double DEFAULT_CROSSOVER_RATE = 0.6;

        /** \brief How the initial population is drawn (see the class description). */
        enum class Seeding
        {
            RANDOM,    ///< uniformly over A x B (the paper)
            CLUSTERS,  ///< one pair per nearest node-cluster pair, nearest first
            MIXED      ///< half of them as CLUSTERS (the even places), half as Random
        };

        /** \brief "comb-GA-wl" when \e localSearch, "comb-GA-nl" otherwise. */
        explicit CombGA(bool localSearch);
        CombGA(const CombGA &) = delete;  // params_ refers to this object
        CombGA &operator=(const CombGA &) = delete;

        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;

        bool usesLocalSearch() const { return localSearch_; }

        /** \brief Population size, at least 2 (parameter "population"). */
        void setPopulationSize(unsigned int n);
        unsigned int getPopulationSize() const { return population_; }

        /** \brief Maximum number of generations (parameter "generations"); 0 keeps the initial population only. */
        void setGenerations(unsigned int g) { generations_ = g; }
        unsigned int getGenerations() const { return generations_; }

        /** \brief Probability, in [0, 1], that a gene mutates (parameter "mutation_rate"). */
        void setMutationRate(double p);
        double getMutationRate() const { return mutationRate_; }

        /** \brief Probability, in [0, 1], that a pair of parents mates (parameter "crossover_rate"). */
        void setCrossoverRate(double p);
        double getCrossoverRate() const { return crossoverRate_; }

        /** \brief Stop once the best pair has not improved for \e g generations (parameter "stall_generations");
            0, the default, never stops before G_max. */
        void setStallGenerations(unsigned int g) { stallGenerations_ = g; }
        unsigned int getStallGenerations() const { return stallGenerations_; }

        /** \brief The initial population's draw (parameter "seeding": "random", the default, "clusters" or
            "mixed"). */
        void setSeeding(Seeding s) { seeding_ = s; }
        Seeding getSeeding() const { return seeding_; }

        /** \brief Restart a stalled population (parameter "restart_stall"): once the best pair has not improved for
            \e g generations since the last improvement or restart, every member but the best is drawn again
            uniformly at random (and climbed, for -wl); 0, the default, never restarts (the paper). */
        void setRestartStall(unsigned int g) { restartStall_ = g; }
        unsigned int getRestartStall() const { return restartStall_; }

    private:
        bool localSearch_;
        Seeding seeding_{Seeding::RANDOM};
        unsigned int restartStall_{0};
        unsigned int population_{DEFAULT_POPULATION};
        unsigned int generations_{DEFAULT_GENERATIONS};
        double mutationRate_{DEFAULT_MUTATION_RATE};
        double crossoverRate_{DEFAULT_CROSSOVER_RATE};
        unsigned int stallGenerations_{0};
    };
}  // namespace meshgap

#endif
