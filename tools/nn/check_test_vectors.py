#!/usr/bin/python3
"""Regenerates the network test data (make_test_vectors.py) into --out and compares it with the committed files,
so that the committed vectors cannot drift from the PyTorch model in tools/nn/sixway_net.py.

Weights, metadata and the guides must match exactly (they come from seeded numpy generators); PyTorch's outputs
must match to NMSE <= 1e-10 and max-abs <= 1e-5 of the tensor's largest magnitude (at least 1): CPU kernels may sum
in another order on another machine, which moves a sum of terms near 5 by a few float32 ulps of 5 (1.7e-5 on an AMD
EPYC against the vectors made elsewhere, NMSE 5e-13).
Exit status: 0 equal, 1 different (each difference printed), 77 when torch or numpy is missing (CTest: skipped).

Usage: /usr/bin/python3 tools/nn/check_test_vectors.py --committed tests/data/nn --out build/nn-vectors
"""
import argparse
import os
import sys

try:
    import numpy as np
    import torch  # noqa: F401  (make_test_vectors needs it)
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_test_vectors  # noqa: E402
from safetensors_io import read_safetensors  # noqa: E402

OUTPUT_NMSE = 1e-10
OUTPUT_MAX_ABS = 1e-5


def compare(name, committed_path, fresh_path):
    problems = []
    committed, committed_meta = read_safetensors(committed_path)
    fresh, fresh_meta = read_safetensors(fresh_path)
    if committed_meta != fresh_meta:
        problems.append(f"{name}: metadata differs")
    if list(committed) != list(fresh):
        problems.append(f"{name}: tensors differ: {sorted(set(committed) ^ set(fresh))}")
        return problems
    exact = not name.endswith("_vectors.safetensors")
    for key, old in committed.items():
        new = fresh[key]
        if old.shape != new.shape:
            problems.append(f"{name}: {key}: shape {old.shape} is now {new.shape}")
        elif exact or key == "input":
            if not np.array_equal(old, new):
                problems.append(f"{name}: {key}: values differ (max-abs {np.abs(old - new).max():.3g})")
        else:
            error = float(np.sum((old.astype(np.float64) - new) ** 2) / max(np.sum(old.astype(np.float64) ** 2), 1e-30))
            worst = float(np.abs(old - new).max())
            scale = max(1.0, float(np.abs(old).max()))
            if error > OUTPUT_NMSE or worst > OUTPUT_MAX_ABS * scale:
                problems.append(f"{name}: {key}: NMSE {error:.3g}, max-abs {worst:.3g}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--committed", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    torch.set_num_threads(1)
    problems = []
    for case in make_test_vectors.CASES:
        make_test_vectors.make_case(case, args.out)
        for name in (f"{case}.safetensors", f"{case}_vectors.safetensors"):
            problems += compare(name, os.path.join(args.committed, name), os.path.join(args.out, name))
    for problem in problems:
        print(problem)
    print("test vectors: " + ("DIFFERENT from the committed ones" if problems else "identical to the committed ones"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
