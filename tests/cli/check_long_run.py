#!/usr/bin/env python3
"""Checks a long run (tests/cli/CMakeLists.txt, cli.long_run*): the per-frame rows of a `sixway render`
timings.json or a `sixway bake --report` must show the device memory of our buffers and images unchanged over
every frame (same bytes, same allocations) and the process's resident set flat once warmed up (growth after the
first tenth of the frames at most LIMIT_MIB). A bake holds every frame's tile until it packs the flipbook: its
report's held_bytes_per_frame, plus MARGIN_BYTES per frame for the heap around them, is allowed on top.
Usage: check_long_run.py REPORT.json FRAMES LIMIT_MIB [MARGIN_BYTES]"""
import json
import sys


def main():
    path, frames, limit_mib = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    margin = int(sys.argv[4]) if len(sys.argv) > 4 else 0
    with open(path) as f:
        report = json.load(f)
    rows = report["frames"]
    if len(rows) != frames:
        sys.exit(f"{path}: {len(rows)} frames, expected {frames}")
    device = {(r["device_bytes"], r["device_allocations"]) for r in rows}
    if len(device) != 1:
        sys.exit(f"{path}: device memory changed over the run: {sorted(device)[:4]} ...")
    warm = frames // 10
    base = rows[warm]["host_resident_bytes"]
    growth = 0.0
    for i in range(warm, frames):
        held = (i - warm) * (report.get("held_bytes_per_frame", 0) + margin)
        growth = max(growth, (rows[i]["host_resident_bytes"] - base - held) / 2**20)
    peak = max(r["host_resident_bytes"] for r in rows[warm:])
    print(f"{frames} frames: device {rows[0]['device_bytes'] / 2**20:.2f} MiB in {rows[0]['device_allocations']} "
          f"allocations throughout; resident set {base / 2**20:.2f} MiB at frame {warm}, peak {peak / 2**20:.2f} MiB "
          f"(growth beyond the frames held {growth:.2f} MiB, limit {limit_mib})")
    if growth > limit_mib:
        sys.exit(f"{path}: the resident set grew by {growth:.2f} MiB after frame {warm}, beyond the frames held")


if __name__ == "__main__":
    main()
