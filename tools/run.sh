#!/usr/bin/env bash
# Installs what is missing, builds, and renders the default scene headless into out/: assets/scenes/showcase.json,
# a plume rising around a cylinder, simulated 90 frames before the first one written (3 s, so it is developed),
# then 64 frames with the camera orbiting 64° and the key light turning the other way, filmic tone map
# (out/render: PNG per frame, contact sheet, video, per-stage GPU timings and smoke coverage), lit by the shipped
# all-orders network (weights/sixway-unet-ms.safetensors); plus the device description (out/info.json).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
sixway="$root/build/src/app/sixway"
mkdir -p "$root/out"
"$sixway" info --validate --report "$root/out/info.json" --force
"$sixway" render --scene "$root/assets/scenes/showcase.json" --frames 64 --out "$root/out/render" --video --force
echo "sixway: wrote $root/out/info.json and the frames in $root/out/render"
