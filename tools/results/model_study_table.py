#!/usr/bin/python3
"""The model study's table (docs/network-study.md) from what tools/results/model_study.sh wrote into DIR:
<variant>_eval.json (sixway eval --dataset), <variant>_bench.json (sixway bench --sections network) and the
weights' own metadata (config, parameters); where the variant was also trained against the single-scattering
targets, <variant>_ss_eval.json (sixway eval --dataset --target single of data/study_model_<variant>_ss).

Usage: /usr/bin/python3 tools/results/model_study_table.py out/model_study
"""
import glob
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "nn"))
from safetensors_io import read_safetensors  # noqa: E402


def describe(model):
    """A short description of a model config."""
    parts = ["widths " + "/".join(str(w) for w in model["widths"])]
    if model.get("block") == "naf":
        parts.append("NAFBlocks in the UNet")
    adapters = model.get("adapters", {})
    if not adapters.get("enabled", True):
        parts.append("no adapters")
    elif adapters.get("blocks", 1) != 1:
        parts.append(f"{adapters['blocks']} NAFBlocks per adapter")
    if model.get("stem") == "half":
        parts.append("half-resolution stem")
    return ", ".join(parts)


def weights_of(directory, variant):
    if variant == "base":
        return os.path.join(directory, "base.safetensors")
    return os.path.join("data", f"study_model_{variant}_ms", "sixway-unet.safetensors")


def row(directory, variant):
    evaluation = json.load(open(os.path.join(directory, f"{variant}_eval.json")))
    bench = json.load(open(os.path.join(directory, f"{variant}_bench.json")))["network"]
    tensors, metadata = read_safetensors(weights_of(directory, variant))
    training = json.loads(metadata["sixway.training"])
    parameters = sum(t.size for t in tensors.values())
    sizes = {s["size"]: s for s in bench["sizes"]}
    splits = evaluation["splits"]
    ss_path = os.path.join(directory, f"{variant}_ss_eval.json")
    ss = json.load(open(ss_path))["splits"] if os.path.exists(ss_path) else None
    return {
        "variant": variant,
        "model": describe(training["config"]["model"]),
        "parameters": parameters,
        "gflop_256": sizes[256]["flops"] / 1e9,
        "ms_128": sizes[128]["whole"]["median_ms"],
        "ms_256": sizes[256]["whole"]["median_ms"],
        "sequence": splits["heldout_sequence"]["psnr_masked_db"],
        "camera": splits["heldout_camera"]["psnr_masked_db"],
        "lights": min(v for k, v in splits["heldout_sequence"]["pairs_psnr_masked_db"].items()
                      if k != "alpha_emissive"),
        "ss": f"{ss['heldout_sequence']['psnr_masked_db']:.2f} / {ss['heldout_camera']['psnr_masked_db']:.2f}"
              if ss else "–",
    }


def main():
    directory = sys.argv[1]
    variants = sorted(os.path.basename(p)[:-len("_eval.json")] for p in glob.glob(os.path.join(directory, "*_eval.json"))
                      if not p.endswith("_ss_eval.json"))
    rows = sorted((row(directory, v) for v in variants), key=lambda r: r["gflop_256"])
    print("| variant | model | parameters | GFLOP at 256² | GLSL ms 128² | GLSL ms 256² | unseen sequences (dB) "
          "| unseen cameras (dB) | weakest light pair, sequences (dB) | SS-trained vs SS targets: sequences / cameras (dB) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['variant']} | {r['model']} | {r['parameters']:,} | {r['gflop_256']:.2f} | {r['ms_128']:.1f} | "
              f"{r['ms_256']:.1f} | {r['sequence']:.2f} | {r['camera']:.2f} | {r['lights']:.2f} | {r['ss']} |")


if __name__ == "__main__":
    main()
