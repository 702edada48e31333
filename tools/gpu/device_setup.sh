# Sourced by the scripts a lent NVIDIA machine runs (docs/gpu.md): unpacks Debian's Vulkan loader (.gl/) and the
# build bundle (.dev/bundle.tar.xz, tools/gpu/bundle.sh) once per machine, links /work/main to this copy (the
# build's compiled-in paths name it), finds NVIDIA's ICD, and sets `vk` (the environment our executables run
# in: the bundled libraries and validation layer) and `sixway`. Needs `root` and `step` from the caller.
step "set-up"
if [[ ! -e .dev/unpacked ]]; then  # a warm machine's second call keeps the first one's
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
  tar -xJf .dev/bundle.tar.xz -C .dev
  rm -rf build && mv .dev/build build
  touch .dev/unpacked
fi
if [[ $root != /work/main ]]; then
  [[ -e /work/main ]] || { mkdir -p /work && ln -s "$root" /work/main; }
  [[ "$(readlink -f /work/main)" == "$(readlink -f "$root")" ]] ||
    { echo "/work/main exists already; the build's paths would not resolve"; exit 1; }
fi
for tool in cmake ctest; do [[ -x /usr/bin/$tool ]] || ln -s "$(command -v $tool)" /usr/bin/$tool; done
icd=$(ls /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json /usr/share/vulkan/icd.d/nvidia_icd.json \
  /etc/vulkan/icd.d/nvidia_icd.json 2>/dev/null | head -1)
[[ -n $icd ]] || icd=$(find / -xdev -name 'nvidia_icd*.json' 2>/dev/null | head -1)
echo "ICD manifest: $icd"
vk=(env LD_LIBRARY_PATH="$root/.dev/lib" VK_LAYER_PATH="$root/.dev/layers" VK_DRIVER_FILES="$icd"
  VK_ICD_FILENAMES="$icd")
sixway=build/src/app/sixway
