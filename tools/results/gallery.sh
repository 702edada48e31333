#!/usr/bin/env bash
# The gallery that opens docs/results.md: one side-by-side strip per shipped scene
# (assets/scenes/*.json but bench.json) at a size where the smoke's detail shows: `sixway eval --scene` of three
# frames after a warm-up, the camera orbiting 45 degrees a frame (0, 45, 90), at SIZE x SIZE pixels (default 256)
# with the default run's 64x64 lightmaps, against the path tracer with every scattering order (GALLERY_SPP
# samples, default 64). The strip shows the last frame, 90 degrees from the first: truth | neural | reference
# (exact single scattering) | traditional-ms (the flipbook baked with multiple scattering from the first frame's
# view, as games ship it), then the three errors. Writes out/results/gallery/<scene>/{report.json,strip.png} and
# docs/results/gallery_<scene>.png.
#
# Scenes that start empty are warmed up WARMUP frames (default 90: 3 s of scene time, as the showcase, the smoke past the
# obstacles); a scene with its own warmup_frames (the showcase) keeps it. About 3-6 minutes a scene on the
# 2-core lavapipe machine (the warm-up's simulation and the 256x256 truths dominate).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
size="${SIZE:-256}"
spp="${GALLERY_SPP:-64}"
warmup="${WARMUP:-90}"
python=/usr/bin/python3
sixway="${SIXWAY:-$root/build/src/app/sixway}"
out="$root/out/results/gallery"
[ -x "$sixway" ] || source "$root/tools/build.sh"
mkdir -p "$out" "$root/docs/results"
for scene in "$root"/assets/scenes/*.json; do
  name=$(basename "$scene" .json)
  [ "$name" = bench ] && continue
  [ -n "${SCENES:-}" ] && [[ " $SCENES " != *" $name "* ]] && continue
  mkdir -p "$out/$name"
  "$python" "$root/tools/results/resized_scene.py" "$scene" "$out/$name/scene.json" --size "$size" --lightmap 64 \
    --warmup "$warmup"
  echo "gallery.sh: $name"
  "$sixway" eval --scene "$out/$name/scene.json" --frames 3 --camera-orbit 45 --spp "$spp" --orders 64 --no-equal-time \
    --out "$out/$name" --report "$out/$name/report.json" --force >"$out/$name/eval.log" 2>&1
  cp "$out/$name/strip.png" "$root/docs/results/gallery_$name.png"
done
