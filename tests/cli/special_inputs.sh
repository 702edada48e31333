#!/usr/bin/env bash
# Inputs that are not what their option means, each refused with one line naming the path and what it is:
# weights given as a FIFO, a directory or a link to a device (made in the test's folder: the suite makes no
# device node; none is opened, so nothing blocks), paths longer than the system allows, empty paths, and a
# directory as sim's report (refused before the simulation: 10⁸ steps would not end in 60 s).
# Usage: special_inputs.sh SIXWAY SCENE DIR
set -u
sixway=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
. "$(dirname "$0")/expect_refused.sh"
mkfifo "$dir/fifo" || exit 1
mkdir "$dir/folder"
ln -s /dev/zero "$dir/zero"

for w in fifo zero folder; do
  case $w in fifo) what="a FIFO" ;; zero) what="a character device" ;; folder) what="a directory" ;; esac
  expect_refused "^sixway: error: $dir/$w: is $what, not a regular file$" \
    "$sixway" bench --sections network --size 16 --weights "$dir/$w"
done
expect_refused "^sixway: error: $dir/fifo: is a FIFO, not a regular file$" \
  "$sixway" render --scene "$scene" --frames 1 --mode neural --weights "$dir/fifo" --out "$dir/render_fifo"
expect_refused "^sixway: error: $dir/folder: is a directory, not a regular file$" \
  "$sixway" eval --scene "$scene" --frames 1 --weights "$dir/folder" --report "$dir/eval.json"
[ ! -e "$dir/render_fifo" ] || { echo "FAILED: render left its output folder"; status=1; }

# 5000 characters of "./" before an existing scene: stat says ENAMETOOLONG, which exists() read as absent.
dots=$(printf './%.0s' $(seq 2500))
long="$dir/${dots}scene.json"
cp "$scene" "$dir/scene.json"
expect_refused ": path is longer than the system allows \(${#long} characters, at most 4095\)$" \
  "$sixway" sim --scene "$long" --steps 1
expect_refused ": path is longer than the system allows \([0-9]+ characters, at most 4095\)$" \
  "$sixway" render --scene "$scene" --frames 1 --out "$dir/${dots}out"
expect_refused ": a name in the path is longer than the system allows \(305 characters, at most 255\)$" \
  "$sixway" sim --scene "$dir/$(printf 'a%.0s' $(seq 300)).json" --steps 1

expect_refused "^sixway: error: --out: an empty path; give a directory's path$" \
  "$sixway" render --scene "$scene" --frames 1 --out ''
expect_refused "^sixway: error: --scene: an empty path; give a file's path$" "$sixway" sim --scene '' --steps 1
expect_refused "^sixway: error: --report: an empty path; give a file's path$" "$sixway" info --report ''
expect_refused "^sixway: error: --weights: an empty path; give a file's path$" \
  "$sixway" bench --sections network --weights ''

expect_refused "^sixway: error: $dir/folder: is a directory, not a regular file; give a file's path$" \
  "$sixway" sim --scene "$scene" --steps 100000000 --report "$dir/folder" --force
[ -d "$dir/folder" ] && [ -p "$dir/fifo" ] || { echo "FAILED: an input was changed"; status=1; }
exit $status
