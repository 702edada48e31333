#!/usr/bin/env bash
# Installs what is missing, builds, and renders the default scene headless into out/: the plume rising around a
# cylinder under an orbiting light, 64 frames (out/render: PNG per frame, contact sheet, video, per-stage GPU
# timings), with the shipped all-orders network when weights/sixway-unet-ms.safetensors exists, else the reference lightmaps;
# plus the device description (out/info.json).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
sixway="$root/build/src/app/sixway"
mkdir -p "$root/out"
"$sixway" info --validate --report "$root/out/info.json" --force
"$sixway" render --scene "$root/assets/scenes/plume.json" --frames 64 --out "$root/out/render" --video --force
echo "sixway: wrote $root/out/info.json and the frames in $root/out/render"
