#!/usr/bin/python3
"""How a network's brightness error depends on the smoke's albedo (docs/network-study.md, "The albedo as an
input"): over the held-out splits and 3,000 random training samples of a training config's data, each sample's
six lightmaps (masked, clipped to [0, 1] as the metrics are) summed over predicted and target pixels; printed: the
mean predicted/target ratio and the PSNR per albedo bin, and what a per-sample brightness scale would give (the
best scale for each sample, and one fitted to the albedo alone on the training samples).

Usage: /usr/bin/python3 tools/results/albedo_bias.py --weights W [--config tools/train_configs/ship_ms_albedo.json]
About 5 minutes on 2 cores.
"""
import argparse
import json
import math
import os
import sys

import numpy as np
import torch

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(root, "tools", "nn"))
from dataset import ShardDataset  # noqa: E402
from sixway_net import decode_output, load_safetensors, run_padded  # noqa: E402

BINS = [(0.80, 0.84), (0.84, 0.88), (0.88, 0.92), (0.92, 0.951)]


def sample_sums(model, data, indices):
    """Per sample: (albedo, split, predicted sum, target sum, squared error, <p, t>, <p, p>, masked values)."""
    rows = []
    with torch.no_grad():
        for chunk in data.chunks_by_size(indices, 16):
            batch = data.batch(chunk)
            p = decode_output(run_padded(model, batch["guide"]), model.config).clamp(0, 1).double()[:, :6]
            t = batch["target"].clamp(0, 1).double()
            mask = (t[:, 6:7] > 0.01).double()
            t = t[:, :6]
            for k, i in enumerate(chunk):
                pm, tm = p[k] * mask[k], t[k] * mask[k]
                count = 6 * float(mask[k].sum())
                if count:
                    rows.append((data.albedo[i], data.samples[i]["split"], float(pm.sum()), float(tm.sum()),
                                 float(((pm - tm) ** 2).sum()), float((pm * tm).sum()), float((pm * pm).sum()), count))
    return rows


def psnr(squared, count):
    return 10 * math.log10(count.sum() / squared.sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--weights", required=True)
    parser.add_argument("--config", default=os.path.join(root, "tools", "train_configs", "ship_ms_albedo.json"))
    args = parser.parse_args()
    torch.set_num_threads(2)
    model, _ = load_safetensors(args.weights)
    model.eval()
    with open(args.config) as f:
        directories = [os.path.join(root, d) for d in json.load(f)["data"]["dir"]]
    data = ShardDataset(directories, target="multiple", guide_channels=model.config["guide_channels"],
                        albedo=bool(model.config.get("albedo_input")))
    rng = np.random.default_rng(0)
    indices = np.concatenate([data.indices("heldout_sequence"), data.indices("heldout_camera"),
                              rng.choice(data.indices("train"), 3000, replace=False)])
    rows = sample_sums(model, data, indices)
    albedo = np.array([r[0] for r in rows])
    split = np.array([r[1] for r in rows])
    predicted, target, squared, pt, pp, count = (np.array([r[k] for r in rows]) for k in range(2, 8))
    tt = squared - pp + 2 * pt  # <t, t>
    ratio = np.log(predicted / np.maximum(target, 1e-9))
    print(f"{args.weights}: corr(log predicted/target, albedo) = {np.corrcoef(ratio, albedo)[0, 1]:.2f}")
    print("| albedo | samples | predicted / target | PSNR, six lightmaps |")
    print("|---|---|---|---|")
    for low, high in BINS:
        m = (albedo >= low) & (albedo < high)
        print(f"| {low:.2f}–{min(high, 0.95):.2f} | {m.sum()} | {math.exp(ratio[m].mean()):.3f} | "
              f"{psnr(squared[m], count[m]):.2f} |")
    best = pt / pp  # the scale s minimising |s p - t|²
    fit = np.linalg.lstsq(np.stack([np.ones_like(albedo), albedo, albedo ** 2], 1)[split == "train"],
                          np.log(best[split == "train"]), rcond=None)[0]
    by_albedo = np.exp(fit[0] + fit[1] * albedo + fit[2] * albedo ** 2)
    scaled = lambda s: s * s * pp - 2 * s * pt + tt  # noqa: E731
    print("| split | PSNR | best scale per sample | scale fitted to the albedo |")
    print("|---|---|---|---|")
    for name in ("heldout_sequence", "heldout_camera", "train"):
        m = split == name
        print(f"| {name} | {psnr(squared[m], count[m]):.2f} | {psnr(scaled(best)[m], count[m]):.2f} | "
              f"{psnr(scaled(by_albedo)[m], count[m]):.2f} |")


if __name__ == "__main__":
    main()
