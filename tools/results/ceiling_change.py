#!/usr/bin/env python3
"""The frame-to-frame change of reference-ms and traditional-ms without their own Monte Carlo noise, from two
ms_ceiling.sh runs of the same scenes that differ only in MS_SPP (N and 4N samples per texel of the orders >= 2).

Each frame's orders >= 2 are traced with a new seed, so a method's squared RMS change is c0^2 + k/N (Monte Carlo
variance goes as 1/N); two runs at N and 4N give c0^2 = (4 rms_4N^2 - rms_N^2) / 3. Printed as a markdown table,
as ratios to the truth's change without its noise (sixway eval --truth-noise), beside the neural network's.

Usage: ceiling_change.py DIR_N DIR_4N (e.g. out/ms_ceiling/lightmap_128_warm90 out/ms_ceiling/lightmap_128_warm90_msspp256)
"""
import glob
import json
import os
import sys

METHODS = ("reference-ms", "traditional-ms")


def temporal(path):
    """The report's summary.temporal, or one error line naming the file."""
    try:
        with open(path) as f:
            return json.load(f)["summary"]["temporal"]
    except (OSError, ValueError, KeyError, TypeError) as error:
        sys.exit(f"ceiling_change.py: {path}: not a sixway eval --scene --truth-noise report ({error!r})")


def main(low_dir, high_dir):
    rows = []
    for high_path in sorted(glob.glob(os.path.join(high_dir, "*.report.json"))):
        low_path = os.path.join(low_dir, os.path.basename(high_path))
        if not os.path.exists(low_path):
            continue
        low, high = temporal(low_path), temporal(high_path)
        try:
            truth = high["truth"]["rms_without_noise"]
            if not truth or abs(truth - low["truth"]["rms_without_noise"]) > 1e-6 * truth:
                sys.exit(f"ceiling_change.py: {high_path}: another truth than {low_path}'s (not the same scene and "
                         "frames), or none")
            cells = []
            for m in METHODS:
                n, four_n = low["methods"][m]["rms"], high["methods"][m]["rms"]
                c0 = max(0.0, (4 * four_n ** 2 - n ** 2) / 3) ** 0.5
                cells.append(f"{n / truth:.2f}×, {four_n / truth:.2f}×, **{c0 / truth:.2f}×**")
            neural = low["methods"]["neural"]["rms"] / truth
        except (KeyError, TypeError) as error:
            sys.exit(f"ceiling_change.py: {high_path} or {low_path}: no frame-to-frame change of {error!r}")
        name = os.path.basename(high_path).removesuffix(".report.json")
        rows.append(f"| {name} | {truth:.4f} | {neural:.2f}× | " + " | ".join(cells) + " |")
    if not rows:
        sys.exit(f"ceiling_change.py: no scene has a report in both {low_dir} and {high_dir}")
    print("| scene | truth's change | neural | " + " | ".join(f"{m}: N, 4N, without noise" for m in METHODS) + " |")
    print("|---|---|---|" + "---|" * len(METHODS))
    print("\n".join(rows))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    main(*sys.argv[1:])
