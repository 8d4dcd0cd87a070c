#!/usr/bin/env bash
# Installs the Debian packages vri builds and runs with, if any is missing (apt-get, as root or via sudo).
#   scripts/install-deps.sh          what make test and make experiments need
#   scripts/install-deps.sh fuzz     that and clang with libFuzzer, for make fuzz
set -euo pipefail

packages=(
  cmake ninja-build g++ make pkg-config
  libopenvdb-dev libboost-iostreams-dev libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev
  libyaml-cpp-dev libcli11-dev doctest-dev libtbb-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-tools glslang-tools glslang-dev
  libglm-dev nlohmann-json3-dev gnuplot-nox libhwy-dev zlib1g-dev
  python3-openvdb python3-numpy pybind11-dev python3-dev libopenvdb-tools teem-apps libtiff-tools
  python3-vtk9 python3-openimageio python3-yaml xvfb xauth   # tools/peers: VTK as a peer
  slurm-wlm munge iproute2   # vri-run --executor slurm, and the test cluster of tests/tools/slurm.sh
  time                       # GNU time: the bad-input suites' peak resident memory (tests/tools/lib/bad_input.sh)
  ccache                     # the Makefile compiles through it when it is there: a rebuild reuses objects
  python3-jsonschema         # the scene card's schema check (tests/tools/scene_card.sh)
  chromium                   # tools/peers/web: three.js, vtk.js and NiiVue in headless Chromium (tests/tools/peers_web.sh)
  help2man                   # the tools' man pages, made from their --help at build time (docs/CMakeLists.txt)
)
if [ "${1:-}" = fuzz ]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1; then
  sudo=(sudo)
else
  echo "install-deps: error: missing packages (${missing[*]}) and neither root nor sudo to install them" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
