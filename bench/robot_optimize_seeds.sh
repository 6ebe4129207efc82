#!/bin/sh
# meshgap_plan --optimize clearance on robot problems, seeds 1..N each: the planner's path (RRTConnect, every motion
# certified) and the optimised one, each path's exact minimum clearance over the dense path with the pair that limits
# it (the summary's "opt before" and "opt after"), and the optimised path checked by FCL pair by pair at densely
# interpolated states (meshgap_bench_robot_path_check), each of its motions asked of the certified RobotMotionValidator
# anew. One row per run, then a total per problem. Extra meshgap_plan options in PLAN_ARGS.
#
#   bench/robot_optimize_seeds.sh [BUILD (build)] [SEEDS (10)] [OPTIMIZE_TIME (30)] [STEP (1e-4)] CFG...
#   (default CFGs: maps/arm_fixture and, when ../shared/data/robots holds it, the fanuc carrying arm_fixture's
#   payload through arm_fixture's wall moved to its forearm's height, as tests/robot/CertifiedAnswerTest.cpp builds it)
set -u
build=${1:-build}; seeds=${2:-10}; optimize=${3:-30}; step=${4:-1e-4}
shift 4 2>/dev/null || shift $#
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
if [ $# -eq 0 ]; then
    set -- "$root/maps/arm_fixture/arm_fixture.cfg"
    robots=${MESHGAP_SHARED_DATA_DIR:-$root/../shared/data}/robots
    if [ -f "$robots/moveit_resources_fanuc_description/urdf/fanuc.urdf" ]; then
        awk '/^v /{printf "v %.17g %.17g %.17g\n", $2 - 0.12, $3, $4 + 0.85; next} {print}' \
            "$root/maps/arm_fixture/arm_fixture_world.obj" > "$out/fixture.obj"
        cat > "$out/fanuc_payload.cfg" <<EOF
[problem]
name = fanuc_payload
robot.urdf = $robots/moveit_resources_fanuc_description/urdf/fanuc.urdf
robot.srdf = $robots/moveit_resources_fanuc_moveit_config/config/fanuc.srdf
robot.package_path = $robots
world = fixture.obj
attach = $root/maps/arm_fixture/arm_fixture_payload.obj link_6 0.1 0 0 0 0 0 1
start.joints = 0 -0.9 -0.9 0 -1.5 0
goal.joints = 0 0 0 0 0 0
EOF
        set -- "$@" "$out/fanuc_payload.cfg"
    fi
fi
echo "| problem | seed | before (dense exact) | pair before | after (dense exact) | pair after | length | optimiser (s) | FCL colliding / checked | motions certified |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for cfg in "$@"; do
    name=$(basename "$cfg" .cfg)
    raised=0; free=0; runs=0
    for seed in $(seq 1 "$seeds"); do
        path="$out/$name.$seed.path"
        summary=$("$build/planners/meshgap_plan" --cfg "$cfg" --seed "$seed" --time 60 -q --optimize clearance \
                  --optimize-time "$optimize" --out "$path" ${PLAN_ARGS:-} 2>/dev/null)
        before=$(echo "$summary" | awk '/^opt before/ {print $3}')
        after=$(echo "$summary" | awk '/^opt after/ {print $3}')
        pb=$(echo "$summary" | sed -n "s/^opt before.*; \(.*\))$/\1/p")
        pa=$(echo "$summary" | sed -n "s/^opt after.*; \(.*\))$/\1/p")
        length=$(echo "$summary" | awk '/^opt length/ {print $3 " -> " $5}')
        secs=$(echo "$summary" | sed -n 's/^optimizer *clearance, \([0-9.e+-]*\) s.*/\1/p')
        checked="-"; colliding="-"; certified="-"
        if [ -n "$after" ]; then
            runs=$((runs + 1))
            [ "$(awk -v a="$after" -v b="$before" 'BEGIN { print (a > b) }')" = 1 ] && raised=$((raised + 1))
            check=$("$build/bench/meshgap_bench_robot_path_check" --cfg "$cfg" --path "$path" --step "$step")
            checked=$(echo "$check" | sed -n 's/.*: \([0-9]*\) states checked.*/\1/p')
            colliding=$(echo "$check" | sed -n 's/.*), \([0-9]*\) colliding by FCL.*/\1/p')
            certified=$(echo "$check" | sed -n 's/.*, \([0-9]* of [0-9]*\) motions certified.*/\1/p')
            [ "$colliding" = 0 ] && free=$((free + 1))
        fi
        echo "| $name | $seed | $before | $pb | $after | $pa | $length | $secs | $colliding / $checked | $certified |"
    done
    echo "| $name | total | | | raised in $raised / $runs | | | | $free / $runs paths free by FCL | |"
done
rm -rf "$out"
