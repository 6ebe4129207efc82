#!/usr/bin/env bash
# Regenerates the benchmark tables of bench/*.md that one command each produces, in place, between their
# `<!-- refresh:NAME -->` ... `<!-- /refresh:NAME -->` markers, each stamped with the commit (`dirty` if the tree has
# uncommitted changes), the date, the machine's load and the command. Builds only the bench targets it runs
# (`cmake --build BUILD --target ...`). The other tables of bench/ are measurements by hand, each with its commit
# (bench/README.md lists both kinds). Last, bench/README.md's list of the commits each page names is rewritten from
# the pages (refresh_tables.py commits).
#
#   bench/refresh.sh [--quick] [--build DIR] [--only NAME[,NAME...]] [--no-build]
#   bench/refresh.sh --list       the blocks: NAME PAGE
#   bench/refresh.sh --dry-run    every block written from made-up output into copies of the pages, then checked
#                                 (no build, no benchmark run: what the ctest entry runs)
#
# --quick: small counts, about half an hour in all on 2 cores; without it the counts of the by-hand tables (three
# hours or so: the planning, samplers', optimiser and MotionBenchMaker blocks take most of it).
# The shared data (../shared/data) is optional: without it the query table runs on maps/ alone and the load table on
# the test meshes, and the blocks that need its robots, MotionBenchMaker's problems or OMPL.app's cubicles (the Python
# blocks) are left out, as is the Dask block where /usr/bin/python3 has no `distributed`.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=build quick=0 only="" dry=0 list=0 nobuild=0
while [ $# -gt 0 ]; do
    case "$1" in
        --quick) quick=1 ;;
        --build) build=${2:?--build needs a folder}; shift ;;
        --only) only=${2:?--only needs block names}; shift ;;
        --no-build) nobuild=1 ;;
        --dry-run) dry=1 ;;
        --list) list=1 ;;
        -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "bench/refresh.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
    shift
done
shared=${MESHGAP_SHARED_DATA_DIR:-$root/../shared/data}
fanuc=$shared/robots/moveit_resources_fanuc_description/meshes/collision
B=$build/bench

# name, page, target, command (full), command (quick), joined by the unit separator (a command may hold a pipe).
# Each command is run from the repository's root.
sep=$'\x1f'
blocks=()
add() { blocks+=("$1$sep$2$sep$3$sep$4$sep$5"); }
data="" few=Easy,Twistycool,cubicles,hand_bowl,twisted
[ -d "$shared/omplapp" ] || { data="--data ''"; few=hand_bowl,slotted_wall,twisted; }
add queries bench/queries.md meshgap_bench_queries \
    "$B/meshgap_bench_queries $data --states 1000 --random 1000 --skip fast,enumeration" \
    "$B/meshgap_bench_queries $data --problems $few --states 500 --random 500 --skip fast,enumeration"
# The motion validation test's summary line as a table (the test fails, and the block with it, if a certified motion
# collides); no quick form.
mv="$build/tests/meshgap_tests --gtest_filter='ClearanceMotionValidator.*' 2>/dev/null"
add motion_validation bench/planning.md meshgap_tests "$mv | python3 bench/motion_validation_table.py" \
    "$mv | python3 bench/motion_validation_table.py"
add primitive_distance bench/primitives.md meshgap_bench_primitive_distance \
    "$B/meshgap_bench_primitive_distance --poses 10000 --seed 1" \
    "$B/meshgap_bench_primitive_distance --poses 2000 --seed 1"
if [ -d "$fanuc" ]; then
    add build bench/scaling.md meshgap_bench_build \
        "python3 bench/build_inputs.py >/dev/null && $B/meshgap_bench_build --repeat 7 $fanuc/*.stl /tmp/meshgap_build_inputs/*.obj" \
        "$B/meshgap_bench_build --repeat 5 $fanuc/*.stl"
else
    add build bench/scaling.md meshgap_bench_build \
        "$B/meshgap_bench_build --repeat 7 tests/resources/cube.obj tests/resources/two_parts.obj" \
        "$B/meshgap_bench_build --repeat 3 tests/resources/cube.obj tests/resources/two_parts.obj"
fi
add triangle_distance bench/primitives.md meshgap_bench_triangle_distance \
    "$B/meshgap_bench_triangle_distance --repeats 21 | grep -v '^(checksum'" \
    "$B/meshgap_bench_triangle_distance --repeats 5 | grep -v '^(checksum'"
if [ -d "$shared/omplapp" ]; then
    add enumeration bench/paper.md meshgap_bench_enumeration \
        "$B/meshgap_bench_enumeration --data $shared/omplapp --repeats 31" \
        "$B/meshgap_bench_enumeration --data $shared/omplapp --repeats 5"
fi
if [ -d "$fanuc" ]; then
    add robot_queries bench/robots.md meshgap_bench_robot_queries \
        "$B/meshgap_bench_robot_queries --paths 10 --repeat 2" "$B/meshgap_bench_robot_queries --paths 2 --repeat 1"
    # The field bench: fanuc links and two generated CAD-like meshes, four streams each.
    cad=/tmp/meshgap_cad_meshes
    q="$B/meshgap_bench_queries --clock thread-cpu --load-repeats 1 STATES"
    field="python3 bench/cad_like_meshes.py $cad >/dev/null"
    field="$field && $q --robot $fanuc/link_6.stl --world $fanuc/base_link.stl"
    field="$field && $q --robot $fanuc/link_1.stl --world $fanuc/link_2.stl"
    field="$field && $q --robot $fanuc/link_4.stl --world $fanuc/base_link.stl,$fanuc/link_1.stl,$fanuc/link_2.stl"
    field="$field,$fanuc/link_3.stl,$fanuc/link_5.stl,$fanuc/link_6.stl"
    field="$field && $q --robot $cad/cad_gripper.stl --world $cad/cad_assembly.stl"
    field="$field && $q --robot $fanuc/link_4.stl --world $cad/cad_assembly.stl"
    add field bench/queries.md meshgap_bench_queries \
        "${field//STATES/--states 600 --random 600}" "${field//STATES/--states 100 --random 100}"
fi
ur5=$shared/mbm/ur5/meshes
if [ -d "$fanuc" ] && [ -d "$ur5" ]; then
    # coal's and trueform's protocols on two pairs each: one table, a row per run (the header kept once).
    pp="$B/meshgap_bench_pair_protocols"
    runs="$pp --protocol coal --robot $fanuc/link_1.stl --world $fanuc/link_2.stl POSES_COAL"
    runs="$runs && $pp --protocol coal --robot $ur5/ur5/collision/forearm.stl --world $ur5/ur5/collision/upperarm.stl"
    runs="$runs POSES_COAL && $pp --protocol trueform --mesh $fanuc/link_2.stl POSES_TF"
    runs="$runs && $pp --protocol trueform --mesh $ur5/robotiq/robotiq_85_base_link_fine.STL POSES_TF"
    full=${runs//POSES_COAL/}; full=${full//POSES_TF/}
    short=${runs//POSES_COAL/--poses 2000}; short=${short//POSES_TF/--poses 300}
    add pair_protocols bench/queries.md meshgap_bench_pair_protocols \
        "{ $full; } | grep '^|' | awk '!seen[\$0]++'" "{ $short; } | grep '^|' | awk '!seen[\$0]++'"
fi
if [ -f "$shared/mbm/ur5/problems.tar.bz2" ]; then
    add moveit_problems bench/motionbenchmaker.md meshgap_bench_moveit_problems \
        "$B/meshgap_bench_moveit_problems --data $shared/mbm/ur5 --quiet" \
        "$B/meshgap_bench_moveit_problems --data $shared/mbm/ur5 --quiet --limit 10"
    # The suite's own tables: every scenario's row per checker, then certified over FCL + discrete per scenario.
    suite="python3 python/meshgap/suite.py $shared/mbm/ur5/problems.tar.bz2 --checkers certified,discrete,fcl"
    suite="$suite --time 10 --runs 1 --seed 1 --executable $B/../planners/meshgap_benchmark --database ''"
    suite="$suite --out \$(mktemp -d) 2>/dev/null"
    add mbm_suite bench/motionbenchmaker.md meshgap_benchmark "$suite" "$suite --limit 2"
fi
py="PYTHONPATH=$build/python /usr/bin/python3"
if [ -f "$shared/omplapp/cubicles.cfg" ]; then
    # The Python module's batch on cubicles' path against the C++ loop, and threads against processes.
    add python_batch bench/python.md "meshgap_python meshgap_bench_path_loop" \
        "$py bench/python_batch.py --build $build --data $shared/omplapp --rounds 9 --million --markdown" \
        "$py bench/python_batch.py --build $build --data $shared/omplapp --rounds 3 --million --markdown"
    pts="$py bench/python_thread_scaling.py --markdown --cfg $shared/omplapp/cubicles.cfg"
    add python_thread_scaling bench/scaling.md meshgap_python \
        "{ $pts --reps 5 --states 20000 --repeat 20 && $pts --reps 5 --states 4000 --repeat 2 --stream random; } | awk '!seen[\$0]++'" \
        "{ $pts --reps 3 --states 5000 --repeat 10 && $pts --reps 3 --states 1000 --repeat 2 --stream random; } | awk '!seen[\$0]++'"
    if /usr/bin/python3 -c 'import distributed' 2>/dev/null; then
        dask="PYTHONPATH=$build/python nice -n 5 /usr/bin/python3 bench/dask_throughput.py"
        dask="$dask --problems maps/hand_bowl/hand_bowl.cfg,$shared/omplapp/cubicles.cfg"
        add dask bench/python.md meshgap_python "$dask" "$dask --poses 4000 --rounds 1 --chunks 100,1000"
    fi
fi
fve="PYTHONPATH=$build/python /usr/bin/python3 bench/fast_vs_exact.py --markdown maps/{hand_bowl,twisted,slotted_wall}/*.cfg"
[ -d "$shared/omplapp" ] && fve="$fve $shared/omplapp/{cubicles,Twistycool,Easy}.cfg"
add fast_vs_exact bench/queries.md meshgap_python "$fve --poses 1000 --rounds 5" "$fve --poses 200 --rounds 1"
add mesh_distances bench/mesh_distances.md meshgap_bench_mesh_distances \
    "$B/meshgap_bench_mesh_distances" "$B/meshgap_bench_mesh_distances --dense 13 26 --on-demand 13 26 52"
# Robot planning over seeds, each path checked by FCL pair by pair and its motions certified anew (the maps' robots;
# the optimiser's also the fanuc when ../shared/data/robots holds it).
add robot_plan_seeds bench/robots.md "meshgap_plan meshgap_bench_robot_path_check" \
    "bench/robot_plan_seeds.sh $build 10 20 1e-4" "bench/robot_plan_seeds.sh $build 3 10 1e-3"
# bench/run_planning_benchmark.sh as a block: NAME PAGE, the runs in full and in --quick, then its settings.
planning() {
    local run="bench/run_planning_benchmark.sh $build \$(mktemp -d)"
    add "$1" "$2" meshgap_benchmark "RUNS=$3 $5 $run" "RUNS=$4 $5 $run"
}
planning robot_checkers bench/robots.md 10 3 "TIME=10 CHECKERS=certified,certified-search,discrete,fcl PROBLEMS=arm_fixture"
add robot_optimize_seeds bench/robots.md "meshgap_plan meshgap_bench_robot_path_check" \
    "bench/robot_optimize_seeds.sh $build 10 60 1e-4" "bench/robot_optimize_seeds.sh $build 2 10 1e-3"
# The control problems: every control planner, the certified checker (about 12 minutes; BugTrap_dcar only with the
# shared data).
add control_problems bench/planning.md meshgap_benchmark \
    "bench/control_table.sh $build 3 10 20" "bench/control_table.sh $build 1 2 2"
if [ -d "$shared/omplapp" ]; then
    # Planning: RRTConnect with each checker; the samplers on slotted_wall; RRT* against RRTConnect on the maps; the
    # clearance optimiser. Each run's .log files go to a folder of its own under /tmp.
    each="CHECKERS=fcl,certified-cmv,certified,fast PROBLEMS='cubicles Easy battery_fixture'"
    planning rrtconnect_checkers bench/planning.md 10 3 "TIME=10 $each"
    planning rrtstar_checkers bench/planning.md 3 1 "TIME=5 PLANNERS=rrtstar ARGS='--objective max_min_clearance' $each"
    # A table script as a block of planning.md: NAME SCRIPT, its settings in full and in --quick.
    table() {
        local run="bench/$2 $build \$(mktemp -d)"
        add "$1" bench/planning.md meshgap_benchmark "$3 $run" "$4 $run"
    }
    table sampler_slotted_wall sampler_table.sh "PLANNER=biest" "PLANNER=biest RUNS=1 TIME=5"
    # RRTConnect on every problem and map within each cfg's limit (Abstract and bugtrap: 300 s a run), every path
    # checked by FCL; the samplers on Abstract (BKPIECE) and on bugtrap (PRM, stopped at its first exact solution).
    table solve_problems clearance_table.sh "PART=solve RUNS=5 JOBS=2" "PART=solve RUNS=2 JOBS=2 SOLVE_TIME=30"
    table sampler_abstract sampler_table.sh "PLANNER=bkpiece PROBLEMS=Abstract RUNS=3 TIME=300 SHARDS=2" \
        "PLANNER=bkpiece PROBLEMS=Abstract RUNS=1 TIME=60 SHARDS=1"
    table sampler_bugtrap sampler_table.sh "FIRST=1 PLANNER=prm PROBLEMS=bugtrap RUNS=3 TIME=300 SHARDS=2" \
        "FIRST=1 PLANNER=prm PROBLEMS=bugtrap SAMPLERS=workspace_medial,uniform RUNS=2 TIME=90 SHARDS=2"
    table clearance_maps clearance_table.sh "PART=clearance" "PART=clearance RUNS=2 TIME=5"
    if command -v valgrind > /dev/null; then
        add instruction_counts bench/queries.md meshgap_bench_queries \
            "bench/instruction_counts.sh $build" "bench/instruction_counts.sh $build Easy"
    fi
    add warm_start_counts bench/queries.md meshgap_plan \
        "bench/warm_start_counts.sh $build 5" "bench/warm_start_counts.sh $build 1"
    add optimizer bench/planning.md meshgap_benchmark \
        "bench/optimizer_table.sh $build \$(mktemp -d)" \
        "RUNS=2 TIME_MAPS=5 TIME_PROBLEMS=3 TWISTY=1 TIME_TWISTY=20 bench/optimizer_table.sh $build \$(mktemp -d)"
fi
add thread_scaling bench/scaling.md meshgap_bench_stress \
    "bench/thread_scaling.sh --markdown $build 2 400000 5" "bench/thread_scaling.sh --markdown $build 2 100000 3"
add scaling bench/scaling.md meshgap_bench_scaling \
    "$B/meshgap_bench_scaling" \
    "$B/meshgap_bench_scaling --max 16384 --poses 50 --fast-on-demand 3"
add scaling_twisted bench/scaling.md meshgap_bench_scaling \
    "$B/meshgap_bench_scaling --map maps/twisted --max 16384 --poses 50 --fast-on-demand 10" \
    "$B/meshgap_bench_scaling --map maps/twisted --max 4096 --poses 20 --fast-on-demand 3"
add stress bench/scaling.md meshgap_bench_stress \
    "$B/meshgap_bench_stress --queries 1000000 --threads 2" \
    "$B/meshgap_bench_stress --queries 200000 --threads 2"

chosen=()
for b in "${blocks[@]}"; do
    name=${b%%"$sep"*}
    if [ -z "$only" ] || [[ ",$only," == *",$name,"* ]]; then
        chosen+=("$b")
    fi
done
if [ -n "$only" ]; then
    for n in ${only//,/ }; do
        printf '%s\n' "${chosen[@]}" | grep -q "^$n$sep" || { echo "bench/refresh.sh: no block '$n' (see --list)" >&2; exit 2; }
    done
fi

if [ $list = 1 ]; then
    for b in "${chosen[@]}"; do IFS=$sep read -r name page _ <<< "$b"; echo "$name $page"; done
    exit 0
fi

pages=$(for b in "${chosen[@]}"; do IFS=$sep read -r _ page _ <<< "$b"; echo "$page"; done | sort -u)
expect=$(for b in "${chosen[@]}"; do IFS=$sep read -r name page _ <<< "$b"; echo "$page:$name"; done)

if [ $dry = 1 ]; then
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    for p in $pages; do cp "$p" "$tmp/$(basename "$p")"; done
    # shellcheck disable=SC2086
    python3 bench/refresh_tables.py check $(for p in $pages; do echo "$tmp/$(basename "$p")"; done) --expect $expect
    for b in "${chosen[@]}"; do
        IFS=$sep read -r name page target full short <<< "$b"
        cmd=$([ $quick = 1 ] && echo "$short" || echo "$full")
        printf 'Rows of %s (made up):\n\n| a | b |\n|---|---|\n| 1 | 2 |\n' "$name" > "$tmp/$name.out"
        python3 bench/refresh_tables.py write "$tmp/$(basename "$page")" "$name" "$tmp/$name.out" \
            --stamp "Dry run." --command "$cmd"
        grep -q "^Rows of $name (made up):\$" "$tmp/$(basename "$page")" || { echo "refresh:$name not written" >&2; exit 1; }
    done
    # shellcheck disable=SC2086
    python3 bench/refresh_tables.py check $(for p in $pages; do echo "$tmp/$(basename "$p")"; done) --expect $expect
    echo "dry run: ${#chosen[@]} block(s) written and checked"
    exit 0
fi

if [ $nobuild = 0 ]; then
    targets=$(for b in "${chosen[@]}"; do IFS=$sep read -r _ _ target _ <<< "$b"; echo "$target"; done | sort -u)
    # shellcheck disable=SC2086
    cmake --build "$build" -j"${MESHGAP_JOBS:-2}" --target $targets
fi
# shellcheck disable=SC2086
python3 bench/refresh_tables.py check $pages --expect $expect
commit=$(git rev-parse --short HEAD)
# Dirty: a change to anything but the pages this script writes (an earlier block's tables are not the code measured).
if [ -n "$(git status --porcelain --untracked-files=no -- . ':(exclude)bench/*.md')" ]; then commit="$commit dirty"; fi
mode=$([ $quick = 1 ] && echo " --quick" || echo "")
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for b in "${chosen[@]}"; do
    IFS=$sep read -r name page target full short <<< "$b"
    cmd=$([ $quick = 1 ] && echo "$short" || echo "$full")
    before=$(cut -d' ' -f1 /proc/loadavg)
    start=$(date +%s)
    echo "== $name: $cmd" >&2
    bash -o pipefail -c "$cmd" > "$out"  # a benchmark that fails inside a pipe fails the block
    sed -i "s|$root/||g" "$out"  # file names as the commands spell them, from the repository's root
    after=$(cut -d' ' -f1 /proc/loadavg)
    stamp="Measured by \`bench/refresh.sh$mode\` at $commit, $(date -u '+%Y-%m-%d %H:%M') UTC, in $(( $(date +%s) - start )) s;"
    stamp="$stamp load $before at the start, $after at the end (1-minute average, $(nproc) cores)."
    python3 bench/refresh_tables.py write "$page" "$name" "$out" --stamp "$stamp" --command "${cmd//$root\//}"
done
# The index's list of the commits each page names, the stamps just written included.
python3 bench/refresh_tables.py commits bench/README.md $(ls bench/*.md | grep -v '^bench/README.md$')
