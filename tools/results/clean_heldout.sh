#!/bin/bash
# The held-out figure on the data with full-resolution all-orders targets, against cleaner targets: the
# held-out sequences of every `young_full*` config made again with the orders >= 2 traced at SPP samples per
# texel (default 64; the training data's are 16, whose noise the network is not meant to reproduce), then each
# network named on the command line evaluated on them in GLSL (`sixway eval --dataset DIR --split
# heldout_sequence --target multiple`), then the table of tools/results/heldout_table.py.
#
# Usage: tools/results/clean_heldout.sh LABEL=WEIGHTS [LABEL=WEIGHTS ...]   (WEIGHTS: a file, or ms / ss)
# Data: data/clean_heldout_sSPP/<config's path>/ holds only the held-out sequences' shards (each made by
# `sixway dataset --shard S/N`, which makes sequence S alone; the dataset.json that lists every shard is removed,
# so `sixway eval` reads the shards present). The flows are the configs' own held-out ones (the simulation and
# cameras do not depend on the target's samples), so no network has seen them. Reports: out/clean_heldout_sSPP/
# LABEL/, kept between calls like heldout.sh's. JOBS=N generators side by side (default 2).
# Time on the 2-core machine: about 20 minutes of generation at 64 samples, then half a minute a set a network.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
sixway="$root/build/src/app/sixway"
spp="${SPP:-64}"
jobs="${JOBS:-2}"
configs=(young_full/jet_plume young_full/jet_bunny young_full/moving_sphere
  young_full64/plume young_full64/jet_plume young_full64/jet_bunny young_full64/moving_sphere young_full64/explosion
  young_full128/plume young_full128/jet_plume young_full128/jet_bunny young_full128/moving_sphere
  young_full128/explosion)
[[ $# -ge 1 ]] || { echo "usage: $0 LABEL=WEIGHTS [LABEL=WEIGHTS ...]" >&2; exit 2; }
[[ $spp =~ ^[1-9][0-9]*$ ]] || { echo "clean_heldout.sh: SPP=$spp is not a positive integer" >&2; exit 2; }
data="data/clean_heldout_s$spp" out="out/clean_heldout_s$spp"
mkdir -p "$data/configs"

# One line per held-out shard to make: CONFIG OUT_DIR SEQUENCE SEQUENCES.
work=()
for config in "${configs[@]}"; do
  source_config="tools/datasets/families/$config.json"
  clean="$data/configs/${config//\//_}.json"
  /usr/bin/python3 - "$source_config" "$clean" "$spp" <<'PY'
import json, os, sys
source, clean, spp = sys.argv[1], sys.argv[2], int(sys.argv[3])
config = json.load(open(source))
# Paths (the base scene, meshes) are relative to the config's folder: make them absolute for the copy's.
def absolute(value):
    if isinstance(value, dict):
        return {k: absolute(v) for k, v in value.items()}
    if isinstance(value, list):
        return [absolute(v) for v in value]
    if isinstance(value, str) and value.startswith("../"):
        return os.path.abspath(os.path.join(os.path.dirname(source), value))
    return value
config = absolute(config)
config["multiple_scattering"] = {**config.get("multiple_scattering", {}), "samples": spp, "downsample": 1}
config["description"] = f"{source} with the orders >= 2 traced at {spp} samples per texel, full resolution: cleaner held-out targets (tools/results/clean_heldout.sh)."
text = json.dumps(config, indent=2) + "\n"
if not os.path.exists(clean) or open(clean).read() != text:
    open(clean, "w").write(text)
PY
  sequences=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["sequences"])' "$clean")
  for s in $(/usr/bin/python3 -c 'import json,sys; print(*json.load(open(sys.argv[1]))["heldout"]["sequences"])' "$clean"); do
    work+=("$clean $data/families/$config $s $sequences")
  done
done
printf '%s\n' "${work[@]}" | xargs -P "$jobs" -L 1 bash -c '
  shard=$(printf "%s/shard_%05d.safetensors" "$1" "$2")
  [[ -f $shard ]] && exit 0
  echo "clean_heldout.sh: $1 sequence $2" >&2
  mkdir -p "$1"
  nice "'"$sixway"'" dataset --config "$0" --out "$1" --shard "$2/$3" >"$1/make_$2.log" 2>&1 ||
    { echo "clean_heldout.sh: $1 sequence $2 failed: $1/make_$2.log" >&2; exit 255; }'
for config in "${configs[@]}"; do rm -f "$data/families/$config/dataset.json"; done

labels=() failed=0
for arg in "$@"; do
  label="${arg%%=*}" weights="${arg#*=}"
  [[ $label != "$arg" && -n $label && -n $weights ]] || { echo "clean_heldout.sh: '$arg' is not LABEL=WEIGHTS" >&2; exit 2; }
  labels+=("$label")
  mkdir -p "$out/$label"
  for config in "${configs[@]}"; do
    report="$out/$label/families_${config//\//_}.json"
    [[ -f $report ]] && continue
    echo "clean_heldout.sh: $label on $data/families/$config"
    "$sixway" eval --dataset "$data/families/$config" --split heldout_sequence --target multiple \
      --weights "$weights" --report "$report" >"${report%.json}.log" 2>&1 ||
      { echo "clean_heldout.sh: $label on $config failed: ${report%.json}.log" >&2; failed=1; }
  done
done
/usr/bin/python3 "$root/tools/results/heldout_table.py" "$out" "${labels[@]}"
exit $failed
