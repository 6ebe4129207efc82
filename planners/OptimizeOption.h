#ifndef MESHGAP_PLANNERS_OPTIMIZE_OPTION_H
#define MESHGAP_PLANNERS_OPTIMIZE_OPTION_H

// meshgap_plan's --optimize: the path optimiser run on the planner's solution, and its summary lines.

#include <ompl/geometric/SimpleSetup.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

#include "CliMain.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/ClearancePathOptimizer.h"

namespace meshgap::cli
{
    /** \brief The optimisers --optimize accepts. */
    inline const char *optimizerNames()
    {
        return "clearance";
    }

    /** \brief Checks --optimize NAME against the clearance \e mode, and its limits (--optimize-time, a number of
        seconds; --optimize-rounds, at least 1) against it: each given without --optimize is refused. \e label
        names an option as the caller spells it (a flag, or a Python keyword); throws meshgap::Exception naming it. */
    template <typename Label>
    void checkOptimizeOptions(const std::string &optimize, const std::string &mode, double seconds, bool timeGiven,
                              unsigned rounds, bool roundsGiven, const Label &label)
    {
        if (!optimize.empty() && optimize != "clearance")
            throw Exception(label("optimize"), "unknown optimiser " + quote(optimize) + "; valid: " + optimizerNames());
        for (const auto &[name, given] :
             {std::pair{"optimize-time", timeGiven}, std::pair{"optimize-rounds", roundsGiven}})
            if (given && optimize.empty())
                throw Exception(label(name), "applies to " + label("optimize") + " only");
        checkSeconds(seconds, label("optimize-time"));
        if (rounds < 1)
            throw Exception(label("optimize-rounds"), "must be at least 1");
        if (!optimize.empty() && mode != "certified")
            throw Exception(label("optimize"), "clearance needs " + label("checker") +
                                                   " certified (it follows the exact clearance gradient)");
    }

    /** \brief Optimise the setup's solution path in place for at most \e seconds and \e rounds; returns the
        summary lines ("optimizer ...", "opt repair ..."), each key padded as meshgap_plan pads its summary. Motions
        of the planner's path the certified validator refuses are repaired first (CertifiedPathRepair, within the
        same time); if one cannot be, the path is left as it is, \e failed is set, the "optimizer" line says why and
        one line "error: ..." naming the motion goes to stderr. */
    inline std::string optimizeSolution(ompl::geometric::SimpleSetup &setup, const ClearanceFieldPtr &checker,
                                        double seconds, unsigned rounds, unsigned long seed, bool &failed)
    {
        std::ostringstream out;
        out.precision(6);
        auto line = [&out](const char *key, const std::string &value)
        {
            char padded[24];
            std::snprintf(padded, sizeof padded, "%-16s", key);
            out << padded << value << "\n";
        };
        ClearancePathOptimizer optimizer(setup.getSpaceInformation(), checker);
        optimizer.setTimeLimit(seconds);
        optimizer.setMaxRounds(rounds);
        optimizer.setSeed(seed);
        failed = false;
        try
        {
            optimizer.optimize(setup.getSolutionPath());
        }
        catch (const Exception &e)
        {
            std::fprintf(stderr,
                         "error: --optimize clearance: %s (within --optimize-time %g s); the planner's path "
                         "is kept, not optimised\n",
                         e.what(), seconds);
            line("optimizer", std::string("failed: ") + e.what());
            failed = true;
            return out.str();
        }
        const ClearancePathOptimizer::Stats &s = optimizer.lastStats();
        std::ostringstream v;
        v.precision(6);
        v << "clearance, " << s.seconds << " s, " << s.rounds << " rounds (" << s.moves << " moves, " << s.inserted
          << " states inserted, " << s.removed << " removed)" << (s.restored ? "; input kept (no gain)" : "");
        line("optimizer", v.str());
        const CertifiedPathRepair::Stats &r = s.repair;
        v.str("");
        if (r.refused == 0)
            v << "none (every motion of the planner's path certified)";
        else
            v << r.refused << " motions refused by the certified validator repaired (" << r.bisected
              << " by bisection, " << r.replanned << " replanned), " << r.inserted << " states inserted, " << r.seconds
              << " s";
        line("opt repair", v.str());
        v.str("");
        v << s.minClearanceBefore << " -> " << s.minClearanceAfter << " (the optimiser's measure: branch and bound "
          << "along each motion)";
        line("opt clearance", v.str());
        v.str("");
        v << s.lengthBefore << " -> " << s.lengthAfter << " (" << s.statesBefore << " -> " << s.statesAfter
          << " states)";
        line("opt length", v.str());
        return out.str();
    }
}  // namespace meshgap::cli

#endif
