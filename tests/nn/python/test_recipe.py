#!/usr/bin/python3
"""tools/train.py --recipe (CTest nn.python_recipe; exit 77 without torch): the tiny recipe makes its data with
the real `sixway dataset` and trains its two phases; run straight, and stopped inside its second phase and rerun,
it ends with bit-identical weights; a finished recipe rerun trains nothing; the second phase starts from the
first's weights; two processes (DDP over gloo) share the data and the phases; the shipped recipes read; bad
recipes get one line naming the file and the key.

Usage: /usr/bin/python3 tests/nn/python/test_recipe.py --work DIR --sixway PATH
"""
import copy
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import unittest

try:
    import numpy as np
    import torch  # noqa: F401 (train.py's dependency: skip without it)
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", "..", ".."))
sys.path.insert(0, os.path.join(root, "tools", "nn"))
from recipe import Recipe, RecipeError, scaled  # noqa: E402
from safetensors_io import read_safetensors  # noqa: E402

TRAIN = os.path.join(root, "tools", "train.py")
TINY = os.path.join(root, "tools", "train_configs", "recipes", "tiny.json")
WORK = SIXWAY = None  # set from the command line


def run_recipe(recipe, out, *extra, env=None):
    command = [sys.executable, TRAIN, "--recipe", recipe, "--out", out, "--data-root", os.path.join(WORK, "data"),
               "--sixway", SIXWAY, *extra]
    return subprocess.run(command, capture_output=True, text=True, env=env)


def weights(path):
    return read_safetensors(path)[0]


def same_weights(a, b):
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def write_recipe(name, edit):
    with open(TINY) as f:
        recipe = json.load(f)
    edit(recipe)
    path = os.path.join(WORK, name)
    with open(path, "w") as f:
        json.dump(recipe, f)
    return path


class RecipeRunTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.straight, cls.resumed = os.path.join(WORK, "straight"), os.path.join(WORK, "resumed")
        cls.runs = [run_recipe("tiny", cls.straight), run_recipe("tiny", cls.resumed, "--stop-at", "5")]
        cls.stopped = os.path.exists(os.path.join(cls.resumed, "sixway-unet.safetensors"))
        cls.runs.append(run_recipe("tiny", cls.resumed))

    def test_runs_succeed(self):
        for run in self.runs:
            self.assertEqual(run.returncode, 0, run.stdout[-2000:] + run.stderr[-2000:])

    def test_the_data_is_made_once(self):
        self.assertTrue(os.path.exists(os.path.join(WORK, "data", "data", "tiny", "shard_00001.safetensors")))
        self.assertIn("wrote 2 shards", self.runs[0].stdout + self.runs[0].stderr)
        self.assertIn("0 to make, 2 already made", self.runs[1].stdout + self.runs[1].stderr)

    def test_a_stopped_recipe_resumes_bit_identically(self):
        self.assertFalse(self.stopped, "--stop-at 5 inside the second phase wrote the recipe's network")
        self.assertIn("phase maps: done", self.runs[2].stdout)
        self.assertIn("phase shaded: resumed", self.runs[2].stdout)
        final = weights(os.path.join(self.straight, "sixway-unet.safetensors"))
        self.assertTrue(same_weights(final, weights(os.path.join(self.resumed, "sixway-unet.safetensors"))))
        self.assertTrue(same_weights(final, weights(os.path.join(self.straight, "02_shaded", "sixway-unet.safetensors"))))
        self.assertFalse(same_weights(final, weights(os.path.join(self.straight, "01_maps", "sixway-unet.safetensors"))))

    def test_a_recipe_stopped_between_phases_has_no_network_yet(self):
        out = os.path.join(WORK, "between")
        run = run_recipe("tiny", out, "--stop-at", "4")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertTrue(os.path.exists(os.path.join(out, "01_maps", "sixway-unet.safetensors")))
        self.assertFalse(os.path.exists(os.path.join(out, "02_shaded")))
        self.assertFalse(os.path.exists(os.path.join(out, "sixway-unet.safetensors")))

    def test_the_summary_and_the_metadata_name_the_recipe(self):
        with open(os.path.join(self.straight, "recipe.json")) as f:
            summary = json.load(f)
        self.assertEqual([(p["name"], p["steps"]) for p in summary["phases"]], [("maps", 4), ("shaded", 4)])
        self.assertGreater(summary["data_seconds"]["data/tiny"], 0)
        self.assertAlmostEqual(summary["wall_seconds"], sum(summary["data_seconds"].values())
                               + sum(p["wall_seconds"] for p in summary["phases"]), delta=0.2)
        self.assertEqual(summary["sha256"], Recipe(TINY, WORK, root, WORK, "cpu").digest)
        _, metadata = read_safetensors(os.path.join(self.straight, "sixway-unet.safetensors"))
        self.assertEqual(json.loads(metadata["sixway.recipe"])["phases"], summary["phases"])
        self.assertEqual(json.loads(metadata["sixway.training"])["steps"], 4)

    def test_a_finished_recipe_rerun_trains_nothing(self):
        export = os.path.join(self.straight, "02_shaded", "sixway-unet.safetensors")
        before = os.stat(export).st_mtime_ns
        run = run_recipe("tiny", self.straight)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("phase maps: done", run.stdout)
        self.assertIn("phase shaded: done", run.stdout)
        self.assertNotIn("train:", run.stdout)
        self.assertEqual(os.stat(export).st_mtime_ns, before)

    def test_each_phase_starts_from_the_one_before(self):
        def frozen(recipe):  # the second phase at a learning rate of 0 keeps the first phase's weights
            recipe["phases"][1]["config"]["train"].update(lr=0.0, min_lr=0.0)
        out = os.path.join(WORK, "frozen")
        run = run_recipe(write_recipe("frozen.json", frozen), out)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertTrue(same_weights(weights(os.path.join(out, "sixway-unet.safetensors")),
                                     weights(os.path.join(self.straight, "01_maps", "sixway-unet.safetensors"))))

    def test_a_phase_that_ended_with_another_config_is_an_error(self):
        def longer(recipe):
            recipe["phases"][0]["config"]["train"]["steps"] = 5
        run = run_recipe(write_recipe("longer.json", longer), self.straight)
        self.assertNotEqual(run.returncode, 0)
        self.assertEqual(run.stderr.strip(), f"train: {os.path.join(self.straight, '01_maps')}: ended with another "
                                             f"'train.steps' than the recipe's phase 'maps'; remove the directory to "
                                             f"train the phase again")

    def test_two_processes_share_the_data_and_the_phases(self):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        out, data = os.path.join(WORK, "ddp"), os.path.join(WORK, "ddp_data")
        processes = []
        for rank in range(2):
            env = dict(os.environ, WORLD_SIZE="2", RANK=str(rank), LOCAL_RANK=str(rank), MASTER_ADDR="127.0.0.1",
                       MASTER_PORT=str(port))
            command = [sys.executable, TRAIN, "--recipe", "tiny", "--out", out, "--data-root", data, "--sixway", SIXWAY]
            processes.append(subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                              text=True))
        logs = [p.communicate(timeout=300)[0] for p in processes]
        for p, log in zip(processes, logs):
            self.assertEqual(p.returncode, 0, log[-2000:])
        self.assertIn("--shard 0/2", logs[0])
        self.assertIn("--shard 1/2", logs[1])
        self.assertIn("2 process(es)", logs[0])
        final = weights(os.path.join(out, "sixway-unet.safetensors"))
        self.assertFalse(same_weights(final, weights(os.path.join(out, "01_maps", "sixway-unet.safetensors"))))

    def test_a_terminated_recipe_counts_its_time_and_stops_making_data(self):
        data, out = os.path.join(WORK, "terminated_data"), os.path.join(WORK, "terminated")
        process = subprocess.Popen([sys.executable, TRAIN, "--recipe", "tiny", "--out", out, "--data-root", data,
                                    "--sixway", SIXWAY], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(600):  # until `sixway dataset` has begun the set
            if os.path.isdir(os.path.join(data, "data", "tiny")) or process.poll() is not None:
                break
            time.sleep(0.1)
        time.sleep(0.5)
        process.send_signal(signal.SIGTERM)
        self.assertEqual(process.wait(timeout=60), 128 + signal.SIGTERM)
        with open(os.path.join(out, "data_seconds.json")) as f:
            self.assertGreater(json.load(f)["data/tiny"], 0)
        running = subprocess.run(["pgrep", "-f", f"dataset .*{data}"], capture_output=True, text=True).stdout
        self.assertEqual(running.strip(), "", "sixway dataset still runs")

    def test_a_data_shard_makes_its_share_only(self):
        data = os.path.join(WORK, "shard_data")
        run = subprocess.run([sys.executable, TRAIN, "--recipe", "tiny", "--out", os.path.join(WORK, "shard"),
                              "--data-root", data, "--sixway", SIXWAY, "--data-shard", "1/2"], capture_output=True,
                             text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(sorted(f for f in os.listdir(os.path.join(data, "data", "tiny")) if f.startswith("shard_")),
                         ["shard_00001.safetensors"])
        with open(os.path.join(WORK, "shard", "data_seconds.json")) as f:
            self.assertGreater(json.load(f)["data/tiny"], 0)
        self.assertFalse(os.path.exists(os.path.join(WORK, "shard", "phases")))


class RecipeFileTest(unittest.TestCase):
    def test_the_shipped_recipes_read(self):
        for name in ("ms", "ss"):
            recipe = Recipe(os.path.join(root, "tools", "train_configs", "recipes", f"{name}.json"), WORK, root, root,
                            "cpu")
            self.assertEqual(recipe.phases[-1].config["model"]["widths"], [24, 48, 96] if name == "ms" else [16, 32, 64])
            for earlier, later in zip(recipe.phases, recipe.phases[1:]):
                self.assertEqual(later.config["train"]["init_from"], earlier.directory)
        ms = Recipe(os.path.join(root, "tools", "train_configs", "recipes", "ms.json"), WORK, root, root, "cpu")
        mantaflow = next(d for d in ms.datasets if d.name == "data/families/mantaflow_train")
        self.assertEqual(mantaflow.sequences((0, 1)), list(range(1, 9)))
        self.assertNotIn("chimney_wind", json.dumps([d.config for d in ms.datasets]))

    def test_a_profile_scales_batch_steps_and_rates(self):
        config = {"train": {"batch": 8, "steps": 1001, "warmup_steps": 100, "log_every": 25, "lr": 0.002,
                            "min_lr": 2e-05}}
        gpu = scaled(copy.deepcopy(config), {"batch_scale": 8, "lr_scale": 2.0})["train"]
        self.assertEqual((gpu["batch"], gpu["steps"], gpu["warmup_steps"], gpu["log_every"]), (64, 126, 13, 4))
        self.assertAlmostEqual(gpu["lr"], 0.004)
        self.assertAlmostEqual(gpu["min_lr"], 4e-05)
        recipe = Recipe(TINY, WORK, root, WORK, "gpu")
        self.assertEqual(recipe.phases[1].config["train"]["batch"], 4)
        self.assertEqual(recipe.phases[1].config["train"]["steps"], 2)

    def test_bad_recipes_are_one_line(self):
        cases = [
            (lambda r: r.update(phasse=[]), "unknown key 'phasse'"),
            (lambda r: r["phases"][1]["config"].update(data={"dir": ["data/other"]}),
             "phases[1]: data.dir 'data/other' is not one of the recipe's datasets"),
            (lambda r: r["phases"][1]["config"]["train"].update(init_from="weights/x.safetensors"),
             "phases[1]: train.init_from is the recipe's (the phase before); remove it"),
            (lambda r: r["datasets"][0].update(config="tools/datasets/none.json"),
             "datasets[0]: tools/datasets/none.json: no such dataset config"),
            (lambda r: r["datasets"][0].update(skip_sequences=[2]),
             "datasets[0]: skip_sequences must be sequence indices in 0..1"),
            (lambda r: r["phases"][1].update(name="maps"), "phases[1]: 'name' must be a unique word"),
            (lambda r: r["profiles"]["gpu"].update(batch_scale=0), "batch_scale must be an integer in 1..1024"),
            (lambda r: r["phases"][0]["config"]["train"].pop("batch"),
             "phases[0]: train.steps and train.batch must be given"),
        ]
        for k, (edit, message) in enumerate(cases):
            path = write_recipe(f"bad{k}.json", edit)
            run = run_recipe(path, os.path.join(WORK, f"bad{k}"), "--profile", "gpu")
            self.assertNotEqual(run.returncode, 0)
            self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
            self.assertTrue(run.stderr.startswith(f"train: {path}: "), run.stderr)
            self.assertIn(message, run.stderr)
            self.assertFalse(os.path.exists(os.path.join(WORK, f"bad{k}")))
        run = run_recipe("none", os.path.join(WORK, "bad"))
        self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
        self.assertIn("recipes/none.json: [Errno 2] No such file or directory", run.stderr)
        with self.assertRaises(RecipeError):
            Recipe(TINY, WORK, root, WORK, "tpu")


if __name__ == "__main__":
    if len(sys.argv) < 5 or sys.argv[1] != "--work" or sys.argv[3] != "--sixway":
        sys.exit(__doc__)
    WORK, SIXWAY = sys.argv[2], sys.argv[4]
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    unittest.main(argv=sys.argv[:1] + sys.argv[5:])
