#!/usr/bin/python3
"""Unit tests of tools/nn/losses.py on cases with known answers (CTest nn.python_losses; exit 77 without torch)."""
import math
import os
import sys
import unittest

try:
    import numpy as np
    import torch
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools", "nn"))
import losses  # noqa: E402
from sixway_net import OUTPUT_CHANNELS, output_encodings, srgb_to_linear  # noqa: E402

SRGB = output_encodings({"encoding": "srgb"})  # an sRGB network's output encodings


def smooth_image(seed, channels=8, size=24):
    """Smooth random images in [0, 1] (sums of a few low-frequency cosines)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:size, 0:size] / size
    out = np.zeros((2, channels, size, size))
    for n in range(2):
        for c in range(channels):
            for _ in range(3):
                fx, fy, phase = rng.uniform(0.5, 2), rng.uniform(0.5, 2), rng.uniform(0, 2 * np.pi)
                out[n, c] += np.cos(2 * np.pi * (fx * x + fy * y) + phase)
    out = (out - out.min()) / (out.max() - out.min())
    return torch.from_numpy(out.astype(np.float32))


def numpy_ssim(x, y, window=11, sigma=1.5):
    """SSIM written out independently: explicit window sums over every valid position, float64."""
    x, y = x.astype(np.float64), y.astype(np.float64)
    r = np.arange(window) - (window - 1) / 2
    g = np.exp(-r * r / (2 * sigma * sigma))
    w = np.outer(g, g) / np.outer(g, g).sum()
    c1, c2 = 0.01 ** 2, 0.03 ** 2
    values = []
    for n in range(x.shape[0]):
        for c in range(x.shape[1]):
            for i in range(x.shape[2] - window + 1):
                for j in range(x.shape[3] - window + 1):
                    a, b = x[n, c, i:i + window, j:j + window], y[n, c, i:i + window, j:j + window]
                    ma, mb = (w * a).sum(), (w * b).sum()
                    va, vb = (w * a * a).sum() - ma * ma, (w * b * b).sum() - mb * mb
                    cab = (w * a * b).sum() - ma * mb
                    values.append((2 * ma * mb + c1) * (2 * cab + c2) / ((ma * ma + mb * mb + c1) * (va + vb + c2)))
    return float(np.mean(values))


class SrgbTest(unittest.TestCase):
    def test_known_values_and_inverse(self):
        x = torch.tensor([0.0, 0.001, 0.0031308, 0.18, 0.5, 1.0, 2.0])
        encoded = losses.srgb_encode(x)
        self.assertAlmostEqual(float(encoded[0]), 0.0)
        self.assertAlmostEqual(float(encoded[1]), 0.01292, places=6)
        self.assertAlmostEqual(float(encoded[4]), 0.735357, places=5)  # the textbook sRGB value of 0.5
        self.assertAlmostEqual(float(encoded[5]), 1.0, places=6)
        torch.testing.assert_close(srgb_to_linear(encoded), x, rtol=1e-5, atol=1e-7)

    def test_loss_space(self):
        target = smooth_image(1) * 1.5
        space = losses.target_to_loss_space(target)
        torch.testing.assert_close(space[:, 6], target[:, 6])  # alpha stays linear
        torch.testing.assert_close(space[:, 0], losses.srgb_encode(target[:, 0]))
        # A linear-output network's raw values map to the same space; an srgb one's are that space already.
        linear, srgb = output_encodings({"encoding": "linear"}), output_encodings({"encoding": "srgb"})
        torch.testing.assert_close(losses.prediction_to_loss_space(target, linear), space)
        torch.testing.assert_close(losses.prediction_to_loss_space(space, srgb), space)
        # An sRGB network whose emissive is the guide's (linear) encodes that channel alone.
        passed = output_encodings({"encoding": "srgb", "guide_channels": 5, "input_channels": 8,
                                   "guide_alpha_step_voxels": 1, "emissive": "guide"})
        mixed = space.clone()
        mixed[:, 7] = target[:, 7]
        torch.testing.assert_close(losses.prediction_to_loss_space(mixed, passed), space)


class ReconstructionTermsTest(unittest.TestCase):
    def test_mse(self):
        a = smooth_image(2)
        self.assertEqual(float(losses.mse(a, a)), 0.0)
        self.assertAlmostEqual(float(losses.mse(a, a + 0.1)), 0.01, places=6)

    def test_ssim_of_an_image_with_itself_is_one(self):
        a = smooth_image(3)
        self.assertAlmostEqual(float(losses.ssim(a, a)), 1.0, places=6)

    def test_ssim_against_independent_implementation(self):
        a, b = smooth_image(4, channels=2, size=16), smooth_image(5, channels=2, size=16)
        b = 0.7 * a + 0.3 * b
        expected = numpy_ssim(a.numpy(), b.numpy())
        self.assertLess(expected, 0.99)
        self.assertAlmostEqual(float(losses.ssim(a, b)), expected, places=5)

    def test_gradient_loss(self):
        a = smooth_image(6)
        self.assertEqual(float(losses.gradient_loss(a, a)), 0.0)
        self.assertAlmostEqual(float(losses.gradient_loss(a, a + 0.3)), 0.0, places=6)  # offsets keep gradients
        ramp = torch.arange(10, dtype=torch.float32).view(1, 1, 1, 10).expand(1, 1, 10, 10) * 0.05
        self.assertAlmostEqual(float(losses.gradient_loss(torch.zeros_like(ramp), ramp)), 0.05, places=6)


class TemporalTest(unittest.TestCase):
    def shifted_pair(self, dx, dy):
        """previous, current = previous moved by (dx, dy) pixels, and the exact motion field."""
        previous = smooth_image(7)
        current = torch.roll(previous, shifts=(dy, dx), dims=(2, 3))
        motion = torch.zeros(2, 2, 24, 24)
        motion[:, 0], motion[:, 1] = dx, dy
        return previous, current, motion

    def test_zero_motion_is_identity(self):
        a = smooth_image(8)
        warped, valid = losses.warp(a, torch.zeros(2, 2, 24, 24))
        torch.testing.assert_close(warped, a)
        self.assertEqual(float(valid.min()), 1.0)

    def test_shift_warped_back_with_exact_motion(self):
        previous, current, motion = self.shifted_pair(3, -2)
        warped, valid = losses.warp(previous, motion)
        # Inside the valid region the warp reproduces the shifted image; the rolled-in border is invalid.
        self.assertLess(float(((warped - current).abs() * valid).max()), 1e-6)
        self.assertEqual(float(valid.sum()) / 2, (24 - 3) * (24 - 2))

    def test_fractional_motion_on_a_linear_ramp(self):
        # Bilinear interpolation is exact on a linear function: a ramp moved by 0.25 px warps back exactly.
        x = torch.arange(24, dtype=torch.float32).view(1, 1, 1, 24).expand(1, 1, 24, 24)
        motion = torch.zeros(1, 2, 24, 24)
        motion[:, 0] = 0.25
        warped, valid = losses.warp(x * 0.01, motion)
        self.assertLess(float(((warped - (x - 0.25) * 0.01).abs() * valid).max()), 1e-6)

    def test_coherent_prediction_costs_nothing(self):
        previous, current, motion = self.shifted_pair(2, 1)
        loss = losses.temporal_loss(current, previous, current, previous, motion, k=20)
        self.assertLess(float(loss), 1e-10)

    def test_flicker_is_punished_where_the_reference_is_coherent(self):
        previous, current, motion = self.shifted_pair(2, 1)
        loss = losses.temporal_loss(current + 0.1, previous, current, previous, motion, k=20)
        valid_fraction = (24 - 2) * (24 - 1) / 24 ** 2
        self.assertAlmostEqual(float(loss), 0.01 * valid_fraction, places=6)

    def test_real_changes_are_not_punished(self):
        # The reference itself brightens by 0.5 (e.g. a light turned on): the prediction that follows it costs
        # exp(-k 0.5) of what a flicker of the same size would.
        previous, current, motion = self.shifted_pair(2, 1)
        loss = losses.temporal_loss(current + 0.5, previous, current + 0.5, previous, motion, k=20)
        valid_fraction = (24 - 2) * (24 - 1) / 24 ** 2
        self.assertAlmostEqual(float(loss), 0.25 * math.exp(-10) * valid_fraction, places=8)


class ChannelWeightsTest(unittest.TestCase):
    def test_weights_scale_each_channels_error(self):
        target = smooth_image(11)
        emissive = 7  # the network's output order: left, right, top, bottom, front, back, alpha, emissive
        pred = target.clone()
        pred[:, emissive] += 0.1
        pred[:, 0] += 0.2
        plain = float(losses.mse(pred, target))
        self.assertAlmostEqual(plain, (0.01 + 0.04) / 8, places=6)
        weighted = losses.mse(pred, target, losses.channel_weight_vector({"emissive": 4, "left": 0}))
        self.assertAlmostEqual(float(weighted), 4 * 0.01 / 8, places=6)
        self.assertIsNone(losses.channel_weight_vector({}))
        unit = losses.mse(pred, target, losses.channel_weight_vector({"emissive": 1}))
        self.assertAlmostEqual(float(unit), plain, places=6)


class AreaWeightsTest(unittest.TestCase):
    @staticmethod
    def alphas(pixels_per_sample, size=20):
        """Linear alphas (N, size, size) whose first `pixels` pixels (row-major) are smoke (0.5), the rest 0.005."""
        alpha = torch.full((len(pixels_per_sample), size * size), 0.005)
        for k, pixels in enumerate(pixels_per_sample):
            alpha[k, :pixels] = 0.5
        return alpha.view(-1, size, size)

    def test_weights_undo_the_area(self):
        self.assertIsNone(losses.area_weights(self.alphas([4, 100]), 0))
        full = losses.area_weights(self.alphas([4, 100]), 1)
        self.assertAlmostEqual(float(full.mean()), 1.0, places=6)
        self.assertAlmostEqual(float(full[0] / full[1]), 25.0, places=4)
        half = losses.area_weights(self.alphas([4, 100]), 0.5)
        self.assertAlmostEqual(float(half[0] / half[1]), 5.0, places=4)
        # No smoke counts as one pixel of it (alpha 0.005 is under the metrics' 0.01), not as a division by 0.
        empty = losses.area_weights(self.alphas([0, 1]), 1)
        self.assertAlmostEqual(float(empty[0] / empty[1]), 1.0, places=6)

    def test_every_samples_masked_error_counts_alike_at_power_1(self):
        # Two samples, the same error 0.1 on their smoke only: a puff of 4 pixels and a plume of 100.
        target = torch.zeros(2, 8, 20, 20)
        target[:, losses.ALPHA_CHANNEL] = self.alphas([4, 100])
        pred = target.clone()
        smoke = (target[:, losses.ALPHA_CHANNEL:losses.ALPHA_CHANNEL + 1] > 0.01).float()
        pred[:, :1] += 0.1 * smoke
        weights = losses.area_weights(target[:, losses.ALPHA_CHANNEL], 1)
        per_sample = [float(losses.mse(pred[k:k + 1], target[k:k + 1], None, weights[k:k + 1])) for k in range(2)]
        self.assertAlmostEqual(per_sample[0], per_sample[1], places=7)
        # The plain mean counts the plume 25x more.
        plain = [float(losses.mse(pred[k:k + 1], target[k:k + 1])) for k in range(2)]
        self.assertAlmostEqual(plain[1] / plain[0], 25.0, places=4)
        shaded = [float(losses.shaded_loss(pred[k:k + 1], target[k:k + 1], losses.SHADING_WEIGHTS,
                                           losses.SHADING_BACKGROUNDS, weights[k:k + 1])) for k in range(2)]
        self.assertAlmostEqual(shaded[0] / shaded[1], 1.0, places=5)


def numpy_shaded_image(maps, directions, energies, ambient, background):
    """The billboard image of linear maps (8, H, W) in the network's order under directional lights, written out
    from docs/conventions.md's "Shading": t = sum_i d_i^2 (d_i >= 0 ? A_i : B_i) per light, the ambient
    (2/3) sum_i [A_i L0 + B_i L0], the emissive, then premultiplied over the background."""
    channel = {name: maps[k].astype(np.float64) for k, name in enumerate(OUTPUT_CHANNELS)}
    a, b = ["right", "top", "back"], ["left", "bottom", "front"]
    image = np.zeros_like(channel["alpha"])
    for d, energy in zip(directions, energies):
        for i in range(3):
            image += energy * d[i] ** 2 * (channel[a[i]] if d[i] >= 0 else channel[b[i]])
    image += 2 / 3 * sum(channel[a[i]] * ambient + channel[b[i]] * ambient for i in range(3))
    return image + channel["emissive"] + (1 - channel["alpha"]) * background


class ShadedTest(unittest.TestCase):
    def test_weights_shade_as_the_billboard_does(self):
        maps = smooth_image(11)[0].numpy()
        directions = torch.nn.functional.normalize(torch.tensor([[[0.3, 0.8, -0.5], [-0.9, -0.2, 0.4]]]), dim=-1)
        energies, ambient, background = torch.tensor([[1.2, 0.4]]), torch.tensor([0.1]), torch.tensor([0.3])
        weights = losses.lighting_weights(directions, energies, ambient, background)
        image = torch.einsum("lc,chw->lhw", weights, torch.from_numpy(maps))[0] + background[0]
        expected = numpy_shaded_image(maps, directions[0].numpy(), energies[0].numpy(), 0.1, 0.3)
        np.testing.assert_allclose(image.numpy(), expected, rtol=1e-5, atol=1e-6)

    def test_an_error_costs_what_the_light_gives_it(self):
        # A light from straight above sees the top map's error whole and the bottom map's not at all.
        weights = losses.lighting_weights(torch.tensor([[[0.0, 1.0, 0.0]]]), torch.tensor([[1.0]]),
                                          torch.tensor([0.0]), torch.tensor([0.0]))
        target = torch.full((1, 8, 4, 4), 0.2)
        for name, cost in (("top", 0.01), ("bottom", 0.0)):
            pred = target.clone()
            pred[:, OUTPUT_CHANNELS.index(name)] += 0.1
            self.assertAlmostEqual(float(losses.shaded_loss(pred, target, weights, torch.zeros(1))), cost, places=7)

    def test_images_clipped_as_eval_clips_them(self):
        # Both images brighter than white (an emissive core) differ in nothing that eval measures.
        weights, backgrounds = losses.shading_lightings(4)
        target = torch.full((1, 8, 4, 4), 0.5)
        target[:, OUTPUT_CHANNELS.index("emissive")] = 3.0
        pred = target.clone()
        pred[:, OUTPUT_CHANNELS.index("emissive")] = 2.0
        self.assertEqual(float(losses.shaded_loss(pred, target, weights, backgrounds)), 0.0)
        pred[:, OUTPUT_CHANNELS.index("emissive")] = 0.0
        self.assertGreater(float(losses.shaded_loss(pred, target, weights, backgrounds)), 0.0)

    def test_the_lightings_are_fixed_and_in_range(self):
        weights, backgrounds = losses.shading_lightings()
        again, _ = losses.shading_lightings()
        torch.testing.assert_close(weights, again)
        torch.testing.assert_close(weights, losses.SHADING_WEIGHTS)
        self.assertEqual(tuple(weights.shape), (losses.SHADED_LIGHTINGS, 8))
        six = [OUTPUT_CHANNELS.index(n) for n in ("right", "left", "top", "bottom", "back", "front")]
        # sum_i d_i^2 = 1 per light: the six weights add up to E_key + E_fill + 4 L0, in [0.5, 1.5 + 0.6 + 0.6].
        total = weights[:, six].sum(1)
        self.assertTrue(bool((weights[:, six] >= 0).all()))
        self.assertTrue(bool((total >= 0.5).all()) and bool((total <= 2.7).all()))
        self.assertTrue(bool((backgrounds >= 0).all()) and bool((backgrounds <= 0.6).all()))


class TrainingLossTest(unittest.TestCase):
    def test_perfect_prediction_has_zero_loss(self):
        target_previous = smooth_image(9)
        target = torch.roll(target_previous, shifts=(1, 2), dims=(2, 3))
        motion = torch.zeros(2, 2, 24, 24)
        motion[:, 0], motion[:, 1] = 2, 1
        raw, raw_previous = losses.target_to_loss_space(target), losses.target_to_loss_space(target_previous)
        weights = {"mse": 1, "ssim": 0.5, "gradient": 0.5, "temporal": 1, "temporal_k": 20, "shaded": 2}
        total, terms = losses.training_loss(raw, raw_previous, target, target_previous, motion, SRGB, weights)
        self.assertEqual(set(terms), {"mse", "ssim", "gradient", "temporal", "shaded"})
        self.assertLess(abs(float(total)), 1e-6)

    def test_gradients_flow_to_the_prediction(self):
        target = smooth_image(10)
        raw = torch.zeros_like(target, requires_grad=True)
        weights = {"mse": 1, "ssim": 0.5, "gradient": 0.5, "temporal": 1, "temporal_k": 20}
        total, _ = losses.training_loss(raw[:1], raw[1:], target[:1], target[1:], torch.zeros(1, 2, 24, 24),
                                        SRGB, weights)
        total.backward()
        self.assertGreater(float(raw.grad.abs().sum()), 0)


if __name__ == "__main__":
    unittest.main()
