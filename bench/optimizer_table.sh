#!/usr/bin/env bash
# The optimiser's table: RRTConnect + the ClearancePathOptimizer (planner rrtconnect+opt: RRTConnect with the clearance
# motion validator, then the optimiser for the rest of the run's time) against RRT* with max-min clearance and
# RRTConnect alone, from meshgap_benchmark runs (OMPL .log files) summarised by clearance_summary.py: median minimum
# clearance by FCL over the densely interpolated path, median length, and whether every path is FCL-free.
#
#   bench/optimizer_table.sh [BUILD_DIR] [OUT_DIR]
#
# Settings (environment): RUNS (5), SEED (1), MAPS (the four maps, TIME_MAPS s a run, default 10), PROBLEMS (cubicles
# Easy, TIME_PROBLEMS s, default 5), TWISTY (Twistycool runs, default 3, TIME_TWISTY s, default 60; 0 skips it),
# BASELINES (1: also RRT* max-min and RRTConnect on PROBLEMS and Twistycool in the same run; default 1). The maps'
# baselines are clearance_table.sh's (bench/planning.md). Paths are not simplified (--no-simplify): the planners' own.
# The benchmarks' own output goes to stderr, so stdout holds the table alone.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-optimizer-results}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
runs="${RUNS:-5}"
seed="${SEED:-1}"
maps="${MAPS-battery_fixture hand_bowl handshake slotted_wall}"
problems="${PROBLEMS-cubicles Easy}"
twisty="${TWISTY:-3}"
baselines="${BASELINES:-1}"
benchmark="$build/planners/meshgap_benchmark"
[ -x "$benchmark" ] || { echo "error: $benchmark: not built" >&2; exit 1; }

cfg_of() {
    if [ -f "$here/../maps/$1/$1.cfg" ]; then echo "$here/../maps/$1/$1.cfg"; else echo "$data/$1.cfg"; fi
}
# bench DIR PROBLEM TIME RUNS ARGS...
bench() {
    local dir="$1" problem="$2" time="$3" n="$4"
    shift 4
    mkdir -p "$dir"
    nice "$benchmark" --cfg "$(cfg_of "$problem")" --checker certified-cmv --runs "$n" --time "$time" \
        --seed "$seed" --no-simplify --out "$dir" "$@" >&2
}

started=$SECONDS
for map in $maps; do
    bench "$out/length.raw" "$map" "${TIME_MAPS:-10}" "$runs" --planner rrtconnect+opt
done
for problem in $problems; do
    bench "$out/length.raw" "$problem" "${TIME_PROBLEMS:-5}" "$runs" --planner rrtconnect+opt
    if [ "$baselines" = 1 ]; then
        bench "$out/length.raw" "$problem" "${TIME_PROBLEMS:-5}" "$runs" --planner rrtconnect
        bench "$out/max_min_clearance.raw" "$problem" "${TIME_PROBLEMS:-5}" "$runs" --planner rrtstar \
            --objective max_min_clearance
    fi
done
if [ "$twisty" != 0 ]; then
    bench "$out/length.raw" Twistycool "${TIME_TWISTY:-60}" "$twisty" --planner rrtconnect+opt
    if [ "$baselines" = 1 ]; then
        mkdir -p "$out/length.simplified"
        nice "$benchmark" --cfg "$(cfg_of Twistycool)" --checker certified-cmv --runs "$twisty" \
            --time "${TIME_TWISTY:-60}" --seed "$seed" --out "$out/length.simplified" --planner rrtconnect >&2
    fi
fi
echo "wall time: $((SECONDS - started)) s (RUNS=$runs SEED=$seed)" >&2
/usr/bin/python3 "$here/clearance_summary.py" clearance "$out"/*/*.log
