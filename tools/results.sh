#!/usr/bin/env bash
# Regenerates docs/results.md and its plots (docs/results/*.png) from scratch on this machine: builds
# sixway if needed, runs the `sixway eval --scene` studies into out/results/, plots them, writes the tables, and
# appends the `sixway bench` tables (to docs/results.md and, between its markers, docs/benchmarks.md) when
# tools/results/bench_tables.py exists.
#
# Default sizes (about 15-25 minutes on the 2-core lavapipe machine): tests/data/scenes/small_plume.json rendered
# at 128x128 with 64x64 lightmaps, 16 frames per study (the camera orbit: 0-90 degrees in 7.5-degree steps, 13
# frames), ground truth 64 spp. Override with FRAMES=N SPP=N ORBIT_STEP=DEG; SIXWAY=path/to/sixway uses that
# binary (no build); BENCH_ARGS="..." are
# passed to `sixway bench` (its defaults otherwise), SKIP_BENCH=1 leaves it out; ABLATIONS=1 first runs
# tools/ablations.sh (the retrained networks, 1.5-2 hours), whose table docs/results.md includes. The page opens
# with tools/results/gallery.sh's strips of every shipped scene at 256x256 (about 30 minutes more; SKIP_GALLERY=1
# leaves it out).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
frames="${FRAMES:-16}"
spp="${SPP:-64}"
orbit_step="${ORBIT_STEP:-7.5}"
orbit_frames=$(awk "BEGIN { print int(90 / $orbit_step + 1.5) }")
python=/usr/bin/python3  # Debian's, with python3-matplotlib (tools/deps.sh)
out="$root/out/results"
sixway="${SIXWAY:-$root/build/src/app/sixway}"
started=$(date +%s)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

[ -x "$sixway" ] || source "$root/tools/build.sh"
# The retrained ablations (hours, so only when asked): they write docs/results/ablations.md, included below.
[ -n "${ABLATIONS:-}" ] && SIXWAY="$sixway" bash "$root/tools/ablations.sh"
rm -rf "$out"
mkdir -p "$out" "$root/docs/results"

# The evaluated scene: the small plume at the network's training size (64x64 lightmaps), a 128x128 frame.
scene="$out/small_plume_128.json"
"$python" - "$root/tests/data/scenes/small_plume.json" "$scene" <<'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "small_plume_128"
scene["render"].update({"width": 128, "height": 128, "lightmap_size": 64})
json.dump(scene, open(sys.argv[2], "w"), indent=1)
EOF

run_eval() {  # name, then extra options
  local name=$1
  shift
  echo "results.sh: eval $name"
  "$sixway" eval --scene "$scene" --spp "$spp" --report "$out/$name.json" "$@"
}
run_eval multiple --frames "$frames" --orders 64 --out "$out/strip"
run_eval single --frames "$frames" --orders 1
run_eval orbit --frames "$orbit_frames" --orders 1 --camera-orbit "$orbit_step"
run_eval density_0.5 --frames "$frames" --orders 1 --density-scale 0.5
run_eval density_2 --frames "$frames" --orders 1 --density-scale 2
run_eval shadows_on --frames "$frames" --orders 1
run_eval shadows_off --frames "$frames" --orders 1 --no-shadows
[ -z "${SKIP_GALLERY:-}" ] && SIXWAY="$sixway" bash "$root/tools/results/gallery.sh"

bench_tables=""
if [ -z "${SKIP_BENCH:-}" ] && [ -f "$root/tools/results/bench_tables.py" ]; then
  echo "results.sh: bench"
  # shellcheck disable=SC2086 # BENCH_ARGS is a list of options
  "$sixway" bench --report "$out/bench.json" ${BENCH_ARGS:-}
  "$python" "$root/tools/results/bench_tables.py" "$out/bench.json" >"$out/bench_tables.md"
  bench_tables="$out/bench_tables.md"
  # The same tables into docs/benchmarks.md, between its "bench tables" markers (the text around them is
  # written by hand and may need updating to the new figures).
  "$python" - "$root/docs/benchmarks.md" "$bench_tables" <<'EOF'
import re, sys
doc, tables = open(sys.argv[1]).read(), open(sys.argv[2]).read()
begin = "<!-- bench tables: begin (written by tools/results.sh from its sixway bench run) -->\n"
end = "<!-- bench tables: end -->"
if begin not in doc or end not in doc:
    sys.exit("results.sh: docs/benchmarks.md has no bench tables markers")
body = re.sub(r"^(#+) ", lambda m: "#" + m.group(1) + " ", tables.split("### Simulation", 1)[-1], flags=re.M)
head, rest = doc.split(begin, 1)
open(sys.argv[1], "w").write(head + begin + "#### Simulation" + body.rstrip() + "\n" + end + rest.split(end, 1)[1])
EOF
fi

plot="$root/tools/plot_eval.py"
"$python" "$plot" frames "$out/multiple.json" "$root/docs/results/psnr_frames.png"
"$python" "$plot" stages "$out/multiple.json" "$root/docs/results/stage_times.png"
"$python" "$plot" equal-time "$out/single.json" "$root/docs/results/equal_time.png"
"$python" "$plot" angle "$out/orbit.json" "$root/docs/results/psnr_angle.png"
cp "$out/strip/strip.png" "$root/docs/results/strip.png"

"$python" - "$out/machine.json" "$load_before" "$started" "$root" \
  "FRAMES=$frames SPP=$spp ORBIT_STEP=$orbit_step" <<'EOF'
import json, os, subprocess, sys, time
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                        cwd=sys.argv[4]).stdout.strip()
json.dump({"cpu": cpu, "cores": os.cpu_count(), "load_before": sys.argv[2],
           "load_after": " ".join(open("/proc/loadavg").read().split()[:3]),
           "minutes": round((time.time() - int(sys.argv[3])) / 60, 1), "date": time.strftime("%Y-%m-%d"),
           "commit": commit or "unknown", "settings": sys.argv[5], "scene": "tests/data/scenes/small_plume.json"},
          open(sys.argv[1], "w"), indent=1)
EOF
"$python" "$root/tools/results/eval_tables.py" "$out" "$out/machine.json" $bench_tables >"$root/docs/results.md"
echo "results.sh: wrote docs/results.md and docs/results/*.png (reports in $out)"
