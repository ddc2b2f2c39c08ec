#!/usr/bin/env bash
# Installs every Debian package meshsal needs, builds it in Release into build/ (the
# Python module too: build/python/meshsal, see README, Python) and installs the `meshsal`
# command on PATH (cmake --install: /usr/local).
# Run as root on Debian 12 (or with sudo available). Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools
  libglm-dev catch2 zlib1g-dev libcli11-dev libstb-dev fonts-dejavu-core
  libmeshoptimizer-dev
  openmpi-bin libopenmpi-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-setuptools python3-pip python3-venv
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMESHSAL_BUILD_PYTHON=ON >/dev/null
cmake --build build -j"$(nproc)"
# `meshsal` on PATH (/usr/local/bin; the library, header and CMake package beside it).
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO cmake --install build >/dev/null
