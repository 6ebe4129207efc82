#!/bin/sh
# RRTConnect on robot problems, seeds 1..N each (meshgap_plan --seed), every path checked by FCL pair by pair at
# densely interpolated states (meshgap_bench_robot_path_check), and each of its motions asked of the certified
# RobotMotionValidator anew. One row per run, then a total per problem. Extra meshgap_plan options in PLAN_ARGS
# (e.g. PLAN_ARGS="--motion discrete").
#
#   bench/robot_plan_seeds.sh [BUILD (build)] [SEEDS (10)] [TIME (20)] [STEP (1e-4)] CFG...
#   (default CFGs: maps/arm_fixture, its floating-base variant, maps/swap_se3, maps/swap_se2)
set -u
build=${1:-build}; seeds=${2:-10}; time=${3:-20}; step=${4:-1e-4}
shift 4 2>/dev/null || shift $#
root=$(cd "$(dirname "$0")/.." && pwd)
[ $# -gt 0 ] || set -- "$root/maps/arm_fixture/arm_fixture.cfg" "$root/maps/arm_fixture/arm_fixture_floating.cfg" \
                        "$root/maps/swap_se3/swap_se3.cfg" \
                        "$root/maps/swap_se2/swap_se2.cfg"
out=$(mktemp -d)
echo "| problem | seed | solved | planning time (s) | FCL-checked states | FCL colliding | motions certified | min exact clearance |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for cfg in "$@"; do
    name=$(basename "$cfg" .cfg)
    solved=0; free=0; total=0
    for seed in $(seq 1 "$seeds"); do
        path="$out/$name.$seed.path"
        summary=$("$build/planners/meshgap_plan" --cfg "$cfg" --seed "$seed" --time "$time" -q --out "$path" ${PLAN_ARGS:-} 2>/dev/null)
        exact=$(echo "$summary" | awk '/^exact solution/ {print $3}')
        secs=$(echo "$summary" | awk '/^planning time/ {print $3}')
        clearance=$(echo "$summary" | awk '/^min clearance/ {print $3}')
        checked="-"; colliding="-"; certified="-"
        if [ "$exact" = yes ]; then
            solved=$((solved + 1))
            check=$("$build/bench/meshgap_bench_robot_path_check" --cfg "$cfg" --path "$path" --step "$step")
            checked=$(echo "$check" | sed -n 's/.*: \([0-9]*\) states checked.*/\1/p')
            colliding=$(echo "$check" | sed -n 's/.*), \([0-9]*\) colliding by FCL.*/\1/p')
            certified=$(echo "$check" | sed -n 's/.*, \([0-9]* of [0-9]*\) motions certified.*/\1/p')
            [ "$colliding" = 0 ] && free=$((free + 1))
        fi
        total=$(echo "$total + ${secs:-0}" | bc -l)
        echo "| $name | $seed | ${exact:-no} | $secs | $checked | $colliding | $certified | $clearance |"
    done
    echo "| $name | total | $solved / $seeds | mean $(echo "scale=3; $total / $seeds" | bc -l) | | $free paths free by FCL | | |"
done
rm -rf "$out"
