#!/usr/bin/python3
"""Would a fixed bound on the all-orders network's emissive help on emissive smoke? (docs/network-study.md, "A gate for emissive scenes")

Runs a network in PyTorch on every sample of the given dataset directories and compares its emissive channel with
the all-orders targets (masked PSNR, as tools/nn/metrics.py) as it is and bounded two ways by the guide's direct
emission E (guide channel 4):
- a gate min(network, k * B(E)), B a Gaussian blur of sigma s pixels or a max-filter of radius s: printed as
  "truth clipped / network gated" dB, the first what the gate would cost a perfect network;
- a floor max(network, c * E): the truth holds E plus the glow the smoke scatters, so it is never below E.

    /usr/bin/python3 tools/results/emissive_gate_study.py data/families/explosion [--weights FILE]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "nn"))
import numpy as np  # noqa: E402
import torch  # noqa: E402
import torch.nn.functional as F  # noqa: E402

from dataset import EMISSION, ShardDataset  # noqa: E402
from metrics import ALPHA_MASK_THRESHOLD  # noqa: E402
from sixway_net import decode_output, load_safetensors, run_padded  # noqa: E402

SIZES = [1, 2, 4, 8, 16]
GAINS = [2, 4, 8, 16, 32, 64]
FLOORS = [0.5, 1.0, 1.5, 2.0, 3.0]


def gaussian_blur(e, sigma):
    r = int(math.ceil(3 * sigma))
    x = torch.arange(-r, r + 1, dtype=e.dtype)
    w = torch.exp(-x * x / (2 * sigma * sigma))
    w = w / w.sum()
    e = F.conv2d(e, w.view(1, 1, 1, -1), padding=(0, r))
    return F.conv2d(e, w.view(1, 1, -1, 1), padding=(r, 0))


def max_filter(e, radius):
    return F.max_pool2d(e, 2 * radius + 1, stride=1, padding=radius)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directories", nargs="+", help="dataset directories with all-orders targets and emission")
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    parser.add_argument("--weights", default=os.path.join(root, "weights", "sixway-unet-ms.safetensors"))
    args = parser.parse_args()
    torch.set_num_threads(1)
    model, _ = load_safetensors(args.weights)
    model.eval()
    data = ShardDataset(args.directories, target="multiple", guide_channels=5)

    sums = {}  # name -> [squared error over the mask, mask pixels]
    totals = {"network": 0.0, "truth": 0.0, "direct emission": 0.0}

    def add(name, error, mask):
        entry = sums.setdefault(name, [0.0, 0.0])
        entry[0] += float((error * mask).sum())
        entry[1] += float(mask.sum())

    for arrays in data.by_size.values():
        for start in range(0, len(arrays["guide"]), 32):
            guide = torch.from_numpy(arrays["guide"][start:start + 32].astype(np.float32))
            target = torch.from_numpy(arrays["target"][start:start + 32].astype(np.float32)).double()
            with torch.no_grad():
                prediction = decode_output(run_padded(model, guide), model.config).double()
            mask = (target[:, 6:7] > ALPHA_MASK_THRESHOLD).double()
            truth, predicted = target[:, 7:8].clamp(0, 1), prediction[:, 7:8].clamp(0, 1)
            emission = guide[:, EMISSION:EMISSION + 1].double().clamp(0, 1)
            totals["network"] += float(predicted.sum())
            totals["truth"] += float(truth.sum())
            totals["direct emission"] += float(emission.sum())
            add("network", (predicted - truth) ** 2, mask)
            for kind, bound in (("blur", gaussian_blur), ("max", max_filter)):
                for size in SIZES:
                    spread = bound(emission, size)
                    for k in GAINS:
                        gate = k * spread
                        add(f"{kind} {size} {k} truth", (torch.minimum(truth, gate) - truth) ** 2, mask)
                        add(f"{kind} {size} {k} network", (torch.minimum(predicted, gate) - truth) ** 2, mask)
            for c in FLOORS:
                add(f"floor {c}", (torch.maximum(predicted, c * emission) - truth) ** 2, mask)

    def db(name):
        error, count = sums[name]
        return math.inf if error == 0 else 10 * math.log10(count / error)

    samples = sum(len(a["guide"]) for a in data.by_size.values())
    print(f"{samples} samples; emissive, masked PSNR against the all-orders targets: network {db('network'):.2f} dB")
    print("sums over the maps: " + ", ".join(f"{k} {v:.1f}" for k, v in totals.items()))
    for kind, label in (("blur", "Gaussian sigma"), ("max", "max-filter radius")):
        for size in SIZES:
            cells = "  ".join(f"k {k}: {db(f'{kind} {size} {k} truth'):.1f}/{db(f'{kind} {size} {k} network'):.2f}"
                              for k in GAINS)
            print(f"gate, {label} {size}: {cells}")
    print("floor max(network, c E): " + "  ".join(f"c {c}: {db(f'floor {c}'):.2f}" for c in FLOORS))


if __name__ == "__main__":
    main()
