#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine. Installs missing packages (apt-get, as root or via
# sudo), configures and builds in ./build (Release), then:
#   ./setup.sh render [lgh-render options]   builds lgh-render only, renders the default scene to cornell_box.png
#   ./setup.sh test   [ctest options]        builds everything, runs the whole test suite
#   ./setup.sh build                         only installs and builds everything
# Every step is idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")"

# openimageio-tools: OpenImageIO's CMake config refers to its command-line tools and fails without them.
# libembree-dev: the CPU reference renderer (lgh-bench); libimgui-dev: the viewer; xvfb, xauth: the
# viewer's test; python3-matplotlib: the sweep's plots; clang-format: the suite's format check;
# libmpich-dev, mpich: lgh-bench under mpiexec / srun (MPICH rather than OpenMPI: CI runs as root, and
# MPICH's mpiexec runs as root as it is, where OpenMPI's refuses unless told --allow-run-as-root).
packages=(
  cmake g++ make pkg-config python3-glad
  libegl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev libglfw3-dev
  libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libopenimageio-dev openimageio-tools libcli11-dev
  libgtest-dev libembree-dev libimgui-dev xvfb xauth python3-matplotlib clang-format libmpich-dev mpich
)

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null | grep -qx installed || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "setup.sh: installing ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup.sh: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
    sudo=(sudo)
  fi
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# build [TARGET...]: the named targets and what they need, or everything.
build() {
  local targets=()
  [ $# -eq 0 ] || targets=(--target "$@")
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j"$(nproc)" "${targets[@]}"
}

command=${1:-}
shift || true
case "$command" in
  render)
    install_missing && build lgh-render
    ./build/lgh-render data/cornell_box.gltf -o cornell_box.png "$@" ;;
  test)
    install_missing && build
    ctest --test-dir build --output-on-failure -j"$(nproc)" "$@" ;;
  build)
    install_missing && build ;;
  *)
    echo "usage: ./setup.sh render [lgh-render options] | ./setup.sh test [ctest options] | ./setup.sh build" >&2
    exit 2 ;;
esac
