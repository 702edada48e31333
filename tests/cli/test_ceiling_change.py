#!/usr/bin/python3
"""tools/results/ceiling_change.py on reports written by hand (CTest results.ceiling_change): a change built as
sqrt(c0^2 + k/N) at N and 4N samples comes back as c0, a scene missing from the first directory is left out, and
two runs with different truths, a broken report and no common scene are one error line."""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "results", "ceiling_change.py")


def write_report(directory, scene, truth, rms_by_method):
    os.makedirs(directory, exist_ok=True)
    methods = {m: {"rms": r} for m, r in rms_by_method.items()}
    report = {"summary": {"temporal": {"truth": {"rms_without_noise": truth}, "methods": methods}}}
    with open(os.path.join(directory, f"{scene}.report.json"), "w") as f:
        json.dump(report, f)


def noisy(c0, k, samples):
    return math.sqrt(c0 ** 2 + k / samples)


def run(low, high):
    return subprocess.run([sys.executable, SCRIPT, low, high], capture_output=True, text=True)


class CeilingChangeTest(unittest.TestCase):
    def test_recovers_the_change_without_noise(self):
        with tempfile.TemporaryDirectory() as work:
            low, high = os.path.join(work, "n64"), os.path.join(work, "n256")
            # truth 0.02; reference-ms c0 = 0.014 (0.70x), traditional-ms c0 = 0.010 (0.50x), different noise.
            for directory, samples in ((low, 64), (high, 256)):
                write_report(directory, "jet", 0.02, {"neural": 0.015, "reference-ms": noisy(0.014, 0.0064, samples),
                                                      "traditional-ms": noisy(0.010, 0.0128, samples)})
            write_report(high, "only_in_high", 0.02, {"neural": 0.01, "reference-ms": 0.01, "traditional-ms": 0.01})
            result = run(low, high)
            self.assertEqual(result.returncode, 0, result.stderr)
            rows = [line for line in result.stdout.splitlines() if line.startswith("| jet ")]
            self.assertEqual(len(rows), 1, result.stdout)
            self.assertIn("| 0.75× |", rows[0])  # the neural change over the truth's
            self.assertIn("**0.70×**", rows[0])
            self.assertIn("**0.50×**", rows[0])
            self.assertIn(f"{noisy(0.014, 0.0064, 64) / 0.02:.2f}×", rows[0])
            self.assertNotIn("only_in_high", result.stdout)

    def test_refuses_runs_with_different_truths(self):
        with tempfile.TemporaryDirectory() as work:
            low, high = os.path.join(work, "a"), os.path.join(work, "b")
            rms = {"neural": 0.01, "reference-ms": 0.02, "traditional-ms": 0.02}
            write_report(low, "plume", 0.020, rms)
            write_report(high, "plume", 0.021, rms)
            result = run(low, high)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("plume.report.json: another truth", result.stderr)

    def test_one_error_line_for_a_broken_report_or_no_common_scene(self):
        with tempfile.TemporaryDirectory() as work:
            low, high = os.path.join(work, "a"), os.path.join(work, "b")
            write_report(high, "plume", 0.02, {"neural": 0.01, "reference-ms": 0.02, "traditional-ms": 0.02})
            result = run(low, high)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("no scene has a report in both", result.stderr)
            os.makedirs(low)
            with open(os.path.join(low, "plume.report.json"), "w") as f:
                f.write("{ not json")
            result = run(low, high)
            self.assertNotEqual(result.returncode, 0)
            self.assertIn("plume.report.json: not a sixway eval --scene --truth-noise report", result.stderr)
            self.assertNotIn("Traceback", result.stderr)

    def test_usage_without_two_directories(self):
        result = subprocess.run([sys.executable, SCRIPT], capture_output=True, text=True)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("Usage: ceiling_change.py DIR_N DIR_4N", result.stderr)


if __name__ == "__main__":
    unittest.main()
