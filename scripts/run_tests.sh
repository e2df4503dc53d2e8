#!/usr/bin/env bash
# Builds rbsim and runs every test: the C++ suites (ctest, both cores), the
# determinism golden hashes again in a Debug build, the parallel step under
# ThreadSanitizer, the Python suite, and the fuzz targets for a bounded time
# each in a clang build (tests/fuzz).
# Assumes scripts/install_deps.sh has run (the README's test command does both).
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=2
build=${RBSIM_BUILD_DIR:-build}
debug_build=${RBSIM_DEBUG_BUILD_DIR:-build-debug}
# Fuzzing: RBSIM_FUZZ_BUILD_DIR (default build-fuzz), RBSIM_FUZZ_SECONDS per
# target (default 10; 0 skips fuzzing, the corpora still run in ctest).
fuzz_seconds=${RBSIM_FUZZ_SECONDS:-10}

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$jobs"
ctest --test-dir "$build" -j"$jobs" --output-on-failure --timeout 900

# The golden state hashes (free bodies, a pile in contact, a world of
# joints) must be the same in Debug as in Release: build just those tests
# unoptimised and run them.
cmake -S . -B "$debug_build" -DCMAKE_BUILD_TYPE=Debug -DRBSIM_BUILD_BENCH=OFF
cmake --build "$debug_build" -j"$jobs" --target test_world test_contact_response test_joints test_parallel
"$debug_build"/tests/test_world --gtest_filter='Determinism.*'
"$debug_build"/tests/test_contact_response --gtest_filter='ContactDeterminism.*'
"$debug_build"/tests/test_joints --gtest_filter='JointDeterminism.GoldenHash'
# The parallel step's goldens on one and two threads (all four counts run
# in the Release ctest above).
RBSIM_PARALLEL_THREAD_COUNTS=1,2 "$debug_build"/tests/test_parallel --gtest_filter='ParallelDeterminism.*'

# ThreadSanitizer (clang): the task pool and the parallel step's scenes on
# 1, 2, 3 and 8 threads, shortened; any data race it reports fails the run.
tsan_build=${RBSIM_TSAN_BUILD_DIR:-build-tsan}
CC=clang CXX=clang++ cmake -S . -B "$tsan_build" -DRBSIM_TSAN=ON -DRBSIM_BUILD_BENCH=OFF
cmake --build "$tsan_build" -j"$jobs" --target test_parallel
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" RBSIM_PARALLEL_STEPS=400 \
  "$tsan_build"/tests/test_parallel

# Python: the lcm-gen types and (later) the client package. Run with Debian's
# interpreter, which has numpy and pytest.
if [ -d tests/python ]; then
  RBSIM_BUILD_DIR="$PWD/$build" /usr/bin/python3 -m pytest -q tests/python
else
  echo "run_tests: no Python tests in this tree (tests/python missing)"
fi

# Fuzzing (clang, ASan + UBSan): each target for a bounded time, two at a
# time; any crash, hang, leak or sanitizer report fails the suite.
if [ "$fuzz_seconds" != 0 ]; then
  RBSIM_FUZZ_SECONDS=$fuzz_seconds bash tests/fuzz/run_fuzzers.sh
else
  echo "run_tests: fuzzing skipped (RBSIM_FUZZ_SECONDS=0)"
fi
