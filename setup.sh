#!/usr/bin/env bash
# Installs the Debian 12 packages Throng builds, tests and runs with. Idempotent: it does nothing
# when every package is present, and refreshes the package lists only when a package is unknown.
set -euo pipefail

packages=(
  # toolchain
  g++ clang libclang-rt-14-dev cmake ninja-build pkg-config git
  # libraries named by the design card
  libvtk9-dev libglm-dev libglfw3-dev libosmesa6-dev libgl-dev libgl1-mesa-dri libtinygltf-dev libmeshoptimizer-dev
  # tests, benchmarks, navigation, scene files, images, GL loader, virtual display
  libgtest-dev libgmock-dev libbenchmark-dev librecast-dev nlohmann-json3-dev libstb-dev libjpeg-dev
  python3 python3-glad xvfb xauth
  # task scheduler (per-actor phases), command lines, the OpenSceneGraph peer benchmark
  libtbb-dev libcli11-dev libopenscenegraph-dev
  # exact key-pose selection (an integer program) to measure the greedy cache against
  libglpk-dev
  # one simulation across processes and machines (optional at build time)
  libopenmpi-dev openmpi-bin
  # the API reference from the headers' comments
  doxygen
  # headless OpenGL through EGL: a GPU without an X server, or Mesa's surfaceless platform
  libegl-dev libegl-mesa0
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=sudo
fi
echo "setup: installing ${missing[*]}"
# Refresh the lists only if apt does not know one of the packages yet (a fresh image ships none).
if ! apt-cache show "${missing[@]}" >/dev/null 2>&1; then
  $sudo apt-get update
fi
$sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
