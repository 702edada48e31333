#!/bin/bash
# A training recipe (docs/training.md) on a lent NVIDIA machine, in one call: its data made by the bundled
# sixway on NVIDIA's Vulkan driver, its phases on the GPU under the recipe's gpu profile, as far as the deadline
# allows (SIGTERM then: the data's time is kept, each phase resumes from its checkpoint). Brings back in $OUT the
# recipe's summary, its data seconds, each phase's config, log and metrics, and the network once every phase has
# run. Another call on the still-warm machine continues where this one stopped (data/ stays between calls).
# Needs .gl/ and .dev/bundle.tar.xz, as tools/gpu/nvidia_check.sh.
#
# Usage: tools/gpu/recipe_run.sh [seconds] [recipe]   (defaults 540, ms; results in $OUT or out/gpu_recipe)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
budget=${1:-540}
recipe=${2:-ms}
start=$(date +%s)
step() { echo "== $(($(date +%s) - start)) s: $*"; }
out=${OUT:-$root/out/gpu_recipe}
mkdir -p "$out"
exec > >(tee -a "$out/log.txt") 2>&1

source tools/gpu/device_setup.sh
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv
# sixway in its bundled environment; Python (the machine's, with PyTorch) in its own.
wrapper="$root/.dev/sixway_bundled"
{
  echo '#!/bin/bash'
  printf 'exec'
  printf ' %q' "${vk[@]}" "$root/$sixway"
  printf ' "$@"\n'
} >"$wrapper"
chmod +x "$wrapper"
"$wrapper" info | head -n 3

runs="$root/data/recipe_${recipe}_gpu"
step "recipe $recipe into $runs"
timeout --signal=TERM $((budget - 40 - ($(date +%s) - start))) \
  python3 tools/train.py --recipe "$recipe" --out "$runs" --profile gpu --sixway "$wrapper"
step "recipe stopped (exit $?)"

cp "$runs"/recipe.json "$runs"/data_seconds.json "$runs"/sixway-unet.safetensors "$out"/ 2>/dev/null
for phase in "$runs"/[0-9][0-9]_*; do
  [[ -d $phase ]] || continue
  mkdir -p "$out/$(basename "$phase")"
  cp "$phase"/config.json "$phase"/log.jsonl "$phase"/metrics.json "$out/$(basename "$phase")"/ 2>/dev/null
done
step "done"
