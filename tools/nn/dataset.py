"""The training shards written by `sixway dataset` (docs/dataset-format.md), read with numpy alone.

A directory holds one `shard_SSSSS.safetensors` per simulated sequence: F16 tensors `guide` [N,3,H,W] (guide,
alpha, depth; versions 3 and 4: [N,4,H,W] with the fine alpha; version 4 also [N,5,H,W] with the fine alpha and
the direct emission; as the metadata's `guide_channels` says), the targets [N,8,H,W] (the baker's channels: Right,
Left, Top, Bottom, Back, Front, alpha, emissive): `target` (single scattering) and/or `target_ms` (multiple
scattering), as the metadata's `targets` says (versions 2 to 4; version 1 shards hold `target` alone), and
`motion` [N,2,H,W] (lightmap pixels, x right, y down: the smoke at p now was at p - motion(p) one frame before),
and the metadata `sixway.dataset` that names each sample's camera, frame and split.

    data = ShardDataset("/work/data/cpu_small")    # target="multiple": train on target_ms; guide_channels=4:
                                                   # with the fine alpha, 5: and the emission
    pairs = data.pairs("train")                    # samples that have the previous frame of their camera
    current, previous = data.pair_batch(pairs[:8], crop=64, rng=np.random.default_rng(0))
    ShardDataset(directory, albedo=True)           # each guide gains a plane: its scene's smoke albedo

Targets are reordered here into the network's output order (sixway_net.ADAPTERS: left, right, top, bottom,
front, back, alpha, emissive), so that everything downstream compares channel i with channel i.
"""
import glob
import json
import os
import re

import numpy as np
import torch

from safetensors_io import read_safetensors

SPLITS = ("train", "heldout_sequence", "heldout_camera")
SHARD_NAME = re.compile(r"shard_(\d{5})\.safetensors$")
# The guide's channels by name; version 3 shards add the fine alpha, version 4 ones may also add the direct emission
# (the dataset config's "guide" block).
GUIDE_NAMES = ["guide", "alpha", "depth", "alpha_fine", "emission"]
EMISSION = GUIDE_NAMES.index("emission")
# Network channel i is baker channel TARGET_TO_NETWORK[i] (baker: Right, Left, Top, Bottom, Back, Front, ...).
TARGET_TO_NETWORK = [1, 0, 2, 3, 5, 4, 6, 7]
# Mirroring the image left-right swaps the Left and Right lightmaps (network channels 0 and 1).
MIRRORED_CHANNELS = [1, 0, 2, 3, 4, 5, 6, 7]
# The targets a shard may hold, by the name `targets` gives them, and their tensors.
TARGET_TENSORS = {"single": "target", "multiple": "target_ms"}


def shard_targets(info):
    """The targets a shard holds: version 1 shards hold single scattering alone."""
    return ["single"] if info.get("version") == 1 else list(info.get("targets", []))


def shard_paths(directory):
    """The complete shards of a directory, by sequence (temporary files of a running generator are skipped)."""
    paths = sorted(p for p in glob.glob(os.path.join(directory, "shard_*.safetensors"))
                   if SHARD_NAME.search(os.path.basename(p)))
    if not paths:
        raise ValueError(f"{directory}: no shard_SSSSS.safetensors files")
    return paths


def read_shard(path):
    """(tensors, info) of one shard, checked against the format: info is the parsed `sixway.dataset`."""
    tensors, metadata = read_safetensors(path)
    if "sixway.dataset" not in metadata:
        raise ValueError(f"{path}: metadata has no 'sixway.dataset'")
    info = json.loads(metadata["sixway.dataset"])
    if info.get("version") not in (1, 2, 3, 4):
        raise ValueError(f"{path}: sixway.dataset.version is {info.get('version')}, this reader knows 1 to 4")
    guide_names = info.get("guide_channels", GUIDE_NAMES[:3]) if info["version"] >= 3 else GUIDE_NAMES[:3]
    if guide_names != GUIDE_NAMES[:len(guide_names)] or len(guide_names) < 3:
        raise ValueError(f"{path}: sixway.dataset.guide_channels is {guide_names!r}")
    targets = shard_targets(info)
    if not targets or any(t not in TARGET_TENSORS for t in targets):
        raise ValueError(f"{path}: sixway.dataset.targets is {info.get('targets')!r}")
    size = info["lightmap_size"]
    samples = info["samples"]
    for name, channels in (("guide", len(guide_names)), *((TARGET_TENSORS[t], 8) for t in targets), ("motion", 2)):
        if name not in tensors:
            raise ValueError(f"{path}: no tensor '{name}'")
        expected = [len(samples), channels, size, size]
        if list(tensors[name].shape) != expected:
            raise ValueError(f"{path}: tensor '{name}' has shape {list(tensors[name].shape)}, expected {expected}")
    for i, sample in enumerate(samples):
        if sample.get("split") not in SPLITS:
            raise ValueError(f"{path}: sixway.dataset.samples[{i}].split is {sample.get('split')!r}")
    return tensors, info


def scene_emits(info):
    """Whether the shard's scene has emissive smoke (an emission intensity > 0; absent, it is 0)."""
    return info["scene"].get("smoke", {}).get("emission", {}).get("intensity", 0) > 0


def shard_albedo(path, info):
    """The smoke's single-scattering albedo of the shard's scene (its `smoke.albedo`; absent, a scene's 0.9)."""
    albedo = info["scene"].get("smoke", {}).get("albedo", 0.9)
    if not isinstance(albedo, (int, float)) or not 0 <= albedo <= 1:
        raise ValueError(f"{path}: sixway.dataset.scene.smoke.albedo is {albedo!r}, not in [0, 1]")
    return float(albedo)


def shard_guide(path, tensors, info, channels):
    """The first `channels` channels of the shard's guide. A guide without the emission channel stands for one
    whose emission is zero, which it is exactly when the scene emits nothing."""
    guide = tensors["guide"]
    held = guide.shape[1]
    if held == EMISSION and channels > held:
        if scene_emits(info):
            raise ValueError(f"{path}: the network reads the guide's emission, which this shard of an emissive scene "
                             f"lacks (regenerate it with the dataset config's \"guide\": {{\"emission\": true}})")
        return np.concatenate([guide, np.zeros_like(guide[:, :1])], axis=1)
    if held < channels:
        raise ValueError(f"{path}: its guide has no {GUIDE_NAMES[held]} channel (the dataset config's \"guide\": "
                         f"{{\"alpha_step_voxels\"}})")
    return guide[:, :channels]


def guide_channel_count(directory):
    """How many guide channels the directory's first shard holds: 3, 4 with the fine alpha, 5 with the emission."""
    tensors, _ = read_shard(shard_paths(directory)[0])
    return tensors["guide"].shape[1]


class ShardDataset:
    """Every sample of every shard of a directory, or of several (one per scene family, say), in memory as F16
    (a CPU dataset is a few hundred MB), with the first `guide_channels` channels of the guide (3, 4 for the
    fine alpha, 5 for the emission).

    The shards may have different lightmap sizes (64² and 128² samples, say): `by_size` holds each size's
    arrays (`guide`, `target`, `motion` are every sample's only when there is one size); `size` is the smallest
    size, the largest crop every sample allows, and a batch of whole maps takes samples of one size. Split
    metrics pool pixels, so a 128² sample weighs four 64² ones."""

    def __init__(self, directories, target="single", guide_channels=3, albedo=False):
        if target not in TARGET_TENSORS:
            raise ValueError(f"target is {target!r}: single or multiple")
        if guide_channels not in (3, 4, 5):
            raise ValueError(f"guide_channels is {guide_channels!r}: 3, 4 or 5")
        self.directories = [directories] if isinstance(directories, str) else list(directories)
        if not self.directories:
            raise ValueError("no shard directory given")
        self.directory = ", ".join(self.directories)
        self.target_kind = target
        self.with_albedo = albedo
        sources = [(path, source) for source, d in enumerate(self.directories) for path in shard_paths(d)]
        self.paths = [path for path, _ in sources]
        self.shard_sources = [source for _, source in sources]
        guides, targets, motions = [], [], []
        self.samples = []  # per sample: dict(camera, frame, split, sequence, source, ...)
        self.infos = []
        for path, source in sources:
            tensors, info = read_shard(path)
            if target not in shard_targets(info):
                raise ValueError(f"{path}: holds {', '.join(shard_targets(info))} scattering targets, not {target} "
                                 f"(the dataset config's \"targets\")")
            guides.append(shard_guide(path, tensors, info, guide_channels))
            self.infos.append(info)
            targets.append(tensors[TARGET_TENSORS[target]][:, TARGET_TO_NETWORK])
            motions.append(tensors["motion"])
            # A played-back VDB sequence has no motion field ("motion": false): no temporal pairs.
            moves = info.get("motion", True)
            self.samples += [dict(s, sequence=info["sequence"], source=source, moves=moves) for s in info["samples"]]
        shard_sizes = [info["lightmap_size"] for info in self.infos]
        # Per sample: its scene's single-scattering albedo (the smoke's, as the shard's scene states it).
        self.albedo = np.concatenate([np.full(len(info["samples"]), shard_albedo(path, info), dtype=np.float32)
                                      for path, info in zip(self.paths, self.infos)])
        self.sample_sizes = np.concatenate([np.full(len(g), size) for g, size in zip(guides, shard_sizes)])
        # Per sample: its row in its size's arrays.
        self.rows = np.zeros(len(self.samples), dtype=np.int64)
        self.by_size = {}
        for size in sorted(set(shard_sizes)):
            chosen = [k for k, s in enumerate(shard_sizes) if s == size]
            self.rows[self.sample_sizes == size] = np.arange(int((self.sample_sizes == size).sum()))
            self.by_size[size] = {"guide": np.concatenate([guides[k] for k in chosen]),
                                  "target": np.concatenate([targets[k] for k in chosen]),
                                  "motion": np.concatenate([motions[k] for k in chosen])}
        self.size = min(self.by_size)
        self.previous = self._previous_frames()

    def _every_sample(self, name):
        if len(self.by_size) > 1:
            raise ValueError(f"{self.directory}: samples of lightmap sizes {self.sizes()} are not one array "
                             f"(use batch)")
        return self.by_size[self.size][name]

    @property
    def guide(self):
        """[N, channels, size, size] F16: every sample's guide (samples of one lightmap size only)."""
        return self._every_sample("guide")

    @property
    def target(self):
        return self._every_sample("target")

    @property
    def motion(self):
        return self._every_sample("motion")

    def _previous_frames(self):
        """Index of the previous sample of the same sequence and camera (samples are ordered by camera, then
        frame, so it is the sample before), -1 for a camera's first frame. A sample without motion (a played-back
        VDB sequence) is its own previous frame: its pair trains the reconstruction terms, and its temporal term
        is zero."""
        previous = np.full(len(self.samples), -1, dtype=np.int64)
        key = lambda k: (self.samples[k]["source"], self.samples[k]["sequence"], self.samples[k]["camera"],
                         self.sample_sizes[k])
        for i in range(len(self.samples)):
            if not self.samples[i]["moves"]:
                previous[i] = i
                continue
            if i == 0:
                continue
            now, before = self.samples[i], self.samples[i - 1]
            if key(i) == key(i - 1):
                if before["frame"] >= now["frame"]:
                    raise ValueError(f"{self.directory}: sequence {now['sequence']} camera {now['camera']}: "
                                     f"frame {now['frame']} follows frame {before['frame']}")
                previous[i] = i - 1
        return previous

    def guide_alpha_step_voxels(self):
        """The fine alpha's step of the shards' guide (0: none), the same for every shard."""
        steps = {info["scene"].get("render", {}).get("guide_alpha_step_voxels", 0) for info in self.infos}
        if len(steps) > 1:
            raise ValueError(f"{self.directory}: the shards' guides have fine alpha steps {sorted(steps)}")
        return steps.pop()

    def dataset_config(self):
        """The dataset config that the shards were generated from (the same for every shard of a directory):
        one config, or a list of them (one per directory) when there are several directories."""
        configs = [self.infos[self.shard_sources.index(k)]["config"] for k in range(len(self.directories))]
        return configs[0] if len(configs) == 1 else configs

    def indices(self, split):
        return np.array([i for i, s in enumerate(self.samples) if s["split"] == split], dtype=np.int64)

    def pairs(self, split):
        """Samples of `split` whose previous frame exists (both are always in the same split)."""
        return np.array([i for i in self.indices(split) if self.previous[i] >= 0], dtype=np.int64)

    def sizes(self):
        """The lightmap sizes of the samples, smallest first."""
        return sorted(self.by_size)

    def chunks_by_size(self, indices, count):
        """`indices` in chunks of at most `count` samples of one lightmap size, size by size, in order."""
        return [same[start:start + count] for size in self.sizes()
                for same in [indices[self.sample_sizes[indices] == size]] for start in range(0, len(same), count)]

    def _whole_map_size(self, indices):
        """The one lightmap size of the samples `indices` (a batch of whole maps stacks maps of one size)."""
        sizes = sorted(set(self.sample_sizes[indices].tolist()))
        if len(sizes) > 1:
            raise ValueError(f"{self.directory}: a batch of whole maps of sizes {sizes}")
        return sizes[0] if sizes else self.size

    def batch(self, indices, crop=None, offsets=None, mirror=None):
        """float32 tensors guide [B,3 to 5,c,c] (one more channel, the albedo plane, with `albedo`), target
        [B,8,c,c], motion [B,2,c,c] of the samples `indices`; `offsets` (B x 2: row, column) place the crops of
        size `crop`; `mirror` (B booleans) flips left-right. Without `crop`, the samples' maps whole: they must
        have one size."""
        c = crop or self._whole_map_size(indices)
        offsets = np.zeros((len(indices), 2), dtype=np.int64) if offsets is None else offsets
        out = {"guide": [], "target": [], "motion": []}
        for k, index in enumerate(indices):
            rows = slice(offsets[k][0], offsets[k][0] + c)
            cols = slice(offsets[k][1], offsets[k][1] + c)
            arrays, row = self.by_size[self.sample_sizes[index]], self.rows[index]
            guide = arrays["guide"][row, :, rows, cols]
            target = arrays["target"][row, :, rows, cols]
            motion = arrays["motion"][row, :, rows, cols]
            if mirror is not None and mirror[k]:
                guide = guide[:, :, ::-1]
                target = target[MIRRORED_CHANNELS, :, ::-1]
                motion = motion[:, :, ::-1] * np.array([-1, 1], dtype=motion.dtype)[:, None, None]
            if self.with_albedo:
                guide = np.concatenate([guide, np.full((1, c, c), self.albedo[index], dtype=np.float32)])
            out["guide"].append(guide)
            out["target"].append(target)
            out["motion"].append(motion)
        return {k: torch.from_numpy(np.stack(v).astype(np.float32)) for k, v in out.items()}

    def pair_batch(self, indices, crop, rng, mirror=False):
        """(current, previous) batches of the samples `indices` and their previous frames, with the same
        random crop (when crop < a sample's size) and the same random mirroring (when `mirror`) drawn from
        `rng`. The crop is at most the smallest sample's size. Without `crop`, whole maps of one size."""
        c = min(crop, int(self.sample_sizes[indices].min())) if crop else self._whole_map_size(indices)
        offsets = rng.integers(0, self.sample_sizes[indices][:, None] - c + 1, size=(len(indices), 2))
        flips = rng.random(len(indices)) < 0.5 if mirror else None
        current = self.batch(indices, c, offsets, flips)
        previous = self.batch(self.previous[indices], c, offsets, flips)
        return current, previous
