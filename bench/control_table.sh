#!/usr/bin/env bash
# The control problems with every control planner of their [planner] sections and the certified checker: the three
# control maps (maps/car_chicane, blimp_window, quadrotor_window) for TIME s a run, and OMPL.app's BugTrap_dcar (when
# ../shared/data has it) for DCAR_TIME s a run; RUNS runs each, seed 1; then a table per problem
# (bench/planning_summary.py --control; the benchmarks' own output goes to stderr). The .log files go to a new folder
# under /tmp.
#
#   bench/control_table.sh [BUILD (build)] [RUNS (3)] [TIME (10)] [DCAR_TIME (20)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
runs="${2:-3}"
time="${3:-10}"
dcar="${4:-20}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
out="$(mktemp -d /tmp/meshgap_control.XXXXXX)"
for m in car_chicane blimp_window quadrotor_window; do
    "$build/planners/meshgap_benchmark" --cfg "$here/../maps/$m/$m.cfg" --checker certified --runs "$runs" \
        --time "$time" --seed 1 --out "$out" >&2
done
if [ -f "$data/BugTrap_dcar.cfg" ]; then
    "$build/planners/meshgap_benchmark" --cfg "$data/BugTrap_dcar.cfg" --checker certified --runs "$runs" \
        --time "$dcar" --seed 1 --out "$out" >&2
fi
echo "The .log files: $out" >&2
python3 "$here/planning_summary.py" --control "$out"/*.log
