#!/usr/bin/env bash
# Two `render --out NEW` (no --force) started together into one new folder: the folder is claimed with one
# mkdir, so exactly one render succeeds and writes every frame; the other fails with one line naming the folder
# and touches nothing of the winner's.
# Usage: render_race.sh SIXWAY SCENE DIR
set -u
sixway=$1 scene=$2 dir=$3
frames=3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
out=$dir/new

pids=()
for run in 1 2; do
  "$sixway" render --scene "$scene" --frames $frames --mode reference --out "$out" --validate \
    > "$dir/out.$run" 2> "$dir/err.$run" &
  pids+=($!)
done
codes=()
for pid in "${pids[@]}"; do
  wait "$pid"
  codes+=($?)
done

status=0
winners=0
for run in 1 2; do
  code=${codes[$((run - 1))]}
  if [ "$code" -eq 0 ]; then
    winners=$((winners + 1))
    grep -q "wrote $frames frames" "$dir/out.$run" || { echo "FAILED: run $run exited 0 without its line"; status=1; }
    ! grep -q "validation:" "$dir/err.$run" || { echo "FAILED: run $run: validation messages"; status=1; }
  elif [ "$(wc -l < "$dir/err.$run")" -ne 1 ] || ! grep -q "^sixway: error: $out: exists already" "$dir/err.$run"; then
    echo "FAILED: run $run: exit $code, expected one line saying $out exists already, got:"; cat "$dir/err.$run"
    status=1
  else
    echo "ok: run $run: exit $code: $(cat "$dir/err.$run")"
  fi
done
[ $winners -eq 1 ] || { echo "FAILED: $winners of the two renders succeeded, expected exactly one"; status=1; }

expected="contact_sheet.png frame_0000.png frame_0001.png frame_0002.png timings.json"
found=$(ls -A "$out" 2> /dev/null | sort | tr '\n' ' ' | sed 's/ $//')
if [ "$found" != "$expected" ]; then
  echo "FAILED: the folder holds '$found', expected '$expected'"
  status=1
else
  echo "ok: the winner's files: $found"
fi
exit $status
