#!/usr/bin/env bash
# Runs stopped half-way leave nothing that the next run trips over. SIGINT (Ctrl-C) and SIGTERM stop render,
# sim and bake at their next frame, removing their staging folder and a folder they made; SIGKILL cannot be
# handled, so the next run into the same folder treats one that holds nothing but dead runs' staging folders
# as absent. A bake stopped over an earlier one leaves it whole. The temporary files of killed writers (a
# report, a dataset shard) go when the same file is written again; a live process's stay.
# Usage: killed_runs.sh SIXWAY SCENE BAKE_SCENE DATASET_CONFIG DIR
set -u
set -m  # job control: without it a shell starts background commands with SIGINT ignored
sixway=$1 scene=$2 bake_scene=$3 dataset_config=$4 dir=$5
rm -rf "$dir" && mkdir -p "$dir" || exit 1
status=0
# A shell started with SIGINT ignored (under nohup, as a background job) passes that on, and sixway leaves an
# ignored signal ignored: then SIGTERM, handled the same way, stands in for it.
int=INT
if (((0x$(sed -n 's/^SigIgn:\t*//p' /proc/$$/status) >> 1) & 1)); then
  int=TERM
  echo "note: SIGINT is ignored here; SIGTERM stands in for it"
fi
fail() {
  echo "FAILED: $*"
  status=1
}
ok() { echo "ok: $*"; }

# stop_when SIGNAL GLOB COMMAND...: runs COMMAND in the background, sends SIGNAL once GLOB matches (the run's
# staging folder has appeared), and sets `code` to its exit status; its output is in $dir/log.
stop_when() {
  local signal=$1 pattern=$2
  shift 2
  "$@" > "$dir/log" 2>&1 &
  local pid=$! i
  for ((i = 0; i < 1200; ++i)); do
    compgen -G "$pattern" > /dev/null && break
    kill -0 $pid 2> /dev/null || break
    sleep 0.05
  done
  compgen -G "$pattern" > /dev/null || fail "$pattern never appeared: $(cat "$dir/log")"
  kill -s "$signal" $pid
  wait $pid
  code=$?
}

# expect_stopped WHAT SIGNAL: the run ended by SIGNAL (exit status 128 + its number), after its line saying so
# unless SIGNAL is KILL.
expect_stopped() {
  local expected=$((128 + $(kill -l "$2")))
  if [ "$code" -ne $expected ]; then
    fail "$1: exit $code, expected $expected (ended by SIG$2): $(cat "$dir/log")"
  elif [ "$2" != KILL ] && ! grep -q "^sixway: stopped by SIG$2$" "$dir/log"; then
    fail "$1: no 'stopped by SIG$2' line: $(cat "$dir/log")"
  else
    ok "$1: ended by SIG$2"
  fi
}

# expect_listing WHAT FOLDER NAMES: FOLDER holds exactly NAMES (hidden ones too), "" when it does not exist.
expect_listing() {
  local found
  found=$(cd "$2" 2> /dev/null && find . -mindepth 1 | sed 's|^\./||' | sort | tr '\n' ' ' | sed 's/ $//')
  if [ "$found" != "$3" ]; then
    fail "$1: $2 holds '$found', expected '$3'"
  else
    ok "$1: '$found'"
  fi
}

# run_ok WHAT COMMAND...: the command succeeds.
run_ok() {
  local what=$1
  shift
  if "$@" > "$dir/log" 2>&1; then ok "$what"; else fail "$what: exit $?: $(cat "$dir/log")"; fi
}

render=("$sixway" render --scene "$scene" --mode guide)
out=$dir/render_int
stop_when $int "$out/.render.*.partial" "${render[@]}" --frames 1000 --out "$out"
expect_stopped "render stopped by SIG$int" $int
expect_listing "render stopped by SIG$int: the folder it made is gone" "$out" ""

out=$dir/render_kill
stop_when KILL "$out/.render.*.partial" "${render[@]}" --frames 1000 --out "$out"
expect_stopped "render killed" KILL
run_ok "render into the killed render's folder, no --force" "${render[@]}" --frames 1 --out "$out"
expect_listing "render after a killed render" "$out" "contact_sheet.png frame_0000.png timings.json"

sim=("$sixway" sim --scene "$scene" --steps 100000)
out=$dir/sim_term
stop_when TERM "$out/.sim.*.partial" "${sim[@]}" --vdb-out "$out"
expect_stopped "sim --vdb-out stopped by SIGTERM" TERM
expect_listing "sim stopped by SIGTERM: the folder it made is gone" "$out" ""
out=$dir/sim_kill
stop_when KILL "$out/.sim.*.partial" "${sim[@]}" --vdb-out "$out"
expect_stopped "sim --vdb-out killed" KILL
run_ok "sim into the killed sim's folder, no --force" "$sixway" sim --scene "$scene" --steps 1 --vdb-out "$out"
name=$(sed -n 's/^ *"name": *"\([^"]*\)".*/\1/p' "$scene" | head -1)
expect_listing "sim after a killed sim" "$out" "${name}_0001.obj ${name}_0001.vdb"

bake=("$sixway" bake --scene "$bake_scene" --tile 16 --scattering single)
out=$dir/bake
run_ok "a first bake" "${bake[@]}" --frames 2 --out "$out"
touch "$out/notes.txt" "$out/frames/notes.txt"
earlier=$(cd "$out" && find . -type f | sort | xargs md5sum)
stop_when $int "$out/.bake.*.partial/frames/frame_0001.exr" "${bake[@]}" --frames 500 --out "$out" --force
expect_stopped "bake --force stopped by SIG$int" $int
if [ "$(cd "$out" && find . -type f | sort | xargs md5sum)" != "$earlier" ]; then
  fail "bake stopped by SIG$int changed the earlier bake: $(cd "$out" && find . | sort)"
else
  ok "bake stopped by SIG$int: the earlier bake is whole, and nothing else is there"
fi
out=$dir/bake_kill
stop_when KILL "$out/.bake.*.partial/frames/frame_0001.exr" "${bake[@]}" --frames 500 --out "$out"
expect_stopped "bake killed" KILL
run_ok "bake into the killed bake's folder, no --force" "${bake[@]}" --frames 1 --out "$out"
textures=$(for t in A B; do for e in exr png tga; do echo -n "flipbook_$t.$e flipbook_$t.$e.meta "; done; done)
expect_listing "bake after a killed bake" "$out" "flipbook.json ${textures}frames frames/frame_0000.exr"

# The temporary files a killed writer leaves: the next writer of the same file removes them, not a live
# process's (this shell's).
sleep 60 &
killed=$!
kill -KILL $killed
wait $killed
out=$dir/partials
mkdir -p "$out"
touch "$out/.report.json.$killed.partial" "$out/.report.json.$$.partial"
touch "$out/.shard_00000.safetensors.$killed.partial"
run_ok "info --report over a killed writer's temporary file" "$sixway" info --report "$out/report.json"
run_ok "dataset over a killed writer's temporary shard" \
  "$sixway" dataset --config "$dataset_config" --out "$out"
expect_listing "temporary files of killed writers" "$out" \
  ".report.json.$$.partial dataset.json report.json shard_00000.safetensors shard_00001.safetensors"
exit $status
