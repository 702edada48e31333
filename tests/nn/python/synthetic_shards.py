"""Small synthetic training shards in the format of `sixway dataset` (tools/nn/dataset.py), for the tests.

Each sequence is a Gaussian puff that drifts by a known whole number of pixels per frame; every camera sees it
with its own brightness. The targets are made from the puff (so the guide predicts them), and the motion is
the exact drift where there is smoke, zero elsewhere and on a camera's first frame. Shards are version 1 (a
3-channel guide), or version 4 with the fine alpha and the direct emission in the guide's channels 3 and 4.
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "nn"))
from safetensors_io import write_safetensors  # noqa: E402

DRIFT = (2, 1)  # pixels per sample: x right, y down
FIRST_FRAME, FRAME_STRIDE = 30, 2
# Per baker channel (Right, Left, Top, Bottom, Back, Front, alpha, emissive): a distinct gain, so that a
# channel reordering bug shows.
GAINS = [0.9, 0.3, 0.7, 0.2, 1.2, 0.5, 1.0, 0.05]
GUIDE_NAMES = ["guide", "alpha", "depth", "alpha_fine", "emission"]


def puff(size, frame, camera, sequence):
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    cx = size * 0.3 + DRIFT[0] * frame + 2 * camera
    cy = size * 0.4 + DRIFT[1] * frame + sequence
    return np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * (size / 8) ** 2))


def sample_tensors(size, frame, camera, sequence, guide_channels=3, emission=0.0):
    """The guide's first `guide_channels` channels; its emission is the puff's density times `emission`."""
    density = puff(size, frame, camera, sequence)
    alpha = 1 - np.exp(-3 * density)
    brightness = 0.6 + 0.2 * camera
    target = np.stack([g * alpha * (1 if c == 6 else brightness) for c, g in enumerate(GAINS)])
    guide = np.stack([alpha * brightness * 1.3, alpha, np.where(alpha > 0.01, 0.5 - 0.3 * density, 1.0),
                      1 - np.exp(-3.3 * density), emission * density][:guide_channels])
    motion = np.zeros((2, size, size))
    if frame > 0:
        motion[0][alpha > 0.01] = DRIFT[0]
        motion[1][alpha > 0.01] = DRIFT[1]
    return guide, target, motion


def write_shards(directory, size=16, cameras=3, frames=4, sequences=2, heldout_camera=2, guide_channels=3,
                 emission=None, albedos=None):
    """Sequences 0..sequences-2 are training sequences (camera `heldout_camera` held out), the last one is a
    held-out sequence. A guide of 4 or 5 channels makes version 4 shards, with a fine alpha step of 1 voxel;
    `emission` (None: none) is the scene's emission intensity; `albedos` (None: none) the smoke's albedo per
    sequence. Returns the shard paths."""
    os.makedirs(directory, exist_ok=True)
    config = {"synthetic": True, "lightmap_size": size}
    paths = []
    for sequence in range(sequences):
        guides, targets, motions, samples = [], [], [], []
        for camera in range(cameras):
            for frame in range(frames):
                guide, target, motion = sample_tensors(size, frame, camera, sequence, guide_channels, emission or 0.0)
                guides.append(guide)
                targets.append(target)
                motions.append(motion)
                split = ("heldout_sequence" if sequence == sequences - 1 else
                         "heldout_camera" if camera == heldout_camera else "train")
                # Simulation frame numbers, as `sixway dataset` writes them: after a warm-up, with a stride.
                samples.append({"camera": camera, "frame": FIRST_FRAME + FRAME_STRIDE * frame, "split": split,
                                "azimuth_deg": 120.0 * camera, "elevation_deg": 10.0})
        info = {"version": 1, "sequence": sequence, "lightmap_size": size, "config": config,
                "scene": {"synthetic_puff": sequence}, "samples": samples}
        if guide_channels > 3:
            info.update(version=4, targets=["single"], guide_channels=GUIDE_NAMES[:guide_channels])
            info["scene"]["render"] = {"guide_alpha_step_voxels": 1.0}
        if emission is not None:
            info["scene"]["smoke"] = {"emission": {"intensity": emission}}
        if albedos is not None:
            info["scene"].setdefault("smoke", {})["albedo"] = albedos[sequence]
        path = os.path.join(directory, f"shard_{sequence:05d}.safetensors")
        tensors = {name: np.stack(values).astype(np.float16)
                   for name, values in (("guide", guides), ("target", targets), ("motion", motions))}
        write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
        paths.append(path)
    return paths
