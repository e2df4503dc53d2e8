#!/usr/bin/env bash
# Builds rbsim and runs every test: the C++ suites (ctest, both cores), the
# determinism golden hash again in a Debug build, and the Python suite.
# Assumes scripts/install_deps.sh has run (the README's test command does both).
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=2
build=${RBSIM_BUILD_DIR:-build}
debug_build=${RBSIM_DEBUG_BUILD_DIR:-build-debug}

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$jobs"
ctest --test-dir "$build" -j"$jobs" --output-on-failure --timeout 900

# The golden state hashes (free bodies, and a pile in contact) must be the
# same in Debug as in Release: build just those tests unoptimised and run them.
cmake -S . -B "$debug_build" -DCMAKE_BUILD_TYPE=Debug -DRBSIM_BUILD_BENCH=OFF
cmake --build "$debug_build" -j"$jobs" --target test_world test_contact_response
"$debug_build"/tests/test_world --gtest_filter='Determinism.*'
"$debug_build"/tests/test_contact_response --gtest_filter='ContactDeterminism.*'

# Python: the lcm-gen types and (later) the client package. Run with Debian's
# interpreter, which has numpy and pytest.
if [ -d tests/python ]; then
  RBSIM_BUILD_DIR="$PWD/$build" /usr/bin/python3 -m pytest -q tests/python
else
  echo "run_tests: no Python tests in this tree (tests/python missing)"
fi
