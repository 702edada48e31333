#!/usr/bin/env bash
# Under an address-space limit (ulimit -v) sixway either runs or stops with one line naming the limit; it never
# crashes inside the driver. Under a limit the command line keeps one malloc arena, and its device maps 366 MiB
# on lavapipe (per-thread arenas made that 622-750 MiB, varying from run to run, and 900,000 KiB crashed now and
# then). The limits below span a refused one (700,000 KiB: the check needs 814 MiB), a tight one and a
# comfortable one; at least one must give the line, so the check itself is exercised, and none may crash.
# Usage: address_space_limit.sh SIXWAY SCENE DIR
set -u
sixway=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
status=0 refused=0
for kib in 700000 900000 1400000; do
  out="$dir/out_$kib"
  (ulimit -v "$kib" && exec "$sixway" render --scene "$scene" --frames 1 --out "$out") >"$dir/log_$kib" 2>&1
  code=$?
  lines=$(grep -c . "$dir/log_$kib")
  if ((code == 0)); then
    echo "ok: ulimit -v $kib: rendered"
  elif ((code == 1)) && grep -qE '^sixway: error: the address-space limit \(ulimit -v\) of [0-9]+ MiB leaves [0-9]+ MiB beside' "$dir/log_$kib" &&
    ((lines == 1)); then
    echo "ok: ulimit -v $kib: $(cat "$dir/log_$kib")"
    refused=$((refused + 1))
    [[ -e "$out" ]] && { echo "FAILED: ulimit -v $kib: refused, but left $out"; status=1; }
  else
    echo "FAILED: ulimit -v $kib: exit $code, $lines lines:"
    cat "$dir/log_$kib"
    status=1
  fi
done
((refused > 0)) || { echo "FAILED: no limit was refused: the check never ran"; status=1; }
exit $status
