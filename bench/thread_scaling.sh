#!/usr/bin/env bash
# Threads sharing one checker against as many single-thread processes, alternating, REPS times each:
# meshgap_bench_stress with --threads T and QUERIES queries, against T processes of QUERIES/T queries each.
# Prints each pair of wall times and the median of throughput(threads) / throughput(processes); with --markdown,
# one Markdown table row of the same (the form bench/refresh.sh writes into bench/scaling.md).
#   bench/thread_scaling.sh [--markdown] [BUILD_DIR=build] [T=2] [QUERIES=400000] [REPS=5]
set -euo pipefail
markdown=0
if [ "${1:-}" = --markdown ]; then markdown=1; shift; fi
build=${1:-build} threads=${2:-2} queries=${3:-400000} reps=${4:-5}
stress="$build/bench/meshgap_bench_stress"
now() { date +%s.%N; }
ratios=() walls_t=() walls_p=()
for ((r = 1; r <= reps; ++r)); do
    t0=$(now); "$stress" --queries "$queries" --threads "$threads" --fast-every 0 >/dev/null 2>&1; t1=$(now)
    pids=()
    for ((p = 0; p < threads; ++p)); do
        "$stress" --queries $((queries / threads)) --threads 1 --fast-every 0 >/dev/null 2>&1 &
        pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid"; done  # a process that fails fails the script
    t2=$(now)
    a=$(echo "$t1 - $t0" | bc -l) b=$(echo "$t2 - $t1" | bc -l)
    ratios+=("$(echo "$b / $a" | bc -l)") walls_t+=("$a") walls_p+=("$b")
    if [ $markdown = 0 ]; then
        printf "run %d: %d threads %.2f s, %d processes %.2f s\n" "$r" "$threads" "$a" "$threads" "$b"
    fi
done
median=$(printf "%s\n" "${ratios[@]}" | sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}')
if [ $markdown = 0 ]; then
    printf "median throughput, threads / processes: %.2f\n" "$median"
    exit 0
fi
span() { printf "%s\n" "$@" | sort -g | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.2f–%.2f s", lo, hi}'; }
echo "Threads sharing one checker against as many single-thread processes (median of the runs' throughput ratios):"
echo
echo "| threads | queries | runs | threads / processes, throughput | wall time, threads | wall time, processes |"
echo "|---:|---:|---:|---:|---|---|"
printf "| %d | %d | %d | **%.2f** | %s | %s |\n" "$threads" "$queries" "$reps" "$median" \
    "$(span "${walls_t[@]}")" "$(span "${walls_p[@]}")"
