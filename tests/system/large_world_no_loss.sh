#!/bin/sh
# A world of 2000 bodies published at 100 Hz reaches a client whole: every
# state's pages arrive and no state is missing (the server pages the state
# into single datagrams; the client asks for a 2 MiB receive buffer).
#   large_world_no_loss.sh RBSERVER STATE_LOSS_PROBE WORLD.yaml
set -eu
rbserver=$1 probe=$2 world=$3
"$rbserver" --config "$world" --duration 4 --state-rate 100 --log-level warning &
server=$!
sleep 0.5
status=0
# 3 s at 100 Hz is 300 states; allow for the start-up of both processes.
"$probe" --seconds 3 --expect 250 || status=$?
wait $server || status=$?
exit $status
