#!/usr/bin/env bash
# Bakes the Mantaflow sequences of tools/datasets/mantaflow/*.json (held out) and
# tools/datasets/mantaflow_train/*.json (trained on), or the configs given, into
# data/mantaflow/<name>/smoke_NNNN.vdb, where the played-back dataset families
# tools/datasets/families/mantaflow_{unseen,train}.json read them (docs/blender.md, "Mantaflow smoke"). A
# sequence already there is kept unless FORCE=1.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
configs=("$@")
((${#configs[@]})) || configs=("$root"/tools/datasets/mantaflow/*.json "$root"/tools/datasets/mantaflow_train/*.json)
mkdir -p "$root/data/mantaflow"
for config in "${configs[@]}"; do
  name="$(basename "$config" .json)"
  out="$root/data/mantaflow/$name"
  if [ -d "$out" ] && [ "${FORCE:-0}" != 1 ]; then
    echo "make_mantaflow: $name: kept ($out exists; FORCE=1 remakes it)"
    continue
  fi
  start=$(date +%s)
  blender -b --factory-startup --python-exit-code 1 --python "$root/tools/blender/mantaflow_smoke.py" -- \
    "$config" "$out" > "$root/data/mantaflow/$name.log" 2>&1 || {
    echo "make_mantaflow: $name failed; see data/mantaflow/$name.log" >&2
    exit 1
  }
  echo "make_mantaflow: $name: $(ls "$out"/smoke_*.vdb | wc -l) frames in $(($(date +%s) - start)) s"
done
