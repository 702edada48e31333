#!/usr/bin/python3
"""Trains the sixway lightmap network (tools/nn/sixway_net.py) on the shards of `sixway dataset`.

    /usr/bin/python3 tools/train.py --config tools/train_configs/cpu_small.json --out /work/data/train_cpu_small
    /usr/bin/python3 tools/train.py --out DIR --resume              # continues exactly where the checkpoint is
    /usr/bin/python3 tools/train.py --recipe ms --out DIR           # data and every phase (tools/nn/recipe.py)
    torchrun --nproc_per_node 8 tools/train.py --config C --out DIR  # DistributedDataParallel, one GPU each

DDP starts when WORLD_SIZE > 1 (NCCL on GPUs, gloo on the CPU). Debian's torch 1.13 launcher fails before
starting the workers (AttributeError in torch.distributed.elastic's `redirects`); there, start one process per
rank with MASTER_ADDR, MASTER_PORT, WORLD_SIZE, RANK and LOCAL_RANK set.

Loss (tools/nn/losses.py): MSE in sRGB space + SSIM and/or gradient + the temporal term on temporal pairs
+ optionally the MSE of the shaded images.
Every batch is B pairs (a frame and the previous frame of its camera, the same random crop), so both frames
train the reconstruction terms and the pair trains the temporal term. Adam with a cosine or step schedule.
Deterministic from the config and the seed: the model's initialisation comes from torch.manual_seed(seed),
the data order and the crops from numpy generators keyed by (seed, epoch) and (seed, step, rank), so a run
resumed from a checkpoint gives bit-identical weights to an uninterrupted one (same device and threads).

DIR receives: config.json (the effective config), log.jsonl (one JSON row per logged step: kind "train" or
"heldout"), checkpoint.pt (model, optimizer, step, RNG states, every `checkpoint_every` steps and at the end),
loss.png, metrics.json (per split, tools/nn/metrics.py) and sixway-unet.safetensors (the exported network with
sixway.training and sixway.metrics in its metadata, docs/network-format.md).
"""
import argparse
import copy
import json
import math
import os
import platform
import signal
import sys
import time

import numpy as np
import torch
import torch.distributed as dist

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "nn"))
from atomic_file import atomic_open, atomic_path  # noqa: E402
from bench_torch import node_flops  # noqa: E402
from dataset import SPLITS, ShardDataset  # noqa: E402
from losses import training_loss  # noqa: E402
from net2deeper import deeper_state  # noqa: E402
from net2wider import wider_state  # noqa: E402
from metrics import SplitMetrics, evaluate_split  # noqa: E402
from recipe import Recipe, RecipeError, make_data, write_summary  # noqa: E402
from safetensors_io import read_safetensors, write_safetensors  # noqa: E402
from sixway_net import (FROM_GUIDE_SUFFIX, OPTIONAL_CONFIG, OUTPUT_CHANNELS, SixwayNet,  # noqa: E402
                        decode_output, export_safetensors, full_config, load_safetensors,
                        output_encodings)

DEFAULTS = {
    "model": {},  # sixway_net.DEFAULT_CONFIG overrides
    "data": {
        "dir": None,  # the shards: a directory or a list of them; relative paths are relative to the repository root
        "crop": None,  # random square crops of this size, or whole maps where smaller (None: whole maps); with
        # several sizes, a crop larger than the smallest size takes batches of one size
        "mirror": True,  # random left-right mirroring (swaps the Left and Right lightmaps)
        "target": "single",  # the shards' targets learnt: single or multiple scattering (target_ms)
    },
    "train": {
        "steps": 1000,
        "batch": 8,  # temporal pairs per step (2 x batch images), over all processes
        "lr": 1e-3,
        "schedule": "cosine",  # cosine: warm-up then cosine to min_lr; step: lr x step_gamma every step_every
        "warmup_steps": 0,
        "min_lr": 1e-5,
        "step_every": 1000,
        "step_gamma": 0.5,
        "weight_decay": 0.0,
        "grad_clip": 1.0,  # max gradient norm (0: none)
        "seed": 0,
        "threads": 2,  # torch.set_num_threads (CPU)
        "log_every": 10,
        "heldout_every": 100,  # the held-out curve: loss and PSNR on heldout_pairs fixed held-out pairs
        "heldout_pairs": 32,
        "checkpoint_every": 500,
        # Fine-tuning: a checkpoint.pt (or a training directory holding one) or an exported network
        # (.safetensors), relative to the repository root, whose model weights start this run; its model config
        # must equal this one, or differ only in fewer guide_channels and input_channels (the new input channels
        # start with zero weights, see widened_weights), or in wider widths (tools/nn/net2wider.py), or in one
        # more level (tools/nn/net2deeper.py). The optimizer starts afresh.
        "init_from": None,
        # The noise in the copied units' incoming weights when init_from's widths are narrower, relative to
        # each layer's weight spread: it lets the copies part (net2wider.wider_state).
        "widen_noise": 0.01,
    },
    # channel_weights: the MSE's factor per output channel ({"emissive": 4}: the others stay 1).
    # shaded: the MSE of the images the maps shade under fixed lightings (losses.shaded_loss).
    # area_power: p of the per-sample weights (smoke area)^-p of the MSE and shaded terms (losses.area_weights).
    "loss": {"mse": 1.0, "ssim": 0.1, "gradient": 0.0, "temporal": 0.1, "temporal_k": 20.0, "shaded": 0.0,
             "channel_weights": {}, "area_power": 0.0},
}
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The model config keys in which train.init_from's checkpoint may have fewer channels than the run.
WIDENED_KEYS = ("guide_channels", "input_channels")
# The outputs that the run may take from the guide where the checkpoint's network computed them.
PASSED_THROUGH_KEYS = ("emissive",)
# The inputs that the run may add to the checkpoint's network (their channel's weights start at zero).
ADDED_INPUT_KEYS = ("albedo_input",)
EXPORT_NAME = "sixway-unet.safetensors"


class ConfigError(Exception):
    pass


def merge_config(config, source):
    """DEFAULTS overridden by `config` (two levels), unknown keys rejected with the file and key named."""
    merged = copy.deepcopy(DEFAULTS)
    for section, values in config.items():
        if section not in merged:
            raise ConfigError(f"{source}: unknown key '{section}'")
        if section == "model":
            try:
                full_config(values)
            except ValueError as error:
                raise ConfigError(f"{source}: model.{str(error).removeprefix('config: ')}")
            merged["model"] = values
            continue
        for key, value in values.items():
            if key not in merged[section]:
                raise ConfigError(f"{source}: unknown key '{section}.{key}'")
            merged[section][key] = value
    if merged["train"]["schedule"] not in ("cosine", "step"):
        raise ConfigError(f"{source}: train.schedule must be cosine or step")
    noise = merged["train"]["widen_noise"]
    if not isinstance(noise, (int, float)) or isinstance(noise, bool) or not 0 <= noise <= 1:
        raise ConfigError(f"{source}: train.widen_noise must be a number in [0, 1]")
    if not isinstance(merged["loss"]["channel_weights"], dict):
        raise ConfigError(f"{source}: loss.channel_weights must be an object {{channel: factor}}")
    for name, factor in merged["loss"]["channel_weights"].items():
        if name not in OUTPUT_CHANNELS:
            raise ConfigError(f"{source}: loss.channel_weights: unknown channel '{name}' (one of "
                              f"{', '.join(OUTPUT_CHANNELS)})")
        if not isinstance(factor, (int, float)) or isinstance(factor, bool) or not 0 <= factor <= 100:
            raise ConfigError(f"{source}: loss.channel_weights.{name} must be a number in [0, 100]")
    power = merged["loss"]["area_power"]
    if not isinstance(power, (int, float)) or isinstance(power, bool) or not 0 <= power <= 1:
        raise ConfigError(f"{source}: loss.area_power must be a number in [0, 1]")
    return merged


def learning_rate(step, train):
    """The rate for optimizer step `step` (0-based)."""
    if step < train["warmup_steps"]:
        return train["lr"] * (step + 1) / train["warmup_steps"]
    if train["schedule"] == "step":
        return train["lr"] * train["step_gamma"] ** (step // train["step_every"])
    progress = (step - train["warmup_steps"]) / max(1, train["steps"] - train["warmup_steps"])
    return train["min_lr"] + 0.5 * (train["lr"] - train["min_lr"]) * (1 + math.cos(math.pi * progress))


class BatchOrder:
    """The pairs of global step s: positions s*B .. s*B+B-1 of an endless sequence of epochs, each epoch a
    permutation of the training pairs drawn from numpy's PCG64 keyed by (seed, epoch); stateless, so resuming
    needs nothing but the step."""

    def __init__(self, pairs, batch, seed):
        self.pairs, self.batch, self.seed = pairs, batch, seed
        self.permutations = {}

    def _permutation(self, epoch):
        if epoch not in self.permutations:
            self.permutations = {epoch: np.random.default_rng([self.seed, epoch]).permutation(len(self.pairs))}
        return self.permutations[epoch]

    def indices(self, step):
        positions = range(step * self.batch, (step + 1) * self.batch)
        return np.array([self.pairs[self._permutation(p // len(self.pairs))[p % len(self.pairs)]]
                         for p in positions])

    def epoch(self, step):
        return step * self.batch / len(self.pairs)


class SizedBatchOrder:
    """BatchOrder for whole maps of several sizes: each epoch permutes the pairs of each size, cuts them into
    batches of B (the pairs left over from a size's last partial batch sit that epoch out; the next permutation
    leaves out others) and shuffles the batches, all from PCG64 keyed by (seed, epoch), so that every batch has one
    size and each size trains in proportion to its pairs; stateless like BatchOrder. An epoch is counted in whole
    batches."""

    def __init__(self, pairs, sizes, batch, seed):
        self.batch, self.seed = batch, seed
        self.groups = [pairs[sizes == size] for size in np.unique(sizes)]
        self.batches_per_epoch = sum(len(group) // batch for group in self.groups)
        self.epoch_batches = {}

    def _batches(self, epoch):
        if epoch not in self.epoch_batches:
            rng = np.random.default_rng([self.seed, epoch])
            batches = []
            for group in self.groups:
                shuffled = group[rng.permutation(len(group))]
                batches += [shuffled[i:i + self.batch] for i in range(0, len(group) - self.batch + 1, self.batch)]
            self.epoch_batches = {epoch: [batches[i] for i in rng.permutation(len(batches))]}
        return self.epoch_batches[epoch]

    def indices(self, step):
        return self._batches(step // self.batches_per_epoch)[step % self.batches_per_epoch]

    def epoch(self, step):
        return step / self.batches_per_epoch


def batch_order(data, pairs, crop, train):
    """BatchOrder, or SizedBatchOrder for several sizes taken whole or in crops larger than the smallest size
    (one size per batch; each batch cropped to the smaller of the crop and its size)."""
    if len(data.sizes()) == 1 or (crop and crop <= min(data.sizes())):
        return BatchOrder(pairs, train["batch"], train["seed"])
    pair_sizes = data.sample_sizes[pairs]
    small = [size for size in data.sizes() if np.sum(pair_sizes == size) < train["batch"]]
    if small:
        names = "/".join(f"{size}x{size}" for size in small)
        raise ConfigError(f"{data.directory}: fewer training pairs of {names} maps than train.batch ({train['batch']}):"
                          f" whole maps of several sizes go in batches of one size")
    return SizedBatchOrder(pairs, pair_sizes, train["batch"], train["seed"])


def heldout_subset(data, count):
    """Up to `count` held-out pairs evenly spread over both held-out splits (the held-out curve)."""
    pairs = np.concatenate([data.pairs(s) for s in SPLITS if s != "train"])
    if len(pairs) <= count:
        return pairs
    return pairs[np.linspace(0, len(pairs) - 1, count).round().astype(np.int64)]


@torch.no_grad()
def heldout_curve_point(net, data, pairs, config, device):
    """Loss terms and PSNR of the fixed held-out pairs, on whole maps, no augmentation."""
    net.eval()
    totals, metrics = {}, SplitMetrics()
    for chunk in data.chunks_by_size(pairs, 8):
        current, previous = data.pair_batch(chunk, None, np.random.default_rng(0))
        raw = net(torch.cat([current["guide"], previous["guide"]]).to(device))
        n = len(current["guide"])
        loss, terms = training_loss(raw[:n], raw[n:], current["target"].to(device), previous["target"].to(device),
                                    current["motion"].to(device), output_encodings(net.config), config["loss"])
        for name, value in dict(terms, loss=float(loss)).items():
            totals[name] = totals.get(name, 0.0) + value * n
        metrics.add(decode_output(raw[:n], net.config).cpu(), current["target"])
    net.train()
    result = {name: value / len(pairs) for name, value in totals.items()}
    result.update({k: v for k, v in metrics.result(len(pairs)).items() if k in ("psnr_masked", "psnr_full")})
    return result


def hardware(device, world):
    if device.type == "cuda":
        return {"device": torch.cuda.get_device_name(device), "processes": world}
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"device": "cpu", "cpu": cpu, "threads": torch.get_num_threads(), "processes": world,
            "cores": os.cpu_count()}


def flops_at(net, size):
    return sum(node_flops(node, size, size) for node in net.nodes)


def save_checkpoint(path, net, optimizer, step, seconds, config, interval):
    """`interval`: the loss sums since the last log row, so that a resumed run logs what a straight one does."""
    state = {"step": step, "seconds": seconds, "config": config, "interval": interval, "model": net.state_dict(),
             "optimizer": optimizer.state_dict(), "torch_rng": torch.get_rng_state(),
             "numpy_rng": np.random.get_state()}
    if torch.cuda.is_available():
        state["cuda_rng"] = torch.cuda.get_rng_state_all()
    with atomic_path(path) as temporary:
        torch.save(state, temporary)


def widens(old, new):
    """Whether model config `new` is `old` with as many or more guide and input channels, possibly an output
    passed through from the guide that `old` computed, possibly wider widths (as many levels, a UNet of conv
    units), and otherwise equal."""
    old, new = ({**OPTIONAL_CONFIG, **full_config(config)} for config in (old, new))
    if any(new[key] < old[key] for key in WIDENED_KEYS):
        return False
    if any(old[key] == "guide" and new[key] != "guide" for key in PASSED_THROUGH_KEYS):
        return False
    if any(old[key] is not None and new[key] != old[key] for key in ADDED_INPUT_KEYS):
        return False
    if new["widths"] != old["widths"] and (
            len(new["widths"]) != len(old["widths"]) or new["block"] != "conv"
            or any(n < o for n, o in zip(new["widths"], old["widths"]))
            or new["widths"][0] == new["adapters"]["width"] != old["widths"][0]):  # an adapter projection lost
        return False
    return dict(old, **{key: new[key] for key in WIDENED_KEYS + PASSED_THROUGH_KEYS + ADDED_INPUT_KEYS
                        + ("widths",)}) == new


def deepens(old, new):
    """Whether model config `new` is `old` with one more level (a width appended), a UNet of conv units with ReLU
    activations, and otherwise equal."""
    old, new = ({**OPTIONAL_CONFIG, **full_config(config)} for config in (old, new))
    return (new["widths"][:-1] == old["widths"] and len(new["widths"]) == len(old["widths"]) + 1
            and new["block"] == "conv" and new["activation"] == "relu" and dict(old, widths=new["widths"]) == new)


def fixed_selection(key):
    """Whether a state dict key is a tensor of a fixed selection (sixway_net.FixedSelection: not trained)."""
    return key.removeprefix("blocks.").split(".")[0].endswith(FROM_GUIDE_SUFFIX)


def more_input_channels(old, new):
    """Whether tensor shape `new` is `old` with more channels in dimension 1 (a conv's input channels)."""
    return len(old) >= 2 and len(new) == len(old) and new[1] > old[1] and new[:1] + new[2:] == old[:1] + old[2:]


def widened_weights(weights, current):
    """A checkpoint's `weights` (a state dict) for a network of state dict `current`: a tensor with more input
    channels here (the first conv) gets the old ones first and zeros after them. The new channels are appended, so
    the widened network computes the old function until training moves the new weights. The fixed selections
    (alpha and emissive from the guide) are the current network's: its config says what they pass through. Any
    other difference is left to load_state_dict to report. Returns the state dict and the widened tensors' names."""
    state = {key: value for key, value in current.items() if fixed_selection(key)}
    widened = []
    for key, old in weights.items():
        if fixed_selection(key):
            continue
        new = current.get(key, old)
        if more_input_channels(old.shape, new.shape):
            old = torch.cat([old, old.new_zeros(new.shape[0], new.shape[1] - old.shape[1], *new.shape[2:])], dim=1)
            widened.append(key.removeprefix("blocks.").replace("/", "."))
        state[key] = old
    return state, widened


def closed_input_channel(net, state, channel):
    """Zeroes input channel `channel`'s weights in `state` in every trained node that reads the input node (the
    first conv), so that a channel the checkpoint saw as zero padding can carry a new input while the network
    still computes the checkpoint's function (its weights there never had a gradient, but need not be zero).
    Returns those nodes' names."""
    readers = [n["name"] for n in net.nodes
               if "input" in n.get("inputs", []) and not n["name"].endswith(FROM_GUIDE_SUFFIX)]
    for name in readers:
        key = "blocks." + name.replace(".", "/") + ".weight"
        state[key] = state[key].clone()
        state[key][:, channel] = 0
    return readers


def first_difference(a, b, prefix=""):
    """The first key path where two configs differ, or None."""
    for key in sorted(set(a) | set(b)):
        if isinstance(a.get(key), dict) and isinstance(b.get(key), dict):
            found = first_difference(a[key], b[key], f"{prefix}{key}.")
            if found:
                return found
        elif a.get(key) != b.get(key):
            return f"{prefix}{key}"
    return None


def truncate_log(path, step):
    """Drops rows logged after the checkpoint's step (the interrupted part of a run)."""
    if not os.path.exists(path):
        return
    with open(path) as f:
        rows = [line for line in f if line.strip() and json.loads(line)["step"] <= step]
    with atomic_open(path) as f:
        f.writelines(rows)


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--config", help="training config JSON (tools/train_configs/); optional with --resume")
    parser.add_argument("--recipe", help="a recipe (tools/train_configs/recipes/NAME.json, or a path): its data "
                                         "and every phase from scratch; rerun the same command to resume")
    parser.add_argument("--out", required=True, help="output directory")
    parser.add_argument("--data", nargs="+", help="shard directories (override data.dir)")
    parser.add_argument("--seed", type=int, help="overrides train.seed")
    parser.add_argument("--resume", action="store_true", help="continue from OUT/checkpoint.pt")
    parser.add_argument("--force", action="store_true", help="start afresh in an existing OUT")
    parser.add_argument("--stop-at", type=int, help="stop (with a checkpoint) after this step, e.g. to fit a "
                                                    "time slot; continue later with --resume (with --recipe: "
                                                    "steps counted over all phases)")
    parser.add_argument("--profile", help="with --recipe: the recipe's profile (default: gpu with CUDA, else cpu)")
    parser.add_argument("--data-root", help="with --recipe: where its datasets go (default: the repository root)")
    parser.add_argument("--data-shard", help="with --recipe: I/N makes worker I's share of the data and stops "
                                             "(N machines, one share each; 0/1: all of it)")
    parser.add_argument("--sixway", default=os.environ.get("SIXWAY", os.path.join(REPO_ROOT, "build/src/app/sixway")),
                        help="with --recipe: the sixway binary that makes the data (default: SIXWAY or build/)")
    args = parser.parse_args()
    if args.recipe and (args.config or args.resume or args.force or args.data or args.seed is not None):
        parser.error("--recipe takes none of --config, --resume, --force, --data, --seed")
    if not args.recipe and (args.profile or args.data_root or args.data_shard):
        parser.error("--profile, --data-root and --data-shard go with --recipe")
    return args


def load_config(args, checkpoint):
    """The config file (or the checkpoint's) with --data and --seed applied; a resumed run must keep the
    checkpoint's config, except data.dir (the shards may have moved)."""
    if args.config:
        try:
            with open(args.config) as f:
                config = merge_config(json.load(f), args.config)
        except (OSError, json.JSONDecodeError) as error:
            raise ConfigError(f"{args.config}: {error}")
    elif checkpoint is not None:
        config = merge_config(checkpoint["config"], "checkpoint")
    else:
        raise ConfigError("--config is required (unless resuming)")
    if args.data:
        config["data"]["dir"] = args.data[0] if len(args.data) == 1 else args.data
    if args.seed is not None:
        config["train"]["seed"] = args.seed
    directories = config["data"]["dir"]
    if directories is None:
        raise ConfigError(f"{args.config}: data.dir is missing (or pass --data)")
    if not (isinstance(directories, str) or (isinstance(directories, list) and directories
                                             and all(isinstance(d, str) for d in directories))):
        raise ConfigError(f"{args.config}: data.dir must be a directory or a list of directories")
    if checkpoint is not None:
        # Merged again so that a checkpoint written before a config key existed compares with its default.
        saved = merge_config(checkpoint["config"], "checkpoint")
        differs = first_difference(dict(config, data=dict(config["data"], dir=None)),
                                   dict(saved, data=dict(saved["data"], dir=None)))
        if differs:
            raise ConfigError(f"{args.config or '--seed'}: '{differs}' differs from the checkpoint's config; "
                              f"resume with the same config")
    return config


class Trainer:
    """One run: the data, the model (DDP-wrapped when WORLD_SIZE > 1), the optimizer and the step reached."""

    def __init__(self, args):
        self.world = int(os.environ.get("WORLD_SIZE", "1"))
        self.rank = int(os.environ.get("RANK", "0"))
        local_rank = int(os.environ.get("LOCAL_RANK", "0"))
        self.device = torch.device(f"cuda:{local_rank}" if torch.cuda.is_available() else "cpu")
        self.owns_group = self.world > 1 and not dist.is_initialized()  # a recipe holds one over its phases
        if self.owns_group:
            dist.init_process_group("nccl" if self.device.type == "cuda" else "gloo")
        if self.device.type == "cuda":
            torch.cuda.set_device(self.device)
        self.lead = self.rank == 0
        self.out = args.out
        self.checkpoint_path = os.path.join(args.out, "checkpoint.pt")
        self.log_path = os.path.join(args.out, "log.jsonl")

        checkpoint = None
        if args.resume:
            if not os.path.exists(self.checkpoint_path):
                raise ConfigError(f"{self.checkpoint_path}: no checkpoint to resume from")
            checkpoint = torch.load(self.checkpoint_path, map_location="cpu", weights_only=False)
        elif self.lead and os.path.isdir(args.out) and os.listdir(args.out) and not args.force:
            raise ConfigError(f"{args.out}: exists and is not empty (use --resume to continue, --force to restart)")
        self.config = load_config(args, checkpoint)
        self.train = self.config["train"]
        torch.set_num_threads(self.train["threads"])
        self._load_data()

        torch.manual_seed(self.train["seed"])
        np.random.seed(self.train["seed"])
        self.net = SixwayNet(self.config["model"]).to(self.device)
        crop = self.config["data"]["crop"]
        multiple = self.net.size_multiple()
        if (crop or 0) % multiple or any(size % multiple for size in self.data.sizes()):
            raise ConfigError(f"data.crop {crop} or a lightmap size {self.data.sizes()} is not a multiple of the "
                              f"network's size multiple {multiple}")
        self.order = batch_order(self.data, self.pairs, crop, self.train)
        self.encodings = output_encodings(self.net.config)
        self.optimizer = torch.optim.Adam(self.net.parameters(), lr=self.train["lr"],
                                          weight_decay=self.train["weight_decay"])
        self.step, self.seconds_before, self.interval = 0, 0.0, {}
        if checkpoint is not None:
            self._restore(checkpoint)
        elif self.train["init_from"]:
            self._initialise_from(self.train["init_from"])
        self.model = self.net
        if self.world > 1:
            ids = [local_rank] if self.device.type == "cuda" else None
            self.model = torch.nn.parallel.DistributedDataParallel(self.net, device_ids=ids)
        self.heldout = heldout_subset(self.data, self.train["heldout_pairs"])
        if self.lead:
            self._prepare_out(resumed=checkpoint is not None)

    def _load_data(self):
        directories = self.config["data"]["dir"]
        directories = [directories] if isinstance(directories, str) else directories
        model = full_config(self.config["model"])
        self.data = ShardDataset([os.path.join(REPO_ROOT, d) for d in directories],
                                 target=self.config["data"]["target"], guide_channels=model["guide_channels"],
                                 albedo=bool(model.get("albedo_input")))
        # The network reads the guide it was trained on: a fine alpha of another step is another input.
        wanted, held = model.get("guide_alpha_step_voxels", 0), self.data.guide_alpha_step_voxels()
        if wanted and wanted != held:
            raise ConfigError(f"{self.data.directory}: the shards' fine alpha step is {held} voxels, "
                              f"model.guide_alpha_step_voxels is {wanted}")
        self.pairs = self.data.pairs("train")
        if len(self.pairs) == 0:
            raise ConfigError(f"{self.data.directory}: no training pairs (split 'train', two consecutive frames)")
        if self.train["batch"] % self.world:
            raise ConfigError(f"train.batch {self.train['batch']} is not a multiple of the {self.world} processes")

    def _restore(self, checkpoint):
        self.net.load_state_dict(checkpoint["model"])
        self.optimizer.load_state_dict(checkpoint["optimizer"])
        torch.set_rng_state(checkpoint["torch_rng"])
        np.random.set_state(checkpoint["numpy_rng"])
        if "cuda_rng" in checkpoint and self.device.type == "cuda":
            torch.cuda.set_rng_state_all(checkpoint["cuda_rng"])
        self.step, self.seconds_before = checkpoint["step"], checkpoint["seconds"]
        self.interval = checkpoint["interval"]

    def _initialise_from(self, source):
        path = os.path.join(REPO_ROOT, source)
        if os.path.isdir(path):
            path = os.path.join(path, "checkpoint.pt")
        if not os.path.isfile(path):
            raise ConfigError(f"{path}: train.init_from names no checkpoint")
        try:
            if path.endswith(".safetensors"):  # an exported network: its config is in the file's metadata
                start, _ = load_safetensors(path)
                model_config, weights = start.config, start.state_dict()
            else:
                start = torch.load(path, map_location="cpu", weights_only=False)
                model_config = start["config"]["model"]
                weights = start["model"]
        except Exception as error:  # a corrupt or foreign file: one line naming it
            raise ConfigError(f"{path}: not a training checkpoint or exported network ({type(error).__name__})")
        if deepens(model_config, self.config["model"]):
            self.net.load_state_dict(deeper_state(SixwayNet(model_config), self.net, weights))
            if self.lead:
                print(f"train.init_from: widths {full_config(model_config)['widths']} deepened to "
                      f"{self.net.config['widths']} (net2deeper: the new level starts closed)", flush=True)
            return
        if not widens(model_config, self.config["model"]):
            raise ConfigError(f"{path}: train.init_from has another model config than this run's")
        # The input first, in a network of the checkpoint's widths; then the widths (net2wider).
        widths = full_config(model_config)["widths"]
        narrow = self.net
        if widths != self.net.config["widths"]:
            narrow = SixwayNet(dict(self.config["model"], widths=widths))
        state, widened = widened_weights(weights, narrow.state_dict())
        if widened and self.lead:
            print(f"train.init_from: {', '.join(widened)} widened to this run's input channels (the new ones "
                  f"start at zero)", flush=True)
        if self.net.config.get("albedo_input") and not full_config(model_config).get("albedo_input"):
            opened = closed_input_channel(narrow, state, self.net.config["guide_channels"])
            if self.lead:
                print(f"train.init_from: the albedo input added; {', '.join(opened)} read it from zero weights",
                      flush=True)
        if narrow is not self.net:
            state = wider_state(narrow, self.net, state, self.train["widen_noise"], self.train["seed"])
            if self.lead:
                print(f"train.init_from: widths {narrow.config['widths']} widened to {self.net.config['widths']} "
                      f"(net2wider, noise {self.train['widen_noise']})", flush=True)
        self.net.load_state_dict(state)

    def _prepare_out(self, resumed):
        os.makedirs(self.out, exist_ok=True)
        with atomic_open(os.path.join(self.out, "config.json")) as f:
            json.dump(self.config, f, indent=2)
        if resumed:
            truncate_log(self.log_path, self.step)
        elif os.path.exists(self.log_path):
            os.remove(self.log_path)
        params = sum(p.numel() for p in self.net.parameters())
        sizes = "/".join(f"{size}x{size}" for size in self.data.sizes())
        print(f"train: {len(self.data.paths)} shards, {len(self.pairs)} training pairs of {sizes}, {params} "
              f"parameters, {flops_at(self.net, 256) / 1e9:.2f} GFLOP at 256x256, "
              f"device {self.device}, {self.world} process(es), {self.train['threads']} threads; "
              f"steps {self.step}..{self.train['steps']}", flush=True)

    def seconds(self):
        return self.seconds_before + time.time() - self.started

    def train_step(self):
        """One optimizer step on this process's share of the global batch of step `self.step`."""
        lr = learning_rate(self.step, self.train)
        for group in self.optimizer.param_groups:
            group["lr"] = lr
        indices = self.order.indices(self.step)[self.rank::self.world]
        rng = np.random.default_rng([self.train["seed"], self.step, self.rank])
        current, previous = self.data.pair_batch(indices, self.config["data"]["crop"], rng,
                                                 self.config["data"]["mirror"])
        raw = self.model(torch.cat([current["guide"], previous["guide"]]).to(self.device))
        n = len(indices)
        loss, terms = training_loss(raw[:n], raw[n:], current["target"].to(self.device),
                                    previous["target"].to(self.device), current["motion"].to(self.device),
                                    self.encodings, self.config["loss"])
        self.optimizer.zero_grad(set_to_none=True)
        loss.backward()
        if self.train["grad_clip"]:
            torch.nn.utils.clip_grad_norm_(self.net.parameters(), self.train["grad_clip"])
        self.optimizer.step()
        for name, value in dict(terms, loss=float(loss), steps=1).items():
            self.interval[name] = self.interval.get(name, 0.0) + value
        self.step += 1
        return lr

    def log_train(self, log, lr):
        count = self.interval.pop("steps")
        row = {"kind": "train", "step": self.step, "epoch": round(self.order.epoch(self.step), 4), "lr": lr,
               **{k: v / count for k, v in self.interval.items()}, "seconds": round(self.seconds(), 2),
               "load": round(os.getloadavg()[0], 2)}
        log.write(json.dumps(row) + "\n")
        log.flush()
        self.interval = {}
        print(f"step {self.step}/{self.train['steps']} epoch {row['epoch']:.2f} loss {row['loss']:.5f} "
              f"lr {lr:.2e} {row['seconds']:.0f}s load {row['load']}", flush=True)

    def log_heldout(self, log):
        point = heldout_curve_point(self.net, self.data, self.heldout, self.config, self.device)
        log.write(json.dumps({"kind": "heldout", "step": self.step, **point}) + "\n")
        log.flush()
        print(f"  held-out loss {point['loss']:.5f} PSNR masked {point['psnr_masked']:.2f} dB "
              f"full {point['psnr_full']:.2f} dB", flush=True)

    def run(self, stop):
        """Trains up to step `stop`; the lead logs, checkpoints, and finishes the run at the last step."""
        self.started = time.time()
        steps = self.train["steps"]
        log = open(self.log_path, "a") if self.lead else None
        while self.step < stop:
            lr = self.train_step()
            if not self.lead:
                continue
            if self.step % self.train["log_every"] == 0 or self.step == steps:
                self.log_train(log, lr)
            if self.step % self.train["heldout_every"] == 0 or self.step == steps:
                self.log_heldout(log)
            if self.step % self.train["checkpoint_every"] == 0 or self.step == stop:
                save_checkpoint(self.checkpoint_path, self.net, self.optimizer, self.step, self.seconds(),
                                self.config, self.interval)
        if log:
            log.close()
        if self.lead and self.step == steps:
            finish(self.out, self.net, self.data, self.config, self.seconds(), self.device, self.world)
        if self.world > 1:
            dist.barrier()
        if self.owns_group:
            dist.destroy_process_group()


def main():
    args = parse_args()
    if args.recipe:
        run_recipe(args)
        return
    trainer = Trainer(args)
    trainer.run(min(trainer.train["steps"], args.stop_at or trainer.train["steps"]))


def recipe_path(name):
    """A recipe's file: a path, or NAME of tools/train_configs/recipes/NAME.json."""
    if os.path.sep in name or name.endswith(".json"):
        return name
    return os.path.join(REPO_ROOT, "tools", "train_configs", "recipes", f"{name}.json")


def parse_shard(text):
    try:
        index, count = (int(part) for part in text.split("/"))
    except ValueError:
        raise ConfigError(f"--data-shard '{text}': expected I/N")
    if not 0 <= index < count:
        raise ConfigError(f"--data-shard '{text}': needs 0 <= I < N")
    return index, count


def finished_phase_seconds(phase):
    """The wall seconds of a phase that ended (its export written at its last step) with this config, or None
    when it has not; a phase that ended with another config is an error."""
    checkpoint_path = os.path.join(phase.directory, "checkpoint.pt")
    if not (os.path.exists(os.path.join(phase.directory, EXPORT_NAME)) and os.path.exists(checkpoint_path)):
        return None
    checkpoint = torch.load(checkpoint_path, map_location="cpu", weights_only=False)
    config, saved = merge_config(phase.config, phase.config_path), merge_config(checkpoint["config"], "checkpoint")
    differs = first_difference(dict(config, data=dict(config["data"], dir=None)),
                               dict(saved, data=dict(saved["data"], dir=None)))
    if differs:
        raise ConfigError(f"{phase.directory}: ended with another '{differs}' than the recipe's phase "
                          f"'{phase.name}'; remove the directory to train the phase again")
    return checkpoint["seconds"] if checkpoint["step"] == config["train"]["steps"] else None


def run_phase(phase, stop):
    """Trains one phase up to step `stop` (resuming its checkpoint); returns its wall seconds so far."""
    seconds = finished_phase_seconds(phase)
    if seconds is not None:
        print(f"recipe: phase {phase.name}: done ({seconds:.0f} s)", flush=True)
        return seconds
    with atomic_open(phase.config_path) as f:
        json.dump(phase.config, f, indent=2)
    resume = os.path.exists(os.path.join(phase.directory, "checkpoint.pt"))
    args = argparse.Namespace(config=phase.config_path, out=phase.directory, data=None, seed=None, resume=resume,
                              force=not resume, stop_at=None)
    print(f"recipe: phase {phase.name}: {'resumed' if resume else 'started'}", flush=True)
    trainer = Trainer(args)
    trainer.run(min(trainer.train["steps"], stop))
    return trainer.seconds()


def run_recipe(args):
    """The recipe's data (made where missing), then its phases in order, then OUT/sixway-unet.safetensors (the
    last phase's network with the recipe in its metadata) and OUT/recipe.json."""
    profile = args.profile or ("gpu" if torch.cuda.is_available() else "cpu")
    out = os.path.abspath(args.out)
    recipe = Recipe(recipe_path(args.recipe), out, REPO_ROOT, os.path.abspath(args.data_root or REPO_ROOT), profile)
    if not os.access(args.sixway, os.X_OK):
        raise ConfigError(f"{args.sixway}: no sixway binary to make the data (tools/build.sh, or pass --sixway)")
    world, rank = int(os.environ.get("WORLD_SIZE", "1")), int(os.environ.get("RANK", "0"))
    log = lambda line: print(f"recipe: {line}", flush=True)  # noqa: E731
    if args.data_shard:
        make_data(recipe, args.sixway, parse_shard(args.data_shard), out, log)
        return
    if world > 1:  # the processes make the data between them, then train each phase together
        dist.init_process_group("nccl" if torch.cuda.is_available() else "gloo")
    # Under DDP each process makes its share; the lead records its own.
    data_seconds = make_data(recipe, args.sixway, (rank, world), out if rank == 0 else None, log)
    if world > 1:
        dist.barrier()
    os.makedirs(os.path.join(out, "phases"), exist_ok=True)
    stop = args.stop_at if args.stop_at is not None else math.inf
    phases, offset = [], 0
    for phase in recipe.phases:
        steps = phase.config["train"]["steps"]
        if stop <= offset:
            break
        seconds = run_phase(phase, stop - offset)
        phases.append({"name": phase.name, "steps": steps, "wall_seconds": round(seconds, 1)})
        offset += steps
    if rank == 0:
        summary = write_summary(recipe, out, data_seconds, phases, hardware(torch.device(
            "cuda" if torch.cuda.is_available() else "cpu"), world))
        if len(phases) == len(recipe.phases) and stop >= offset:  # every phase ran to its end
            tensors, metadata = read_safetensors(os.path.join(recipe.phases[-1].directory, EXPORT_NAME))
            with atomic_path(os.path.join(out, EXPORT_NAME)) as temporary:
                write_safetensors(temporary, tensors, dict(metadata, **{"sixway.recipe": json.dumps(summary)}))
            print(f"recipe: {os.path.join(out, EXPORT_NAME)} after {summary['wall_seconds']:.0f} s "
                  f"(data {sum(data_seconds.values()):.0f} s)", flush=True)
    if world > 1:
        dist.destroy_process_group()


def finish(out, net, data, config, seconds, device, world):
    """Held-out metrics per split, the export with its metadata, and the loss plot."""
    net.eval()
    metrics = {"definition": "docs/conventions.md, \"Metrics\": PSNR on decoded linear lightmaps clipped to "
                             "[0, 1], MSE pooled over all pixels and channels of the split; masked = reference "
                             "alpha > 0.01; per channel group masked; PyTorch float32, whole maps",
               "pytorch": {split: evaluate_split(net, data, split, device) for split in SPLITS}}
    with atomic_open(os.path.join(out, "metrics.json")) as f:
        json.dump(metrics, f, indent=2)
    for split, m in metrics["pytorch"].items():
        print(f"{split}: {m['samples']} samples, PSNR masked {m['psnr_masked']} dB, full {m['psnr_full']} dB")
    training = {
        "config": config,
        "steps": config["train"]["steps"],
        "epochs": config["train"]["steps"] * config["train"]["batch"] / len(data.pairs("train")),
        "wall_seconds": round(seconds, 1),
        "hardware": hardware(device, world),
        "torch": torch.__version__,
        "parameters": sum(p.numel() for p in net.parameters()),
        "flops_256": flops_at(net, 256),
        "dataset": {"dir": data.directories[0] if len(data.directories) == 1 else data.directories,
                    "shards": len(data.paths), "lightmap_size": data.size, "lightmap_sizes": data.sizes(),
                    "samples": {split: len(data.indices(split)) for split in SPLITS},
                    "config": data.dataset_config()},
    }
    export_safetensors(net.cpu(), os.path.join(out, EXPORT_NAME),
                       {"sixway.training": training, "sixway.metrics": metrics})
    try:
        import plot
        plot.plot_log(os.path.join(out, "log.jsonl"), os.path.join(out, "loss.png"),
                      f"sixway training: {os.path.basename(os.path.normpath(out))}")
    except ImportError as missing:
        print(f"loss plot skipped: {missing} (tools/deps.sh installs python3-matplotlib)")
    print(f"exported {os.path.join(out, EXPORT_NAME)} after {seconds:.0f} s")


if __name__ == "__main__":
    # SIGTERM ends the run as Ctrl-C does: the recipe records the time spent and stops its `sixway dataset`.
    signal.signal(signal.SIGTERM, lambda number, frame: sys.exit(128 + number))
    try:
        main()
    except (ConfigError, RecipeError, ValueError) as error:
        sys.exit(f"train: {error}")
