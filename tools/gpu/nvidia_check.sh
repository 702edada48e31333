#!/bin/bash
# sixway on a lent NVIDIA machine (docs/gpu.md), in one call: the whole suite under validation on NVIDIA's
# Vulkan driver, `sixway bench` at the paper's sizes (the network in each tiling, the lightmaps and the whole
# frame, the lattices, the lattice against the memory), and the default run's frames with their GPU timings.
# Needs .gl/ (Debian's Vulkan loader and libglvnd as .debs) and .dev/bundle.tar.xz (tools/gpu/bundle.sh). Every
# step has a deadline so that the results come back inside the call.
#
# Usage: tools/gpu/nvidia_check.sh [seconds]   (default 480; results in $OUT or out/gpu)
set -u
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
budget=${1:-480}
start=$(date +%s)
left() { echo $((start + budget - $(date +%s))); }
step() { echo "== $(($(date +%s) - start)) s: $*"; }
out=${OUT:-$root/out/gpu}
work="$root/.dev/results"
mkdir -p "$out" "$work"
exec > >(tee "$out/log.txt") 2>&1

source tools/gpu/device_setup.sh
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm,clocks.max.mem --format=csv
"${vk[@]}" $sixway info

# A step gets at most its own limit and never more than leaves 30 s for packing the results.
limit() { local t=$(($(left) - 30)); ((t < $1)) && echo $t || echo $1; }

# The cooperative-matrix kernel and the networks built on it first (they are new on this driver), then the rest
# of the suite, long tests included. Left out: what the machine lacks, not the driver (docs/gpu.md): an X
# server, a compiler, ffmpeg, Debian's Python.
step "cooperative-matrix tests"
(cd build && "${vk[@]}" SIXWAY_VALIDATE=1 timeout "$(limit 90)" ctest -j16 --timeout 80 \
  -R 'ConvMatrix|NetworkParity' --output-on-failure >"$work/ctest_matrix.log" 2>&1)
step "cooperative-matrix tests done (exit $?)"
grep -E "NMSE|max-abs|tests passed|Failed|\*\*\*|Skipped" "$work/ctest_matrix.log" | head -n 80
step "the suite"
(cd build && "${vk[@]}" SIXWAY_VALIDATE=1 timeout "$(limit 200)" ctest -j16 --timeout 150 \
  -E '^(nn\.python_|demo\.|runtime\.public_headers_alone|cli\.render_outputs)|ConvMatrix|NetworkParity' \
  --output-junit "$work/ctest.xml" >"$work/ctest.log" 2>&1)
step "suite done (exit $?)"
tail -n 30 "$work/ctest.log"

bench() {  # report name, then sixway bench options
  local name=$1 t
  shift
  t=$(limit 100)
  ((t > 10)) || { step "bench $name skipped: no time left"; return; }
  step "bench $name: $*"
  "${vk[@]}" timeout $t $sixway bench --warmup 5 --repeats 20 --report "$work/bench_$name.json" "$@"
}
# The targets first: the network at 256² in fp16 (each tiling), the frame, the lattice against the memory.
for tiling in matrix pixels; do
  bench "network_${tiling}_fp16" --sections network --size 256 512 --tiling "$tiling" --fp16
done
bench frame_fp16 --sections frame lightmaps --grid 64x128x64 --size 256 --frame-lightmaps 256 --fp16
bench sim --sections sim --population-storage fp32 fp16 --repeats-large 10
if (($(limit 60) > 10)); then
  step "stream_bound_bench"
  "${vk[@]}" timeout "$(limit 60)" build/tests/sim/stream_bound_bench 20
fi
bench frame_fp32 --sections frame --grid 64x128x64 --frame-lightmaps 256
# The default run (tools/run.sh): the showcase's 64 frames, their per-stage GPU timings.
for precision in fp16 fp32; do
  t=$(limit 90)
  ((t > 20)) || break
  step "the default run's frames ($precision maps)"
  flags=()
  [[ $precision == fp16 ]] && flags=(--fp16)
  "${vk[@]}" timeout "$t" $sixway render --scene assets/scenes/showcase.json --frames 64 --force \
    --out "$work/render_$precision" "${flags[@]}" | tail -n 4
  rm -f "$work/render_$precision"/frame_00[0-4]*.png "$work/render_$precision"/frame_005[0-8].png
done
bench network_blocks_fp16 --sections network --size 256 --tiling blocks --fp16
# The model study's networks (tools/gpu/bundle.sh packs those trained here), where there are any.
for weights in .dev/study/*.safetensors; do
  [[ -f $weights ]] && bench "$(basename "$weights" .safetensors)" --sections network --size 256 --weights "$weights" --fp16
done

tar -C .dev -czf "$out/results.tar.gz" results
step "done"
