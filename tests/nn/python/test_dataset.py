#!/usr/bin/python3
"""Tests of tools/nn/dataset.py on synthetic shards (CTest nn.python_dataset; exit 77 without torch)."""
import json
import os
import sys
import tempfile
import unittest

try:
    import numpy as np
    import torch  # noqa: F401  (dataset.py returns torch tensors)
except ImportError as missing:
    print(f"skipped: {missing} (install python3-torch and python3-numpy)")
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "..", "tools", "nn"))
import synthetic_shards  # noqa: E402
from baselines import baselines  # noqa: E402
from dataset import ShardDataset  # noqa: E402
from losses import warp  # noqa: E402
from metrics import evaluate_split  # noqa: E402
from safetensors_io import read_safetensors, write_safetensors  # noqa: E402


class DatasetTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        synthetic_shards.write_shards(cls.tmp.name, size=16, cameras=3, frames=4, sequences=2)
        # A generator's unfinished file must be ignored.
        open(os.path.join(cls.tmp.name, "shard_00002.safetensors.tmp"), "wb").close()
        cls.data = ShardDataset(cls.tmp.name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_splits_and_pairs(self):
        self.assertEqual(len(self.data.paths), 2)
        self.assertEqual(len(self.data.indices("train")), 2 * 4)  # sequence 0, cameras 0 and 1
        self.assertEqual(len(self.data.indices("heldout_camera")), 4)
        self.assertEqual(len(self.data.indices("heldout_sequence")), 3 * 4)
        self.assertEqual(len(self.data.pairs("train")), 2 * 3)  # every frame but a camera's first
        for i in self.data.pairs("heldout_sequence"):
            now, before = self.data.samples[i], self.data.samples[self.data.previous[i]]
            self.assertEqual((before["sequence"], before["camera"], before["frame"] + synthetic_shards.FRAME_STRIDE),
                             (now["sequence"], now["camera"], now["frame"]))
        first = [i for i, s in enumerate(self.data.samples) if s["frame"] == synthetic_shards.FIRST_FRAME]
        self.assertEqual(len(first), 2 * 3)
        self.assertTrue(all(self.data.previous[i] == -1 for i in first))

    def test_several_directories_are_one_dataset_without_pairs_across_them(self):
        with tempfile.TemporaryDirectory() as other:
            synthetic_shards.write_shards(other, size=16, cameras=3, frames=4, sequences=2)
            both = ShardDataset([self.tmp.name, other])
            self.assertEqual(len(both.paths), 4)
            for split in ("train", "heldout_camera", "heldout_sequence"):
                self.assertEqual(len(both.indices(split)), 2 * len(self.data.indices(split)))
                self.assertEqual(len(both.pairs(split)), 2 * len(self.data.pairs(split)))
            second = len(self.data.samples)  # the other directory's first sample: sequence 0, camera 0 again
            self.assertEqual(both.previous[second], -1)
            self.assertEqual([s["source"] for s in both.samples[second - 1:second + 1]], [0, 1])
            self.assertIsInstance(both.dataset_config(), list)
            self.assertEqual(len(both.dataset_config()), 2)
        with self.assertRaisesRegex(ValueError, "no shard directory"):
            ShardDataset([])

    def test_directories_of_two_lightmap_sizes(self):
        with tempfile.TemporaryDirectory() as large:
            synthetic_shards.write_shards(large, size=32, cameras=3, frames=4, sequences=2)
            both = ShardDataset([self.tmp.name, large])
            self.assertEqual(both.sizes(), [16, 32])
            self.assertEqual(both.size, 16)
            big = len(self.data.samples) + 1  # the 32² directory's second sample
            whole = both.batch(np.array([big]))
            self.assertEqual(tuple(whole["guide"].shape), (1, 3, 32, 32))
            np.testing.assert_array_equal(whole["target"][0].numpy(),
                                          ShardDataset(large).batch(np.array([1]))["target"][0].numpy())
            # A crop of a 32² sample sits where its offset says; samples of both sizes share a cropped batch.
            crop = both.batch(np.array([1, big]), crop=16, offsets=np.array([[0, 0], [8, 4]]))
            np.testing.assert_array_equal(crop["guide"][1].numpy(), whole["guide"][0, :, 8:24, 4:20].numpy())
            np.testing.assert_array_equal(crop["guide"][0].numpy(), self.data.batch(np.array([1]))["guide"][0].numpy())
            pairs = both.pairs("train")
            current, previous = both.pair_batch(pairs, 16, np.random.default_rng(1), mirror=True)
            self.assertEqual(tuple(current["target"].shape), (len(pairs), 8, 16, 16))
            # A crop larger than the smallest sample's size: batches of one size, cropped to at most that size.
            large_pairs = pairs[both.sample_sizes[pairs] == 32]
            current, _ = both.pair_batch(large_pairs, 24, np.random.default_rng(1))
            self.assertEqual(tuple(current["target"].shape), (len(large_pairs), 8, 24, 24))
            current, _ = both.pair_batch(pairs[both.sample_sizes[pairs] == 16], 24, np.random.default_rng(1))
            self.assertEqual(tuple(current["target"].shape[2:]), (16, 16))
            with self.assertRaisesRegex(ValueError, r"whole maps of sizes \[16, 32\]"):
                both.batch(np.array([1, big]))
            with self.assertRaisesRegex(ValueError, "not one array"):
                both.guide
            # Whole-map metrics go size by size: the split's sample count is both directories'.
            model = lambda guide, intermediates=None: torch.zeros(guide.shape[0], 8, *guide.shape[2:])
            model.size_multiple, model.config = (lambda: 1), {"encoding": "linear"}
            result = evaluate_split(model, both, "train", "cpu")
            self.assertEqual(result["samples"], 2 * len(self.data.indices("train")))

    def test_targets_in_network_order(self):
        # Baker order Right, Left, Top, Bottom, Back, Front -> network left, right, top, bottom, front, back.
        _, target, _ = synthetic_shards.sample_tensors(16, 1, 0, 0)
        batch = self.data.batch(np.array([1]))  # sequence 0, camera 0, frame 1
        for network, baker in enumerate([1, 0, 2, 3, 5, 4, 6, 7]):
            np.testing.assert_allclose(batch["target"][0, network].numpy(), target[baker], atol=2e-3)

    def test_mirror_swaps_left_and_right_and_negates_motion_x(self):
        index = np.array([2])
        plain = self.data.batch(index)
        mirrored = self.data.batch(index, mirror=np.array([True]))
        torch.testing.assert_close(mirrored["target"][0, 0], plain["target"][0, 1].flip(-1))
        torch.testing.assert_close(mirrored["target"][0, 4], plain["target"][0, 4].flip(-1))
        torch.testing.assert_close(mirrored["guide"][0], plain["guide"][0].flip(-1))
        torch.testing.assert_close(mirrored["motion"][0, 0], -plain["motion"][0, 0].flip(-1))
        torch.testing.assert_close(mirrored["motion"][0, 1], plain["motion"][0, 1].flip(-1))

    def test_pairs_share_the_crop_and_the_motion_still_warps(self):
        pairs = self.data.pairs("train")
        current, previous = self.data.pair_batch(pairs, 8, np.random.default_rng(3), mirror=True)
        self.assertEqual(tuple(current["target"].shape), (len(pairs), 8, 8, 8))
        # The previous frame's alpha warped with the current motion lands on the current alpha (to the accuracy
        # of the F16 storage and of the puff's edge, where the motion is zero by construction).
        warped, valid = warp(previous["target"][:, 6:7], current["motion"])
        inside = valid * (current["target"][:, 6:7] > 0.05)
        self.assertLess(float(((warped - current["target"][:, 6:7]).abs() * inside).max()), 0.01)

    def test_bad_shape_names_the_file_and_tensor(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)[0]
            tensors, metadata = read_safetensors(path)
            tensors["motion"] = tensors["motion"][:, :1]
            write_safetensors(path, tensors, metadata)
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: tensor 'motion' has shape"):
                ShardDataset(tmp)

    def test_bad_split_is_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)[0]
            tensors, metadata = read_safetensors(path)
            info = json.loads(metadata["sixway.dataset"])
            info["samples"][1]["split"] = "test"
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            with self.assertRaisesRegex(ValueError, r"samples\[1\]\.split is 'test'"):
                ShardDataset(tmp)

    def test_version_2_shards_choose_their_targets(self):
        """A shard with single- and multiple-scattering targets: each reads its own tensor; a shard without the
        asked-for targets is named."""
        with tempfile.TemporaryDirectory() as tmp:
            path = synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)[0]
            tensors, metadata = read_safetensors(path)
            info = json.loads(metadata["sixway.dataset"])
            info.update(version=2, targets=["single", "multiple"])
            tensors["target_ms"] = (tensors["target"].astype(np.float32) * 2).astype(np.float16)
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            single, multiple = ShardDataset(tmp), ShardDataset(tmp, target="multiple")
            np.testing.assert_allclose(multiple.target.astype(np.float32), 2 * single.target.astype(np.float32),
                                       rtol=1e-3)
            info["targets"] = ["single"]
            del tensors["target_ms"]
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: holds single scattering targets, "
                                                    r"not multiple"):
                ShardDataset(tmp, target="multiple")
            info["version"] = 5
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            with self.assertRaisesRegex(ValueError, r"version is 5, this reader knows 1 to 4"):
                ShardDataset(tmp)

    def test_version_3_shards_add_the_fine_alpha(self):
        """A shard whose guide holds the fine alpha: a 3-channel reader takes the first three, a 4-channel one all
        four, and the step comes from the shards' scenes; a shard without it is named."""
        with tempfile.TemporaryDirectory() as tmp:
            path = synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)[0]
            tensors, metadata = read_safetensors(path)
            info = json.loads(metadata["sixway.dataset"])
            three = ShardDataset(tmp, guide_channels=3)
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: its guide has no alpha_fine channel"):
                ShardDataset(tmp, guide_channels=4)
            fine = np.clip(tensors["guide"][:, 1:2].astype(np.float32) * 1.1, 0, 1).astype(np.float16)
            tensors["guide"] = np.concatenate([tensors["guide"], fine], axis=1)
            info.update(version=3, targets=["single"], guide_channels=["guide", "alpha", "depth", "alpha_fine"],
                        scene={"render": {"guide_alpha_step_voxels": 0.5}})
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            four = ShardDataset(tmp, guide_channels=4)
            self.assertEqual(four.guide.shape[1], 4)
            np.testing.assert_array_equal(four.guide[:, :3], three.guide)
            np.testing.assert_array_equal(four.guide[:, 3:], fine)
            self.assertEqual(four.guide_alpha_step_voxels(), 0.5)
            self.assertEqual(ShardDataset(tmp).guide.shape[1], 3)
            self.assertEqual(tuple(four.batch(np.array([0]), mirror=np.array([True]))["guide"].shape), (1, 4, 8, 8))
            info["guide_channels"] = ["guide", "alpha", "depth", "alpha_coarse"]
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            with self.assertRaisesRegex(ValueError, r"guide_channels is \['guide', 'alpha', 'depth', 'alpha_coarse'\]"):
                ShardDataset(tmp)

    def test_version_4_shards_add_the_emission(self):
        """A version 4 shard whose guide holds the emission as a 5th channel: a 5-channel reader takes all five
        (mirrored like the others), a 4-channel one the first four."""
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=2, frames=2, sequences=1, guide_channels=5, emission=2.0)
            five, four = ShardDataset(tmp, guide_channels=5), ShardDataset(tmp, guide_channels=4)
            self.assertEqual(five.guide.shape[1], 5)
            np.testing.assert_array_equal(five.guide[:, :4], four.guide)
            guide, _, _ = synthetic_shards.sample_tensors(8, 1, 0, 0, guide_channels=5, emission=2.0)
            np.testing.assert_array_equal(five.guide[1], guide.astype(np.float16))
            self.assertGreater(float(five.guide[:, 4].max()), 1.0)
            self.assertEqual(five.guide_alpha_step_voxels(), 1.0)
            plain = five.batch(np.array([1]))["guide"]
            mirrored = five.batch(np.array([1]), mirror=np.array([True]))["guide"]
            torch.testing.assert_close(mirrored, plain.flip(-1))

    def test_the_albedo_plane_follows_the_guide(self):
        """With `albedo`, a batch's guide gains a plane of its sample's scene albedo (a scene's 0.9 where the shard
        states none), crops and mirroring included; an albedo outside [0, 1] names the shard."""
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=2, frames=2, sequences=2, albedos=[0.8, 0.95])
            data = ShardDataset(tmp, albedo=True)
            indices = np.array([0, len(data.samples) - 1])
            batch = data.batch(indices, crop=4, offsets=np.array([[1, 2], [0, 0]]), mirror=np.array([True, False]))
            self.assertEqual(tuple(batch["guide"].shape), (2, 4, 4, 4))
            torch.testing.assert_close(batch["guide"][:, :3], ShardDataset(tmp).batch(
                indices, crop=4, offsets=np.array([[1, 2], [0, 0]]), mirror=np.array([True, False]))["guide"])
            self.assertTrue(torch.equal(batch["guide"][0, 3], torch.full((4, 4), 0.8)))
            self.assertTrue(torch.equal(batch["guide"][1, 3], torch.full((4, 4), 0.95)))
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)
            self.assertTrue(torch.equal(ShardDataset(tmp, albedo=True).batch(np.array([0]))["guide"][0, 3],
                                        torch.full((8, 8), 0.9)))
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1, albedos=[1.5])
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: sixway\.dataset\.scene\.smoke\.albedo "
                                                    r"is 1\.5, not in \[0, 1\]"):
                ShardDataset(tmp, albedo=True)

    def test_a_guide_without_the_emission_is_zero_emission_unless_its_scene_emits(self):
        """A 5-channel reader of 4-channel shards: zeros for the emission where the scene has no emission or an
        intensity of 0; for an emissive scene, the shard is named; a 3-channel shard lacks the fine alpha."""
        for emission in (None, 0.0):
            with tempfile.TemporaryDirectory() as tmp:
                synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1, guide_channels=4,
                                              emission=emission)
                five = ShardDataset(tmp, guide_channels=5)
                self.assertEqual(five.guide.shape[1], 5)
                np.testing.assert_array_equal(five.guide[:, :4], ShardDataset(tmp, guide_channels=4).guide)
                self.assertFalse(five.guide[:, 4].any())
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1, guide_channels=4, emission=2.0)
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: the network reads the guide's "
                                                    r"emission, which this shard of an emissive scene lacks"):
                ShardDataset(tmp, guide_channels=5)
            self.assertEqual(ShardDataset(tmp, guide_channels=4).guide.shape[1], 4)
        with tempfile.TemporaryDirectory() as tmp:
            synthetic_shards.write_shards(tmp, size=8, cameras=1, frames=2, sequences=1)
            with self.assertRaisesRegex(ValueError, r"shard_00000\.safetensors: its guide has no alpha_fine channel"):
                ShardDataset(tmp, guide_channels=5)

    def test_baselines_score_the_baker_and_the_alphas(self):
        """tools/nn/baselines.py on shards whose light and emissive channels are 0.25 (single) and 0.5 (multiple
        scattering): the baker's masked MSE is 7/8 of 0.25² (the alphas agree); the guide's alpha equals the targets' (inf), the
        fine alpha is off by 0.1 where the smoke is."""
        with tempfile.TemporaryDirectory() as tmp:
            path = synthetic_shards.write_shards(tmp, size=8, cameras=2, frames=2, sequences=2)[1]
            tensors, metadata = read_safetensors(path)
            info = json.loads(metadata["sixway.dataset"])
            alpha = tensors["target"][:, 6:7].astype(np.float32)
            tensors["target"][:, :6] = 0.25
            tensors["target"][:, 7] = 0.25
            tensors["target_ms"] = tensors["target"].copy()
            tensors["target_ms"][:, :6] = 0.5
            tensors["target_ms"][:, 7] = 0.5
            tensors["guide"] = np.concatenate([tensors["guide"][:, :1], alpha.astype(np.float16),
                                               tensors["guide"][:, 2:3], np.clip(alpha + 0.1, 0, 1).astype(np.float16)],
                                              axis=1)
            info.update(version=3, targets=["single", "multiple"],
                        guide_channels=["guide", "alpha", "depth", "alpha_fine"])
            write_safetensors(path, tensors, {"sixway.dataset": json.dumps(info)})
            os.remove(os.path.join(tmp, "shard_00000.safetensors"))
            figures = baselines(tmp)["heldout_sequence"]
            self.assertEqual(figures["samples"], 4)
            self.assertAlmostEqual(figures["single_vs_multiple"], 10 * np.log10(1 / (7 / 8 * 0.0625)), places=3)
            self.assertEqual(figures["guide_alpha"], float("inf"))
            mask = alpha > 0.01
            fine = np.clip(alpha + 0.1, 0, 1).astype(np.float16).astype(np.float64)
            expected = 10 * np.log10(mask.sum() / (((fine - alpha.astype(np.float64)) ** 2) * mask).sum())
            self.assertAlmostEqual(figures["fine_alpha"], expected, places=3)

    def test_a_sequence_without_motion_pairs_each_sample_with_itself(self):
        """A played-back VDB sequence ("motion": false) has no previous frames to warp: every sample is its own
        pair, so it trains the reconstruction terms and its temporal term is zero."""
        with tempfile.TemporaryDirectory() as tmp:
            paths = synthetic_shards.write_shards(tmp, size=8, cameras=2, frames=3, sequences=2)
            tensors, metadata = read_safetensors(paths[1])
            info = json.loads(metadata["sixway.dataset"])
            info["motion"] = False
            tensors["motion"] = np.zeros_like(tensors["motion"])
            write_safetensors(paths[1], tensors, {"sixway.dataset": json.dumps(info)})
            data = ShardDataset(tmp)
            played = [i for i, s in enumerate(data.samples) if s["sequence"] == 1]
            self.assertEqual(len(played), 2 * 3)
            self.assertTrue(all(data.previous[i] == i for i in played))
            self.assertEqual(len(data.pairs("heldout_sequence")), 2 * 3)
            self.assertEqual(len(data.pairs("train")), 2 * 2)  # sequence 0: each camera's frames after its first


if __name__ == "__main__":
    unittest.main()
