#include "support/PlanOptions.h"

#include <algorithm>
#include <cmath>

#include "CliMain.h"
#include "OptimizeOption.h"
#include "meshgap/Exception.h"
#include "meshgap/Text.h"
#include "meshgap/ompl/MotionValidatorFactory.h"
#include "meshgap/ompl/PlannerFactory.h"
#include "meshgap/ompl/SamplerFactory.h"

namespace meshgap
{
    namespace cli
    {
        std::string PlanOptions::label(const std::string &name) const
        {
            return keywords ? planKeyword(name) : "--" + name;
        }

        std::string planKeyword(const std::string &name)
        {
            std::string keyword = name;
            std::replace(keyword.begin(), keyword.end(), '-', '_');
            return keyword;
        }

        const std::vector<PlanOption> &planOptionTable()
        {
            using K = PlanOptionKind;
            using O = PlanOptions;
            static const std::vector<PlanOption> table = {
                {"cfg", 0, K::FILE, &O::cfg, "OMPL.app problem file (.cfg)"},
                {"planner", 0, K::TEXT, &O::planner, "planner (default rrtconnect): " + joinNames(plannerNames())},
                {"param", 0, K::TEXTS, &O::params,
                 "PLANNER.NAME=VALUE: one of the planner's OMPL parameters, e.g. rrtconnect.range=5 or "
                 "rrtstar.use_k_nearest=0; repeatable"},
                {"time", 0, K::REAL, &O::time, "time limit in seconds (default 10)"},
                {"objective", 0, K::TEXT, &O::objective,
                 "length, clearance (integral of 1/clearance), max_min_clearance, or weighted (length + W * "
                 "clearance); default: the cfg's objective, else length"},
                {"weight", 0, K::REAL, &O::weight, "W of --objective weighted, a length (default: a tenth of the "
                                                   "robot's radius)"},
                {"checker", 0, K::TEXT, &O::checker,
                 "clearance checker: certified (exact; the default) or fast (an upper bound from the paper's solver, "
                 "warm-started: APPROXIMATE)"},
                {"motion", 0, K::TEXT, &O::motion,
                 "motion validator: discrete (OMPL's, sampled; the default) or clearance (conservative advancement, "
                 "certified); a robot problem's motions are certified unless discrete is given"},
                {"seed", 0, K::COUNT, &O::seed, "OMPL's random seed (default 1)"},
                {"out", 0, K::FILE, &O::out, "write the path here (.path)"},
                {"clearance-csv", 0, K::FILE, &O::csv,
                 "write the exact clearance along the densely interpolated path here (CSV)"},
                {"dense", 0, K::COUNT, &O::dense, "states per OMPL validity-check segment of the dense path "
                                                  "(default 4)"},
                {"summary", 0, K::FILE, &O::summaryFile, "also write the summary here"},
                {"export-glb", 0, K::FILE, &O::glb,
                 "write the scene as glTF 2.0 binary (.glb): the world, the robot at --export-states states evenly "
                 "spaced along the dense path (start and goal without a path) and the exact closest-point segment at "
                 "each"},
                {"export-states", 0, K::COUNT, &O::exportStates, "robot states in the --export-glb file (default 8)"},
                {"report", 0, K::FILE, &O::report,
                 "write a self-contained HTML report (3D scene with the robot along the dense path, clearance plot, "
                 "summary) here"},
                {"optimize", 0, K::TEXT, &O::optimize,
                 "after planning, optimise the path: clearance (raise its minimum clearance up the exact gradient, "
                 "every motion certified; needs --checker certified)"},
                {"optimize-time", 0, K::REAL, &O::optimizeTime, "time limit of --optimize in seconds (default 5)"},
                {"optimize-rounds", 0, K::COUNT, &O::optimizeRounds,
                 "at most this many rounds of --optimize (default 1000: in practice until it converges or its time "
                 "ends)"},
                {"sampler", 0, K::TEXT, &O::sampler,
                 "valid-state sampler of planners that use one (PRM, EST, ...; default: the cfg's sampler, else "
                 "uniform): " + joinNames(validStateSamplerNames())},
                {"quiet", 'q', K::SWITCH, &O::quiet, "print errors only (no OMPL messages, no warnings, no progress)"}};
            return table;
        }

        void checkPlanOptions(const PlanOptions &o)
        {
            if (o.cfg.empty() && o.moveit.urdf.empty())
                throw Exception(o.keywords ? "cfg" : "command line",
                                "--cfg FILE (or --urdf with --scene and --request) is required; see --help");
            if (o.checker != "certified" && o.checker != "fast")
                throw Exception(o.label("checker"), quote(o.checker) + " is not certified or fast");
            checkMotionValidatorName(o.motion, o.label("motion"));
            if (o.motion == "clearance" && o.checker != "certified")
                throw Exception(o.label("motion"), "clearance needs " + o.label("checker") +
                                                       " certified (it steps by exact clearance)");
            checkSeconds(o.time, o.label("time"));
            if (o.dense < 1)
                throw Exception(o.label("dense"), "must be at least 1");
            if (o.exportStates < 1)
                throw Exception(o.label("export-states"), "must be at least 1");
            checkOptimizeOptions(o.optimize, o.checker, o.optimizeTime, o.isGiven("optimize-time"), o.optimizeRounds,
                                 o.isGiven("optimize-rounds"), [&o](const std::string &name) { return o.label(name); });
            if (o.isGiven("weight") && !(o.weight > 0.0 && std::isfinite(o.weight)))
                throw Exception(o.label("weight"), "must be positive and finite");
        }
    }  // namespace cli
}  // namespace meshgap
