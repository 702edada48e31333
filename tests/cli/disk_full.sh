#!/usr/bin/env bash
# A full disk is one error line naming the file and the reason, with a non-zero exit; no empty or
# truncated file is left under a final name, and a good file that a --force rerun fails to replace stays as it
# was. Each case runs in a private mount namespace on a tmpfs of a few KiB (unshare: as root, or through user
# namespaces; where neither works the test is skipped, exit 77).
# Usage: disk_full.sh SIXWAY SCENE
set -u
sixway=$1 scene=$2
if ! unshare -rm true 2>/dev/null; then
  echo "skipped: this machine cannot make a private mount namespace (unshare -rm)"
  exit 77
fi

# in_tmpfs SIZE SCRIPT: runs SCRIPT with $dir a fresh tmpfs of SIZE (and $sixway, $scene); its exit code.
in_tmpfs() {
  unshare -rm env sixway="$sixway" scene="$scene" size="$1" bash -c '
    set -u
    dir=$(mktemp -d) && mount -t tmpfs -o size=$size tmpfs "$dir" || exit 90
    # expect_full NAME COMMAND...: the command fails with one stderr line saying the disk is full.
    expect_full() {
      local name=$1; shift
      "$@" > /dev/null 2> "$dir.err"; local code=$?
      local lines; lines=$(wc -l < "$dir.err")
      if [ $code -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -q "No space left on device" "$dir.err"; then
        echo "$name: expected one line about the full disk and a failure, got exit $code and:"; cat "$dir.err"
        exit 1
      fi
      echo "$name: exit $code: $(cat "$dir.err")"
      if [ -n "$(find "$dir" -type f \( -size 0 -o -name "*.partial" \))" ]; then
        echo "$name: left empty or temporary files:"; find "$dir" -type f \( -size 0 -o -name "*.partial" \); exit 1
      fi
    }
    '"$2"
}

status=0
# Frames: PNGs of 1-2 KB fill 12 KiB within a few frames. The error names the frame, and a failed first run
# leaves no output directory (the frames are published only when the run is complete).
in_tmpfs 12k '
  expect_full render "$sixway" render --scene "$scene" --frames 12 --mode reference --out "$dir/render"
  grep -q "$dir/render/frame_00[0-9][0-9].png: cannot write the file" "$dir.err" || { echo "render: names no frame"; exit 1; }
  [ ! -e "$dir/render" ] || { echo "render: left $(ls -A "$dir/render")"; exit 1; }' || status=1
# VDB frames (26 KB each) into 16 KiB.
in_tmpfs 16k '
  expect_full sim "$sixway" sim --scene "$scene" --steps 8 --vdb-out "$dir/vdb"' || status=1
# A good report, the disk then filled: the --force rerun fails and the report is unchanged.
in_tmpfs 16k '
  "$sixway" info --report "$dir/info.json" > /dev/null || exit 1
  cp "$dir/info.json" "$dir.before"
  dd if=/dev/zero of="$dir/fill" bs=1k count=64 2> /dev/null
  expect_full report "$sixway" info --report "$dir/info.json" --force
  cmp -s "$dir/info.json" "$dir.before" || { echo "report: the good report was changed"; exit 1; }' || status=1
exit $status
