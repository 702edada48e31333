#!/usr/bin/python3
"""A weighted average of networks fine-tuned from one network (a "model soup", Wortsman et al. 2022): every
tensor is the weighted mean of the files' tensors. Only networks of one architecture average (the same
sixway.config); the result keeps the first file's graph and config.

    /usr/bin/python3 tools/nn/average_weights.py --out data/soup/sixway-unet.safetensors \\
        2:data/train_a/sixway-unet.safetensors 1:data/train_b/sixway-unet.safetensors

sixway.training of the result is the first file's (its training config, which the runtime checks) with
"weight_average" added: each component's weight, file, seed, steps and data. With --metrics-data CONFIG (a
training config) the result's held-out metrics are measured in PyTorch on that config's data, as train.py does at
the end of a run, written to sixway.metrics and to metrics.json beside the output; without it the result has no
sixway.metrics (the components' do not describe it).
"""
import argparse
import json
import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from atomic_file import atomic_open, atomic_path  # noqa: E402
from dataset import SPLITS, ShardDataset  # noqa: E402
from metrics import evaluate_split  # noqa: E402
from sixway_net import export_safetensors, full_config, load_safetensors  # noqa: E402

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
METRICS_DEFINITION = ("docs/conventions.md, \"Metrics\": PSNR on decoded linear lightmaps clipped to [0, 1], MSE "
                      "pooled over all pixels and channels of the split; masked = reference alpha > 0.01; per channel "
                      "group masked; PyTorch float32, whole maps")


def parse_component(text):
    weight, sep, path = text.partition(":")
    try:
        value = float(weight)
    except ValueError:
        value = None
    if not sep or not path or value is None or not value > 0:
        raise ValueError(f"'{text}' is not WEIGHT:FILE with a positive weight")
    return value, path


def average(components):
    """The weighted mean network of [(weight, path)] and its sixway.training metadata."""
    models = []
    for _, path in components:
        try:
            models.append(load_safetensors(path))
        except (OSError, KeyError, ValueError) as error:
            message = str(error)  # the reader's messages already name the file
            raise ValueError(message if path in message else f"{path}: {message}")
    first_model, first_metadata = models[0]
    for (_, path), (model, _) in zip(components[1:], models[1:]):
        if model.config != first_model.config:
            raise ValueError(f"{path}: another architecture than {components[0][1]} (sixway.config differs)")
    total = sum(weight for weight, _ in components)
    states = [model.state_dict() for model, _ in models]
    mean = {key: sum(weight * state[key].double() for (weight, _), state in zip(components, states)) / total
            for key in states[0]}
    first_model.load_state_dict({key: value.float() for key, value in mean.items()})
    training = json.loads(first_metadata.get("sixway.training", "{}"))
    parts = []
    for (weight, path), (_, metadata) in zip(components, models):
        source = json.loads(metadata.get("sixway.training", "{}"))
        config = source.get("config", {})
        parts.append({"weight": weight / total, "file": path, "seed": config.get("train", {}).get("seed"),
                      "steps": source.get("steps"), "init_from": config.get("train", {}).get("init_from"),
                      "data": config.get("data", {}).get("dir")})
    training["weight_average"] = parts
    return first_model, training


def measure(model, config_path):
    """train.py's end-of-run metrics of `model` on the data of the training config at `config_path`."""
    with open(config_path) as f:
        config = json.load(f)
    directories = config["data"]["dir"]
    directories = [directories] if isinstance(directories, str) else directories
    settings = full_config(config["model"])
    data = ShardDataset([os.path.join(REPO_ROOT, d) for d in directories], target=config["data"]["target"],
                        guide_channels=settings["guide_channels"], albedo=bool(settings.get("albedo_input")))
    model.eval()
    return {"definition": METRICS_DEFINITION,
            "pytorch": {split: evaluate_split(model, data, split, torch.device("cpu")) for split in SPLITS}}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="the averaged network (.safetensors); must not exist")
    parser.add_argument("--metrics-data", help="a training config whose data measures the result")
    parser.add_argument("components", nargs="+", help="WEIGHT:FILE, two or more")
    args = parser.parse_args()
    if len(args.components) < 2:
        raise ValueError("give two or more WEIGHT:FILE components")
    if os.path.exists(args.out):
        raise ValueError(f"{args.out}: exists; not overwritten")
    model, training = average([parse_component(text) for text in args.components])
    metadata = {"sixway.training": training}
    if args.metrics_data:
        metrics = measure(model, args.metrics_data)
        metadata["sixway.metrics"] = metrics
        with atomic_open(os.path.join(os.path.dirname(os.path.abspath(args.out)), "metrics.json")) as f:
            json.dump(metrics, f, indent=2)
    with atomic_path(args.out) as partial:  # an interrupted write leaves no broken network behind
        export_safetensors(model, partial, metadata)
    print(f"wrote {args.out}: " + ", ".join(f"{w:.3g} × {p}" for w, p in
                                            ((part["weight"], part["file"]) for part in training["weight_average"])))


if __name__ == "__main__":
    try:
        main()
    except (ValueError, OSError, KeyError, json.JSONDecodeError) as error:
        sys.exit(f"average_weights: {error}")
