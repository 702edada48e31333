#!/bin/bash
# Issue #24: the second call on a still-warm device machine after tools/gpu/nvidia_check.sh (docs/gpu.md).
# The first call leaves data/inputs and the model study's trainings (data/gpu_*) on the machine when its
# deadline stops them; this one resumes each from its checkpoint for at most SECONDS and packs what they
# exported (or their checkpoints) into $OUT.
#
# Usage: tools/gpu/train_more.sh [seconds]   (default 230)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
seconds=${1:-230}
out=${OUT:-$root/out/gpu}
mkdir -p "$out/r"
for cfg in base wide wider levels4; do
  [[ -f data/gpu_$cfg/checkpoint.pt ]] || { echo "$cfg: no checkpoint in data/gpu_$cfg"; continue; }
  timeout "$seconds" python3 tools/train.py --out data/gpu_$cfg --resume >"data/train_$cfg.log" 2>&1 &
done
wait
for cfg in base wide wider levels4; do
  [[ -d data/gpu_$cfg ]] || continue
  tail -n 4 "data/train_$cfg.log"
  mkdir -p "$out/r/$cfg"
  cp data/gpu_$cfg/{config.json,log.jsonl,metrics.json,sixway-unet.safetensors} "$out/r/$cfg/" 2>/dev/null
  # An unfinished training's checkpoint comes back on its own (a file may be 16 MiB at most).
  [[ -f data/gpu_$cfg/sixway-unet.safetensors ]] || cp "data/gpu_$cfg/checkpoint.pt" "$out/checkpoint_$cfg.pt"
done
tar -C "$out" -czf "$out/trained.tar.gz" r && rm -rf "$out/r"
