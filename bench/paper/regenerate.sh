#!/usr/bin/env bash
# Regenerate everything in bench/paper with one command:
#   1. the reproduction of Section IV (meshgap_bench_paper_reproduction: results.csv, history_*.csv; the maps as
#      generated, Table I's parameters, RUNS runs per algorithm),
#   2. the time-history figures and the table beside the paper's Tables III, V and VI (plot_paper.py, stdout saved
#      to paper_tables.md),
#   3. the reliability tables (meshgap_bench_reliability): comb-GA-wl and comb-SA-wl over RELIABILITY_RUNS seeds on
#      every paper scene-pose and at POSES poses of every OMPL.app problem, uniform against adaptive node sizing
#      (reliability_<sizing>.md / .csv), and comb-GA-wl against its variants (seeding from the nearest node-cluster
#      pairs, restarts of a stalled population; reliability_variants_<maps|omplapp>.md / .csv),
#   4. warm-fast along the paths against the warm certified query (meshgap_bench_warm_fast: warm_fast.md / .csv; with
#      comb-GA-wl as its global search: warm_fast_ga.md / .csv, and seeded from the clusters: warm_fast_clusters.*).
#
#   bench/paper/regenerate.sh [BUILD_DIR]
#   RUNS=100 RELIABILITY_RUNS=100 ADAPTIVE_OMPL_RUNS=5 POSES=20 STATES=1000 \
#       PARTS="reproduction plots reliability warm" bench/paper/regenerate.sh build      (the defaults; about 15 min)
#
# Needs the targets meshgap_bench_paper_reproduction, meshgap_bench_reliability and meshgap_bench_warm_fast built in
# BUILD_DIR (default: build), python3-matplotlib for the figures, and ../shared/data/omplapp for the OMPL.app rows
# (skipped without it). Run from anywhere; paths are relative to the repository.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$repo/build}" && pwd)"
runs="${RUNS:-100}"
reliabilityRuns="${RELIABILITY_RUNS:-100}"
adaptiveOmplRuns="${ADAPTIVE_OMPL_RUNS:-5}"  # on-demand mesh distances: about a second per comb-SA-wl run
poses="${POSES:-20}"
states="${STATES:-1000}"
parts="${PARTS:-reproduction plots reliability warm}"
data="${MESHGAP_SHARED_DATA_DIR:-$repo/../shared/data}/omplapp"
cd "$repo"
for part in $parts; do
    case "$part" in
        reproduction)
            "$build/bench/meshgap_bench_paper_reproduction" --maps maps --runs "$runs" --out "$here" \
                > "$here/reproduction_table.md" ;;
        plots)
            /usr/bin/python3 bench/plot_paper.py --dir "$here" > "$here/paper_tables.md" ;;
        reliability)
            # The paper scenes as generated (their node counts are the paper's) and with adaptive sizing on top;
            # the OMPL.app problems with meshgap_distance's default (uniform, 1/25 of each body's size) and adaptive.
            "$build/bench/meshgap_bench_reliability" --maps maps --problems none --runs "$reliabilityRuns" \
                --sizing none --csv "$here/reliability_maps_none.csv" > "$here/reliability_maps_none.md"
            "$build/bench/meshgap_bench_reliability" --maps maps --problems none --runs "$reliabilityRuns" \
                --sizing adaptive --csv "$here/reliability_maps_adaptive.csv" > "$here/reliability_maps_adaptive.md"
            "$build/bench/meshgap_bench_reliability" --data "$data" --scenes "" --runs "$reliabilityRuns" \
                --poses "$poses" --sizing uniform --csv "$here/reliability_omplapp_uniform.csv" \
                > "$here/reliability_omplapp_uniform.md"
            "$build/bench/meshgap_bench_reliability" --data "$data" --scenes "" --runs "$adaptiveOmplRuns" \
                --poses "$poses" --sizing adaptive --csv "$here/reliability_omplapp_adaptive.csv" \
                > "$here/reliability_omplapp_adaptive.md"
            variants=comb-GA-wl,comb-GA-wl:seeding=clusters,comb-GA-wl:restart_stall=10
            variants="$variants,comb-GA-wl:seeding=clusters:restart_stall=10"
            "$build/bench/meshgap_bench_reliability" --maps maps --problems none --runs "$reliabilityRuns" \
                --algorithms "$variants" --csv "$here/reliability_variants_maps.csv" \
                > "$here/reliability_variants_maps.md"
            "$build/bench/meshgap_bench_reliability" --data "$data" --scenes "" --runs "$reliabilityRuns" \
                --poses "$poses" --sizing uniform --algorithms "$variants" \
                --csv "$here/reliability_variants_omplapp.csv" > "$here/reliability_variants_omplapp.md" ;;
        warm)
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" \
                --csv "$here/warm_fast.csv" > "$here/warm_fast.md"
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" --budget-mib 1 \
                --csv "$here/warm_fast_ondemand.csv" > "$here/warm_fast_ondemand.md"
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" --no-patch \
                > "$here/warm_fast_nopatch.md"
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" --gap 1e300 \
                > "$here/warm_fast_nogap.md"
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" \
                --global-search comb-GA-wl --csv "$here/warm_fast_ga.csv" > "$here/warm_fast_ga.md"
            "$build/bench/meshgap_bench_warm_fast" --maps maps --data "$data" --states "$states" \
                --global-search comb-GA-wl --global-seeding clusters --csv "$here/warm_fast_clusters.csv" \
                > "$here/warm_fast_clusters.md" ;;
        *)
            echo "unknown part '$part' (valid: reproduction plots reliability warm)" >&2
            exit 1 ;;
    esac
done
