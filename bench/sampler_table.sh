#!/usr/bin/env bash
# The sampler table: one planner that uses a valid-state sampler (default PRM) with every sampler side by
# side (meshgap_benchmark --sampler, a dimension of the experiment), meshgap-certified checker, summarised by
# clearance_summary.py solve: runs, exact solutions, FCL-free paths, median and largest time per sampler.
#
#   bench/sampler_table.sh [BUILD_DIR] [OUT_DIR]
#
# Settings (environment): PROBLEMS (default "slotted_wall"; maps/ or ../shared/data/omplapp names, or paths of
# .cfg files), RUNS (3), TIME (10 s a run), SEED (1), PLANNER (prm), SAMPLERS (all eight),
# SHARDS (1: the grid in that many processes at once; shard i seeds with SEED + i - 1), FIRST (0; 1: each run stops at
# its first exact solution, so that the time column is the time to solve even for PRM, which otherwise runs to its
# limit: a copy of the cfg in OUT_DIR with objective.threshold = 1e9 and its meshes' paths made absolute). The
# benchmarks' own output goes to stderr, so stdout holds the table alone.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="${1:-$here/../build}"
out="${2:-sampler-results}"
data="${MESHGAP_SHARED_DATA_DIR:-$here/../../shared/data}/omplapp"
samplers="${SAMPLERS:-uniform,gaussian,obstacle_based,bridge_test,max_clearance,narrow_passage,retraction,workspace_medial}"
benchmark="$build/planners/meshgap_benchmark"
[ -x "$benchmark" ] || { echo "error: $benchmark: not built" >&2; exit 1; }
started=$SECONDS
for problem in ${PROBLEMS:-slotted_wall}; do
    if [ -f "$problem" ]; then cfg="$problem"; problem="$(sed -n 's/^name *= *//p' "$cfg" | head -1)"
    elif [ -f "$here/../maps/$problem/$problem.cfg" ]; then cfg="$here/../maps/$problem/$problem.cfg"
    else cfg="$data/$problem.cfg"; fi
    mkdir -p "$out"
    rm -f "$out/$problem".*.log
    if [ "${FIRST:-0}" = 1 ]; then
        dir="$(cd "$(dirname "$cfg")" && pwd)"
        awk -v dir="$dir" '
            /^\[/ { section = $0; print; if (section == "[problem]") print "objective.threshold = 1e9"; next }
            section == "[problem]" && /^(robot|world)[ \t]*=/ {
                key = $0; sub(/[ \t]*=.*/, "", key); value = $0; sub(/^[^=]*=[ \t]*/, "", value)
                n = split(value, files, /[ \t]*,[ \t]*/); line = key " = "
                for (i = 1; i <= n; ++i) line = line (i > 1 ? ", " : "") (files[i] ~ /^\// ? "" : dir "/") files[i]
                print line; next
            }
            section == "[problem]" && /^objective\.threshold[ \t]*=/ { next }
            { print }' "$cfg" > "$out/$problem.first.cfg"
        cfg="$out/$problem.first.cfg"
    fi
    shards="${SHARDS:-1}"
    for ((i = 1; i <= shards; ++i)); do
        nice "$benchmark" --cfg "$cfg" --planner "${PLANNER:-prm}" --checker certified --sampler "$samplers" \
            --runs "${RUNS:-3}" --time "${TIME:-10}" --seed "${SEED:-1}" --shard "$i/$shards" --out "$out" >&2 &
    done
    wait
done
echo "wall time: $((SECONDS - started)) s" >&2
/usr/bin/python3 "$here/clearance_summary.py" solve "$out"/*.log
