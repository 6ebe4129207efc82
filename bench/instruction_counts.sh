#!/usr/bin/env bash
# Instructions, not time: callgrind over meshgap's Scene::distance only (so the machine's load does not enter), cold on
# 300 path states and warm on 1,000, and over FCL's fcl::distance on the same 1,000 states, on OMPL.app problems and
# on the maps in maps/ (meshgap_bench_queries' own path streams); a table of millions of instructions, the warm
# query's share spent on penetration depth (the colliding states' depth estimate) and warm over FCL; the collision-only
# test (Scene::inCollision) against FCL's collide (test::fclCollide, which calls fcl::collide: that name would match
# the nested fcl::collide<double, solver> too, and a toggle there turns collection off) on the same 1,000 states.
# Each count from a run of its own where toggles could interfere.
# Then, where ../shared/data holds the fanuc's and the UR5's meshes, mesh pairs on 200 random poses
# (meshgap_bench_queries --robot/--world --streams random): the cold certified query, the same without the depth of
# colliding poses, and the collision-only test, each against FCL's call.
#
#   bench/instruction_counts.sh [BUILD (build)] [PROBLEMS (Easy Twistycool cubicles battery_fixture slotted_wall)]
#   PAIRS=0 bench/instruction_counts.sh ...   # without the mesh pairs' table
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
problems="${2:-Easy Twistycool cubicles battery_fixture slotted_wall}"
shared="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}"
data="$shared/omplapp"
command -v valgrind > /dev/null || { echo "bench/instruction_counts.sh: needs valgrind" >&2; exit 1; }
out="$(mktemp -d /tmp/meshgap_callgrind.XXXXXX)"
others="cold-nodepth,warm-nodepth,fast,collision,collision-warm,enumeration,random"
# The inclusive count of the function whose name matches $2 in the callgrind output $1, in millions.
count() {
    callgrind_annotate --inclusive=yes "$1" > "$1.txt" 2>/dev/null
    awk -v pattern="$2" '$0 ~ pattern { gsub(",", "", $1); printf "%.1f", $1 / 1e6; exit }' "$1.txt"
}
declare -A cold warm depth fcl coll fclc
for p in $problems; do
    # A map of this repository's maps/, or an OMPL.app problem.
    source=(--data "$data")
    [ -d "$here/../maps/$p" ] && source=(--maps "$here/../maps")
    q=("$build/bench/meshgap_bench_queries" "${source[@]}" --problems "$p" --random 0)
    echo "== $p" >&2
    valgrind --tool=callgrind --toggle-collect='meshgap::Scene::distance*' --callgrind-out-file="$out/$p.cold" \
        "${q[@]}" --states 300 --skip "warm,$others" > /dev/null 2>&1
    valgrind --tool=callgrind --toggle-collect='meshgap::Scene::distance*' --toggle-collect='*fcl::distance<*' \
        --callgrind-out-file="$out/$p.warm" "${q[@]}" --states 1000 --skip "cold,$others" > /dev/null 2>&1
    valgrind --tool=callgrind --toggle-collect='meshgap::Scene::inCollision*' --callgrind-out-file="$out/$p.coll" \
        "${q[@]}" --states 1000 --skip "cold,warm,${others/collision,/}" > /dev/null 2>&1
    # FCL's collide alone: with another toggle in the same run, some streams lose their counts.
    valgrind --tool=callgrind --toggle-collect='meshgap::test::fclCollide*' --callgrind-out-file="$out/$p.fclc" \
        "${q[@]}" --states 1000 --skip "cold,warm,$others" > /dev/null 2>&1
    cold[$p]=$(count "$out/$p.cold" 'meshgap::Scene::distance\(')
    warm[$p]=$(count "$out/$p.warm" 'meshgap::Scene::distance\(')
    depth[$p]=$(count "$out/$p.warm" 'meshgap::penetrationDepth\(')
    depth[$p]=${depth[$p]:-0.0}  # no colliding state: never called
    fcl[$p]=$(count "$out/$p.warm" 'fcl::distance<')
    coll[$p]=$(count "$out/$p.coll" 'meshgap::Scene::inCollision\(')
    fclc[$p]=$(count "$out/$p.fclc" 'meshgap::test::fclCollide\(')
    [ -n "${cold[$p]}" ] && [ -n "${warm[$p]}" ] && [ -n "${fcl[$p]}" ] && [ -n "${coll[$p]}" ] &&
        [ -n "${fclc[$p]}" ] ||
        { echo "bench/instruction_counts.sh: no count for $p (callgrind outputs in $out)" >&2; exit 1; }
done
echo "Millions of instructions (callgrind; the path stream of meshgap_bench_queries):"
echo
row() { printf '| %s |' "$1"; shift; for v in "$@"; do printf ' %s |' "$v"; done; echo; }
row "" $problems
row "---" $(for p in $problems; do echo -n "---: "; done)
row "cold certified, 300 states" $(for p in $problems; do echo "${cold[$p]}"; done)
row "warm certified, 1,000 states" $(for p in $problems; do echo "${warm[$p]}"; done)
row "of which penetration depth" $(for p in $problems; do echo "${depth[$p]}"; done)
row "FCL distance, 1,000 states" $(for p in $problems; do echo "${fcl[$p]}"; done)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f\n", a / b }'; }
row "warm / FCL" $(for p in $problems; do ratio "${warm[$p]}" "${fcl[$p]}"; done)
row "collision-only, 1,000 states" $(for p in $problems; do echo "${coll[$p]}"; done)
row "FCL collide, 1,000 states" $(for p in $problems; do echo "${fclc[$p]}"; done)
row "collision-only / FCL collide" $(for p in $problems; do ratio "${coll[$p]}" "${fclc[$p]}"; done)

# Mesh pairs on random poses: NAME (~ for a space) ROBOT WORLD[,WORLD...], each pair whose files are here.
fanuc="$shared/robots/moveit_resources_fanuc_description/meshes/collision"
ur5="$shared/mbm/ur5/meshes/ur5/collision"
pairs=()
[ -d "$fanuc" ] && pairs+=("link_1~vs~link_2 $fanuc/link_1.stl $fanuc/link_2.stl"
                           "link_6~vs~base_link $fanuc/link_6.stl $fanuc/base_link.stl")
[ -d "$ur5" ] && pairs+=("forearm~vs~upperarm~+~base~(UR5) $ur5/forearm.stl $ur5/upperarm.stl,$ur5/base.stl")
if [ "${PAIRS:-1}" = 1 ] && [ ${#pairs[@]} -gt 0 ]; then
    echo
    # One line: the table's caption.
    printf '%s%s%s\n' "Mesh pairs, 200 random poses (\`meshgap_bench_queries --robot R --world W --states 200" \
        " --random 200 --streams random\`), millions of instructions and the ratio to FCL's call (distance;" \
        " collision-only to collide):"
    echo
    row "pair" "colliding" "cold certified" "cold, no depth" "collision-only" "FCL distance" "FCL collide"
    row "---" "---:" "---:" "---:" "---:" "---:" "---:"
    for entry in "${pairs[@]}"; do
        read -r name robot world <<< "$entry"
        echo "== $name" >&2
        q=("$build/bench/meshgap_bench_queries" --robot "$robot" --world "$world" --states 200 --random 200
           --streams random --load-repeats 1)
        # One run a column (FCL's two columns always run): cold with FCL's distance, FCL's collide alone.
        for column in cold cold-nodepth collision fcl-collide; do
            skip=$(echo "cold,warm,cold-nodepth,warm-nodepth,fast,collision,collision-warm,enumeration" |
                   tr ',' '\n' | grep -vx -- "$column" | paste -sd,)
            case $column in
                cold) toggles=(--toggle-collect='meshgap::Scene::distance*' --toggle-collect='*fcl::distance<*') ;;
                cold-nodepth) toggles=(--toggle-collect='meshgap::Scene::distance*') ;;
                collision) toggles=(--toggle-collect='meshgap::Scene::inCollision*') ;;
                fcl-collide) toggles=(--toggle-collect='meshgap::test::fclCollide*') ;;
            esac
            valgrind --tool=callgrind "${toggles[@]}" --callgrind-out-file="$out/pair.$column" "${q[@]}" \
                --skip "$skip" > "$out/pair.$column.stdout" 2>&1
        done
        colliding=$(grep -o 'colliding ([0-9]*)' "$out/pair.cold.stdout" | head -1 | tr -dc 0-9)
        c=$(count "$out/pair.cold" 'meshgap::Scene::distance\(')
        n=$(count "$out/pair.cold-nodepth" 'meshgap::Scene::distance\(')
        k=$(count "$out/pair.collision" 'meshgap::Scene::inCollision\(')
        fd=$(count "$out/pair.cold" 'fcl::distance<')
        fc=$(count "$out/pair.fcl-collide" 'meshgap::test::fclCollide\(')
        [ -n "$c" ] && [ -n "$n" ] && [ -n "$k" ] && [ -n "$fd" ] && [ -n "$fc" ] ||
            { echo "bench/instruction_counts.sh: no count for $name (callgrind outputs in $out)" >&2; exit 1; }
        row "${name//\~/ }" "${colliding:-0}" "$c ($(ratio "$c" "$fd"))" "$n ($(ratio "$n" "$fd"))" \
            "$k ($(ratio "$k" "$fc"))" "$fd" "$fc"
    done
fi
rm -rf "$out"
