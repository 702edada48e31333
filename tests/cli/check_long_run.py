#!/usr/bin/env python3
"""Checks a long `sixway render` run (tests/cli/CMakeLists.txt, cli.long_run*): its timings.json must show the
device memory of our buffers and images unchanged over every frame (same bytes, same allocations) and the
process's resident set flat once warmed up (growth after the first tenth of the frames at most LIMIT_MIB).
Usage: check_long_run.py TIMINGS.json FRAMES LIMIT_MIB"""
import json
import sys


def main():
    path, frames, limit_mib = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    with open(path) as f:
        rows = json.load(f)["frames"]
    if len(rows) != frames:
        sys.exit(f"{path}: {len(rows)} frames, expected {frames}")
    device = {(r["device_bytes"], r["device_allocations"]) for r in rows}
    if len(device) != 1:
        sys.exit(f"{path}: device memory changed over the run: {sorted(device)[:4]} ...")
    warm = frames // 10
    base = rows[warm]["host_resident_bytes"]
    peak = max(r["host_resident_bytes"] for r in rows[warm:])
    growth = (peak - base) / 2**20
    print(f"{frames} frames: device {rows[0]['device_bytes'] / 2**20:.2f} MiB in {rows[0]['device_allocations']} "
          f"allocations throughout; resident set {base / 2**20:.2f} MiB at frame {warm}, peak {peak / 2**20:.2f} MiB "
          f"(growth {growth:.2f} MiB, limit {limit_mib})")
    if growth > limit_mib:
        sys.exit(f"{path}: the resident set grew by {growth:.2f} MiB after frame {warm}")


if __name__ == "__main__":
    main()
