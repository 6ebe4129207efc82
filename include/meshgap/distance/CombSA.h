#ifndef MESHGAP_DISTANCE_COMB_SA_H
#define MESHGAP_DISTANCE_COMB_SA_H

#include "meshgap/distance/DistanceSolver.h"

namespace meshgap
{
    MESHGAP_CLASS_FORWARD(CombSA);

    /**
       @anchor mgCombSA
       @par Short description
       The paper's comb-SA: simulated annealing over node pairs (one node per body). It starts at
       DistanceRequest::start (warm start, III-D) or at a node pair drawn from the request's seed. Each iteration makes
       a trial point by the random move (randomMove(), III-C.2) of both nodes of the current pair, along mesh paths,
       within a radius that shrinks as the temperature falls; the trial point replaces the current one if it is not
       worse, and otherwise with the Metropolis probability of eq. 3, p_b = exp((f(x_{i-1}) - f(x_i)) / (k_B t)),
       f = d^2. The best pair ever seen is kept (the paper's Figs. 8, 11, 14 decrease monotonically).

       Where the paper is silent (see CombSA.cpp for the reasons):
       - Cooling: every trial point is one iteration, and iteration i (1, 2, ...) runs at t_i = t_ini - (i - 1), so the
         search makes ceil(t_ini) trials and stops when t would reach 0. With Table I's t_ini = G_max N_pop = 2500
         that is the GA's trial budget, which is what the paper sets t_ini for.
       - Radius: r_i = r_max exp(1 - t_ini / t_i), r_max = max(D)/2 of each body (the mutation's radius), a
         Boltzmann-type factor exp(-E / t) scaled to r_max at t_ini: r_max/e at half the run, 5% of r_max at three
         quarters, less than one edge near the end (the move then takes one edge, see randomMove()).
       - The Metropolis draw is uniform in [0, 1) (the paper's "normally distributed ... 0 <= rho <= 1" can only be
         meant as uniform).

       Units: f = d^2 is in the scene's units squared, and Table I's k_B = 1e-4 fixes how much worse a trial point
       may be and still be accepted: k_B t runs from 0.25 down to 1e-4. In centimetres (the paper's battery) that
       explores; in millimetres almost every worse point is rejected. Scale "boltzmann" with the square of the unit.

       "comb-SA-wl" hill-climbs (hillClimb(), III-E) every trial point before the acceptance test and uses the improved
       pair; "comb-SA-nl" does not.

       Cost: evaluations counts every d^2; iterations counts trial points; convergedAt is the iteration at which the
       final best was first found (0: the start). history[0] is the start's distance and history[i] the best after
       iteration i. DistanceRequest::maxEvaluations is a hard cap.
       @par External documentation
       The paper in shared/paper, Sections II-B.1 and III-A, III-B.3, III-C, III-D, III-E; parameters: Table I.
       S. Kirkpatrick, C. D. Gelatt, M. P. Vecchi, Optimization by simulated annealing, Science 220, 1983.
    */
    class CombSA : public DistanceSolver
    {
    public:
        /** \brief Table I: Boltzmann constant k_B (in the scene's units squared per unit of temperature). */
        static constexpr double DEFAULT_BOLTZMANN = 0.0001;
        /** \brief Table I: initial temperature t_ini = G_max N_pop (also the number of iterations). */
        static constexpr double DEFAULT_INITIAL_TEMPERATURE = 2500.0;

        /** \brief "comb-SA-wl" when \e localSearch, "comb-SA-nl" otherwise. */
        explicit CombSA(bool localSearch);
        CombSA(const CombSA &) = delete;  // params_ refers to this object
        CombSA &operator=(const CombSA &) = delete;

        void solve(const Body &a, const Body &b, const Eigen::Isometry3d &X_AB, const DistanceRequest &request,
                   DistanceResult &result) const override;

        bool usesLocalSearch() const { return localSearch_; }

        /** \brief Boltzmann constant k_B > 0 of eq. 3 (parameter "boltzmann"). */
        void setBoltzmannConstant(double k);
        double getBoltzmannConstant() const { return boltzmann_; }

        /** \brief Initial temperature t_ini >= 0 (parameter "initial_temperature"); the run makes ceil(t_ini)
            iterations. */
        void setInitialTemperature(double t);
        double getInitialTemperature() const { return initialTemperature_; }

        /** \brief The temperature of iteration \e i (1-based) of a run started at \e initialTemperature. */
        static double temperature(double initialTemperature, std::size_t i);

        /** \brief The move radius at temperature \e t of a run started at \e initialTemperature, for a body whose
            largest move is \e maxRadius. */
        static double moveRadius(double maxRadius, double initialTemperature, double t);

    private:
        bool localSearch_;
        double boltzmann_{DEFAULT_BOLTZMANN};
        double initialTemperature_{DEFAULT_INITIAL_TEMPERATURE};
    };
}  // namespace meshgap

#endif
