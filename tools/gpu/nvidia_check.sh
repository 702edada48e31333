#!/bin/bash
# Issue #24 on a lent NVIDIA machine (docs/gpu.md), in one call: the suite under validation on NVIDIA's
# Vulkan driver, `sixway bench` at the default and the paper's sizes, and the model study's larger networks
# trained with PyTorch on the GPU from a dataset made there by `sixway dataset` (same config and seed as
# data/inputs here). Needs .gl/ (Debian's Vulkan loader and libglvnd as .debs) and .dev/bundle.tar.xz
# (tools/gpu/bundle.sh). Every step has a deadline so that the results come back inside the call.
#
# Usage: tools/gpu/nvidia_check.sh [seconds]   (default 520; results in $OUT or out/gpu)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
budget=${1:-520}
start=$(date +%s)
left() { echo $((start + budget - $(date +%s))); }
step() { echo "== $(($(date +%s) - start)) s: $*"; }
out=${OUT:-$root/out/gpu}
work="$root/.dev/results"
mkdir -p "$out" "$work"
exec > >(tee "$out/log.txt") 2>&1

step "set-up"
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
tar -xJf .dev/bundle.tar.xz -C .dev
rm -rf build && mv .dev/build build
# The build's test lists and compiled-in paths name /work/main.
if [[ $root != /work/main ]]; then
  [[ -e /work/main ]] && { echo "/work/main exists already; the build's paths would not resolve"; exit 1; }
  mkdir -p /work && ln -s "$root" /work/main
fi
for tool in cmake ctest; do [[ -x /usr/bin/$tool ]] || ln -s "$(command -v $tool)" /usr/bin/$tool; done
icd=$(ls /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
  /etc/vulkan/icd.d/nvidia_icd.json 2>/dev/null | head -1)
[[ -n $icd ]] || icd=$(find / -xdev -name 'nvidia_icd*.json' 2>/dev/null | head -1)
echo "ICD manifest: $icd"
# Our executables get the bundled libraries; PyTorch keeps the machine's own.
vk=(env LD_LIBRARY_PATH="$root/.dev/lib" VK_LAYER_PATH="$root/.dev/layers" VK_DRIVER_FILES="$icd"
  VK_ICD_FILENAMES="$icd")
sixway=build/src/app/sixway
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv
"${vk[@]}" $sixway info

step "dataset (4 workers) beside the suite (which fills the driver's shader cache for the benchmarks)"
workers=()
for i in 0 1 2 3; do
  "${vk[@]}" timeout 240 $sixway dataset --config tools/datasets/studies/inputs.json --out data/inputs \
    --shard $i/4 >"$work/dataset_$i.log" 2>&1 &
  workers+=($!)
done
# Left out: what the machine lacks, not the driver (docs/gpu.md): an X server, a compiler, ffmpeg, Debian's Python.
(cd build && "${vk[@]}" SIXWAY_VALIDATE=1 timeout 240 ctest -j16 --timeout 200 -LE long \
  -E '^(nn\.python_|demo\.|runtime\.public_headers_alone|cli\.render_outputs)' \
  --output-junit "$work/ctest.xml" >"$work/ctest.log" 2>&1)
step "suite done (exit $?)"
tail -n 25 "$work/ctest.log"
wait "${workers[@]}"
step "dataset done: $(ls data/inputs/shard_*.safetensors 2>/dev/null | wc -l) shards"

# A step gets at most its own limit and never more than leaves 40 s for packing the results.
limit() { local t=$(($(left) - 40)); ((t < $1)) && echo $t || echo $1; }
bench() {  # report name, then sixway bench options
  local name=$1 t
  shift
  t=$(limit 120)
  ((t > 10)) || { step "bench $name skipped: no time left"; return; }
  step "bench $name: $*"
  "${vk[@]}" timeout $t $sixway bench --warmup 5 --repeats 20 --report "$work/bench_$name.json" "$@"
}
# The targets first (network at 256² in fp16, the frame, the LBM against a copy), then the rest.
for tiling in pixels blocks; do
  bench "network_${tiling}_fp16" --sections network --size 256 512 --tiling "$tiling" --fp16
done
bench frame --sections frame lightmaps --grid 64x128x64 --size 256 --frame-lightmaps 256
bench sim --sections sim --population-storage fp32 fp16 --repeats-large 10
if (($(limit 60) > 10)); then
  step "stream_bound_bench"
  "${vk[@]}" timeout "$(limit 60)" build/tests/sim/stream_bound_bench 20
fi
for tiling in pixels blocks; do
  bench "network_$tiling" --sections network --size 256 512 --tiling "$tiling"
done
for weights in .dev/study/*.safetensors; do
  [[ -f $weights ]] && bench "$(basename "$weights" .safetensors)" --sections network --size 256 --weights "$weights" --fp16
done

trainers=()
if [[ $(ls data/inputs/shard_*.safetensors 2>/dev/null | wc -l) == 16 ]]; then
  for cfg in base wide wider levels4; do
    python3 tools/train.py --config tools/train_configs/gpu/${cfg}_long_ms.json --out data/gpu_$cfg --force \
      >"$work/train_$cfg.log" 2>&1 &
    trainers+=($!)
  done
fi
while (($(left) > 30)) && [[ -n $(jobs -pr) ]]; do sleep 5; done
step "trainings: $(jobs -pr | wc -l) still running (stopped now)"
kill "${trainers[@]}" 2>/dev/null
sleep 2
for cfg in base wide wider levels4; do
  dir=data/gpu_$cfg
  [[ -d $dir ]] || continue
  mkdir -p "$work/$cfg"
  cp "$dir"/{config.json,log.jsonl,metrics.json,sixway-unet.safetensors} "$work/$cfg/" 2>/dev/null
  # An unfinished training's checkpoint comes back on its own (a file may be 16 MiB at most).
  [[ -f $dir/sixway-unet.safetensors ]] || cp "$dir/checkpoint.pt" "$out/checkpoint_$cfg.pt" 2>/dev/null
  tail -n 3 "$work/train_$cfg.log"
done
tar -C .dev -czf "$out/results.tar.gz" results
step "done"
