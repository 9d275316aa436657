#!/usr/bin/env bash
# Installs the Debian packages the project needs; does nothing when all are present.
# clang-14, libclang-rt-14-dev (libFuzzer, sanitizer runtimes) and llvm-14 (llvm-symbolizer for
# readable sanitizer stacks) serve `make sanitize` and `make fuzz`.
set -euo pipefail

packages=(
  build-essential cmake ccache pkg-config libcli11-dev
  libmrpt-dev mrpt-apps mrpt-common
  liboctomap-dev libeigen3-dev libopencv-dev
  libembree-dev libassimp-dev libnanoflann-dev libtinyxml2-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libssl-dev
  libegl1 libegl-mesa0 libgl1-mesa-dri libopengl0
  libcairo2-dev fonts-dejavu-core
  clang-14 libclang-rt-14-dev llvm-14
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "Installing missing packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
