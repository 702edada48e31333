#!/usr/bin/python3
"""What the cheap methods score on a dataset's held-out splits, with no network: the yardsticks a network must beat.

Per split, masked lightmap PSNR (docs/conventions.md, "Metrics"; network channel order):
- `single_vs_multiple`: the exact single-scattering baker (`target`) against the multiple-scattering targets
  (`target_ms`), all eight channels. This is what the baker, the cheap exact method, scores against the truth.
- `guide_alpha` / `fine_alpha`: the guide's coarse alpha (channel 1) and its fine alpha (channel 3, in version-3
  shards) against the targets' alpha.

    /usr/bin/python3 tools/nn/baselines.py data/inputs [--json out.json]
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dataset import SPLITS, ShardDataset, guide_channel_count  # noqa: E402
from metrics import ALPHA_MASK_THRESHOLD  # noqa: E402

ALPHA = 6  # network channel order


def masked_psnr(squared, mask):
    """squared: (N, C, H, W) errors; mask: (N, 1, H, W). PSNR of the mean over masked values."""
    count = mask.sum() * squared.shape[1]
    if count == 0:
        return None
    mse = float((squared * mask).sum() / count)
    return math.inf if mse == 0 else 10 * math.log10(1 / mse)


def split_baselines(single, multiple, indices):
    """The figures of one split: `single` and `multiple` are ShardDatasets of the same directory."""
    truth = np.clip(multiple.target[indices].astype(np.float64), 0, 1)
    mask = truth[:, ALPHA:ALPHA + 1] > ALPHA_MASK_THRESHOLD
    baker = np.clip(single.target[indices].astype(np.float64), 0, 1)
    out = {"samples": int(len(indices)), "single_vs_multiple": masked_psnr((baker - truth) ** 2, mask)}
    alpha = truth[:, ALPHA:ALPHA + 1]
    for name, channel in (("guide_alpha", 1), ("fine_alpha", 3)):
        if channel < single.guide.shape[1]:
            guess = np.clip(single.guide[indices, channel:channel + 1].astype(np.float64), 0, 1)
            out[name] = masked_psnr((guess - alpha) ** 2, mask)
    return out


def baselines(directory):
    channels = guide_channel_count(directory)
    single = ShardDataset(directory, "single", channels)
    multiple = ShardDataset(directory, "multiple", channels)
    return {split: split_baselines(single, multiple, single.indices(split)) for split in SPLITS
            if len(single.indices(split))}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("data", help="a shard directory with both targets (the dataset config's \"targets\": \"both\")")
    parser.add_argument("--json", help="also write the figures here")
    args = parser.parse_args()
    try:
        result = baselines(args.data)
    except (OSError, ValueError) as error:
        sys.exit(f"baselines: {error}")
    for split, figures in result.items():
        print(f"{split} ({figures['samples']} samples): " +
              ", ".join(f"{k} {v:.2f} dB" for k, v in figures.items() if k != "samples" and v is not None))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(result, f, indent=2)


if __name__ == "__main__":
    main()
