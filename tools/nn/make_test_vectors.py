#!/usr/bin/python3
"""Writes the network test data of tests/data/nn/ (docs/network-format.md, "Test data"):

  default.safetensors          the default config, untrained: random weights (seeded), for tests and benchmarks
  default_vectors.safetensors  a 32x48 guide, and what PyTorch computes from it with default.safetensors
  tiny.safetensors             a tiny config that exercises the other options (NAF levels, gelu, bilinear
                               upsampling, odd channel counts, an adapter with dw_expand 3)
  tiny_vectors.safetensors     a 29x45 guide (not a multiple of the size multiple: padded, then cropped)
  fine_alpha.safetensors       a small network whose guide has the fine alpha as a 4th channel, passed through
                               as its alpha
  fine_alpha_vectors.safetensors  a 20x36 guide of 4 channels
  half_stem.safetensors        the UNet and adapters at half resolution behind a stride-2 stem, transposed heads
  half_stem_vectors.safetensors   a 27x41 guide of 4 channels (padded to the size multiple 8, then cropped)
  naf_wide.safetensors         NAFBlocks of 24 and 20 channels: wider than NN_UNROLLED_GROUPS, so the kernels loop
                               over their channel groups
  naf_wide_vectors.safetensors    a 18x22 guide
  emission_guide.safetensors   like fine_alpha, with the guide's direct emission as a 5th channel: the input is
                               padded to 8 channels (two vec4s), and alpha_from_guide reads 2 + 8 channels
  emission_guide_vectors.safetensors  a 20x28 guide of 5 channels
  emission_passthrough.safetensors   like emission_guide, with the guide's emission passed through as the emissive
                               (linear, not sRGB-decoded): alpha_emissive_from_guide picks both
  emission_passthrough_vectors.safetensors  a 22x26 guide of 5 channels

A vectors file holds "input" (3 to 5 x H x W), "raw" (the 8 output channels in the network's encoding), "lightmap_a"
and "lightmap_b" (decoded and packed, 4 x H x W each) and "node.<name>" intermediates (at the padded size).
Everything is deterministic (numpy PCG64 seeds, float32 CPU evaluation), so `--out DIR` regenerates the same
files; check_test_vectors.py compares a regeneration with the committed ones.

Usage: /usr/bin/python3 tools/nn/make_test_vectors.py [--out tests/data/nn]
"""
import argparse
import json
import os
import sys

import numpy as np
import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from safetensors_io import write_safetensors  # noqa: E402
from sixway_net import (SixwayNet, decode_output, export_safetensors, pack_lightmaps,  # noqa: E402
                        randomize, run_padded)

TINY_CONFIG = {
    "widths": [7, 10, 12],
    "depth": 2,
    "block": "naf",
    "activation": "gelu",
    "upsample": "bilinear",
    "adapters": {"enabled": True, "width": 6, "blocks": 1, "dw_expand": 3, "ffn_expand": 2},
}

FINE_ALPHA_CONFIG = {
    "guide_channels": 4,
    "guide_alpha_step_voxels": 0.5,
    "alpha": "guide",
    "widths": [5, 8],
    "depth": 1,
    "adapters": {"enabled": True, "width": 4, "blocks": 1},
}

HALF_STEM_CONFIG = {
    "guide_channels": 4,
    "guide_alpha_step_voxels": 1,
    "alpha": "guide",
    "stem": "half",
    "widths": [6, 8, 12],
    "depth": 2,
    "adapters": {"enabled": True, "width": 5, "blocks": 1},
}

NAF_WIDE_CONFIG = {
    "widths": [24],
    "depth": 2,
    "block": "naf",
    "adapters": {"enabled": True, "width": 20, "blocks": 1},
}

# The fine-alpha network with the emission as a 5th guide channel (two groups of four input channels).
EMISSION_GUIDE_CONFIG = dict(FINE_ALPHA_CONFIG, guide_channels=5, input_channels=8)
# The same with the emission passed through as the emissive output (the single-scattering network's setting).
EMISSION_PASSTHROUGH_CONFIG = dict(EMISSION_GUIDE_CONFIG, emissive="guide")
# The emission network reading the smoke's albedo in its 6th input channel; its vectors hold the albedo.
ALBEDO_INPUT_CONFIG = dict(EMISSION_GUIDE_CONFIG, albedo_input={"offset": 0.875, "scale": 13.333333})
ALBEDO = 0.82

# name: (config, weights seed, guide seed, guide height, guide width, intermediates)
CASES = {
    "default": (None, 6, 60, 32, 48, ["enc.0.1", "down.0", "mid.1", "up.0", "dec.0.1", "adapters.0.blocks.0",
                                      "adapters.3.head"]),
    "tiny": (TINY_CONFIG, 7, 70, 29, 45, ["enc.0.1", "mid.1", "up.1", "dec.0.1", "adapters.1.proj",
                                          "adapters.1.blocks.0", "adapters.2.head"]),
    "fine_alpha": (FINE_ALPHA_CONFIG, 8, 80, 20, 36, ["enc.0.0", "adapters.3.head", "alpha_from_guide"]),
    "half_stem": (HALF_STEM_CONFIG, 9, 90, 27, 41, ["stem", "enc.0.1", "mid.1", "dec.0.1", "adapters.0.blocks.0",
                                                    "adapters.2.head", "alpha_from_guide"]),
    "naf_wide": (NAF_WIDE_CONFIG, 10, 100, 18, 22, ["mid.1", "adapters.0.proj", "adapters.1.blocks.0"]),
    "emission_guide": (EMISSION_GUIDE_CONFIG, 11, 110, 20, 28, ["enc.0.0", "adapters.3.head", "alpha_from_guide"]),
    "emission_passthrough": (EMISSION_PASSTHROUGH_CONFIG, 12, 120, 22, 26, ["adapters.3.head",
                                                                            "alpha_emissive_from_guide"]),
    "albedo_input": (ALBEDO_INPUT_CONFIG, 13, 130, 19, 30, ["enc.0.0", "adapters.3.head"]),
}


def guide_image(seed, height, width, count=3):
    """A guide-like input: smooth blobs of guide and alpha in [0, 1], depth in [0, 1] (and the fine alpha and the
    emission), plus a little noise."""
    rng = np.random.default_rng(seed)
    y, x = np.meshgrid(np.linspace(-1, 1, height), np.linspace(-1, 1, width), indexing="ij")
    channels = []
    for _ in range(count):
        cx, cy, r = rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(0.3, 0.8)
        blob = np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (r * r))
        channels.append(np.clip(blob + rng.uniform(-0.05, 0.05, blob.shape), 0.0, 1.0))
    return torch.from_numpy(np.stack(channels)[None].astype(np.float32))


def make_case(name, out_dir):
    config, weight_seed, guide_seed, height, width, nodes = CASES[name]
    torch.manual_seed(0)
    model = randomize(SixwayNet(config), weight_seed).eval()
    export_safetensors(model, os.path.join(out_dir, f"{name}.safetensors"),
                       {"sixway.training": {"note": "untrained: random weights for tests and benchmarks",
                                            "seed": weight_seed}})
    guide = guide_image(guide_seed, height, width, model.config["guide_channels"])
    tensors = {"input": guide[0]}
    if model.config.get("albedo_input"):  # the raw albedo as a plane after the guide (sixway_net.SixwayNet.forward)
        guide = torch.cat([guide, torch.full_like(guide[:, :1], ALBEDO)], dim=1)
        tensors["albedo"] = torch.tensor([ALBEDO])
    intermediates = {}
    with torch.no_grad():
        raw = run_padded(model, guide, intermediates)
        a, b = pack_lightmaps(decode_output(raw, model.config))
    tensors.update({"raw": raw[0], "lightmap_a": a[0], "lightmap_b": b[0]})
    for node in nodes:
        tensors[f"node.{node}"] = intermediates[node][0]
    tensors = {k: v.numpy().astype(np.float32) for k, v in tensors.items()}
    metadata = {"sixway.vectors": json.dumps({"weights": f"{name}.safetensors", "guide_seed": guide_seed,
                                              "height": height, "width": width})}
    write_safetensors(os.path.join(out_dir, f"{name}_vectors.safetensors"), tensors, metadata)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data", "nn"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    torch.set_num_threads(1)  # one thread: the same summation order on every machine
    for name in CASES:
        make_case(name, args.out)
        print(f"wrote {name}.safetensors and {name}_vectors.safetensors to {args.out}")


if __name__ == "__main__":
    main()
