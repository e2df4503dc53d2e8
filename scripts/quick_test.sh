#!/usr/bin/env bash
# The inner loop, for use while working: builds build/ incrementally (just
# the libraries and the unit test executables) and runs the fast suites,
# the ctest cases labelled "unit": the GoogleTest suites of tests/unit and
# the layering checks, without the e2e, system, browser, soak and fuzz parts.
# The README's test command (scripts/run_tests.sh) still runs everything.
#
#   bash scripts/quick_test.sh              # build, then every unit case
#   bash scripts/quick_test.sh -R Joint     # extra arguments go to ctest
#
# Environment: RBSIM_BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/build_support.sh

build=${RBSIM_BUILD_DIR:-build}
if [ ! -f "$build/CMakeCache.txt" ]; then
  configure "$build" -DCMAKE_BUILD_TYPE=Release
fi
start=$(date +%s.%N)
cmake --build "$build" -j2 --target rbsim_unit_tests
built=$(date +%s.%N)
ctest --test-dir "$build" -j2 --output-on-failure -L unit "$@"
done_at=$(date +%s.%N)
awk "BEGIN{printf \"quick_test: build %.1f s, tests %.1f s\\n\", $built - $start, $done_at - $built}"
