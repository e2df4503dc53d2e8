#!/bin/sh
# rbview's benchmark (clients/web/bench/viewer_bench.mjs) in a private network
# namespace: 2000 bodies, state at 60 Hz, headless chromium. Prints JSON; keeps
# the screenshot and the figures in BUILD/bench/viewer/.
#   clients/web/bench/run_viewer_bench.sh [BUILD_DIR] [SECONDS]
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../../.." && pwd)
build=$(cd "${1:-$repo/build}" && pwd)
export RBSIM_BUILD_DIR="$build" RBSIM_PRIVATE_NETWORK=1 SECONDS_TO_MEASURE="${2:-20}"
export RBVIEW_ARTIFACTS="$build/bench/viewer" RBVIEW_WORK="$build/bench/viewer/work"
exec "$repo/tests/tools/in_private_network.sh" node "$here/viewer_bench.mjs"
