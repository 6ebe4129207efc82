#!/usr/bin/env bash
# meshgap_plan --optimize clearance with the default motion settings (RRTConnect with OMPL's sampled motion
# validator, --time 10, --optimize-time 5): for every problem and seed, what the repair of motions the certified
# validator refuses did, the minimum clearance before (the repaired path) and after (the optimiser's measure), and the
# written path checked by meshgap_bench_path_check: motions certified, densely FCL-free, least FCL distance.
#
#   bench/optimize_defaults.sh [BUILD_DIR] [OUT_DIR] [EXTRA.cfg ...]
#
# The problems: the maps, the OMPL.app problems (skipped when absent) and the planar barriers of planar_barriers.py
# (written to OUT_DIR/barriers), then any EXTRA cfg. "solved" is meshgap_plan's (approximate: the planner found no
# path within --time; the optimiser still ran on its path). Exit status 2 with an exact solution: --optimize failed.
#
# Settings (environment): SEEDS (1 2 3), PLANAR_SEEDS (seeds of planar problems, 1..10), PROBLEMS (the maps and the
# OMPL.app problems), STEPS (states checked per motion, 50), TIME (10), OPTIMIZE_TIME (5). Markdown rows on stdout.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-optimize-defaults}"
shift $(( $# > 2 ? 2 : $# ))
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
seeds="${SEEDS:-1 2 3}"
planar_seeds="${PLANAR_SEEDS:-1 2 3 4 5 6 7 8 9 10}"
problems="${PROBLEMS-battery_fixture hand_bowl handshake slotted_wall twisted Abstract Easy Twistycool bugtrap cubicles cubicles_opt barriers}"
steps="${STEPS:-50}"
plan="$build/planners/meshgap_plan"
check="$build/bench/meshgap_bench_path_check"
for exe in "$plan" "$check"; do [ -x "$exe" ] || { echo "error: $exe: not built" >&2; exit 1; }; done
mkdir -p "$out"
/usr/bin/python3 "$here/planar_barriers.py" "$out/barriers"

cfg_of() {
    if [ -f "$1" ]; then echo "$1"
    elif [ "$1" = barriers ]; then echo "$out/barriers/barriers.cfg"
    elif [ -f "$here/../maps/$1/$1.cfg" ]; then echo "$here/../maps/$1/$1.cfg"
    else echo "$data/$1.cfg"; fi
}
field() { sed -n "s/^$1  *//p" "$2" | head -1; }

echo "| problem | seed | solved | exit | repaired (bisected/replanned), states inserted | min clearance before -> after | certified motions | FCL-free | FCL min |"
echo "|---|---|---|---|---|---|---|---|---|"
for problem in $problems "$@"; do
    cfg="$(cfg_of "$problem")"
    [ -f "$cfg" ] || { echo "skipped $problem: no $cfg" >&2; continue; }
    name="$(basename "$cfg" .cfg)"
    list="$seeds"
    grep -q '^start\.z' "$cfg" || list="$planar_seeds"
    for seed in $list; do
        stem="$out/${name}_$seed"
        status=0
        nice "$plan" --cfg "$cfg" --seed "$seed" --quiet --time "${TIME:-10}" --optimize clearance \
            --optimize-time "${OPTIMIZE_TIME:-5}" --out "$stem.path" --summary "$stem.txt" >/dev/null 2>"$stem.err" || status=$?
        if [ ! -f "$stem.path" ]; then
            echo "| $name | $seed | no | $status | $(head -c 200 "$stem.err" | tr '\n' ' ') | | | | |"
            continue
        fi
        repair="$(field "opt repair" "$stem.txt" | sed -E 's/ motions refused by the certified validator repaired \(([0-9]+) by bisection, ([0-9]+) replanned\), ([0-9]+) states inserted.*/ (\1\/\2), \3/; s/^none.*/0/')"
        clearance="$(field "opt clearance" "$stem.txt" | sed 's/ (the.*//')"
        [ -n "$clearance" ] || clearance="$(field optimizer "$stem.txt")"
        read -r _ _ _ motions _ certified _ fclfree _ fclmin _ _ _ _ < <(nice "$check" --cfg "$cfg" --path "$stem.path" --steps "$steps")
        solved="$(field solved "$stem.txt" | sed 's/yes (exact)/exact/')"
        echo "| $name | $seed | $solved | $status | $repair | $clearance | $certified/$motions | $fclfree | $fclmin |"
    done
done
