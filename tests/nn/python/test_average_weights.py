#!/usr/bin/python3
"""tools/nn/average_weights.py against the mean written out in numpy (CTest nn.python_average_weights; exit 77
without torch)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

try:
    import numpy as np
    import torch  # noqa: F401
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "nn")
sys.path.insert(0, TOOLS)
from safetensors_io import read_safetensors  # noqa: E402
from sixway_net import SixwayNet, export_safetensors, randomize  # noqa: E402

SMALL = {"widths": [4, 8], "depth": 1, "adapters": {"enabled": True, "width": 4, "blocks": 1}}


def network(path, seed, config=SMALL, training_seed=None):
    model = SixwayNet(config)
    randomize(model, seed)
    training = {"config": {"train": {"seed": training_seed or seed}, "data": {"dir": f"data/{seed}"}}, "steps": 7}
    export_safetensors(model, path, {"sixway.training": training})


def run(*args):
    return subprocess.run([sys.executable, os.path.join(TOOLS, "average_weights.py"), *args],
                          capture_output=True, text=True)


class AverageWeightsTest(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.TemporaryDirectory()
        self.a, self.b = (os.path.join(self.work.name, name) for name in ("a.safetensors", "b.safetensors"))
        network(self.a, 1)
        network(self.b, 2)
        self.out = os.path.join(self.work.name, "soup.safetensors")

    def tearDown(self):
        self.work.cleanup()

    def test_every_tensor_is_the_weighted_mean(self):
        result = run("--out", self.out, f"3:{self.a}", f"1:{self.b}")
        self.assertEqual(result.returncode, 0, result.stderr)
        (a, _), (b, _), (soup, metadata) = (read_safetensors(p) for p in (self.a, self.b, self.out))
        self.assertEqual(set(soup), set(a))
        differs = 0
        for name in a:
            expected = 0.75 * a[name].astype(np.float64) + 0.25 * b[name].astype(np.float64)
            np.testing.assert_allclose(soup[name], expected, rtol=1e-6, atol=1e-7, err_msg=name)
            differs += not np.array_equal(a[name], b[name])
        self.assertGreater(differs, 0)  # the two networks are not the same, so the mean is not trivially either
        parts = json.loads(metadata["sixway.training"])["weight_average"]
        self.assertEqual([(p["weight"], p["seed"], p["data"]) for p in parts],
                         [(0.75, 1, "data/1"), (0.25, 2, "data/2")])
        self.assertNotIn("sixway.metrics", metadata)  # the components' metrics do not describe the mean

    def test_bad_input_is_one_line_naming_the_file(self):
        other = os.path.join(self.work.name, "other.safetensors")
        network(other, 3, config={**SMALL, "widths": [4, 12]})
        for args, message in (([f"1:{self.a}", f"1:{other}"], f"{other}: another architecture"),
                              ([f"1:{self.a}", f"0:{self.b}"], "positive weight"),
                              ([f"1:{self.a}", f"1:{self.work.name}/missing"], "missing"),
                              ([f"1:{self.a}"], "two or more")):
            result = run("--out", self.out, *args)
            self.assertNotEqual(result.returncode, 0, args)
            self.assertIn(message, result.stderr)
            self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
            self.assertFalse(os.path.exists(self.out))

    def test_an_existing_output_is_not_overwritten(self):
        with open(self.out, "w") as f:
            f.write("kept")
        result = run("--out", self.out, f"1:{self.a}", f"1:{self.b}")
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("not overwritten", result.stderr)
        with open(self.out) as f:
            self.assertEqual(f.read(), "kept")


if __name__ == "__main__":
    unittest.main()
