#!/usr/bin/env bash
# Paths that are not UTF-8 (a POSIX path may hold any bytes): render, bench and bake do their work and write
# their JSON (timings.json, the report, the flipbook's sidecar) with U+FFFD in place of each invalid byte,
# where writing the JSON failed after the work (and render lost its frames, bake left a partial flipbook).
# Usage: non_utf8_paths.sh SIXWAY SCENE BAKE_SCENE WEIGHTS DIR
set -u
sixway=$1 scene=$2 bake_scene=$3 weights=$4 dir=$5
rm -rf "$dir" && mkdir -p "$dir" || exit 1
bad=$'\xff\xfe'
status=0
fail() { echo "FAILED: $*"; status=1; }
# has_replacement FILE KEY...: FILE is UTF-8 JSON whose value at KEY... holds U+FFFD.
has_replacement() {
  python3 - "$@" <<'PY'
import json, sys
value = json.load(open(sys.argv[1], encoding="utf-8"))
for key in sys.argv[2:]:
    value = value[key]
sys.exit(0 if "\ufffd" in value else 1)
PY
}

cp "$scene" "$dir/scene$bad.json"
"$sixway" render --scene "$dir/scene$bad.json" --frames 1 --mode guide --out "$dir/render$bad" || fail "render"
[ -f "$dir/render$bad/frame_0000.png" ] || fail "render wrote no frame"
has_replacement "$dir/render$bad/timings.json" scene || fail "timings.json does not name the scene with U+FFFD"

cp "$weights" "$dir/w$bad.safetensors"
"$sixway" bench --sections network --size 16 --warmup 0 --repeats 1 --weights "$dir/w$bad.safetensors" \
  --report "$dir/bench$bad.json" || fail "bench"
has_replacement "$dir/bench$bad.json" network weights || fail "the bench report does not name the weights with U+FFFD"

cp "$bake_scene" "$dir/bake$bad.json"
"$sixway" bake --scene "$dir/bake$bad.json" --frames 1 --tile 16 --out "$dir/bake$bad" || fail "bake"
has_replacement "$dir/bake$bad/flipbook.json" provenance source scene ||
  fail "the flipbook's sidecar does not name the scene with U+FFFD"

leftovers=$(find "$dir" -name "*.partial")
[ -z "$leftovers" ] || fail "temporary files left: $leftovers"
exit $status
