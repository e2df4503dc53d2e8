#!/usr/bin/env bash
# Installs rbserver as a systemd service, as root, from the repository after
# building (docs/server.md, "Running it as a daemon"):
#   scripts/install_service.sh [BUILD_DIR]          (default build/)
# DESTDIR=/some/root puts everything under that root instead (for packaging
# and tests/python/test_systemd_units.py); nothing is started.
#   /usr/local/bin/rbserver
#   /etc/rbsim/default.yaml, /etc/rbsim/meshes/      (kept if already there)
#   /etc/systemd/system/rbserver.service, rbserver@.service, rbsim-multicast-route.service
#   /usr/local/share/doc/rbsim/                       (the documentation the units name)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$repo/build}
root=${DESTDIR:-}

[ -x "$build/server/daemon/rbserver" ] || { echo "install_service: build first ($build/server/daemon/rbserver missing)" >&2; exit 1; }
install -D -m 0755 "$build/server/daemon/rbserver" "$root/usr/local/bin/rbserver"
install -d -m 0755 "$root/etc/rbsim"
[ -e "$root/etc/rbsim/default.yaml" ] || install -m 0644 "$repo/config/default.yaml" "$root/etc/rbsim/default.yaml"
[ -e "$root/etc/rbsim/meshes" ] || cp -r "$repo/config/meshes" "$root/etc/rbsim/meshes"
install -d -m 0755 "$root/etc/systemd/system"
for unit in rbserver.service rbserver@.service rbsim-multicast-route.service; do
  install -m 0644 "$repo/config/systemd/$unit" "$root/etc/systemd/system/$unit"
done
doc="$root/usr/local/share/doc/rbsim"
install -d -m 0755 "$doc"
install -m 0644 "$repo/README.md" "$repo/docs/server.md" "$repo/docs/lcm.md" "$repo/docs/cli.md" "$doc/"
[ -e "$build/docs/messages.md" ] && install -m 0644 "$build/docs/messages.md" "$doc/"
if [ -z "$root" ] && [ -d /run/systemd/system ]; then systemctl daemon-reload; fi
echo "installed; start with: systemctl enable --now rbserver (or rbserver@NAME for /etc/rbsim/NAME.yaml)"
