#!/usr/bin/env bash
# Outputs given as special files: a FIFO, a socket (standing in for a device node: the suite makes none), a
# link to a FIFO, or a file where a directory is meant and the other way round. Each is refused with one line
# naming the path and what it is, with or without --force, and stays as it was: a regular file is never
# renamed over a FIFO or device.
# Usage: special_outputs.sh SIXWAY SCENE DIR
set -u
sixway=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
mkfifo "$dir/fifo" || exit 1
ln -s fifo "$dir/link_to_fifo"
python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$dir/socket" || exit 1
mkdir "$dir/folder"
echo "a user's file" > "$dir/file"

status=0
# expect_refused EXPECT COMMAND...: the command fails with exactly one stderr line matching EXPECT (grep -E).
expect_refused() {
  local expect=$1; shift
  timeout 60 "$@" > /dev/null 2> "$dir.err"; local code=$?
  if [ $code -eq 0 ] || [ "$(wc -l < "$dir.err")" -ne 1 ] || ! grep -Eq "$expect" "$dir.err"; then
    echo "FAILED: $*: expected one line matching '$expect' and a failure, got exit $code and:"; cat "$dir.err"
    status=1
  else
    echo "ok: exit $code: $(cat "$dir.err")"
  fi
}

for force in "" --force; do
  expect_refused "$dir/fifo: is a FIFO, not a regular file" "$sixway" info --report "$dir/fifo" $force
  expect_refused "$dir/socket: is a socket, not a regular file" "$sixway" info --report "$dir/socket" $force
  expect_refused "$dir/link_to_fifo: is a FIFO, not a regular file" "$sixway" info --report "$dir/link_to_fifo" $force
  expect_refused "$dir/folder: is a directory, not a regular file" "$sixway" info --report "$dir/folder" $force
  expect_refused "$dir/fifo: is a FIFO, not a regular file" "$sixway" sim --scene "$scene" --steps 1 --report "$dir/fifo" $force
  expect_refused "$dir/socket: is a socket, not a regular file" "$sixway" bench --sections sim --report "$dir/socket" $force
  expect_refused "$dir/fifo: is a FIFO, not a directory" "$sixway" render --scene "$scene" --frames 1 --out "$dir/fifo" $force
  expect_refused "$dir/file: is a regular file, not a directory" "$sixway" render --scene "$scene" --frames 1 --out "$dir/file" $force
  expect_refused "$dir/socket: is a socket, not a directory" "$sixway" sim --scene "$scene" --steps 1 --vdb-out "$dir/socket" $force
  expect_refused "$dir/fifo: is a FIFO, not a directory" "$sixway" bake --scene "$scene" --frames 1 --out "$dir/fifo" $force
done

[ -p "$dir/fifo" ] || { echo "FAILED: the FIFO was replaced"; status=1; }
[ -S "$dir/socket" ] || { echo "FAILED: the socket was replaced"; status=1; }
[ -L "$dir/link_to_fifo" ] && [ -p "$dir/link_to_fifo" ] || { echo "FAILED: the link to the FIFO was replaced"; status=1; }
[ "$(cat "$dir/file")" = "a user's file" ] || { echo "FAILED: the user's file was changed"; status=1; }
leftovers=$(find "$dir" -name "*.partial")
[ -z "$leftovers" ] || { echo "FAILED: temporary files left: $leftovers"; status=1; }
exit $status
