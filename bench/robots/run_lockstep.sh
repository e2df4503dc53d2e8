#!/bin/sh
# The lock-step benchmark (lockstep.cpp) three times against one rbserver on
# config/worlds/robot_arm.yaml, in a private network namespace (nothing
# leaves the host), then the median of the runs per path.
#   bench/robots/run_lockstep.sh [BUILD_DIR] [RUNS] [CYCLES] [raised|default]
# raised (the default): the world file with limits.client_rate and
# client_burst lifted, so that what is timed is the messaging; under the
# server's default limit (5000 messages/s per client) the per-joint path's
# eight messages a cycle stop it at 625 cycles/s, and the benchmark fails
# when the server drops a message.
set -eu
build=${1:-build}
runs=${2:-3}
cycles=${3:-2000}
limits=${4:-raised}
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp)
world=$(mktemp --suffix=.yaml)
trap 'rm -f "$out" "$world"' EXIT
sed "s|urdf: \.\./robots/|urdf: $root/config/robots/|" "$root/config/worlds/robot_arm.yaml" >"$world"
if [ "$limits" = raised ]; then
  printf 'limits: {client_rate: 100000000, client_burst: 100000000}\n' >>"$world"
fi
"$root/tests/tools/in_private_network.sh" sh -c '
  "$1/server/daemon/rbserver" --config "$2" --paused >/dev/null 2>&1 &
  server=$!
  i=0
  while [ "$i" -lt "$3" ]; do
    "$1/bench/robots/bench_robots_lockstep" --cycles "$4" --paths "$5" || { kill "$server"; exit 1; }
    i=$((i + 1))
  done
  kill "$server"; wait "$server" || true
' sh "$build" "$world" "$runs" "$cycles" "${RBSIM_LOCKSTEP_PATHS:-robot,robot-client,joints}" | tee "$out"
echo "median of $runs runs:"
echo "ROW | path | cycles/s | p50 us | p99 us | client cpu us |"
for path in robot robot-client joints; do
  grep "^ROW | $path |" "$out" | awk -F'|' -v p="$path" '
    { c[NR] = $4; m[NR] = $5; n[NR] = $6; u[NR] = $8 }
    function median(a, k,   i, j, t) {
      for (i = 1; i <= k; i++) for (j = i + 1; j <= k; j++) if (a[j] + 0 < a[i] + 0) { t = a[i]; a[i] = a[j]; a[j] = t }
      return a[int((k + 1) / 2)]
    }
    END { if (NR) printf "ROW | %s | %s | %s | %s | %s |\n", p, median(c, NR), median(m, NR), median(n, NR), median(u, NR) }'
done
