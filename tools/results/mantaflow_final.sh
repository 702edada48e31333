#!/usr/bin/env bash
# Final images of the held-out Mantaflow scenes (tools/datasets/families/mantaflow/*.json, made by
# tools/blender/make_mantaflow.sh) against the path tracer: `sixway eval --scene` of frame WARMUP (default 40) of
# each, 256² frames and 64² lightmaps, a camera at (5, 1.6, 3) looking at (1, 1.2, −1), SPP samples of the truth
# (default 32), every order; then a markdown table of masked PSNRs (neural, reference-ms, traditional-ms).
#
# Usage: tools/results/mantaflow_final.sh LABEL=WEIGHTS [LABEL=WEIGHTS ...]   (WEIGHTS: ms, ss or a file)
# Reports: out/mantaflow_final/LABEL/<scene>.report.json (kept; FORCE=1 makes them again). About a minute a
# scene and network on the 2-core machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
sixway="${SIXWAY:-$root/build/src/app/sixway}"
[ -x "$sixway" ] || source "$root/tools/build.sh"
[[ $# -ge 1 ]] || { echo "usage: $0 LABEL=WEIGHTS [LABEL=WEIGHTS ...]" >&2; exit 2; }
warmup="${WARMUP:-40}" spp="${SPP:-32}"
out="$root/out/mantaflow_final"
for pair in "$@"; do
  [[ $pair == *=* ]] || { echo "mantaflow_final.sh: '$pair' is not LABEL=WEIGHTS" >&2; exit 2; }
  label="${pair%%=*}" weights="${pair#*=}"
  mkdir -p "$out/$label"
  for scene in "$root"/tools/datasets/families/mantaflow/*.json; do
    name=$(basename "$scene" .json)
    report="$out/$label/$name.report.json"
    [ -f "$report" ] && [ "${FORCE:-0}" != 1 ] && continue
    copy="$out/$label/$name.scene.json"
    # The copy leaves the scene's folder: its file pattern becomes absolute.
    /usr/bin/python3 - "$scene" "$copy" "$warmup" <<'PY'
import json, os, sys
source, copy, warmup = sys.argv[1], sys.argv[2], int(sys.argv[3])
scene = json.load(open(source))
scene["vdb"]["pattern"] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(source)), scene["vdb"]["pattern"]))
scene["render"].update({"width": 256, "height": 256, "lightmap_size": 64, "warmup_frames": warmup})
scene["camera"] = {"position": [5.0, 1.6, 3.0], "target": [1.0, 1.2, -1.0], "fov_deg": 40.0}
json.dump(scene, open(copy, "w"), indent=1)
PY
    echo "mantaflow_final.sh: $label $name" >&2
    "$sixway" eval --scene "$copy" --frames 1 --spp "$spp" --orders 64 --weights "$weights" --no-equal-time \
      --report "$report" --force >&2
  done
done
/usr/bin/python3 - "$out" "$@" <<'PY'
import json, os, sys
out, labels = sys.argv[1], [pair.split("=", 1)[0] for pair in sys.argv[2:]]
methods = ["neural", "reference-ms", "traditional-ms"]
print("| scene | network | " + " | ".join(methods) + " |")
print("|---|---|" + "---|" * len(methods))
for label in labels:
    for name in sorted(f.removesuffix(".report.json") for f in os.listdir(os.path.join(out, label)) if f.endswith(".report.json")):
        image = json.load(open(os.path.join(out, label, f"{name}.report.json")))["summary"]["image"]
        print(f"| {name} | {label} | " + " | ".join(f"{image[m]['psnr_masked_db']:.2f}" for m in methods) + " |")
PY
