#!/usr/bin/env bash
# Installs what is missing, builds, and runs sixway headless into out/.
# Until the real-time renderer lands (issue #5) this runs the most complete pipeline there is: the
# default scene's smoke simulation, baked frame by frame into a reference six-way flipbook
# (out/flipbook/), plus the device description (out/info.json).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/tools/deps.sh"
source "$root/tools/build.sh"
sixway="$root/build/src/app/sixway"
mkdir -p "$root/out"
"$sixway" info --validate --report "$root/out/info.json" --force
"$sixway" bake --scene "$root/assets/scenes/plume.json" --frames 8 --tile 64 --out "$root/out/flipbook" --force
echo "sixway: wrote $root/out/info.json and the flipbook in $root/out/flipbook"
