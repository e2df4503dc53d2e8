#!/usr/bin/env bash
# Records an rbsim session with lcm-logger, then plots it with
# `python3 -m rbsim plot`.
#
#   clients/python/examples/record_and_plot.sh [OUT_DIR]
#
# Writes OUT_DIR/session.lcmlog and OUT_DIR/session.png (OUT_DIR defaults to
# ./rbsim_session). The server runs the world $WORLD (default
# config/default.yaml) for $DURATION s of simulated time (default 2) at
# real-time factor $RTF (default 4); halfway through (simulated time), a client pushes body
# $BODY (default bouncy_ball, of config/default.yaml) up with $FORCE N (default 500) for 0.5 s. Everything uses the LCM URL
# $LCM_DEFAULT_URL (default udpm://239.255.76.67:7667?ttl=0); to keep the
# traffic off your network, run it as
#   tests/tools/in_private_network.sh clients/python/examples/record_and_plot.sh OUT_DIR
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)
build=${RBSIM_BUILD_DIR:-$repo/build}
out=${1:-rbsim_session}
world=${WORLD:-$repo/config/default.yaml}
duration=${DURATION:-2}
rtf=${RTF:-4}
body=${BODY:-bouncy_ball}
force=${FORCE:-500}
timeout=${TIMEOUT:-5}   # s that each CLI call waits for the server
url=${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}
python=/usr/bin/python3
export PYTHONPATH="$repo/clients/python${PYTHONPATH:+:$PYTHONPATH}"
export RBSIM_BUILD_DIR="$build"

mkdir -p "$out"
log="$out/session.lcmlog"
png="$out/session.png"

logger_pid=
server_pid=
cleanup() {
  [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null || true
  [ -n "$logger_pid" ] && kill "$logger_pid" 2>/dev/null || true
}
trap cleanup EXIT

lcm-logger -q -f --lcm-url="$url" "$log" &
logger_pid=$!
sleep 0.5   # let the logger join the multicast group before anything is sent
kill -0 "$logger_pid" 2>/dev/null || { echo "record_and_plot: lcm-logger failed to start" >&2; exit 1; }

# The server starts paused, so that the push can be scheduled before anything moves.
"$build/server/daemon/rbserver" --config "$world" --lcm-url "$url" --log-level warning \
    --duration "$duration" --real-time-factor "$rtf" --paused &
server_pid=$!
sleep 0.2
kill -0 "$server_pid" 2>/dev/null || { echo "record_and_plot: rbserver failed to start" >&2; exit 1; }

# Halfway through (in simulated time), push the body up for 0.5 s: the step
# number comes from the world's dt, which `bodies --json` reports.
dt=$("$python" -m rbsim --url "$url" --timeout "$timeout" bodies --json |
     "$python" -c 'import json, sys; print(json.load(sys.stdin)["dt"])')
half=$("$python" -c "print(round($duration / 2 / $dt))")
"$python" -m rbsim --url "$url" --timeout "$timeout" wrench "$body" --force 0 0 "$force" \
    --mode duration --duration 0.5 --at-step "$half"
"$python" -m rbsim --url "$url" --timeout "$timeout" resume

wait "$server_pid"
server_pid=
sleep 0.3   # the last messages reach the logger
kill -INT "$logger_pid"
wait "$logger_pid" || true
logger_pid=

"$python" -m rbsim plot "$log" -o "$png"
