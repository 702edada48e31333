#!/bin/bash
# Packs what an NVIDIA machine without our Debian packages needs to run the build (docs/gpu.md): the build tree without objects (executables stripped), the shared libraries they load
# beyond the C/C++ runtime, Khronos' validation layer, and the study networks to time. Writes
# .dev/bundle.tar.xz, which tools/gpu/nvidia_check.sh unpacks on the device machine.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT

# The build tree as ctest reads it: test lists, executables, scripts; no objects or archives.
cp -a build "$stage/build"
find "$stage/build" \( -name CMakeFiles -o -name Testing -o -name artifacts \) -prune -exec rm -rf {} +
find "$stage/build" \( -name '*.o' -o -name '*.a' \) -delete
find "$stage/build" -type f -executable -exec sh -c '[ "$(head -c4 "$1" | tail -c3)" = ELF ] && strip --strip-unneeded "$1"' _ {} \;

# Every shared library the executables load, except the C and C++ runtime the device machine has newer.
mkdir -p "$stage/lib" "$stage/layers"
find build -type f -executable -exec sh -c '[ "$(head -c4 "$1" | tail -c3)" = ELF ] && ldd "$1"' _ {} \; |
  awk '/=>/ {print $3}' | sort -u |
  grep -vE '/(libc|libm|libstdc\+\+|libgcc_s|libpthread|libdl|librt)\.so' |
  while read -r lib; do cp -L "$lib" "$stage/lib/"; done
strip --strip-unneeded "$stage"/lib/*.so*

# Khronos' validation layer (the suite runs with it on), its manifest pointing next to itself.
cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$stage/layers/"
strip --strip-unneeded "$stage/layers/libVkLayer_khronos_validation.so"
sed 's#"library_path": *"[^"]*"#"library_path": "./libVkLayer_khronos_validation.so"#' \
  /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >"$stage/layers/VkLayer_khronos_validation.json"

# The trained networks of the model study (lavapipe's and the GPU's), timed beside the shipped ones.
mkdir -p "$stage/study"
for dir in data/study_model_*_ms data/gpu_*; do
  [[ -f $dir/sixway-unet.safetensors ]] && cp "$dir/sixway-unet.safetensors" "$stage/study/$(basename "$dir").safetensors"
done

mkdir -p .dev
tar -C "$stage" -cf - build lib layers study | xz -T2 -6 >.dev/bundle.tar.xz
du -h .dev/bundle.tar.xz
