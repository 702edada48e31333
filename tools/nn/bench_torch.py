#!/usr/bin/python3
"""PyTorch CPU side of the inference benchmark (docs/benchmarks.md, "Neural inference"): the same network
(read from the same safetensors file as `sixway bench`), the same sizes, 2 threads, warm-up then the median of
repeated runs, in total and per layer, with GFLOP/s counted from the graph by the rule of the GLSL side
(2 FLOPs per multiply-add of the convolutions over the real channels; normalisation and elementwise work are
not counted).

Usage: /usr/bin/python3 tools/nn/bench_torch.py [--weights tests/data/nn/default.safetensors] [--size 128 256]
                                                [--threads 2] [--repeats 10] [--report out.json]
"""
import argparse
import json
import os
import statistics
import sys
import time

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from atomic_file import atomic_open  # noqa: E402
from sixway_net import input_channel_count, load_safetensors  # noqa: E402


def node_flops(node, height, width):
    """FLOPs of one node for an input of height x width (the counting rule of src/nn)."""
    pixels = (height // node["scale"]) * (width // node["scale"])
    op = node["op"]
    if op == "conv2d":
        return 2.0 * node["in_channels"] * node["out_channels"] * node["kernel"] ** 2 * pixels
    if op == "conv_transpose2d":
        return 2.0 * node["in_channels"] * node["out_channels"] * pixels
    if op == "naf_block":
        c = node["in_channels"]
        g, f = c * node["dw_expand"] // 2, c * node["ffn_expand"] // 2
        return 2.0 * pixels * (c * 2 * g + 9 * 2 * g + g * c + c * 2 * f + f * c)
    return 0.0


def layer_kind(node):
    if node["op"] in ("conv2d", "conv_transpose2d"):
        k = node["kernel"]
        return f"{node['op']} {k}x{k}" + (" s2" if node["op"] == "conv2d" and node["stride"] == 2 else "")
    return node["op"]


def bench_size(model, size, warmup, repeats):
    guide = torch.rand(1, input_channel_count(model.config), size, size)
    with torch.no_grad():
        for _ in range(warmup):
            model(guide)
        totals = []
        for _ in range(repeats):
            start = time.perf_counter()
            model(guide)
            totals.append(time.perf_counter() - start)
        per_node = {node["name"]: [] for node in model.nodes}
        for _ in range(repeats):
            seconds = {}
            model(guide, seconds=seconds)
            for name, s in seconds.items():
                per_node[name].append(s)
    layers, kinds, total_flops = [], {}, 0.0
    for node in model.nodes:
        ms = statistics.median(per_node[node["name"]]) * 1e3
        flops = node_flops(node, size, size)
        total_flops += flops
        layers.append({"name": node["name"], "kind": layer_kind(node), "ms": ms, "flops": flops,
                       "gflops_per_s": flops / ms * 1e-6 if ms > 0 else 0.0})
        entry = kinds.setdefault(layer_kind(node), {"ms": 0.0, "flops": 0.0})
        entry["ms"] += ms
        entry["flops"] += flops
    for entry in kinds.values():
        entry["gflops_per_s"] = entry["flops"] / entry["ms"] * 1e-6 if entry["ms"] > 0 else 0.0
    total_ms = statistics.median(totals) * 1e3
    return {"size": size, "total_ms": total_ms, "flops": total_flops,
            "gflops_per_s": total_flops / total_ms * 1e-6, "layers": layers, "by_kind": kinds}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    parser.add_argument("--weights", default=os.path.join(root, "tests", "data", "nn", "default.safetensors"))
    parser.add_argument("--size", type=int, nargs="+", default=[128, 256])
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--warmup", type=int, default=3)
    parser.add_argument("--repeats", type=int, default=10)
    parser.add_argument("--report")
    args = parser.parse_args()
    torch.set_num_threads(args.threads)
    model, _ = load_safetensors(args.weights)
    model.eval()
    report = {"torch": torch.__version__, "threads": args.threads, "weights": args.weights, "sizes": []}
    print(f"PyTorch {torch.__version__} CPU, {args.threads} threads: {args.weights}")
    for size in args.size:
        result = bench_size(model, size, args.warmup, args.repeats)
        report["sizes"].append(result)
        print(f"\n{size}x{size}: {result['total_ms']:.2f} ms (median of {args.repeats}), "
              f"{result['flops'] * 1e-9:.2f} GFLOP, {result['gflops_per_s']:.1f} GFLOP/s")
        print("  per layer type (timed node by node):")
        for kind, entry in sorted(result["by_kind"].items()):
            print(f"  {kind:45s} {entry['ms']:9.3f} {entry['gflops_per_s']:9.1f}")
    if args.report:
        with atomic_open(args.report) as f:
            json.dump(report, f, indent=2)


if __name__ == "__main__":
    main()
