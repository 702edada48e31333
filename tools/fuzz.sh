#!/usr/bin/env bash
# The long fuzz pass: configures build-fuzz (clang, libFuzzer, ASan + UBSan), builds every target
# of tests/fuzz/ and runs each for SECONDS (default 600) over its committed seeds, one after the other. New
# inputs collect in build-fuzz/tests/fuzz/work/<target>/corpus (kept between runs); a crash, hang, leak or
# sanitizer report stops that target with the input saved there, the others still run, and the pass exits 1
# naming the targets with findings. docs/robustness.md, "Fuzzing".
#   tools/fuzz.sh [SECONDS] [TARGET...]     e.g. tools/fuzz.sh 60 scene obj
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-600}"
shift $(($# > 0 ? 1 : 0))
build="$root/build-fuzz"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DSIXWAY_FUZZ=ON -DSIXWAY_FUZZ_SECONDS="$seconds" \
  "${launcher[@]}"
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in "$root"/tests/fuzz/corpus/*/; do targets+=("$(basename "$dir")"); done
fi
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"
found=()
for target in "${targets[@]}"; do
  ctest --test-dir "$build" --output-on-failure -R "^fuzz\.${target}\$" || found+=("$target")
done
if [ ${#found[@]} -gt 0 ]; then
  echo "fuzz.sh: findings in ${found[*]} (inputs in $build/tests/fuzz/work/<target>/)" >&2
  exit 1
fi
