#!/bin/sh
# The server issue's real-time benchmark: rbserver at 1 kHz with 100 bodies
# for S seconds (default 60) while a probe sends one-step wrenches at 100 Hz
# and times their acks. Prints the server's step-start lateness against the
# schedule (p50/p99/max), its achieved real-time factor and overruns, and the
# probe's wrench-to-ack latency (p50/p99). Runs in a private network
# namespace; build first (cmake --build build).
#   bench/run_realtime_bench.sh [BUILD_DIR] [SECONDS]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
seconds=${2:-60}
exec "$here/tests/tools/in_private_network.sh" sh -c '
  build=$1 here=$2 seconds=$3
  "$build/server/daemon/rbserver" --config "$here/bench/worlds/realtime_100.yaml" \
      --duration "$seconds" --state-rate 100 2>&1 | grep -E "stopped at step" &
  sleep 0.5
  "$build/tests/latency_probe" --body box0 --rate 100 --seconds "$(echo "$seconds - 2" | bc)"
  wait
' sh "$build" "$here" "$seconds"
