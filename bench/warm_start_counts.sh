#!/usr/bin/env bash
# How a planner's certified queries use their warm starts: meshgap_plan on OMPL.app's cubicles and Easy with RRT*
# (max-min clearance objective) and with RRTConnect and RRT (the clearance motion validator), TIME s each, seed 1;
# the summary's "warm starts" line (queries that carried a recent certificate, wrote one, or were answered cold) and
# its count of clearance queries, as a table.
#
#   bench/warm_start_counts.sh [BUILD (build)] [TIME (5)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
time="${2:-5}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
echo "meshgap_plan --time $time --seed 1 on each problem; the summary's warm starts (certified queries):"
echo
echo "| problem | planner | clearance queries | carried | written | cold |"
echo "|---|---|---:|---:|---:|---:|"
for problem in cubicles Easy; do
    for run in "rrtstar --objective clearance" "rrtconnect --motion clearance" "rrt --motion clearance"; do
        read -r -a args <<< "$run"
        # (meshgap_plan exits 1 when it finds no exact solution in time: its summary is still printed.)
        summary=$("$build/planners/meshgap_plan" --cfg "$data/$problem.cfg" --planner "${args[@]}" --time "$time" \
                  --seed 1 2>/dev/null || true)
        queries=$(echo "$summary" | sed -n 's/^clearance calls *\([0-9]*\)$/\1/p')
        counts=$(echo "$summary" | sed -n 's/^warm starts *\([0-9]*\) carried, \([0-9]*\) written, \([0-9]*\) cold.*/\1 | \2 | \3/p')
        [ -n "$counts" ] || { echo "bench/warm_start_counts.sh: no warm starts line for $problem, ${args[0]}" >&2; exit 1; }
        name=${args[0]/rrtstar/RRT\\*}; name=${name/rrtconnect/RRTConnect}; name=${name/rrt/RRT}
        printf '| %s | %s `%s` | %s | %s |\n' "$problem" "$name" "${args[*]:1}" "${queries:--}" "$counts"
    done
done
