#!/usr/bin/env bash
# The two planning tables of bench/planning.md, from meshgap_benchmark runs (OMPL .log files) summarised by
# clearance_summary.py:
#
#   solve:     RRTConnect on every OMPL.app problem in ../shared/data/omplapp and every map in maps/, RUNS runs each
#              within the cfg's own time_limit, SOLVE_CHECKERS (default certified): runs, exact solutions,
#              whether FCL finds every state of each (simplified, densely interpolated) path collision-free, times.
#   clearance: on each map, RRT* with max_min_clearance and RRTConnect, TIME s, RUNS seeds, meshgap-certified-cmv
#              (RRTConnect also with meshgap-certified and its path simplified): median path min clearance by FCL
#              over the densely interpolated path, median length.
#
#   bench/clearance_table.sh [BUILD_DIR] [OUT_DIR]
#   PART=clearance JOBS=2 bench/clearance_table.sh build clearance-results     # only the clearance table
#
# Settings (environment): PART (solve, clearance or all; default all), RUNS (10), TIME (10, the clearance runs),
# SEED (1), JOBS (1 or 2: with 2, every benchmark runs as two shards at once, shard 2 seeded SEED + 1),
# MAPS, PROBLEMS, SOLVE_CHECKERS, SOLVE_TIME (default: each cfg's time_limit), RRTSTAR_PARAMS (RRT*'s OMPL
# parameters, space-separated, default none: OMPL's own; RRTSTAR_PARAMS=use_k_nearest=0 takes the neighbours within
# RRT*'s range instead of OMPL's k nearest, whose k in SE(3), 1.1 * 2^7 e (1 + 1/6) log n = 446 log n, makes every
# state of a tree of a few thousand a neighbour of each new one). A problem's old .log files in OUT_DIR are removed
# before it runs; the tables cover every .log in OUT_DIR. The benchmarks' own output goes to stderr, so stdout holds
# the tables alone. The .log files load into Planner Arena:
# ompl_benchmark_statistics OUT_DIR/*/*.log -d results.db
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-clearance-results}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
maps="$here/../maps"
part="${PART:-all}"
runs="${RUNS:-10}"
time="${TIME:-10}"
seed="${SEED:-1}"
jobs="${JOBS:-1}"
map_names="${MAPS:-battery_fixture hand_bowl handshake slotted_wall}"
problems="${PROBLEMS:-Abstract bugtrap cubicles cubicles_opt Easy Twistycool}"
solve_checkers="${SOLVE_CHECKERS:-certified}"
rrtstar_params=()
for p in ${RRTSTAR_PARAMS:-}; do rrtstar_params+=(--param "rrtstar.$p"); done
benchmark="$build/planners/meshgap_benchmark"
if [ ! -x "$benchmark" ]; then
    echo "error: $benchmark: not built (cmake --build BUILD --target meshgap_benchmark)" >&2
    exit 1
fi
case "$jobs" in 1|2) ;; *) echo "error: JOBS=$jobs: 1 or 2" >&2; exit 1 ;; esac

# bench DIR ARGS...: one meshgap_benchmark into DIR, as JOBS shards at once.
bench() {
    local dir="$1"
    shift
    mkdir -p "$dir"
    if [ "$jobs" = 1 ]; then
        nice "$benchmark" "$@" --seed "$seed" --out "$dir" >&2
    else
        nice "$benchmark" "$@" --seed "$seed" --out "$dir" --shard 1/2 >&2 &
        local first=$!
        nice "$benchmark" "$@" --seed "$seed" --out "$dir" --shard 2/2 >&2
        wait "$first"
    fi
}

cfg_of() {
    if [ -f "$maps/$1/$1.cfg" ]; then echo "$maps/$1/$1.cfg"; else echo "$data/$1.cfg"; fi
}

started=$SECONDS
if [ "$part" = all ] || [ "$part" = solve ]; then
    for problem in $problems $map_names; do
        cfg="$(cfg_of "$problem")"
        [ -f "$cfg" ] || { echo "error: $cfg: not found (set MESHGAP_SHARED_DATA_DIR)" >&2; exit 1; }
        rm -f "$out/solve/$problem".*.log
        bench "$out/solve" --cfg "$cfg" --planner rrtconnect --checker "$solve_checkers" --runs "$runs" \
            ${SOLVE_TIME:+--time "$SOLVE_TIME"}
    done
fi
if [ "$part" = all ] || [ "$part" = clearance ]; then
    for map in $map_names; do
        cfg="$(cfg_of "$map")"
        rm -f "$out"/clearance/*/"$map".*.log
        # The planners' own paths (meshgap_plan does not simplify either); RRTConnect once more, simplified as
        # OMPL's Benchmark does by default, which pulls the path tight against the obstacles.
        bench "$out/clearance/max_min_clearance.raw" --cfg "$cfg" --planner rrtstar --objective max_min_clearance \
            --checker certified-cmv --runs "$runs" --time "$time" --no-simplify "${rrtstar_params[@]}"
        bench "$out/clearance/length.raw" --cfg "$cfg" --planner rrtconnect --objective length \
            --checker certified-cmv,certified --runs "$runs" --time "$time" --no-simplify
        bench "$out/clearance/length.simplified" --cfg "$cfg" --planner rrtconnect --objective length \
            --checker certified --runs "$runs" --time "$time"
    done
fi
echo "wall time: $((SECONDS - started)) s (PART=$part RUNS=$runs TIME=$time SEED=$seed JOBS=$jobs" \
    "RRTSTAR_PARAMS=${RRTSTAR_PARAMS:-})" >&2

if [ "$part" = all ] || [ "$part" = solve ]; then
    python3 "$here/clearance_summary.py" solve "$out"/solve/*.log
    echo
fi
if [ "$part" = all ] || [ "$part" = clearance ]; then
    python3 "$here/clearance_summary.py" clearance "$out"/clearance/*/*.log
fi
