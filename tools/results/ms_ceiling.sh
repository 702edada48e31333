#!/usr/bin/env bash
# The six-way ceiling under full transport on every shipped scene: `sixway eval --scene` of each
# assets/scenes/*.json (but bench.json) at a small size (128x128 frames, 64x64 lightmaps), against the path
# tracer with every scattering order, printed as a markdown table of masked PSNRs (reference-ms: the
# multiply-scattered lightmaps through the six-way shading; reference: single scattering; neural;
# traditional-ms: a flipbook baked with multiple scattering), then each method's frame-to-frame change over the
# truth's (RMS where the smoke is; the truth traced twice a frame to take its noise out: `--truth-noise`). The
# obstacles are left out of every image (`--no-obstacles`): the study is of the lightmaps. No equal-time study
# (tools/results.sh makes it at the default size).
# About 10-15 minutes on the 2-core lavapipe machine. FRAMES=N (default 8) SPP=N (truth, default 128)
# LIGHTMAP=N (lightmap size, default 64: half the frame's; 128 separates the lightmaps' resolution from the
# six-way model) WEIGHTS=ms|ss|PATH (the network, default ms); reports go to out/ms_ceiling/lightmap_N/, or
# out/ms_ceiling/lightmap_N_ss or out/ms_ceiling/lightmap_N_<name> with WEIGHTS=PATH (the file's directory).
# WARMUP=N (default 0) first simulates N frames unseen (scenes with their own warm-up keep it): the smoke developed
# rather than the first puffs at the inlet; reports then go to a directory ending in _warmN. SCENES="plume jet_plume"
# (default: every scene) evaluates only those; the table lists every report in the directory. MS_SPP=N (default 64)
# traces reference-ms's and traditional-ms's orders >= 2 with N samples per texel (their own noise, which adds to
# their frame-to-frame change, falls as 1/N); reports then go to a directory ending in _msspp<N>.
# tools/results/ceiling_change.py takes two such directories (N and 4N) to their change without that noise.
# FIT=N (default 0: none) also measures reference-fit, the six maps fitted to the smoke lit from N directions
# (`--fit-directions N`, about N/6 times reference-ms's cost), its column first; reports then go to a directory
# ending in _fit<N>.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
frames="${FRAMES:-8}"
spp="${SPP:-128}"
lightmap="${LIGHTMAP:-64}"
warmup="${WARMUP:-0}"
ms_spp="${MS_SPP:-64}"
fit="${FIT:-0}"
for name in ${SCENES:-}; do
  [ -f "$root/assets/scenes/$name.json" ] || { echo "ms_ceiling.sh: SCENES: no assets/scenes/$name.json" >&2; exit 2; }
done
python=/usr/bin/python3
weights="${WEIGHTS:-ms}"
out="$root/out/ms_ceiling/lightmap_$lightmap"
case "$weights" in ms) ;; ss) out="${out}_ss" ;; *) out="${out}_$(basename "$(dirname "$weights")")" ;; esac
[ "$warmup" = 0 ] || out="${out}_warm$warmup"
[ "$ms_spp" = 64 ] || out="${out}_msspp$ms_spp"
[ "$fit" = 0 ] || out="${out}_fit$fit"
sixway="${SIXWAY:-$root/build/src/app/sixway}"
[ -x "$sixway" ] || source "$root/tools/build.sh"
mkdir -p "$out"
for scene in "$root"/assets/scenes/*.json; do
  name=$(basename "$scene" .json)
  [ "$name" = bench ] && continue
  [ -z "${SCENES:-}" ] || [[ " $SCENES " == *" $name "* ]] || continue
  small="$out/$name.json"
  "$python" "$root/tools/results/resized_scene.py" "$scene" "$small" --size 128 --lightmap "$lightmap" --warmup "$warmup"
  echo "ms_ceiling.sh: $name" >&2
  "$sixway" eval --scene "$small" --frames "$frames" --spp "$spp" --orders 64 --ms-spp "$ms_spp" --weights "$weights" \
    --fit-directions "$fit" --truth-noise --no-equal-time --no-obstacles --report "$out/$name.report.json" --force >&2
done
"$python" - "$out" <<'PY'
import glob, json, os, sys
reports = sorted(glob.glob(os.path.join(sys.argv[1], "*.report.json")))
fitted = any("reference-fit" in json.load(open(p))["methods"] for p in reports)
methods = ["reference-fit"] * fitted + ["reference-ms", "reference", "neural", "traditional-ms", "traditional"]
changes = ["neural", "reference-ms", "traditional-ms"]
print("| scene | " + " | ".join(methods) + " | truth's change | " + " | ".join(f"{m} change" for m in changes) + " |")
print("|---|" + "---|" * (len(methods) + 1 + len(changes)))
for path in reports:
    summary = json.load(open(path))["summary"]
    image, temporal = summary["image"], summary.get("temporal") or {}
    name = os.path.basename(path).removesuffix(".report.json")
    truth = temporal.get("truth", {}).get("rms_without_noise")
    ratios = [temporal.get("methods", {}).get(m, {}).get("rms_ratio") for m in changes]
    print(f"| {name} | " + " | ".join(f"{image[m]['psnr_masked_db']:.2f}" for m in methods)
          + (f" | {truth:.4f} | " if truth is not None else " | – | ")
          + " | ".join(f"{r:.2f}×" if r is not None else "–" for r in ratios) + " |")
PY
