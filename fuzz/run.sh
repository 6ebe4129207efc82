#!/usr/bin/env bash
# Build the libFuzzer targets (clang, library instrumented with ASan + UBSan) and run each for a while on its seed
# corpus. Exit status 1 if any target crashed, hung or broke an invariant; the inputs are in $OUT/crashes/<target>/.
#
#   fuzz/run.sh [SECONDS_PER_TARGET (default 60)] [TARGET ...]
#
# targets: mesh config pose distance urdf srdf robot_problem moveit (default), loader. urdf, srdf, robot_problem and
# moveit read the bytes as a URDF, an SRDF, a robot problem .cfg or a MoveIt planning scene and motion plan request
# (YAML) in a folder that holds a fixture robot (arm.urdf, arm.srdf), meshes (robot.obj, world.obj) and a package
# (pkg/meshes/cube.obj); see FuzzTargets.h. A target's dictionary, fuzz/<target>.dict, is passed when there is one.
#
# loader (assimp on the bytes as .obj/.stl/.ply) is not run by default: assimp is not instrumented, so the fuzzer is
# blind inside it, and Debian's assimp 5.2.5 hangs on a PLY header with non-ASCII bytes in a property name
# (fuzz/known/assimp_ply_header_hang.bin, found in the first minute). Run it by name: fuzz/run.sh 60 loader.
# Environment: BUILD_DIR (default build-fuzz), OUT (default $BUILD_DIR/fuzz-out), JOBS (build jobs, default 2). The
# build uses ccache when there is one.
# New corpus entries go to $OUT/corpus/<target>/; the seeds in fuzz/corpus/ are read, never changed. To keep a crash
# as a regression test, copy its input to tests/resources/fuzz/<target>/ (FuzzRegressionTest replays it).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
seconds=${1:-60}
shift || true
if [ $# -gt 0 ]; then targets=("$@"); else targets=(mesh config pose distance urdf srdf robot_problem moveit); fi
build=${BUILD_DIR:-$root/build-fuzz}
out=${OUT:-$build/fuzz-out}

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S "$root" -B "$build" "${launcher[@]}" -DMESHGAP_FUZZ=ON -DBUILD_TESTING=OFF -DMESHGAP_BUILD_BENCH=OFF \
    -DMESHGAP_BUILD_PLANNERS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer" >/dev/null || exit 2
nice cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]/#/meshgap_fuzz_}" || exit 2

# UB is a crash, not a message; leaks in third-party code (assimp, OMPL singletons) are not ours.
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
status=0
for t in "${targets[@]}"; do
    corpus="$out/corpus/$t" crashes="$out/crashes/$t"
    mkdir -p "$corpus" "$crashes"
    maxlen=4096
    [ "$t" = loader ] && maxlen=16384
    [ "$t" = moveit ] && maxlen=8192  # MotionBenchMaker's scenes are 6 to 9 kB
    echo "== $t: ${seconds} s"
    dict=()
    [ -f "$here/$t.dict" ] && dict=(-dict="$here/$t.dict")
    nice "$build/fuzz/meshgap_fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=$maxlen \
        "${dict[@]}" -print_final_stats=1 -artifact_prefix="$crashes/" "$corpus" "$here/corpus/$t" >"$out/$t.log" 2>&1
    rc=$?
    grep -E "^#[0-9]+[[:space:]]+(INITED|DONE)|^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)" "$out/$t.log"
    if [ $rc -ne 0 ] || [ -n "$(ls -A "$crashes")" ]; then
        echo "!! $t: FAILED (exit $rc), inputs in $crashes, log in $out/$t.log"
        grep -E "ERROR|invariant violated|runtime error|terminate" "$out/$t.log" | head -5
        status=1
    fi
done
exit $status
