#!/usr/bin/env bash
# Instructions, not time: callgrind over meshgap's Scene::distance only (so the machine's load does not enter), cold on
# 300 path states and warm on 1,000, and over FCL's fcl::distance on the same 1,000 states, on OMPL.app problems and
# on the maps in maps/ (meshgap_bench_queries' own path streams); a table of millions of instructions, the warm
# query's share spent on penetration depth (the colliding states' depth estimate) and warm over FCL.
#
#   bench/instruction_counts.sh [BUILD (build)] [PROBLEMS (Easy Twistycool cubicles battery_fixture slotted_wall)]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
problems="${2:-Easy Twistycool cubicles battery_fixture slotted_wall}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
command -v valgrind > /dev/null || { echo "bench/instruction_counts.sh: needs valgrind" >&2; exit 1; }
out="$(mktemp -d /tmp/meshgap_callgrind.XXXXXX)"
others="cold-nodepth,warm-nodepth,fast,collision,collision-warm,enumeration,random"
# The inclusive count of the function whose name matches $2 in the callgrind output $1, in millions.
count() {
    callgrind_annotate --inclusive=yes "$1" > "$1.txt" 2>/dev/null
    awk -v pattern="$2" '$0 ~ pattern { gsub(",", "", $1); printf "%.1f", $1 / 1e6; exit }' "$1.txt"
}
declare -A cold warm depth fcl
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
    cold[$p]=$(count "$out/$p.cold" 'meshgap::Scene::distance\(')
    warm[$p]=$(count "$out/$p.warm" 'meshgap::Scene::distance\(')
    depth[$p]=$(count "$out/$p.warm" 'meshgap::penetrationDepth\(')
    depth[$p]=${depth[$p]:-0.0}  # no colliding state: never called
    fcl[$p]=$(count "$out/$p.warm" 'fcl::distance<')
    [ -n "${cold[$p]}" ] && [ -n "${warm[$p]}" ] && [ -n "${fcl[$p]}" ] ||
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
row "warm / FCL" $(for p in $problems; do awk -v w="${warm[$p]}" -v f="${fcl[$p]}" 'BEGIN { printf "%.3f\n", w / f }'; done)
rm -rf "$out"
