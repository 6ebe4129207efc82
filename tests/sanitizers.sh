#!/usr/bin/env bash
# The test suite under the sanitizers, as CI runs it after the Release suite:
#   1. AddressSanitizer + UndefinedBehaviorSanitizer: every test, the executables the CLI tests run included (the
#      test files themselves without UBSan, tests/CMakeLists.txt);
#   2. ThreadSanitizer: the tests that query one checker or scene from several threads (their files only built).
# Each has its own build directory beside `build`. No Python module there (an instrumented .so cannot be loaded by
# an uninstrumented python3). A sanitizer report fails the run (UBSan does not recover).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${MESHGAP_JOBS:-2}

# LeakSanitizer: one object allocated inside libassimp and never freed (not ours); everything else counts.
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/sanitizers/tsan.supp"

echo "== AddressSanitizer + UBSan =="
# -O1: the sanitized builds take most of CI's time, and -O1 compiles them faster than -O3 at a modest cost in run time.
# Release only: the install-and-consume test (it builds an uninstrumented consumer against the instrumented
# library), and the examples (RRT* and PRM* runs with a time limit: slowed down 2-5x, they would test the clock; so
# they are not built here either).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DMESHGAP_SANITIZE=address \
      -DMESHGAP_BUILD_BENCH=OFF -DMESHGAP_PYTHON=OFF -DMESHGAP_BUILD_EXAMPLES=OFF
cmake --build build-asan -j"$jobs"
# The heavy randomized tests at a tenth of their random states, motions, seeds and poses (tests/TestScale.h): a
# memory or undefined-behaviour error shows on any state, and each costs 10 to 100 times more instrumented; the
# Release run above checks them all against their oracles.
MESHGAP_TEST_SCALE=0.1 ctest --test-dir build-asan --output-on-failure -j"$jobs" -E '^(cmake_export|example_)'

echo "== ThreadSanitizer =="
# meshgap_tests here is built of the test files that hold a threaded test only (tests/CMakeLists.txt): the same
# tests as -R 'Thread' below, without compiling the rest of the suite instrumented.
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DMESHGAP_SANITIZE=thread \
      -DMESHGAP_BUILD_BENCH=OFF -DMESHGAP_PYTHON=OFF \
      -DMESHGAP_BUILD_PLANNERS=OFF
cmake --build build-tsan -j"$jobs" --target meshgap_tests
ctest --test-dir build-tsan --output-on-failure -j"$jobs" -R 'Thread'
