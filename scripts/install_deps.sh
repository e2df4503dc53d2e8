#!/usr/bin/env bash
# Installs the Debian 12 packages rbsim needs. Idempotent: when every package is
# already present it only checks (no apt-get update, no download) and returns
# in well under a second.
set -euo pipefail

packages=(
  # build
  build-essential cmake pkg-config git ninja-build ccache
  # LCM (C/C++ library, lcm-gen, logger/player, Java jar for lcm-spy)
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev
  libjchart2d-java openjdk-17-jdk-headless openjdk-17-jre
  # physics and config
  libeigen3-dev libccd-dev libyaml-cpp-dev libqhull-dev
  # robots from URDF (urdfdom, and tinyxml2 for the load report's line numbers)
  liburdfdom-dev libtinyxml2-dev
  # COLLADA meshes (server/meshio/collada_mesh.h)
  libassimp-dev
  # terrains' height maps from PNG (server/meshio/height_grid.h)
  libpng-dev
  # rbctl --json
  nlohmann-json3-dev
  # tests and benchmarks
  libgtest-dev googletest libgmock-dev libbenchmark-dev
  # fuzzing (tests/fuzz): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # python side (run with /usr/bin/python3)
  python3 python3-numpy python3-pytest python3-matplotlib
  # hermetic multi-process tests (network namespaces)
  iproute2 util-linux
  # systemd-analyze, which scores the service units' hardening (tests/python/test_systemd_units.py)
  systemd
  # rbview, the browser viewer (clients/web): its bridge, and the browser its tests drive
  python3-websockets chromium
)
# rbview's page is built with node and npm: Debian's, unless a node with npm is
# already installed (e.g. from NodeSource, which bundles npm and conflicts with
# Debian's npm package).
if ! command -v npm >/dev/null 2>&1 || ! command -v node >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install_deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
