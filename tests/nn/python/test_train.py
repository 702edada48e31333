#!/usr/bin/python3
"""Smoke test of tools/train.py (CTest nn.python_train; exit 77 without torch): the tiny config for 6 steps on
synthetic shards, once straight through and once stopped at step 3 and resumed; the two must give bit-identical
weights and optimizer state. The straight run's export is left in WORK/straight/ for nn.train_export_bench
(the C++ runner loads it). Also train.init_from into a network with the guide's emission as a 5th input.

Usage: /usr/bin/python3 tests/nn/python/test_train.py --work DIR
"""
import json
import os
import subprocess
import sys
import types
import unittest

try:
    import numpy as np
    import torch
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, "..", "..", ".."))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(root, "tools", "nn"))
sys.path.insert(0, os.path.join(root, "tools"))
import synthetic_shards  # noqa: E402
import train as train_module  # noqa: E402
from safetensors_io import read_safetensors  # noqa: E402
from bench_torch import node_flops  # noqa: E402
from sixway_net import (OUTPUT_CHANNELS, SixwayNet, decode_output, export_safetensors, load_safetensors,  # noqa: E402
                        randomize, run_padded)
from net2deeper import deeper_state  # noqa: E402
from net2wider import wider_state  # noqa: E402

TRAIN = os.path.join(root, "tools", "train.py")
CONFIG = os.path.join(root, "tools", "train_configs", "tiny.json")
WORK = None  # set from --work


def train(out, *extra):
    data = os.path.join(WORK, "data")
    result = subprocess.run([sys.executable, TRAIN, "--config", CONFIG, "--data", data, "--out", out, *extra],
                            capture_output=True, text=True)
    return result


class HalfStemTest(unittest.TestCase):
    """model.stem "half": the UNet and adapters at half resolution; the output stays at the guide's size."""

    def test_half_stem_keeps_the_size_and_quarters_the_flops(self):
        config = {"widths": [16, 32, 64]}
        full, half = SixwayNet(config), SixwayNet({**config, "stem": "half"})
        self.assertEqual(half.size_multiple(), 2 * full.size_multiple())
        with torch.no_grad():
            self.assertEqual(tuple(half(torch.rand(1, 4, 16, 24)).shape), (1, 8, 16, 24))
        flops = [sum(node_flops(node, 256, 256) for node in net.nodes) for net in (full, half)]
        self.assertLess(flops[1], 0.3 * flops[0])
        self.assertGreater(flops[1], 0.2 * flops[0])
        with self.assertRaisesRegex(ValueError, "stem must be full or half"):
            SixwayNet({"stem": "quarter"})
        # The GLSL input node holds two groups of four channels (src/nn/graph.cpp).
        with self.assertRaisesRegex(ValueError, "input_channels must be at most 8"):
            SixwayNet({"input_channels": 12})


def tune_from_checkpoint(name, old_config, old, guide_channels, model, exported=False, **train_settings):
    """A one-step run at lr 0 of `model` with train.init_from a checkpoint of network `old` (config `old_config`), or
    with `exported` the network's .safetensors file, on synthetic shards of `guide_channels`. Returns the finished
    process and the run's directory."""
    checkpoint = os.path.join(WORK, name, "checkpoint.pt")
    os.makedirs(os.path.dirname(checkpoint), exist_ok=True)
    torch.save({"config": {"model": old_config}, "model": old.state_dict()}, checkpoint)
    if exported:
        checkpoint = os.path.join(WORK, name, "exported", "network.safetensors")
        os.makedirs(os.path.dirname(checkpoint), exist_ok=True)
        export_safetensors(old, checkpoint)
    data = os.path.join(WORK, f"data_{name}")
    synthetic_shards.write_shards(data, size=16, cameras=3, frames=4, sequences=2, guide_channels=guide_channels)
    with open(CONFIG) as f:
        tune = json.load(f)
    tune["model"] = model
    tune["train"].update(init_from=checkpoint if exported else os.path.dirname(checkpoint), lr=0.0, min_lr=0.0, steps=1, **train_settings)
    config = os.path.join(WORK, f"tune_{name}.json")
    with open(config, "w") as f:
        json.dump(tune, f)
    out = os.path.join(WORK, f"{name}_tuned")
    run = subprocess.run([sys.executable, TRAIN, "--config", config, "--data", data, "--out", out, "--force"],
                         capture_output=True, text=True)
    return run, out


class WidenedInitTest(unittest.TestCase):
    """train.init_from from a network of 4 guide channels into one that also reads the emission (5 of 8 inputs)."""
    FOUR = {"widths": [4, 8], "depth": 1, "adapters": {"width": 4}, "guide_channels": 4,
            "guide_alpha_step_voxels": 1.0, "alpha": "guide"}
    FIVE = dict(FOUR, guide_channels=5, input_channels=8)

    def widened(self):
        old = randomize(SixwayNet(self.FOUR), 3).eval()
        new = SixwayNet(self.FIVE).eval()
        state, widened = train_module.widened_weights(old.state_dict(), new.state_dict())
        new.load_state_dict(state)
        return old, new, widened

    def test_the_widened_network_computes_the_old_function(self):
        old, new, widened = self.widened()
        self.assertEqual(widened, ["enc.0.0.weight"])  # alpha_from_guide is the new network's own selection
        guide = torch.rand(2, 4, 8, 8, generator=torch.Generator().manual_seed(1))
        with torch.no_grad():
            torch.testing.assert_close(new(torch.cat([guide, torch.zeros(2, 1, 8, 8)], 1)), old(guide),
                                       rtol=0, atol=1e-6)

    def test_the_emission_trains_the_new_weights(self):
        # The new input weights start at zero, so the step-0 output ignores the emission; the gradient reaches the
        # emission's weights exactly when the emission is not zero.
        _, new, _ = self.widened()
        guide = torch.rand(2, 5, 8, 8, generator=torch.Generator().manual_seed(2))
        outputs = []
        for emission, moves in ((0.0, False), (3.0, True)):
            new.zero_grad()
            outputs.append(new(torch.cat([guide[:, :4], emission * guide[:, 4:]], 1)))
            outputs[-1].square().mean().backward()
            grad = new.module("enc.0.0").weight.grad
            self.assertEqual(bool(grad[:, 4].abs().sum() > 0), moves)
            self.assertFalse(grad[:, 5:].any())
        self.assertTrue(torch.equal(outputs[0], outputs[1]))

    def test_the_emission_passed_through(self):
        """A 4-channel network widened into one whose emissive is the guide's emission: the other seven outputs
        are the old network's, the emissive is the emission itself (linear; decoded unchanged, clamped at 0)."""
        old = randomize(SixwayNet(self.FOUR), 5).eval()
        new = SixwayNet(dict(self.FIVE, emissive="guide")).eval()
        state, widened = train_module.widened_weights(old.state_dict(), new.state_dict())
        new.load_state_dict(state)
        self.assertEqual(widened, ["enc.0.0.weight"])
        guide = torch.rand(2, 5, 8, 8, generator=torch.Generator().manual_seed(3))
        with torch.no_grad():
            before = decode_output(old(guide[:, :4]), old.config)
            after = decode_output(new(guide), new.config)
        emissive = OUTPUT_CHANNELS.index("emissive")
        others = [k for k in range(8) if k != emissive]
        torch.testing.assert_close(after[:, others], before[:, others], rtol=0, atol=1e-6)
        torch.testing.assert_close(after[:, emissive], guide[:, 4], rtol=0, atol=0)

    def test_the_emission_passed_through_needs_it_in_the_guide(self):
        with self.assertRaisesRegex(ValueError, "emissive from the guide needs its emission"):
            SixwayNet(dict(self.FOUR, emissive="guide"))
        with self.assertRaisesRegex(ValueError, "emissive must be network or guide"):
            SixwayNet(dict(self.FIVE, emissive="baker"))

    def test_only_more_guide_and_input_channels_widen(self):
        widens = train_module.widens
        self.assertTrue(widens(self.FOUR, self.FIVE))
        self.assertTrue(widens(self.FOUR, self.FOUR))
        self.assertFalse(widens(self.FIVE, self.FOUR))
        self.assertFalse(widens(self.FOUR, dict(self.FIVE, widths=[4, 4])))
        self.assertFalse(widens(self.FOUR, dict(self.FIVE, alpha="network")))
        self.assertTrue(widens(self.FOUR, dict(self.FIVE, emissive="guide")))  # an output passed through
        self.assertTrue(widens(dict(self.FOUR, emissive="network"), self.FIVE))  # the default spelt out
        self.assertFalse(widens(dict(self.FIVE, emissive="guide"), self.FIVE))
        self.assertFalse(widens({"widths": [4, 8], "depth": 1, "adapters": {"width": 4}}, self.FIVE))  # a step more

    def test_init_from_a_narrower_checkpoint(self):
        """A 4-channel checkpoint starts a 5-channel run on 4-channel shards of a scene without emission (their
        emission reads as zeros): at a zero rate the export is the checkpoint widened with zeros."""
        old = randomize(SixwayNet(self.FOUR), 4)
        run, out = tune_from_checkpoint("four", self.FOUR, old, 4, self.FIVE)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("train.init_from: enc.0.0.weight widened", run.stdout)
        tuned, _ = read_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        for name, value in old.named_tensors().items():
            if name.startswith("alpha_from_guide."):
                continue  # a fixed selection: the new network's own (below)
            value = value.detach().numpy()
            self.assertTrue(np.array_equal(tuned[name][:, :4] if name == "enc.0.0.weight" else tuned[name], value),
                            name)
        self.assertFalse(tuned["enc.0.0.weight"][:, 4:].any())
        fresh = SixwayNet(self.FIVE).named_tensors()["alpha_from_guide.weight"].detach().numpy()
        self.assertTrue(np.array_equal(tuned["alpha_from_guide.weight"], fresh))


class AlbedoInputTest(unittest.TestCase):
    """train.init_from from a network of 5 guide channels in 8 inputs into one that also reads the smoke's albedo
    in the 6th: that channel's weights start at zero (whatever the checkpoint held there), so the function is kept."""
    FIVE = dict(WidenedInitTest.FIVE)
    ALBEDO = dict(FIVE, albedo_input={"offset": 0.875, "scale": 13.333333})

    def test_the_albedo_is_encoded_in_the_channel_after_the_guide(self):
        net = randomize(SixwayNet(self.ALBEDO), 6).eval()
        node = net.nodes[0]
        self.assertEqual(node["albedo"], {"channel": 5, "offset": 0.875, "scale": 13.333333})
        guide = torch.rand(1, 5, 8, 8, generator=torch.Generator().manual_seed(4))
        encoded = torch.cat([guide, (torch.full((1, 1, 8, 8), 0.95) - 0.875) * 13.333333, torch.zeros(1, 2, 8, 8)], 1)
        plain = SixwayNet(dict(self.FIVE))
        plain.load_state_dict(net.state_dict())
        with torch.no_grad():
            torch.testing.assert_close(net(torch.cat([guide, torch.full((1, 1, 8, 8), 0.95)], 1)), plain(encoded),
                                       rtol=0, atol=1e-6)
        # run_padded pads the guide with zeros and the albedo with itself, as the GLSL input kernel writes it.
        intermediates = {}
        with torch.no_grad():
            run_padded(net, torch.cat([guide[:, :, :7, :7], torch.full((1, 1, 7, 7), 0.95)], 1), intermediates)
        torch.testing.assert_close(intermediates["input"][0, 5], (torch.full((8, 8), 0.95) - 0.875) * 13.333333)
        self.assertFalse(intermediates["input"][0, :5, 7:].any())
        self.assertFalse(intermediates["input"][0, :5, :, 7:].any())

    def test_bad_albedo_configs(self):
        for bad, message in (({"offset": 0.875}, "albedo_input must be"), ({"offset": 0, "scale": 0}, "albedo_input must be"),
                             ({"offset": 0, "scale": 1, "bias": 2}, "albedo_input must be")):
            with self.assertRaisesRegex(ValueError, message):
                SixwayNet(dict(self.FIVE, albedo_input=bad))
        with self.assertRaisesRegex(ValueError, "albedo_input needs an input channel after the guide's"):
            SixwayNet(dict(self.FIVE, input_channels=5, albedo_input={"offset": 0, "scale": 1}))

    def test_only_an_added_albedo_widens(self):
        widens = train_module.widens
        self.assertTrue(widens(self.FIVE, self.ALBEDO))
        self.assertTrue(widens(WidenedInitTest.FOUR, self.ALBEDO))
        self.assertFalse(widens(self.ALBEDO, self.FIVE))
        self.assertFalse(widens(self.ALBEDO, dict(self.ALBEDO, albedo_input={"offset": 0.5, "scale": 2})))

    def test_init_from_a_network_without_the_albedo(self):
        """At a zero rate the export is the checkpoint with the 6th input channel's weights zeroed: the albedo
        changes nothing until training moves them."""
        old = randomize(SixwayNet(self.FIVE), 7)
        self.assertTrue(old.module("enc.0.0").weight[:, 5].abs().sum() > 0)
        run, out = tune_from_checkpoint("albedo", self.FIVE, old, 5, self.ALBEDO)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("train.init_from: the albedo input added; enc.0.0 read it from zero weights", run.stdout)
        tuned, _ = read_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        weight = old.module("enc.0.0").weight.detach().numpy()
        self.assertFalse(tuned["enc.0.0.weight"][:, 5].any())
        self.assertTrue(np.array_equal(tuned["enc.0.0.weight"][:, [0, 1, 2, 3, 4, 6, 7]], weight[:, [0, 1, 2, 3, 4, 6, 7]]))
        net, _ = load_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        guide = torch.rand(2, 5, 8, 8, generator=torch.Generator().manual_seed(5))
        with torch.no_grad():
            for albedo in (0.8, 0.95):
                torch.testing.assert_close(net(torch.cat([guide, torch.full((2, 1, 8, 8), albedo)], 1)),
                                           old.eval()(guide), rtol=0, atol=1e-6)


class WiderWidthsTest(unittest.TestCase):
    """train.init_from from a network of narrower widths (tools/nn/net2wider.py)."""
    NARROW = {"widths": [4, 8], "depth": 2, "adapters": {"width": 4}, "guide_channels": 4,
              "guide_alpha_step_voxels": 1.0, "alpha": "guide"}
    WIDE = dict(NARROW, widths=[6, 12])  # its adapters get a projection from 6 to 4 channels the narrow one lacks

    def wider(self, narrow_config, wide_config, noise):
        old = randomize(SixwayNet(narrow_config), 5).eval()
        new = SixwayNet(wide_config).eval()
        new.load_state_dict(wider_state(old, new, old.state_dict(), noise, seed=1))
        guide = torch.rand(2, 4, 16, 16, generator=torch.Generator().manual_seed(3))
        with torch.no_grad():
            return old, new, old(guide), new(guide)

    def test_the_wider_network_computes_the_old_function(self):
        variants = {"transposed": {}, "bilinear": {"upsample": "bilinear"}, "half stem": {"stem": "half"},
                    "a projection in both": {"adapters": {"width": 5}}}
        for variant, change in variants.items():
            with self.subTest(variant=variant):
                narrow = dict(self.NARROW, **change)
                _, new, before, after = self.wider(narrow, dict(narrow, widths=[6, 12]), noise=0.0)
                self.assertIn("adapters.0.proj", [node["name"] for node in new.nodes])
                torch.testing.assert_close(after, before, rtol=1e-4, atol=1e-4)  # sums in another order

    def test_the_noise_parts_the_copies(self):
        _, new, before, after = self.wider(self.NARROW, self.WIDE, noise=0.01)
        exact = self.wider(self.NARROW, self.WIDE, noise=0.0)[1].module("enc.0.0").weight
        weight = new.module("enc.0.0").weight  # 6 units: 4 and 5 copy 0 and 1, with noise
        self.assertTrue(torch.equal(weight[:4], exact[:4]))
        parted = (weight[4:] - exact[4:]).std() / weight.std()
        self.assertTrue(0.005 < parted < 0.02, parted)
        self.assertFalse(torch.equal(after, before))

    def test_only_wider_widths_of_as_many_levels_widen(self):
        widens = train_module.widens
        self.assertTrue(widens(self.NARROW, self.WIDE))
        self.assertFalse(widens(self.WIDE, self.NARROW))
        self.assertFalse(widens(self.NARROW, dict(self.NARROW, widths=[4, 8, 16])))
        self.assertFalse(widens(self.NARROW, dict(self.WIDE, block="naf")))
        self.assertFalse(widens(self.NARROW, dict(self.WIDE, adapters={"width": 6})))
        lost = dict(self.NARROW, adapters={"width": 6})  # its projection from 4 to 6 has no place at [6, 12]
        self.assertFalse(widens(lost, dict(lost, widths=[6, 12])))
        with self.assertRaisesRegex(ValueError, "node adapters.0.proj is not in the wider network"):
            wider_state(SixwayNet(lost), SixwayNet(dict(lost, widths=[6, 12])), SixwayNet(lost).state_dict(), 0, 0)
        with self.assertRaisesRegex(ValueError, "block: conv"):
            naf = dict(self.NARROW, block="naf")
            wider_state(SixwayNet(naf), SixwayNet(dict(naf, widths=[6, 12])), SixwayNet(naf).state_dict(), 0, 0)

    def test_init_from_a_narrower_checkpoint(self):
        """At a zero rate and no noise, a run from a checkpoint of narrower widths and fewer input channels exports
        its function (the emission's new input weights start at zero)."""
        old = randomize(SixwayNet(self.NARROW), 6).eval()
        wide = dict(self.WIDE, guide_channels=5, input_channels=8)
        run, out = tune_from_checkpoint("narrow", self.NARROW, old, 5, wide, widen_noise=0.0)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("enc.0.0.weight widened to this run's input channels", run.stdout)
        self.assertIn("widths [4, 8] widened to [6, 12]", run.stdout)
        tuned, _ = load_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        guide = torch.rand(1, 5, 16, 16, generator=torch.Generator().manual_seed(4))
        with torch.no_grad():
            torch.testing.assert_close(tuned.eval()(guide), old(guide[:, :4]), rtol=1e-4, atol=1e-4)


class DeeperTest(unittest.TestCase):
    """train.init_from from a network of one level fewer (tools/nn/net2deeper.py)."""
    SHALLOW = {"widths": [4, 8], "depth": 2, "adapters": {"width": 4}, "guide_channels": 4,
               "guide_alpha_step_voxels": 1.0, "alpha": "guide"}

    def deeper(self, shallow_config):
        old = randomize(SixwayNet(shallow_config), 5).eval()
        new = randomize(SixwayNet(dict(shallow_config, widths=shallow_config["widths"] + [16])), 9).eval()
        new.load_state_dict(deeper_state(old, new, old.state_dict()))
        guide = torch.rand(2, 4, 16, 16, generator=torch.Generator().manual_seed(3))
        with torch.no_grad():
            return new, old(guide), new(guide), guide

    def test_the_deeper_network_computes_the_old_function(self):
        variants = {"transposed": {}, "bilinear": {"upsample": "bilinear"}, "half stem": {"stem": "half"},
                    "depth 1": {"depth": 1}, "depth 3": {"depth": 3}, "three levels": {"widths": [4, 8, 12]}}
        for variant, change in variants.items():
            with self.subTest(variant=variant):
                _, before, after, _ = self.deeper(dict(self.SHALLOW, **change))
                torch.testing.assert_close(after, before, rtol=1e-5, atol=1e-5)

    def test_the_new_level_gets_gradients(self):
        """The zero weights that read the new bottleneck are not a dead end: the first step's gradient moves them."""
        new, _, _, guide = self.deeper(self.SHALLOW)
        new(guide).square().sum().backward()
        reading_the_new_level = new.module("dec.1.0").weight.grad[:, :8]
        self.assertGreater(float(reading_the_new_level.abs().max()), 0.0)

    def test_only_one_more_level_of_relu_conv_units_deepens(self):
        deepens, deeper = train_module.deepens, dict(self.SHALLOW, widths=[4, 8, 16])
        self.assertTrue(deepens(self.SHALLOW, deeper))
        self.assertFalse(deepens(deeper, self.SHALLOW))
        self.assertFalse(deepens(self.SHALLOW, dict(deeper, widths=[4, 8, 16, 32])))
        self.assertFalse(deepens(self.SHALLOW, dict(deeper, widths=[6, 8, 16])))
        self.assertFalse(deepens(self.SHALLOW, dict(deeper, depth=3)))
        leaky = dict(self.SHALLOW, activation="leaky_relu")
        self.assertFalse(deepens(leaky, dict(leaky, widths=[4, 8, 16])))
        with self.assertRaisesRegex(ValueError, "ReLU"):
            deeper_state(SixwayNet(leaky), SixwayNet(dict(leaky, widths=[4, 8, 16])), SixwayNet(leaky).state_dict())
        with self.assertRaisesRegex(ValueError, "one more level"):
            deeper_state(SixwayNet(self.SHALLOW), SixwayNet(dict(self.SHALLOW, widths=[4, 16, 16])),
                         SixwayNet(self.SHALLOW).state_dict())

    def test_init_from_an_exported_shallower_network(self):
        """At a zero rate, a run from an exported network (.safetensors) of one level fewer exports its function."""
        old = randomize(SixwayNet(self.SHALLOW), 6).eval()
        run, out = tune_from_checkpoint("shallow", self.SHALLOW, old, 4, dict(self.SHALLOW, widths=[4, 8, 16]),
                                        exported=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("widths [4, 8] deepened to [4, 8, 16]", run.stdout)
        tuned, _ = load_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        guide = torch.rand(1, 4, 16, 16, generator=torch.Generator().manual_seed(4))
        with torch.no_grad():
            torch.testing.assert_close(tuned.eval()(guide), old(guide), rtol=1e-5, atol=1e-5)


class TrainTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        synthetic_shards.write_shards(os.path.join(WORK, "data"), size=16, cameras=3, frames=4, sequences=2)
        cls.straight = os.path.join(WORK, "straight")
        cls.resumed = os.path.join(WORK, "resumed")
        cls.runs = [train(cls.straight, "--force"), train(cls.resumed, "--force", "--stop-at", "3")]
        cls.runs.append(train(cls.resumed, "--resume"))

    def test_runs_succeed(self):
        for run in self.runs:
            self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertNotIn("exported", self.runs[1].stdout)  # stopped at step 3: no export yet

    def test_resume_is_bit_identical(self):
        a, _ = read_safetensors(os.path.join(self.straight, "sixway-unet.safetensors"))
        b, _ = read_safetensors(os.path.join(self.resumed, "sixway-unet.safetensors"))
        self.assertEqual(list(a), list(b))
        for name in a:
            self.assertTrue(np.array_equal(a[name], b[name]), name)
        ca = torch.load(os.path.join(self.straight, "checkpoint.pt"))
        cb = torch.load(os.path.join(self.resumed, "checkpoint.pt"))
        self.assertEqual(ca["step"], 6)
        self.assertEqual(cb["step"], 6)
        for state_a, state_b in zip(ca["optimizer"]["state"].values(), cb["optimizer"]["state"].values()):
            self.assertTrue(torch.equal(state_a["exp_avg_sq"], state_b["exp_avg_sq"]))

    def test_training_moved_the_weights(self):
        torch.manual_seed(5)  # the tiny config's seed: the initial weights of the run
        from sixway_net import SixwayNet
        initial = SixwayNet(json.load(open(CONFIG))["model"]).named_tensors()
        trained, _ = read_safetensors(os.path.join(self.straight, "sixway-unet.safetensors"))
        moved = sum(float(np.abs(trained[n] - t.numpy()).sum()) for n, t in initial.items())
        self.assertGreater(moved, 0)

    def test_export_metadata_and_reload(self):
        path = os.path.join(self.straight, "sixway-unet.safetensors")
        model, metadata = load_safetensors(path)
        for key in ("sixway.graph", "sixway.config", "sixway.training", "sixway.metrics"):
            self.assertIn(key, metadata)
        training = json.loads(metadata["sixway.training"])
        self.assertEqual(training["steps"], 6)
        self.assertEqual(training["dataset"]["samples"], {"train": 8, "heldout_sequence": 12, "heldout_camera": 4})
        self.assertEqual(training["dataset"]["config"]["synthetic"], True)
        metrics = json.loads(metadata["sixway.metrics"])["pytorch"]
        for split in ("train", "heldout_sequence", "heldout_camera"):
            self.assertGreater(metrics[split]["psnr_masked"], 0)
            self.assertIn("psnr_masked_left_right", metrics[split])
        self.assertEqual(model.config["widths"], [4, 8])

    def test_log_and_plot(self):
        rows = [json.loads(line) for line in open(os.path.join(self.resumed, "log.jsonl"))]
        self.assertEqual([r["step"] for r in rows if r["kind"] == "train"], [2, 4, 6])
        self.assertEqual([r["step"] for r in rows if r["kind"] == "heldout"], [3, 6])
        straight = [json.loads(line) for line in open(os.path.join(self.straight, "log.jsonl"))]
        self.assertEqual([r["loss"] for r in rows], [r["loss"] for r in straight])
        with open(os.path.join(self.straight, "loss.png"), "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")

    def test_init_from_starts_at_the_given_weights(self):
        # Fine-tuning at a zero rate keeps the weights it started from: the straight run's, not a fresh seed's.
        with open(CONFIG) as f:
            tune = json.load(f)
        tune["train"].update(init_from=self.straight, lr=0.0, min_lr=0.0, steps=2, seed=11)
        config = os.path.join(WORK, "tune.json")
        with open(config, "w") as f:
            json.dump(tune, f)
        out = os.path.join(WORK, "tuned")
        run = subprocess.run([sys.executable, TRAIN, "--config", config, "--data", os.path.join(WORK, "data"),
                              "--out", out, "--force"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        start, _ = read_safetensors(os.path.join(self.straight, "sixway-unet.safetensors"))
        tuned, _ = read_safetensors(os.path.join(out, "sixway-unet.safetensors"))
        for name in start:
            self.assertTrue(np.array_equal(start[name], tuned[name]), name)
        # Another architecture cannot start from it: one line naming the checkpoint.
        tune["model"]["widths"] = [4, 4]
        with open(config, "w") as f:
            json.dump(tune, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", config, "--data", os.path.join(WORK, "data"),
                              "--out", out, "--force"], capture_output=True, text=True)
        self.assertNotEqual(run.returncode, 0)
        self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
        self.assertIn("checkpoint.pt: train.init_from has another model config", run.stderr)

    def test_two_lightmap_sizes_train_in_crops_or_whole(self):
        large = os.path.join(WORK, "data32")
        synthetic_shards.write_shards(large, size=32, cameras=3, frames=4, sequences=2)
        out = os.path.join(WORK, "two_sizes")
        run = subprocess.run([sys.executable, TRAIN, "--config", CONFIG, "--data", os.path.join(WORK, "data"), large,
                              "--out", out, "--force"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("training pairs of 16x16/32x32", run.stdout)
        with open(os.path.join(out, "metrics.json")) as f:
            samples = json.load(f)["pytorch"]["heldout_sequence"]["samples"]
        self.assertEqual(samples, 2 * 3 * 4)  # sequence 1 of both directories, whole maps of each size
        # Without a crop, whole maps of two sizes train in batches of one size each.
        whole = os.path.join(WORK, "whole.json")
        with open(CONFIG) as f:
            config = json.load(f)
        config["data"]["crop"] = None
        with open(whole, "w") as f:
            json.dump(config, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", whole, "--data", os.path.join(WORK, "data"), large,
                              "--out", os.path.join(WORK, "whole"), "--force"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("training pairs of 16x16/32x32", run.stdout)
        # A crop larger than the smaller size trains in batches of one size: the 16² maps whole, the 32² cropped.
        config["data"]["crop"] = 32
        with open(whole, "w") as f:
            json.dump(config, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", whole, "--data", os.path.join(WORK, "data"), large,
                              "--out", os.path.join(WORK, "whole"), "--force"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("training pairs of 16x16/32x32", run.stdout)

    def test_sized_batches_have_one_size_and_cover_every_size(self):
        pairs = np.arange(40)
        sizes = np.where(pairs < 30, 64, 128)  # 30 pairs of 64², 10 of 128²
        order = train_module.SizedBatchOrder(pairs, sizes, 4, seed=5)
        self.assertEqual(order.batches_per_epoch, 7 + 2)  # whole batches per size; the partial ones wait
        epoch = [order.indices(step) for step in range(order.batches_per_epoch)]
        for batch in epoch:
            self.assertEqual(len(batch), 4)
            self.assertEqual(len(set(sizes[batch])), 1)
        self.assertEqual(sum(sizes[batch[0]] == 128 for batch in epoch), 2)
        self.assertEqual(len(set(np.concatenate(epoch))), 36)  # no pair twice in an epoch
        again = train_module.SizedBatchOrder(pairs, sizes, 4, seed=5)  # stateless: the step alone decides
        np.testing.assert_array_equal(again.indices(12), order.indices(12))
        self.assertAlmostEqual(order.epoch(order.batches_per_epoch), 1.0)
        # A size with fewer pairs than a batch would never train: one line naming it.
        data = types.SimpleNamespace(sizes=lambda: [64, 128], sample_sizes=sizes, directory="shards")
        with self.assertRaisesRegex(train_module.ConfigError, r"shards: fewer training pairs of 128x128 maps than "
                                                              r"train.batch \(16\)"):
            train_module.batch_order(data, pairs, None, {"batch": 16, "seed": 5})
        self.assertIsInstance(train_module.batch_order(data, pairs, 32, {"batch": 16, "seed": 5}),
                              train_module.BatchOrder)  # crops every size allows: any batch may mix sizes
        self.assertIsInstance(train_module.batch_order(data, pairs, 96, {"batch": 4, "seed": 5}),
                              train_module.SizedBatchOrder)  # a crop larger than 64²: batches of one size

    def test_bad_input_is_one_line(self):
        run = train(os.path.join(WORK, "straight"))  # exists, no --resume or --force
        self.assertNotEqual(run.returncode, 0)
        self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
        self.assertIn("exists and is not empty", run.stderr)
        bad = os.path.join(WORK, "bad.json")
        with open(bad, "w") as f:
            json.dump({"train": {"stpes": 3}}, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--out", os.path.join(WORK, "bad")],
                             capture_output=True, text=True)
        self.assertEqual(run.stderr.strip(), f"train: {bad}: unknown key 'train.stpes'")
        with open(bad, "w") as f:
            json.dump({"loss": {"channel_weights": {"emisive": 4}}}, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--out", os.path.join(WORK, "bad")],
                             capture_output=True, text=True)
        self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
        self.assertIn(f"train: {bad}: loss.channel_weights: unknown channel 'emisive'", run.stderr)
        with open(bad, "w") as f:
            json.dump({"loss": {"channel_weights": 3}}, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--out", os.path.join(WORK, "bad")],
                             capture_output=True, text=True)
        self.assertEqual(run.stderr.strip(), f"train: {bad}: loss.channel_weights must be an object {{channel: factor}}")
        with open(bad, "w") as f:
            json.dump({"train": {"widen_noise": -0.1}}, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--out", os.path.join(WORK, "bad")],
                             capture_output=True, text=True)
        self.assertEqual(run.stderr.strip(), f"train: {bad}: train.widen_noise must be a number in [0, 1]")
        with open(bad, "w") as f:
            json.dump({"loss": {"area_power": 2}}, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--out", os.path.join(WORK, "bad")],
                             capture_output=True, text=True)
        self.assertEqual(run.stderr.strip(), f"train: {bad}: loss.area_power must be a number in [0, 1]")
        # A network that reads the fine alpha needs shards whose guide has it (version 3).
        with open(CONFIG) as f:
            fine = json.load(f)
        fine["model"].update(guide_channels=4, guide_alpha_step_voxels=1.0)
        with open(bad, "w") as f:
            json.dump(fine, f)
        run = subprocess.run([sys.executable, TRAIN, "--config", bad, "--data", os.path.join(WORK, "data"),
                              "--out", os.path.join(WORK, "fine")], capture_output=True, text=True)
        self.assertNotEqual(run.returncode, 0)
        self.assertEqual(run.stderr.strip().count("\n"), 0, run.stderr)
        self.assertIn("shard_00000.safetensors: its guide has no alpha_fine channel", run.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] != "--work":
        sys.exit(__doc__)
    WORK = sys.argv[2]
    os.makedirs(WORK, exist_ok=True)
    unittest.main(argv=sys.argv[:1] + sys.argv[3:])
