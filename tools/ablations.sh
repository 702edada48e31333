#!/usr/bin/env bash
# The ablations that need retrained networks (docs/results.md, "Ablations"): the guide lights
# (front only; front, left and right; front, top and bottom as shipped) and the NAFBlock channel adapters
# (with, without). Every variant trains for the same budget (tools/train_configs/ablations/*.json: 1,000 steps of
# the shipped network's recipe) on the same sequences, cameras and targets (tools/datasets/cpu_small.json and its
# guide-light variants in tools/datasets/ablations/), and is measured on the held-out splits by the C++ pipeline
# (`sixway eval --dataset`: GLSL inference on the exported file). Writes out/ablations/<variant>/ and the table
# docs/results/ablations.md, which docs/results.md includes.
#
# About 1.5-2 hours on the 2-core machine (three datasets of 7 minutes, four trainings of 10-20 minutes, the
# evaluations); the datasets are kept in DATA (default data/) and reused, a finished training is reused and an
# interrupted one resumed from its last checkpoint (every 250 steps) unless FORCE=1. Not part of tools/results.sh's default run: ABLATIONS=1 tools/results.sh runs it too.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${DATA:-$root/data}"
out="$root/out/ablations"
python=/usr/bin/python3
sixway="${SIXWAY:-$root/build/src/app/sixway}"
[ -x "$sixway" ] || source "$root/tools/build.sh"
mkdir -p "$data" "$out" "$root/docs/results"

# variant, dataset config, dataset directory. Every dataset is made here with the current simulation (the
# baseline's too, rather than reusing data/cpu_small, which an older build may have made), so that the variants
# differ only in what they ablate.
variants=(
  "baseline tools/datasets/cpu_small.json cpu_small_guide_front_top_bottom"
  "guide_front tools/datasets/ablations/cpu_small_guide_front.json cpu_small_guide_front"
  "guide_front_left_right tools/datasets/ablations/cpu_small_guide_front_left_right.json cpu_small_guide_front_left_right"
  "no_adapters tools/datasets/cpu_small.json cpu_small_guide_front_top_bottom"
)
for entry in "${variants[@]}"; do
  read -r variant config dataset <<<"$entry"
  echo "ablations.sh: $variant"
  # Resumable: a complete dataset is only checked.
  "$sixway" dataset --config "$root/$config" --out "$data/$dataset"
  if [ -n "${FORCE:-}" ] || { [ ! -f "$out/$variant/sixway-unet.safetensors" ] && [ ! -f "$out/$variant/checkpoint.pt" ]; }; then
    "$python" "$root/tools/train.py" --config "$root/tools/train_configs/ablations/$variant.json" \
      --data "$data/$dataset" --out "$out/$variant" --force
  elif [ ! -f "$out/$variant/sixway-unet.safetensors" ]; then  # an interrupted training goes on where it stopped
    "$python" "$root/tools/train.py" --resume --data "$data/$dataset" --out "$out/$variant"
  fi
  "$sixway" eval --dataset "$data/$dataset" --weights "$out/$variant/sixway-unet.safetensors" \
    --report "$out/$variant/eval.json" --force
done
"$python" "$root/tools/results/ablation_table.py" "$out" >"$root/docs/results/ablations.md"
echo "ablations.sh: wrote docs/results/ablations.md"
