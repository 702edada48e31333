#!/usr/bin/env python3
"""The ablation table of docs/results.md (tools/ablations.sh): per variant in OUT (out/ablations/<variant>/),
the held-out lightmap PSNR measured by the C++ pipeline (eval.json of `sixway eval --dataset`), the network's
size and training time (the sixway.training metadata of its weights file) and its flicker (metrics.json of
tools/train.py). Markdown on stdout; one error line and exit 1 for a missing or malformed file."""
import json
import os
import struct
import sys

VARIANTS = [  # directory, guide lights, adapters
    ("baseline", "front, top, bottom", "yes"),
    ("guide_front", "front", "yes"),
    ("guide_front_left_right", "front, left, right", "yes"),
    ("no_adapters", "front, top, bottom", "no"),
]


def fail(message):
    print(f"ablation_table.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def load_json(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: {e}")


def training_metadata(path):
    try:
        with open(path, "rb") as f:
            (length,) = struct.unpack("<Q", f.read(8))
            header = json.loads(f.read(length))
        return json.loads(header["__metadata__"]["sixway.training"])
    except (OSError, ValueError, KeyError, struct.error) as e:
        fail(f"{path}: no training metadata ({e})")


def db(value):
    return "—" if value is None else f"{value:.2f}"


def main():
    if len(sys.argv) != 2:
        fail("usage: ablation_table.py OUT_DIR")
    out = sys.argv[1]
    rows, baseline = [], None
    for name, lights, adapters in VARIANTS:
        directory = os.path.join(out, name)
        ev = load_json(os.path.join(directory, "eval.json"))
        metrics = load_json(os.path.join(directory, "metrics.json"))["pytorch"]
        training = training_metadata(os.path.join(directory, "sixway-unet.safetensors"))
        seq, cam = ev["splits"].get("heldout_sequence"), ev["splits"].get("heldout_camera")
        if seq is None or cam is None:
            fail(f"{directory}/eval.json: both held-out splits are needed")
        if baseline is None:
            baseline = (seq["psnr_masked_db"], cam["psnr_masked_db"])
        delta = f"{seq['psnr_masked_db'] - baseline[0]:+.2f} / {cam['psnr_masked_db'] - baseline[1]:+.2f}"
        pairs = seq["pairs_psnr_masked_db"]
        held = metrics["heldout_sequence"]
        flicker = held["mean_abs_frame_difference_prediction"] / held["mean_abs_frame_difference_reference"]
        rows.append(
            f"| {name} | {lights} | {adapters} | {training['parameters']:,} | {training['wall_seconds'] / 60:.1f} | "
            f"**{db(seq['psnr_masked_db'])}** | {db(cam['psnr_masked_db'])} | {delta} | {db(pairs['right_left'])} / "
            f"{db(pairs['top_bottom'])} / {db(pairs['back_front'])} / {db(pairs['alpha_emissive'])} | "
            f"{flicker:.2f} |")
    print("| variant | guide lights | adapters | parameters | training, min | held-out sequences: PSNR masked, dB | "
          "held-out camera | vs baseline, dB (sequences / camera) | per pair (sequences): right-left / top-bottom / back-front / alpha-emissive | "
          "flicker (prediction ÷ reference) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for row in rows:
        print(row)


if __name__ == "__main__":
    main()
