#!/usr/bin/env bash
# Planning throughput of meshgap's checkers against the FCL checker on OMPL.app problems and maps:
# RRTConnect, every checker (or CHECKERS), RUNS runs of at most TIME s each per problem, then a Markdown table
# (bench/planning_summary.py; the benchmarks' own output goes to stderr).
#
#   bench/run_planning_benchmark.sh [BUILD_DIR] [OUT_DIR]
#   RUNS=5 TIME=10 PROBLEMS="cubicles Easy" PLANNERS=rrtconnect bench/run_planning_benchmark.sh build results
#   CHECKERS=certified,fast,fcl PROBLEMS="cubicles Easy battery_fixture" bench/run_planning_benchmark.sh build results
#   PLANNERS=rrtstar ARGS="--objective max_min_clearance" bench/run_planning_benchmark.sh build results
#
# ARGS: more meshgap_benchmark options, split at spaces.
# PROBLEMS are names of maps/ (maps/NAME/NAME.cfg) or of ../shared/data/omplapp (NAME.cfg). The .log files go to
# OUT_DIR (default: planning-results); load them into Planner Arena with
#   ompl_benchmark_statistics OUT_DIR/*.log -d OUT_DIR/results.db
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-planning-results}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
runs="${RUNS:-5}"
time="${TIME:-10}"
planners="${PLANNERS:-rrtconnect}"
seed="${SEED:-1}"
checkers=()
[ -n "${CHECKERS:-}" ] && checkers=(--checker "$CHECKERS")
read -r -a extra <<< "${ARGS:-}"
mkdir -p "$out"
for problem in ${PROBLEMS:-cubicles Easy}; do
    cfg="$data/$problem.cfg"
    [ -f "$here/../maps/$problem/$problem.cfg" ] && cfg="$here/../maps/$problem/$problem.cfg"
    [ -f "$cfg" ] || { echo "error: $cfg: not found (set MESHGAP_SHARED_DATA_DIR)" >&2; exit 1; }
    nice "$build/planners/meshgap_benchmark" --cfg "$cfg" --planner "$planners" --runs "$runs" --time "$time" \
        --seed "$seed" --out "$out" "${checkers[@]}" "${extra[@]}" >&2
done
python3 "$here/planning_summary.py" "$out"/*.log
