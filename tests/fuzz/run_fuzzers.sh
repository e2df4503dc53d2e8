#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a
# bounded time, two at a time. Any crash, hang, leak, out-of-memory or
# sanitizer report fails the run; the input that caused it is kept in
# <build>/fuzz-artifacts/ and the target's log in <build>/fuzz-logs/.
#
#   bash tests/fuzz/run_fuzzers.sh                 # every target, as scripts/run_tests.sh does
#   RBSIM_FUZZ_SECONDS=600 bash tests/fuzz/run_fuzzers.sh obj_mesh   # one target, longer
#
# Environment:
#   RBSIM_FUZZ_BUILD_DIR  build directory (default build-fuzz)
#   RBSIM_FUZZ_SECONDS    seconds per target (default 15)
#   RBSIM_FUZZ_JOBS       targets run at once (default 2, one per core)
#   RBSIM_FUZZ_BUILD_ONLY 1: build the targets and stop (run_tests.sh times
#                         the build and the runs apart)
#   RBSIM_FUZZ_SEED       libFuzzer's seed (default 1: a run from the same
#                         corpora explores the same inputs in the same order,
#                         so the suite's short run is reproducible and a
#                         longer clean run vouches for every shorter one;
#                         0: a random seed, for exploration)
# Each target starts from its seed corpus (tests/fuzz/corpus/<target>), the
# inputs that once found bugs (tests/fuzz/regressions/<target>) and what
# earlier runs found (<build>/fuzz-corpus/<target>, not checked in).
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/build_support.sh

build=${RBSIM_FUZZ_BUILD_DIR:-build-fuzz}
seconds=${RBSIM_FUZZ_SECONDS:-15}
seed=${RBSIM_FUZZ_SEED:-1}
jobs=${RBSIM_FUZZ_JOBS:-2}
fuzz=tests/fuzz

if ! command -v clang++ >/dev/null; then
  echo "run_fuzzers: clang++ not found (bash scripts/install_deps.sh installs clang and libclang-rt-14-dev)" >&2
  exit 1
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ configure "$build" -DRBSIM_FUZZ=ON
fi
nice -n 5 cmake --build "$build" -j2 --target rbsim_fuzz_targets
if [ "${RBSIM_FUZZ_BUILD_ONLY:-0}" = 1 ]; then
  exit 0
fi

if [ $# -gt 0 ]; then
  targets=("$@")
else
  # Every target CMake knows, in the order of tests/fuzz/CMakeLists.txt.
  mapfile -t targets < <(sed -n '/^set(RBSIM_FUZZ_TARGETS/,/^)/{/^  [a-z_]*$/p}' "$fuzz/CMakeLists.txt" | tr -d ' ')
fi

dictionary_for() {
  case "$1" in
    world_config | body_yaml) echo "$fuzz/dictionaries/yaml.dict" ;;
    obj_mesh) echo "$fuzz/dictionaries/obj.dict" ;;
    stl_mesh) echo "$fuzz/dictionaries/stl.dict" ;;
    dae_mesh) echo "$fuzz/dictionaries/dae.dict" ;;
    urdf_robot) echo "$fuzz/dictionaries/urdf.dict" ;;
    wrench_message | command_message | joint_command_message | robot_command_message | command_handler | replay_log) echo "$fuzz/dictionaries/lcm.dict" ;;
  esac
}

mkdir -p "$build/fuzz-logs" "$build/fuzz-artifacts"
# A stack trace for every UBSan report (they abort: -fno-sanitize-recover).
export UBSAN_OPTIONS=print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1

run_one() {
  local target=$1
  local dictionary
  dictionary=$(dictionary_for "$target")
  mkdir -p "$build/fuzz-corpus/$target"
  # -timeout: one input taking longer is a hang; -rss_limit_mb also bounds a
  # single allocation (malloc_limit_mb defaults to it).
  "$build/tests/fuzz/fuzz_$target" \
    -max_total_time="$seconds" -seed="$seed" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    ${dictionary:+-dict="$dictionary"} \
    -artifact_prefix="$build/fuzz-artifacts/$target-" \
    "$build/fuzz-corpus/$target" "$fuzz/corpus/$target" "$fuzz/regressions/$target" \
    >"$build/fuzz-logs/$target.log" 2>&1
}

failed=()
pids=()
names=()
wait_for_one() {
  local pid=${pids[0]} name=${names[0]}
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
  if wait "$pid"; then
    # "#123 DONE cov: 456 ft: 789 corp: ... exec/s: 321 rss: 100Mb"
    local done_line
    done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$build/fuzz-logs/$name.log" | tail -1 || true)
    echo "run_fuzzers: $name ok: ${done_line:-no stats}"
  else
    echo "run_fuzzers: $name FAILED, see $build/fuzz-logs/$name.log:" >&2
    grep -E 'ERROR|SUMMARY|runtime error|Test unit written' "$build/fuzz-logs/$name.log" | head -8 >&2 || true
    failed+=("$name")
  fi
}

echo "run_fuzzers: ${#targets[@]} targets, ${seconds} s each, $jobs at a time"
for target in "${targets[@]}"; do
  if [ ! -x "$build/tests/fuzz/fuzz_$target" ]; then
    echo "run_fuzzers: no such target: $target" >&2
    exit 1
  fi
  run_one "$target" &
  pids+=($!)
  names+=("$target")
  if [ ${#pids[@]} -ge "$jobs" ]; then wait_for_one; fi
done
while [ ${#pids[@]} -gt 0 ]; do wait_for_one; done

if [ ${#failed[@]} -gt 0 ]; then
  echo "run_fuzzers: failures in ${failed[*]}" >&2
  exit 1
fi
echo "run_fuzzers: no findings"
