#!/usr/bin/env bash
# Runs every scene of the public robots' benchmark on rbsim and, when they
# were built, MuJoCo and Bullet, one engine after the other, pinned to one
# core, and collects the ROW lines.
#   bench/robots/run_public.sh [BUILD_DIR] [STEPS] [REPS] [CPU]
# Defaults: build, 3000 steps (the scenes' own length), 1 rep, core 1.
# Short run while working: bench/robots/run_public.sh build 300 1
# Environment: SCENES (default all; e.g. SCENES=hold-iiwa,fold-iiwa),
# SELF_COLLISION (on|off: override the scenes' own setting).
set -euo pipefail
build=${1:-build}
steps=${2:-3000}
reps=${3:-1}
cpu=${4:-1}
scenes=${SCENES:-all}
args=(--scene "$scenes" --steps "$steps" --reps "$reps")
if [ -n "${SELF_COLLISION:-}" ]; then args+=(--self-collision "$SELF_COLLISION"); fi
pin=()
if command -v taskset >/dev/null 2>&1; then pin=(taskset -c "$cpu"); fi
log=$(mktemp)
for engine in bench_robots_public bench_robots_public_mujoco bench_robots_public_bullet; do
  binary="$build/bench/robots/$engine"
  if [ ! -x "$binary" ]; then
    echo "# $engine not built: skipped" | tee -a "$log"
    continue
  fi
  "${pin[@]}" "$binary" "${args[@]}" | tee -a "$log"
done
echo
echo "| engine | scene | self-collision | bodies | joints | mean ms | median ms | p99 ms | real-time factor | contact points (mean) | max joint error |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
grep '^ROW' "$log" | grep -v '| engine |' | sed 's/^ROW //'
rm -f "$log"
