#!/bin/sh
# Runs a command in a private network namespace with only loopback, routed for
# multicast, so LCM traffic of a test never leaves the host and never meets
# another test's (docs/lcm.md, "Hermetic multi-process tests"). Needs root (CI runs as root) or
# unprivileged user namespaces (then: unshare -rn).
#   tests/tools/in_private_network.sh COMMAND [ARGS...]
if [ "$(id -u)" -eq 0 ]; then flags=-n; else flags=-rn; fi
exec unshare $flags sh -c 'ip link set lo up && ip route add 224.0.0.0/4 dev lo && exec "$@"' sh "$@"
