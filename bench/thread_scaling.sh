#!/usr/bin/env bash
# Threads sharing one checker against as many single-thread processes, alternating, REPS times each:
# meshgap_bench_stress with --threads T and QUERIES queries, against T processes of QUERIES/T queries each.
# Prints each pair of wall times and the median of throughput(threads) / throughput(processes).
#   bench/thread_scaling.sh [BUILD_DIR=build] [T=2] [QUERIES=400000] [REPS=5]
set -euo pipefail
build=${1:-build} threads=${2:-2} queries=${3:-400000} reps=${4:-5}
stress="$build/bench/meshgap_bench_stress"
now() { date +%s.%N; }
ratios=()
for ((r = 1; r <= reps; ++r)); do
    t0=$(now); "$stress" --queries "$queries" --threads "$threads" --fast-every 0 >/dev/null 2>&1; t1=$(now)
    for ((p = 0; p < threads; ++p)); do
        "$stress" --queries $((queries / threads)) --threads 1 --fast-every 0 >/dev/null 2>&1 &
    done
    wait; t2=$(now)
    a=$(echo "$t1 - $t0" | bc -l) b=$(echo "$t2 - $t1" | bc -l)
    ratios+=("$(echo "$b / $a" | bc -l)")
    printf "run %d: %d threads %.2f s, %d processes %.2f s\n" "$r" "$threads" "$a" "$threads" "$b"
done
printf "median throughput, threads / processes: %.2f\n" "$(printf "%s\n" "${ratios[@]}" | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')"
