#!/bin/bash
# The held-out table: each network named on the command line, evaluated in GLSL (`sixway eval --dataset
# DIR --target multiple`) on the held-out splits of every family dataset the MS networks train on, plus the
# unseen family (data/families/chimney_wind); then one markdown table, a column per network
# (tools/results/heldout_table.py). A family whose dataset is not on this machine is skipped and named.
#
# Usage: tools/results/heldout.sh LABEL=WEIGHTS [LABEL=WEIGHTS ...]   (WEIGHTS: a file, or ms / ss)
# Reports go to out/heldout/LABEL/; a report already there is kept, so a second network costs only its own runs
# and a family that failed (e.g. its dataset still being made) is evaluated on the next call. Exit status 1 when
# one failed.
# Time on the 2-core machine: about 1-2 minutes per family and network.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
sixway="$root/build/src/app/sixway"
families=(inputs families/explosion families/jet_plume families/jet_bunny families/moving_sphere
  families/young/plume families/young/jet_plume families/young/jet_bunny families/young/moving_sphere
  families/young/explosion families/young/explosion_views families/young/explosion_start
  families/young128/plume families/young128/jet_plume families/young128/jet_bunny
  families/young128/moving_sphere families/young128/explosion families/young_lattice/jet_plume
  families/young_lattice/jet_bunny families/young_lattice/moving_sphere families/young_full/jet_plume
  families/young_full/jet_bunny families/young_full/moving_sphere
  families/young_full64/plume families/young_full64/jet_plume families/young_full64/jet_bunny
  families/young_full64/moving_sphere families/young_full64/explosion families/young_full128/plume
  families/young_full128/jet_plume families/young_full128/jet_bunny families/young_full128/moving_sphere
  families/young_full128/explosion families/chimney_wind)
[[ $# -ge 1 ]] || { echo "usage: $0 LABEL=WEIGHTS [LABEL=WEIGHTS ...]" >&2; exit 2; }
labels=() failed=0
for arg in "$@"; do
  label="${arg%%=*}" weights="${arg#*=}"
  [[ $label != "$arg" && -n $label && -n $weights ]] || { echo "heldout.sh: '$arg' is not LABEL=WEIGHTS" >&2; exit 2; }
  labels+=("$label")
  for family in "${families[@]}"; do
    if [[ ! -f data/$family/dataset.json ]]; then
      echo "heldout.sh: data/$family: no dataset on this machine, skipped" >&2
      continue
    fi
    report="out/heldout/$label/${family//\//_}.json"
    [[ -f $report ]] && continue
    mkdir -p "out/heldout/$label"
    echo "heldout.sh: $label on data/$family"
    "$sixway" eval --dataset "data/$family" --target multiple --weights "$weights" --report "$report" \
      >"${report%.json}.log" 2>&1 || { echo "heldout.sh: $label on data/$family failed: ${report%.json}.log" >&2; failed=1; }
  done
done
/usr/bin/python3 "$root/tools/results/heldout_table.py" out/heldout "${labels[@]}"
exit $failed
