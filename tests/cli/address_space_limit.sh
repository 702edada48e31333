#!/usr/bin/env bash
# Under an address-space limit (ulimit -v) sixway either runs or stops with one line naming the limit; it never
# crashes inside the driver. How much the Vulkan device maps differs from run to run by tens of MiB, so whether a
# given limit leaves enough is not fixed: the limits below span the default scene's crash (1,050,000 KiB) to a
# comfortable one, and at least one must give the line, so the check itself is exercised.
# Usage: address_space_limit.sh SIXWAY SCENE DIR
set -u
sixway=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
status=0 refused=0
for kib in 900000 1050000 1400000; do
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
