"""Held-out metrics (docs/conventions.md, "Metrics"), computed in PyTorch on the decoded linear lightmaps.

PSNR = 10 log10(1 / MSE) on linear values clipped to [0, 1], the MSE pooled over every pixel and channel of
every sample of a split: "masked" counts only pixels where the reference alpha > 0.01, "full" every pixel.
Per channel group (the network's adapters: left_right, top_bottom, front_back, alpha_emissive) masked, and alpha
and emissive alone.
Temporal stability: the mean absolute frame-to-frame difference (consecutive frames of one camera) of the
prediction and of the reference, side by side.
"""
import math

import torch

from sixway_net import ADAPTERS, decode_output, run_padded

ALPHA_MASK_THRESHOLD = 0.01


def psnr(squared_error_sum, count):
    if count == 0:
        return None
    mse = squared_error_sum / count
    return math.inf if mse == 0 else 10 * math.log10(1 / mse)


class SplitMetrics:
    """Accumulates squared errors of decoded predictions against linear targets, batch by batch."""

    def __init__(self):
        self.sums = {}  # name -> [squared error sum, value count]
        self.frame_difference = {"prediction": [0.0, 0], "reference": [0.0, 0]}

    def _add(self, name, squared, count):
        entry = self.sums.setdefault(name, [0.0, 0])
        entry[0] += float(squared)
        entry[1] += int(count)

    def add(self, prediction, target):
        """prediction, target: (N, 8, H, W) linear, network channel order."""
        p, t = prediction.clamp(0, 1).double(), target.clamp(0, 1).double()
        squared = (p - t) ** 2
        mask = (target[:, 6:7] > ALPHA_MASK_THRESHOLD).double()
        self._add("full", squared.sum(), squared.numel())
        self._add("masked", (squared * mask).sum(), mask.sum() * squared.shape[1])
        self._add("zero_prediction_masked", (t ** 2 * mask).sum(), mask.sum() * squared.shape[1])
        for i, (group, _) in enumerate(ADAPTERS):
            part = squared[:, 2 * i:2 * i + 2]
            self._add(f"masked_{group}", (part * mask).sum(), mask.sum() * 2)
        for channel in (6, 7):  # alpha and emissive alone (network order)
            self._add(f"masked_{ADAPTERS[3][1][channel - 6]}", (squared[:, channel] * mask[:, 0]).sum(), mask.sum())

    def add_frame_differences(self, prediction, prediction_previous, target, target_previous):
        for key, (a, b) in {"prediction": (prediction, prediction_previous),
                            "reference": (target, target_previous)}.items():
            d = (a.clamp(0, 1).double() - b.clamp(0, 1).double()).abs()
            self.frame_difference[key][0] += float(d.sum())
            self.frame_difference[key][1] += d.numel()

    def result(self, samples):
        out = {"samples": int(samples)}
        out.update({f"psnr_{name}": psnr(*entry) for name, entry in self.sums.items()})
        for key, (total, count) in self.frame_difference.items():
            out[f"mean_abs_frame_difference_{key}"] = total / count if count else None
        return out


@torch.no_grad()
def evaluate_split(model, data, split, device, batch_size=16):
    """Metrics of one split on whole maps (model in eval mode; the caller restores train mode); samples of
    several lightmap sizes go in batches of one size."""
    indices = data.indices(split)
    metrics = SplitMetrics()
    last = {}  # sample -> decoded prediction of the chunk before (previous frames are the sample before)
    for chunk in data.chunks_by_size(indices, batch_size):
        batch = data.batch(chunk)
        prediction = decode_output(run_padded(model, batch["guide"].to(device)), model.config).cpu()
        metrics.add(prediction, batch["target"])
        current = {int(i): prediction[k] for k, i in enumerate(chunk)}
        recent = {**last, **current}
        last = current
        rows = [k for k, i in enumerate(chunk) if int(data.previous[i]) in recent]
        if rows:
            before = data.previous[chunk[rows]]
            metrics.add_frame_differences(prediction[rows], torch.stack([recent[int(i)] for i in before]),
                                          batch["target"][rows], data.batch(before)["target"])
    return metrics.result(len(indices))
