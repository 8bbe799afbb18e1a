#!/usr/bin/env bash
# Installs every Debian 12 package Repose needs to build, run and test. Run as root.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-tools vulkan-validationlayers
  glslc glslang-tools spirv-tools
  libeigen3-dev libglm-dev catch2 libtomlplusplus-dev libcli11-dev libstb-dev
  libsqlite3-dev libopenmpi-dev openmpi-bin nlohmann-json3-dev libhwy-dev libxxhash-dev python3-xxhash
  git
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
