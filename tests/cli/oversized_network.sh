#!/usr/bin/env bash
# Weights whose graph makes a network the device cannot hold even at the smallest lightmaps: the line names
# the weights file and the graph's field, with the size the map needs (it blamed the scene's
# render.lightmap_size, with a size that had wrapped 32 bits).
# Usage: oversized_network.sh SIXWAY SCENE WEIGHTS DIR
set -u
sixway=$1 scene=$2 weights=$3 dir=$4
rm -rf "$dir" && mkdir -p "$dir" || exit 1
. "$(dirname "$0")/expect_refused.sh"
widen() { python3 "$(dirname "$0")/widen_network.py" "$weights" "$dir/$1" "$2" "$3" || exit 1; }

# At 4096x4096, 64 channels take more than 4 GiB: beyond any device's storage-buffer range.
widen padded.safetensors 4096 64
expect_refused "^sixway: error: $dir/padded.safetensors: sixway.graph.size_multiple is 4096: it pads 16×16 \
lightmaps to 4096×4096, where padded.safetensors [a-z.0-9]+ needs a storage buffer of [0-9.]+ [GM]iB, more \
than the [0-9.]+ [GM]iB that .* can bind; reduce it$" \
  "$sixway" render --scene "$scene" --frames 1 --mode neural --weights "$dir/padded.safetensors" --out "$dir/r1"
widen wrapped.safetensors 1000000000 8
expect_refused "^sixway: error: $dir/wrapped.safetensors: sixway.graph.size_multiple: must be in \[1, 4096\] \
\(got 1000000000\)$" \
  "$sixway" render --scene "$scene" --frames 1 --mode neural --weights "$dir/wrapped.safetensors" --out "$dir/r2"
[ ! -e "$dir/r1" ] && [ ! -e "$dir/r2" ] || { echo "FAILED: an output folder was left"; status=1; }
exit $status
