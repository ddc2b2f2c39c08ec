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
  libmeshoptimizer-dev libtinygltf-dev
  openmpi-bin libopenmpi-dev
  pybind11-dev python3-dev python3-numpy python3-pytest python3-setuptools python3-pip python3-venv
  chromium
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

# Node.js for the web tools (web: three.js bundled into `meshsal view` pages, and the
# Khronos glTF-Validator the tests run). Debian's nodejs and npm, unless a Node.js with its
# own npm is already installed (NodeSource's bundles npm, and Debian's npm conflicts with it).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  command -v node >/dev/null || $SUDO apt-get install -y -qq nodejs
  command -v npm >/dev/null || $SUDO apt-get install -y -qq npm
fi
# The exact versions of package-lock.json, into web/node_modules (again only when the
# lock file changed since the last install).
lock_sum=$(sha256sum web/package-lock.json | cut -d' ' -f1)
if [ "$(cat web/node_modules/.meshsal-lock 2>/dev/null)" != "$lock_sum" ]; then
  (cd web && npm ci --no-audit --no-fund --loglevel=error)
  echo "$lock_sum" > web/node_modules/.meshsal-lock
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMESHSAL_BUILD_PYTHON=ON >/dev/null
cmake --build build -j"$(nproc)"
# `meshsal` on PATH (/usr/local/bin; the library, header and CMake package beside it).
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
$SUDO cmake --install build >/dev/null
