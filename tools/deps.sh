#!/usr/bin/env bash
# Installs the Debian 12 packages sixway needs, only those missing (idempotent). Sourced by
# run.sh and test.sh; run it alone to prepare a machine.
set -euo pipefail

SIXWAY_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools spirv-tools
  libglm-dev libglfw3-dev libopenexr-dev libopenvdb-dev libboost-iostreams-dev libtbb-dev
  libstb-dev nlohmann-json3-dev libcli11-dev libtinyobjloader-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  ffmpeg  # sixway render --video
  libimgui-dev xvfb xauth  # sixway-demo: its panel; the demo test runs it in a virtual X server
  python3-torch python3-numpy  # tools/nn: the PyTorch network; the test that regenerates its test vectors
  python3-matplotlib  # tools/train.py: the loss plot
  blender  # tools/blender and the tests labelled "blender": Mantaflow, Cycles, the add-on
)

missing=()
for package in "${SIXWAY_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "sixway: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
