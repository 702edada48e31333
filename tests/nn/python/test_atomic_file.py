#!/usr/bin/python3
"""tools/nn/atomic_file.py and the writers built on it (CTest nn.python_atomic_file): a write interrupted by an
exception leaves no file under the final name and no temporary file; a failed rewrite keeps the earlier file."""
import os
import sys
import tempfile
import unittest

try:
    import numpy as np
except ImportError as missing:
    print(f"skipped: {missing} (install python3-numpy)")
    sys.exit(77)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "nn"))
from atomic_file import atomic_open, atomic_path  # noqa: E402
from safetensors_io import read_safetensors, write_safetensors  # noqa: E402


class Interrupted(Exception):
    pass


class AtomicFileTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "out.json")

    def tearDown(self):
        self.dir.cleanup()

    def test_complete_write_appears_under_the_final_name(self):
        with atomic_open(self.path) as f:
            f.write("{}")
        with open(self.path) as f:
            self.assertEqual(f.read(), "{}")
        self.assertEqual(os.listdir(self.dir.name), ["out.json"])

    def test_interrupted_write_leaves_nothing(self):
        with self.assertRaises(Interrupted):
            with atomic_open(self.path) as f:
                f.write("{\"half\": ")
                raise Interrupted()
        self.assertEqual(os.listdir(self.dir.name), [])

    def test_interrupted_rewrite_keeps_the_earlier_file(self):
        with atomic_open(self.path) as f:
            f.write("first")
        with self.assertRaises(Interrupted):
            with atomic_path(self.path) as temporary:
                with open(temporary, "w") as f:
                    f.write("sec")
                raise Interrupted()
        with open(self.path) as f:
            self.assertEqual(f.read(), "first")
        self.assertEqual(os.listdir(self.dir.name), ["out.json"])

    def test_refused_safetensors_rewrite_keeps_the_earlier_file(self):
        """A dtype safetensors lacks is refused; the weights written before stay as they were."""
        path = os.path.join(self.dir.name, "w.safetensors")
        write_safetensors(path, {"a": np.arange(4, dtype=np.float32)})
        with self.assertRaises(ValueError):
            write_safetensors(path, {"a": np.zeros(2, dtype=np.float32), "b": np.zeros(2, dtype=np.complex64)})
        tensors, _ = read_safetensors(path)
        np.testing.assert_array_equal(tensors["a"], np.arange(4, dtype=np.float32))
        self.assertEqual(os.listdir(self.dir.name), ["w.safetensors"])


if __name__ == "__main__":
    unittest.main()
