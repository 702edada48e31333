#!/bin/bash
# The model study (docs/network-study.md, "The model study"): for the base network and each variant
# trained by tools/train_configs/studies/model_<variant>_ms.json into data/study_model_<variant>_ms, the held-out
# PSNR in GLSL (`sixway eval --dataset data/inputs --target multiple`) and the network's time on this device
# (`sixway bench --sections network`), then the table (tools/results/model_study_table.py); a variant also trained
# against the single-scattering targets (data/study_model_<variant>_ss) is evaluated against those too.
#
# The base is the plume-only MS network shipped before commit cd51124 (inputs_4ch_guide_alpha_ms.json: the same
# data, steps and seed as the variants); it is taken from git history.
#
# Usage: tools/results/model_study.sh [variant ...]   (default: every variant with a trained network)
# Time on the 2-core machine: about 1 minute of evaluation and 1-3 minutes of benchmark per variant; run it on
# an otherwise idle machine, since the benchmark is timed.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
sixway="$root/build/src/app/sixway"
out="$root/out/model_study"
mkdir -p "$out"

if [[ ! -f "$out/base.safetensors" ]]; then
  git show cd51124^:weights/sixway-unet-ms.safetensors >"$out/base.safetensors"
fi
variants=("$@")
if [[ ${#variants[@]} -eq 0 ]]; then
  variants=(base)
  for dir in data/study_model_*_ms; do
    [[ -f "$dir/sixway-unet.safetensors" ]] || continue
    name="${dir#data/study_model_}"
    variants+=("${name%_ms}")
  done
fi

for v in "${variants[@]}"; do
  weights="data/study_model_${v}_ms/sixway-unet.safetensors"
  [[ $v == base ]] && weights="$out/base.safetensors"
  echo "model_study.sh: $v ($weights)"
  "$sixway" eval --dataset data/inputs --target multiple --weights "$weights" --report "$out/${v}_eval.json" \
    --force >"$out/${v}_eval.log" 2>&1
  "$sixway" bench --sections network --size 128 256 --repeats 7 --weights "$weights" \
    --report "$out/${v}_bench.json" --force >"$out/${v}_bench.log" 2>&1
  # The same variant trained against the single-scattering targets, where it was (model_<variant>_ss.json).
  ss="data/study_model_${v}_ss/sixway-unet.safetensors"
  if [[ -f $ss ]]; then
    "$sixway" eval --dataset data/inputs --target single --weights "$ss" --report "$out/${v}_ss_eval.json" \
      --force >"$out/${v}_ss_eval.log" 2>&1
  fi
done
/usr/bin/python3 "$root/tools/results/model_study_table.py" "$out"
