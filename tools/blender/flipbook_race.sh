#!/usr/bin/env bash
# The flipbook race (docs/blender.md, "Flipbooks from Blender"): a 64-frame Mantaflow cache (the campfire,
# frames 16-79) made into six-way flipbooks by `sixway bake` (the default: exact single scattering + traced
# orders) and by Cycles rendering the six lights per frame (what DCC exporters do), both against a
# high-sample Cycles reference on sampled frames. Prints wall times, agreement and the time Cycles needs to
# agree as well as the bake. Needs the build (tools/build.sh) and Blender; minutes on 2 cores.
#   tools/blender/flipbook_race.sh [OUT_DIR]   (default out/flipbook_race)
# Environment: TILE (64), REF_SPP (1024), SPPS ("16 64 256"), FRAMES (bake indices compared: "24 63").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out="${1:-$root/out/flipbook_race}"
tile="${TILE:-64}" ref_spp="${REF_SPP:-1024}" spps="${SPPS:-16 64 256}" frames="${FRAMES:-24 63}"
sixway="$root/build/src/app/sixway" compare="$root/build/tests/blender/compare_lightmaps"
blender=(blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/cycles_lightmaps.py" --)
"$root/tools/blender/make_mantaflow.sh" "$root/tools/datasets/mantaflow/campfire.json"
mkdir -p "$out"
files=()
for i in $(seq 16 79); do files+=("$(printf '%s/data/mantaflow/campfire/smoke_%04d.vdb' "$root" "$i")"); done
start=$(date +%s%N)
"$sixway" bake --vdb "${files[@]}" --out "$out/bake" --force --tile "$tile" --voxels native --emission 2 \
  --camera-position 4 -5 2.5 --camera-target 1 1 1.2 --camera-up 0 0 1 > "$out/bake.log"
ms=$((($(date +%s%N) - start) / 1000000))
echo "sixway bake: 64 frames, ${tile}² tiles, all orders: $((ms / 1000)).$(printf '%03d' $((ms % 1000))) s wall," \
  "$((ms / 64)) ms a frame" | tee "$out/race.txt"
cycles() {  # FRAME OUT SPP SEED: Cycles' six maps of a baked frame
  "${blender[@]}" --flipbook "$out/bake/flipbook.json" --frame "$1" --out "$2" --spp "$3" --seed "$4" > "$2.log" 2>&1 ||
    { echo "flipbook_race: Cycles failed; see $2.log" >&2; exit 1; }
}
for frame in $frames; do
  ref="$out/reference_${frame}_${tile}px_${ref_spp}spp"
  [ -f "$ref/cycles.json" ] || cycles "$frame" "$ref" "$ref_spp" 9
  baked="$(printf '%s/bake/frames/frame_%04d.exr' "$out" "$frame")"
  agreement=$("$compare" "$baked" "$ref")
  echo "frame $frame: sixway bake: $agreement (light, emissive, alpha dB against Cycles at $ref_spp spp)" |
    tee -a "$out/race.txt"
  for spp in $spps; do
    run="$out/cycles_${frame}_$spp"
    cycles "$frame" "$run" "$spp" 1
    seconds=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["render_seconds"])' "$run/cycles.json")
    agreement=$("$compare" "$run" "$ref")
    echo "frame $frame: Cycles $spp spp, $seconds s: $agreement" | tee -a "$out/race.txt"
  done
done
