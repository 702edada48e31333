"""A training recipe: the data sets a network needs and the phases that train it from scratch, in one file
(docs/training.md). `tools/train.py --recipe NAME --out DIR` makes the data that is missing (`sixway dataset`, each
set resuming shard by shard) and runs the phases in order, each starting from the weights the phase before it
ended with; every phase resumes exactly from its checkpoint, so an interrupted recipe rerun with the same command
ends with the weights an uninterrupted one does.

The recipe file (JSON, unknown keys rejected):
  description   for people
  datasets      [{config, out, skip_sequences?, prepare?}]: a `sixway dataset` config and its output directory
                (relative to the repository root / the data root); skip_sequences: sequence indices not made (the
                config's simulated base sequence of a played-back family); prepare: a command (argv, the first
                element a path relative to the repository root) run before the set is made, e.g. the Blender
                script that bakes the VDB files the set plays back
  phases        [{name, config}]: the first config is a whole training config (tools/train_configs/); each later
                one overrides the one before it key by key (two levels; data.dir whole). Every phase's data.dir
                names only the recipe's datasets; train.init_from is the recipe's (the phase before)
  profiles      {name: {batch_scale, lr_scale}}: a larger batch for a faster device: every phase's batch times
                batch_scale, its step counts (steps, warm-up, log, held-out and checkpoint intervals) divided by it
                (the same epochs), its learning rates times lr_scale
"""
import copy
import hashlib
import json
import math
import os
import subprocess
import time

from atomic_file import atomic_open

RECIPE_KEYS = {"description", "datasets", "phases", "profiles"}
DATASET_KEYS = {"config", "out", "skip_sequences", "prepare"}
PHASE_KEYS = {"name", "config"}
PROFILE_KEYS = {"batch_scale", "lr_scale"}
# The train keys that count steps, divided by a profile's batch_scale.
STEP_KEYS = ("steps", "warmup_steps", "log_every", "heldout_every", "checkpoint_every", "step_every")
SUMMARY_NAME = "recipe.json"
DATA_SECONDS_NAME = "data_seconds.json"


class RecipeError(Exception):
    pass


def _require(condition, where, message):
    if not condition:
        raise RecipeError(f"{where}: {message}")


def _unknown_keys(values, allowed, where):
    _require(isinstance(values, dict), where, "must be an object")
    unknown = sorted(set(values) - allowed)
    _require(not unknown, where, f"unknown key '{unknown[0] if unknown else ''}'")


def overridden(base, overrides):
    """`base` with each section's keys replaced by `overrides`' (two levels, as train.merge_config reads them;
    model, data.dir and lists are replaced whole)."""
    merged = copy.deepcopy(base)
    for section, values in overrides.items():
        if section == "model" or not isinstance(values, dict) or not isinstance(merged.get(section), dict):
            merged[section] = copy.deepcopy(values)
        else:
            merged[section].update(copy.deepcopy(values))
    return merged


def sequence_count(config_path):
    """How many sequences a dataset config makes: its simulated ones and its VDB scenes."""
    try:
        with open(config_path) as f:
            config = json.load(f)
    except (OSError, json.JSONDecodeError) as error:
        raise RecipeError(f"{config_path}: {error}")
    return int(config.get("sequences", 0)) + len(config.get("vdb_scenes", []))


class Dataset:
    def __init__(self, entry, where, repo_root, data_root):
        _unknown_keys(entry, DATASET_KEYS, where)
        _require(isinstance(entry.get("config"), str), where, "'config' (a dataset config path) is required")
        _require(isinstance(entry.get("out"), str), where, "'out' (the set's directory) is required")
        self.name = entry["out"]
        self.config = os.path.join(repo_root, entry["config"])
        _require(os.path.isfile(self.config), where, f"{entry['config']}: no such dataset config")
        self.out = os.path.join(data_root, entry["out"])
        self.count = sequence_count(self.config)
        skip = entry.get("skip_sequences", [])
        _require(isinstance(skip, list) and all(isinstance(s, int) and 0 <= s < self.count for s in skip), where,
                 f"skip_sequences must be sequence indices in 0..{self.count - 1}")
        self.skip = set(skip)
        prepare = entry.get("prepare", [])
        _require(isinstance(prepare, list) and all(isinstance(a, str) for a in prepare), where,
                 "prepare must be a command (a list of strings)")
        self.prepare = [os.path.join(repo_root, prepare[0])] + prepare[1:] if prepare else []

    def sequences(self, shard):
        """The sequence indices this worker makes: all but the skipped, those with S mod N = I for shard (I, N)."""
        index, workers = shard
        return [s for s in range(self.count) if s not in self.skip and s % workers == index]

    def make(self, sixway, shard, log):
        """Runs `prepare` and `sixway dataset` for this worker's sequences (a set already made is kept: the command
        resumes shard by shard)."""
        wanted = self.sequences(shard)
        if not wanted:
            return
        if self.prepare:
            self._run(self.prepare, log)
        command = [sixway, "dataset", "--config", self.config, "--out", self.out]
        if len(wanted) == self.count:
            self._run(command, log)
        elif shard[1] > 1 and not self.skip:
            self._run(command + ["--shard", f"{shard[0]}/{shard[1]}"], log)
        else:  # skipped sequences: one worker of `count` per sequence made
            for s in wanted:
                self._run(command + ["--shard", f"{s}/{self.count}"], log)

    def _run(self, command, log):
        log(" ".join(command))
        result = subprocess.run(command)
        if result.returncode != 0:
            raise RecipeError(f"{self.name}: '{os.path.basename(command[0])}' failed (exit {result.returncode})")


class Phase:
    def __init__(self, index, name, config, out):
        self.index, self.name, self.config = index, name, config
        self.directory = os.path.join(out, f"{index + 1:02d}_{name}")
        self.config_path = os.path.join(out, "phases", f"{index + 1:02d}_{name}.json")


def scaled(config, profile):
    """A phase's config under a profile: batch × k, step counts ÷ k (rounded up), learning rates × lr_scale."""
    k, lr_scale = profile.get("batch_scale", 1), profile.get("lr_scale", 1.0)
    train = config.setdefault("train", {})
    if "batch" in train:
        train["batch"] *= k
    for key in STEP_KEYS:
        if key in train:
            train[key] = max(1, math.ceil(train[key] / k))
    for key in ("lr", "min_lr"):
        if key in train:
            train[key] *= lr_scale
    return config


class Recipe:
    """A recipe file read and checked: its datasets and its phases' effective configs under `profile`."""

    def __init__(self, path, out, repo_root, data_root, profile):
        self.path = path
        try:
            with open(path, "rb") as f:
                raw = f.read()
            recipe = json.loads(raw)
        except (OSError, json.JSONDecodeError) as error:
            raise RecipeError(f"{path}: {error}")
        self.digest = hashlib.sha256(raw).hexdigest()
        _unknown_keys(recipe, RECIPE_KEYS, path)
        datasets = recipe.get("datasets")
        _require(isinstance(datasets, list) and datasets, path, "'datasets' must be a non-empty list")
        self.datasets = [Dataset(entry, f"{path}: datasets[{i}]", repo_root, data_root)
                         for i, entry in enumerate(datasets)]
        profiles = recipe.get("profiles", {})
        _unknown_keys(profiles, set(profiles), f"{path}: profiles")
        self.profile_name = profile
        if profile == "cpu" and "cpu" not in profiles:
            self.profile = {}
        else:
            _require(profile in profiles, path, f"no profile '{profile}' (has {', '.join(sorted(profiles)) or 'none'})")
            self.profile = profiles[profile]
            _unknown_keys(self.profile, PROFILE_KEYS, f"{path}: profiles.{profile}")
            k = self.profile.get("batch_scale", 1)
            _require(isinstance(k, int) and not isinstance(k, bool) and 1 <= k <= 1024, f"{path}: profiles.{profile}",
                     "batch_scale must be an integer in 1..1024")
            s = self.profile.get("lr_scale", 1.0)
            _require(isinstance(s, (int, float)) and not isinstance(s, bool) and 0 < s <= 100,
                     f"{path}: profiles.{profile}", "lr_scale must be a number in (0, 100]")
        self.phases = self._phases(recipe.get("phases"), out, data_root)

    def _phases(self, entries, out, data_root):
        _require(isinstance(entries, list) and entries, self.path, "'phases' must be a non-empty list")
        known = {d.name: d.out for d in self.datasets}
        phases, config, names = [], {}, set()
        for i, entry in enumerate(entries):
            where = f"{self.path}: phases[{i}]"
            _unknown_keys(entry, PHASE_KEYS, where)
            name = entry.get("name")
            _require(isinstance(name, str) and name.replace("_", "").isalnum() and name not in names, where,
                     "'name' must be a unique word (letters, digits, _)")
            names.add(name)
            _require(isinstance(entry.get("config"), dict), where, "'config' must be an object")
            _require("init_from" not in entry["config"].get("train", {}), where,
                     "train.init_from is the recipe's (the phase before); remove it")
            config = overridden(config, entry["config"])
            train = config.get("train", {})
            _require(all(isinstance(train.get(k), int) and train[k] > 0 for k in ("steps", "batch")), where,
                     "train.steps and train.batch must be given (whole numbers > 0): a profile scales them")
            directories = config.get("data", {}).get("dir")
            directories = [directories] if isinstance(directories, str) else directories
            _require(isinstance(directories, list) and directories, where, "data.dir must name the recipe's datasets")
            for d in directories:
                _require(d in known, where, f"data.dir '{d}' is not one of the recipe's datasets")
            effective = scaled(copy.deepcopy(config), self.profile)
            effective["data"]["dir"] = [known[d] for d in directories]
            phase = Phase(i, name, effective, out)
            if phases:
                effective["train"]["init_from"] = phases[-1].directory
            phases.append(phase)
        return phases


def make_data(recipe, sixway, shard, out, log):
    """Makes every dataset's sequences of worker `shard` (index, count), adding each set's seconds to
    OUT/data_seconds.json, also when interrupted (SIGTERM, Ctrl-C: the work a rerun redoes counts too; OUT None:
    not recorded); returns the seconds per set so far."""
    path = os.path.join(out, DATA_SECONDS_NAME) if out else None
    seconds = {}
    if path and os.path.exists(path):
        with open(path) as f:
            seconds = json.load(f)
    if path:
        os.makedirs(out, exist_ok=True)
    for d in recipe.datasets:
        start = time.time()
        try:
            d.make(sixway, shard, log)
        finally:
            seconds[d.name] = round(seconds.get(d.name, 0.0) + time.time() - start, 1)
            if path:
                with atomic_open(path) as f:
                    json.dump(seconds, f, indent=2)
    return seconds


def write_summary(recipe, out, data_seconds, phases, hardware):
    """OUT/recipe.json: the recipe (path and SHA-256), the profile, the data's and each phase's wall time."""
    summary = {"recipe": os.path.relpath(recipe.path), "sha256": recipe.digest, "profile": recipe.profile_name,
               "hardware": hardware, "data_seconds": data_seconds, "phases": phases,
               "wall_seconds": round(sum(data_seconds.values()) + sum(p["wall_seconds"] for p in phases), 1)}
    with atomic_open(os.path.join(out, SUMMARY_NAME)) as f:
        json.dump(summary, f, indent=2)
    return summary
