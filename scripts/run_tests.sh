#!/usr/bin/env bash
# Builds rbsim and runs every test: the C++ suites (ctest, both cores), the
# viewer's browser tests, the determinism golden hashes again in a Debug
# build, the parallel step under ThreadSanitizer, the Python suite, and the
# fuzz targets for a bounded time each in a clang build (tests/fuzz).
# At its end (pass or fail) it prints one line per phase with its wall time.
# Nothing here is shortened to save time: while working, use
# scripts/quick_test.sh, which builds incrementally and runs the fast suites.
#
# Environment: RBSIM_BUILD_DIR (default build), RBSIM_DEBUG_BUILD_DIR
# (build-debug), RBSIM_TSAN_BUILD_DIR (build-tsan), RBSIM_FUZZ_BUILD_DIR
# (build-fuzz), RBSIM_FUZZ_SECONDS per fuzz target (default 10; 0 skips
# fuzzing, the corpora still run in ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_support.sh

jobs=2
build=${RBSIM_BUILD_DIR:-build}
debug_build=${RBSIM_DEBUG_BUILD_DIR:-build-debug}
tsan_build=${RBSIM_TSAN_BUILD_DIR:-build-tsan}
fuzz_seconds=${RBSIM_FUZZ_SECONDS:-10}

# Phase timing: run_phase NAME COMMAND... runs one command (a function for
# several), records its wall time, and passes its exit status on; the table
# is printed on exit, so a failing run still shows where its time went.
phase_lines=()
run_start=$(date +%s.%N)
run_phase() {
  local name=$1 status=0 start end
  shift
  start=$(date +%s.%N)
  "$@" || status=$?
  end=$(date +%s.%N)
  phase_lines+=("$(printf '%-28s %8.1f s%s' "$name" "$(awk "BEGIN{print $end - $start}")" \
                   "$([ "$status" -eq 0 ] || echo "  FAILED (exit $status)")")")
  return "$status"
}
print_phases() {
  local status=$? total
  total=$(awk "BEGIN{print $(date +%s.%N) - $run_start}")
  echo
  echo "run_tests: wall time per phase"
  printf '  %s\n' "${phase_lines[@]}"
  printf '  %-28s %8.1f s\n' "total" "$total"
  if command -v ccache >/dev/null 2>&1; then
    echo "run_tests: compiler cache: $(ccache --print-stats 2>/dev/null | awk -F'\t' \
      '$1=="direct_cache_hit"||$1=="preprocessed_cache_hit"{h+=$2} $1=="cache_miss"{m+=$2} END{printf "%d hits, %d misses since its statistics were zeroed", h, m}')"
  fi
  return "$status"
}
trap print_phases EXIT

# Each phase is one command; the phases of several commands are these
# functions, whose commands are joined by && so that the first failure ends
# the phase (set -e does not apply inside a function called from a ||).
release_build() {
  configure "$build" -DCMAKE_BUILD_TYPE=Release && cmake --build "$build" -j"$jobs"
}
# The golden state hashes (free bodies, a pile in contact, a world of joints,
# the parallel step) must be the same in Debug as in Release: build just
# those tests with assertions on (Eigen's index checks, ours, and the
# standard library's with _GLIBCXX_ASSERTIONS), debug information, and
# GCC's debugging level -Og rather than -O0. The hashes are the same at
# -O0, -Og and -O2 (-ffp-contract=off, no -ffast-math); at -O0, where
# nothing of Eigen is inlined, the parallel scenes took about 22 minutes of
# the run, at -Og about one.
debug_build() {
  configure "$debug_build" -DCMAKE_BUILD_TYPE=Debug -DRBSIM_BUILD_BENCH=OFF \
    "-DCMAKE_CXX_FLAGS_DEBUG=-Og -g -D_GLIBCXX_ASSERTIONS" &&
    cmake --build "$debug_build" -j"$jobs" --target test_goldens test_parallel
}
debug_goldens() {
  # The lockstep runs (two worlds compared step by step) run in Release;
  # here the hashes, which a single run must reproduce bit for bit.
  "$debug_build"/tests/test_goldens --gtest_filter='*.GoldenHash' &&
    RBSIM_PARALLEL_THREAD_COUNTS=1,2 "$debug_build"/tests/test_parallel --gtest_filter='ParallelDeterminism.*'
}
# ThreadSanitizer (clang): the task pool and the parallel step's scenes on
# 1, 2, 3 and 8 threads, shortened, and queries (rays, batches, shape
# casts) from many threads at once; any data race it reports fails the run.
# RBSIM_POOL_ALWAYS_SHARE=1: every loop is offered to the workers. Left to
# itself the pool runs loops on the caller alone while its workers do too
# little of them (task_pool.h), which TSan's slow-down makes likely, and a
# loop on one thread has no race to find. (A TSan build shares always when
# the variable is unset too; it is set here so the run says what it checks.)
tsan_build() {
  CC=clang CXX=clang++ configure "$tsan_build" -DRBSIM_TSAN=ON -DRBSIM_BUILD_BENCH=OFF &&
    cmake --build "$tsan_build" -j"$jobs" --target test_parallel test_ray_casts
}
tsan_run() {
  TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" RBSIM_PARALLEL_STEPS=400 RBSIM_POOL_ALWAYS_SHARE=1 \
    "$tsan_build"/tests/test_parallel &&
    TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" RBSIM_POOL_ALWAYS_SHARE=1 \
      "$tsan_build"/tests/test_ray_casts --gtest_filter='*Concurrent*:*BatchEqualsSingle*'
}
# Python: the lcm-gen types, the client package, the CLIs, the READMEs'
# commands. Run with Debian's interpreter, which has numpy and pytest.
python_suite() {
  RBSIM_BUILD_DIR="$PWD/$build" /usr/bin/python3 -m pytest -q tests/python
}

run_phase "install check" bash scripts/install_deps.sh
run_phase "release build" release_build
run_phase "ctest (C++, e2e, system)" \
  ctest --test-dir "$build" -j"$jobs" --output-on-failure --timeout 900 -E '^web\.'
run_phase "ctest (browser, web.*)" \
  ctest --test-dir "$build" -j"$jobs" --output-on-failure --timeout 900 -R '^web\.'
run_phase "debug build" debug_build
run_phase "debug goldens" debug_goldens
run_phase "tsan build" tsan_build
run_phase "tsan run" tsan_run
run_phase "pytest" python_suite
# Fuzzing (clang, ASan + UBSan): each target for a bounded time, two at a
# time; any crash, hang, leak or sanitizer report fails the suite. The
# script builds build-fuzz first: its two parts are timed apart.
if [ "$fuzz_seconds" != 0 ]; then
  run_phase "fuzz build" env RBSIM_FUZZ_BUILD_ONLY=1 bash tests/fuzz/run_fuzzers.sh
  run_phase "fuzz run" env RBSIM_FUZZ_SECONDS="$fuzz_seconds" bash tests/fuzz/run_fuzzers.sh
else
  echo "run_tests: fuzzing skipped (RBSIM_FUZZ_SECONDS=0)"
fi
