"""The sixway lightmap network in PyTorch: a UNet with four NAFBlock channel adapters (docs/network-format.md).

The model is built from a config (widths, depth, activation, block type, adapters, output encoding) into a
graph: a list of nodes, each one op with named inputs. `forward` walks that graph, and the same graph is
written into the safetensors metadata (`sixway.graph`) that the GLSL runner (src/nn) builds itself from, so
what PyTorch computes and what the runner computes are described by one list.

    from sixway_net import SixwayNet, export_safetensors, load_safetensors
    model = SixwayNet(config)                 # config: dict, missing keys take DEFAULT_CONFIG's values
    raw = model(guide)                        # (N, 3 to 5, H, W) -> (N, 8, H, W), in the network's encoding
                                              # (with albedo_input: one more channel, the smoke's albedo)
    a, b = pack_lightmaps(decode_output(raw, model.config))   # Unity packing, linear
    export_safetensors(model, "net.safetensors", {"sixway.training": json.dumps(...)})

NAFBlock follows NAFNet (Chen et al. 2022, "Simple Baselines for Image Restoration").
"""
import copy
import json
import math
import time

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from safetensors_io import read_safetensors, write_safetensors

GRAPH_VERSION = 1

DEFAULT_CONFIG = {
    "guide_channels": 3,  # guide, alpha, depth (4: and the fine alpha; 5: and the emission)
    "input_channels": 4,  # the guide padded with zeros to whole vec4s
    "widths": [16, 32, 64],  # one per encoder level; the last is the bottleneck
    "depth": 2,  # units per level: a 3x3 conv + activation, then depth-1 units of `block`
    "block": "conv",  # "conv" (3x3 conv + activation) or "naf" (NAFBlock)
    "activation": "relu",  # relu | leaky_relu | gelu | silu
    "negative_slope": 0.1,  # leaky_relu only
    "upsample": "transposed",  # "transposed" (2x2 stride 2) or "bilinear" (1x1 conv, then bilinear x2)
    "adapters": {"enabled": True, "width": 16, "blocks": 1, "dw_expand": 2, "ffn_expand": 2},
    "encoding": "srgb",  # lightmap channels are learnt sRGB-encoded; alpha (and an emissive from the guide) is linear
}

# Keys a config may add to DEFAULT_CONFIG; absent, the config (and so the export) stays as it was.
# guide_alpha_step_voxels: the fine alpha's step of a guide of 4 or 5 channels (the runtime's guide computes it;
#   the 5th channel is the direct emitted luminance reaching the camera, marched along with the fine alpha).
# alpha: "network" (the alpha_emissive head's) or "guide" (the fine alpha passed through: 4 or 5 guide channels).
# emissive: "network" (the alpha_emissive head's) or "guide" (the guide's direct emission passed through, linear:
#   5 guide channels; the single-scattering target's emissive is that light, which the guide marches at its own step).
# stem: "full" (the UNet's first level at the guide's resolution) or "half": a 3x3 stride-2 conv stem runs the
#   whole UNet and the adapters at half resolution, and each head is a 2x2 stride-2 transposed conv back to full
#   resolution. The stem sees each 2x2 block of the guide (and its neighbours), so it holds pixel-unshuffle + 1x1
#   conv as a special case; the transposed head is exactly a 1x1 conv + pixel shuffle. About 4x fewer FLOPs.
# albedo_input: {"offset": o, "scale": s}: the input channel after the guide's holds (albedo - o) * s, the smoke's
#   single-scattering albedo (a scene constant: the guide's in-scattered light is albedo x the single-scattered light,
#   so the multiply-scattered light, a series in powers of the albedo, is not a function of the guide alone).
#   Centred and scaled so that the training range spans about [-1, 1]: the channel starts as a zero-mean plane.
OPTIONAL_CONFIG = {"guide_alpha_step_voxels": 0.0, "alpha": "network", "emissive": "network", "stem": "full",
                   "albedo_input": None}

# The four adapters and the two channels of each head (docs/conventions.md, "Channels and packing").
ADAPTERS = [("left_right", ["left", "right"]), ("top_bottom", ["top", "bottom"]),
            ("front_back", ["front", "back"]), ("alpha_emissive", ["alpha", "emissive"])]
# The eight output channels by name, in the network's order.
OUTPUT_CHANNELS = [name for _, names in ADAPTERS for name in names]
# Unity packing: lightmap A = (Right, Top, Back, alpha), B = (Left, Bottom, Front, emissive).
PACKING = {"A": ["right", "top", "back", "alpha"], "B": ["left", "bottom", "front", "emissive"]}
ACTIVATIONS = ("relu", "leaky_relu", "gelu", "silu")
# The name ending of the fixed (untrained) selections that pass guide channels through as outputs; train.py takes
# every tensor of a node so named from the network being trained, never from a checkpoint, so no trained node may
# end in it.
FROM_GUIDE_SUFFIX = "_from_guide"
# The outputs a config may take from the guide: (their channel in the alpha_emissive head, their guide channel).
FROM_GUIDE_CHANNELS = {"alpha": (0, 3), "emissive": (1, 4)}
LAYER_NORM_EPS = 1e-6


def full_config(config=None):
    """DEFAULT_CONFIG overridden by `config` (one level deep for "adapters"), checked."""
    merged = copy.deepcopy(DEFAULT_CONFIG)
    for key, value in (config or {}).items():
        if key not in merged and key not in OPTIONAL_CONFIG:
            raise ValueError(f"config: unknown key '{key}'")
        if key == "adapters":
            for sub in value:
                if sub not in merged["adapters"]:
                    raise ValueError(f"config: unknown key 'adapters.{sub}'")
            merged["adapters"].update(value)
        else:
            merged[key] = value
    if len(merged["widths"]) < 1 or merged["depth"] < 1:
        raise ValueError("config: need at least one width and depth >= 1")
    if merged["block"] not in ("conv", "naf"):
        raise ValueError(f"config: block must be conv or naf, not {merged['block']}")
    if merged["activation"] not in ACTIVATIONS:
        raise ValueError(f"config: activation must be one of {ACTIVATIONS}")
    if merged["upsample"] not in ("transposed", "bilinear"):
        raise ValueError("config: upsample must be transposed or bilinear")
    if merged["encoding"] not in ("srgb", "linear"):
        raise ValueError("config: encoding must be srgb or linear")
    if merged["input_channels"] < merged["guide_channels"]:
        raise ValueError("config: input_channels < guide_channels")
    if merged["input_channels"] > 8:
        raise ValueError("config: input_channels must be at most 8 (the GLSL input node's two groups of four)")
    if not 1 <= merged["guide_channels"] <= 5:
        raise ValueError("config: guide_channels must be 1 to 5")
    if (merged["guide_channels"] >= 4) != (merged.get("guide_alpha_step_voxels", 0) > 0):
        raise ValueError("config: a 4th guide channel is the fine alpha: guide_channels 4 or 5 goes with "
                         "guide_alpha_step_voxels > 0")
    for channel in ("alpha", "emissive"):
        if merged.get(channel, "network") not in ("network", "guide"):
            raise ValueError(f"config: {channel} must be network or guide")
    if merged.get("stem", "full") not in ("full", "half"):
        raise ValueError("config: stem must be full or half")
    if merged.get("alpha") == "guide" and merged["guide_channels"] < 4:
        raise ValueError("config: alpha from the guide needs its fine alpha (guide_channels 4 or 5)")
    if merged.get("emissive") == "guide" and merged["guide_channels"] < 5:
        raise ValueError("config: emissive from the guide needs its emission (guide_channels 5)")
    albedo = merged.get("albedo_input")
    if albedo is not None:
        if (not isinstance(albedo, dict) or set(albedo) != {"offset", "scale"}
                or not all(isinstance(albedo[k], (int, float)) and math.isfinite(albedo[k]) for k in albedo)
                or albedo["scale"] == 0):
            raise ValueError("config: albedo_input must be {\"offset\": number, \"scale\": nonzero number}")
        if merged["input_channels"] < merged["guide_channels"] + 1:
            raise ValueError("config: albedo_input needs an input channel after the guide's (input_channels)")
    return merged


def input_channel_count(config):
    """The channels a caller passes to the network: the guide's, and the raw albedo after them with albedo_input."""
    return config["guide_channels"] + (1 if config.get("albedo_input") else 0)


def output_encodings(config):
    """The encoding of each output channel (OUTPUT_CHANNELS order): alpha and a channel passed through from the
    guide are linear, the others the config's encoding."""
    config = full_config(config)
    linear = {"alpha"} | ({"emissive"} if config.get("emissive") == "guide" else set())
    return ["linear" if name in linear else config["encoding"] for name in OUTPUT_CHANNELS]


class LayerNorm2d(nn.Module):
    """LayerNorm over the channels of each pixel (NAFNet): biased variance, eps inside the root."""

    def __init__(self, channels, eps=LAYER_NORM_EPS):
        super().__init__()
        self.weight = nn.Parameter(torch.ones(channels))
        self.bias = nn.Parameter(torch.zeros(channels))
        self.eps = eps

    def forward(self, x):
        mean = x.mean(1, keepdim=True)
        var = (x - mean).pow(2).mean(1, keepdim=True)
        y = (x - mean) / (var + self.eps).sqrt()
        return self.weight.view(1, -1, 1, 1) * y + self.bias.view(1, -1, 1, 1)


def simple_gate(x):
    """SimpleGate (NAFNet): the first half of the channels times the second half."""
    a, b = x.chunk(2, dim=1)
    return a * b


class NAFBlock(nn.Module):
    """NAFNet's block: LN, 1x1 expand, 3x3 depthwise, SimpleGate, simplified channel attention, 1x1,
    beta-scaled residual; then LN, 1x1, SimpleGate, 1x1, gamma-scaled residual."""

    def __init__(self, c, dw_expand=2, ffn_expand=2):
        super().__init__()
        dw = c * dw_expand
        ffn = c * ffn_expand
        self.norm1 = LayerNorm2d(c)
        self.conv1 = nn.Conv2d(c, dw, 1)
        self.conv2 = nn.Conv2d(dw, dw, 3, padding=1, groups=dw)
        self.sca = nn.Conv2d(dw // 2, dw // 2, 1)  # after a global average pool
        self.conv3 = nn.Conv2d(dw // 2, c, 1)
        self.norm2 = LayerNorm2d(c)
        self.conv4 = nn.Conv2d(c, ffn, 1)
        self.conv5 = nn.Conv2d(ffn // 2, c, 1)
        # NAFNet starts beta and gamma at zero (the block is an identity until trained).
        self.beta = nn.Parameter(torch.zeros(1, c, 1, 1))
        self.gamma = nn.Parameter(torch.zeros(1, c, 1, 1))

    def forward(self, inp):
        x = simple_gate(self.conv2(self.conv1(self.norm1(inp))))
        x = x * self.sca(x.mean((2, 3), keepdim=True))
        y = inp + self.conv3(x) * self.beta
        x = self.conv5(simple_gate(self.conv4(self.norm2(y))))
        return y + x * self.gamma


def activate(x, node):
    kind = node.get("activation", "none")
    if kind == "relu":
        return F.relu(x)
    if kind == "leaky_relu":
        return F.leaky_relu(x, node["negative_slope"])
    if kind == "gelu":
        return F.gelu(x)
    if kind == "silu":
        return F.silu(x)
    return x


class FixedSelection(nn.Conv2d):
    """A 1x1 convolution that copies input channels `picks` (one per output channel) and is not trained: the
    graph has no copy op, and a conv that selects is exact in GLSL too."""

    def __init__(self, in_channels, picks):
        super().__init__(in_channels, len(picks), 1)
        with torch.no_grad():
            self.weight.zero_()
            self.bias.zero_()
            for out, pick in enumerate(picks):
                self.weight[out, pick] = 1.0
        self.requires_grad_(False)


class SixwayNet(nn.Module):
    def __init__(self, config=None):
        super().__init__()
        self.config = full_config(config)
        self.nodes = []
        self.blocks = nn.ModuleDict()  # node name with '.' -> '/', because ModuleDict keys cannot hold dots
        self._build()

    # -- graph construction -------------------------------------------------------------------------------
    def _add(self, node, module=None):
        self.nodes.append(node)
        if module is not None:
            self.blocks[node["name"].replace(".", "/")] = module
        return node["name"]

    def _conv(self, name, inputs, cin, cout, kernel, stride, scale, activation=True):
        node = {"name": name, "op": "conv2d", "inputs": inputs, "in_channels": cin, "out_channels": cout,
                "kernel": kernel, "stride": stride, "scale": scale, "activation": "none"}
        if activation:
            node["activation"] = self.config["activation"]
            if node["activation"] == "leaky_relu":
                node["negative_slope"] = self.config["negative_slope"]
        return self._add(node, nn.Conv2d(cin, cout, kernel, stride=stride, padding=kernel // 2))

    def _naf(self, name, x, channels, scale, dw_expand=2, ffn_expand=2):
        node = {"name": name, "op": "naf_block", "inputs": [x], "in_channels": channels,
                "out_channels": channels, "dw_expand": dw_expand, "ffn_expand": ffn_expand,
                "eps": LAYER_NORM_EPS, "scale": scale}
        return self._add(node, NAFBlock(channels, dw_expand, ffn_expand))

    def _level(self, prefix, inputs, cin, width, scale):
        """A 3x3 conv to `width` channels, then depth-1 units of the configured block."""
        x = self._conv(f"{prefix}.0", inputs, cin, width, 3, 1, scale)
        for i in range(1, self.config["depth"]):
            if self.config["block"] == "naf":
                x = self._naf(f"{prefix}.{i}", x, width, scale)
            else:
                x = self._conv(f"{prefix}.{i}", [x], width, width, 3, 1, scale)
        return x

    def _build(self):
        c = self.config
        widths = c["widths"]
        levels = len(widths) - 1
        node = {"name": "input", "op": "input", "out_channels": c["input_channels"],
                "guide_channels": c["guide_channels"], "scale": 1}
        if c.get("guide_alpha_step_voxels", 0) > 0:
            node["guide_alpha_step_voxels"] = c["guide_alpha_step_voxels"]
        if c.get("albedo_input"):
            node["albedo"] = {"channel": c["guide_channels"], **c["albedo_input"]}
        x = self._add(node)
        skips = []
        cin = c["input_channels"]
        base = self._stem_factor()
        if base == 2:
            x = self._conv("stem", [x], cin, widths[0], 3, 2, 2)
            cin = widths[0]
        for level in range(levels):
            scale = base * 2 ** level
            x = self._level(f"enc.{level}", [x], cin, widths[level], scale)
            skips.append(x)
            x = self._conv(f"down.{level}", [x], widths[level], widths[level + 1], 3, 2, 2 * scale)
            cin = widths[level + 1]
        x = self._level("mid", [x], cin, widths[levels], base * 2 ** levels)
        for level in reversed(range(levels)):
            scale = base * 2 ** level
            if c["upsample"] == "transposed":
                node = {"name": f"up.{level}", "op": "conv_transpose2d", "inputs": [x],
                        "in_channels": widths[level + 1], "out_channels": widths[level], "kernel": 2,
                        "stride": 2, "scale": scale, "activation": "none"}
                x = self._add(node, nn.ConvTranspose2d(widths[level + 1], widths[level], 2, stride=2))
            else:
                x = self._conv(f"up.{level}.conv", [x], widths[level + 1], widths[level], 1, 1, 2 * scale,
                               activation=False)
                x = self._add({"name": f"up.{level}", "op": "upsample_bilinear", "inputs": [x],
                               "in_channels": widths[level], "out_channels": widths[level], "factor": 2,
                               "scale": scale})
            x = self._level(f"dec.{level}", [x, skips[level]], 2 * widths[level], widths[level], scale)
        heads = []
        adapters = c["adapters"]
        for index in range(len(ADAPTERS)):
            prefix = f"adapters.{index}"
            y, channels = x, widths[0]
            if adapters["enabled"]:
                if adapters["width"] != channels:
                    y = self._conv(f"{prefix}.proj", [y], channels, adapters["width"], 1, 1, base,
                                   activation=False)
                    channels = adapters["width"]
                for b in range(adapters["blocks"]):
                    y = self._naf(f"{prefix}.blocks.{b}", y, channels, base, adapters["dw_expand"],
                                  adapters["ffn_expand"])
            if base == 2:
                node = {"name": f"{prefix}.head", "op": "conv_transpose2d", "inputs": [y], "in_channels": channels,
                        "out_channels": 2, "kernel": 2, "stride": 2, "scale": 1, "activation": "none"}
                heads.append(self._add(node, nn.ConvTranspose2d(channels, 2, 2, stride=2)))
            else:
                heads.append(self._conv(f"{prefix}.head", [y], channels, 2, 1, 1, 1, activation=False))
        from_guide = [name for name in FROM_GUIDE_CHANNELS if c.get(name) == "guide"]
        if from_guide:
            # The alpha_emissive head's channels, each the head's own or the guide's (input channel 3: the fine
            # alpha, 4: the emission), selected from [head, input].
            picks = [2 + guide if name in from_guide else head for name, (head, guide) in FROM_GUIDE_CHANNELS.items()]
            node = {"name": "_".join(from_guide) + FROM_GUIDE_SUFFIX, "op": "conv2d", "inputs": [heads[3], "input"],
                    "in_channels": 2 + c["input_channels"], "out_channels": 2, "kernel": 1, "stride": 1,
                    "scale": 1, "activation": "none"}
            heads[3] = self._add(node, FixedSelection(2 + c["input_channels"], picks))
        self._add({"name": "output", "op": "output", "inputs": heads, "in_channels": 8, "channels": OUTPUT_CHANNELS,
                   "encoding": output_encodings(c), "packing": PACKING, "scale": 1})

    # -- evaluation ----------------------------------------------------------------------------------------
    def module(self, name):
        return self.blocks[name.replace(".", "/")]

    def forward(self, guide, intermediates=None, seconds=None):
        """guide: (N, input_channel_count(config) to input_channels, H, W), H and W multiples of size_multiple();
        with albedo_input, channel guide_channels holds the raw albedo (encoded here, as the input node says).
        Returns the 8 raw output channels (the network's encoding). When `intermediates` is a dict, every
        node's output is stored in it by node name; when `seconds` is, the time each node took (benchmarks)."""
        if guide.shape[1] < input_channel_count(self.config):
            raise ValueError(f"the network reads {input_channel_count(self.config)} channels (the guide's, then the "
                             f"albedo), got {guide.shape[1]}")
        values = {}
        for node in self.nodes:
            start = time.perf_counter()
            op = node["op"]
            if op == "input":
                pad = node["out_channels"] - guide.shape[1]
                out = F.pad(guide, (0, 0, 0, 0, 0, pad)) if pad > 0 else guide
                if "albedo" in node:
                    k, albedo = node["albedo"]["channel"], node["albedo"]
                    out = torch.cat([out[:, :k], (out[:, k:k + 1] - albedo["offset"]) * albedo["scale"],
                                     out[:, k + 1:]], dim=1)
            else:
                inputs = [values[name] for name in node["inputs"]]
                x = torch.cat(inputs, dim=1) if len(inputs) > 1 else inputs[0]
                if op == "conv2d" or op == "conv_transpose2d":
                    out = activate(self.module(node["name"])(x), node)
                elif op == "naf_block":
                    out = self.module(node["name"])(x)
                elif op == "upsample_bilinear":
                    out = F.interpolate(x, scale_factor=node["factor"], mode="bilinear", align_corners=False)
                elif op == "output":
                    out = x
                else:
                    raise ValueError(f"unknown op {op}")
            values[node["name"]] = out
            if seconds is not None:
                seconds[node["name"]] = time.perf_counter() - start
        if intermediates is not None:
            intermediates.update(values)
        return values["output"]

    def _stem_factor(self):
        return 2 if self.config.get("stem", "full") == "half" else 1

    def size_multiple(self):
        return self._stem_factor() * 2 ** (len(self.config["widths"]) - 1)

    def graph(self):
        return {"version": GRAPH_VERSION, "size_multiple": self.size_multiple(), "nodes": self.nodes}

    def named_tensors(self):
        """The parameters under their safetensors names: <node name>.<parameter>, e.g. enc.0.0.weight."""
        out = {}
        for key, value in self.state_dict().items():
            module, _, param = key[len("blocks."):].partition(".")
            out[module.replace("/", ".") + "." + param] = value
        return out


def run_padded(model, guide, intermediates=None):
    """Runs a guide of any size: zero-padded at the right and bottom to the size multiple, as the GLSL runner
    does, and cropped back; the albedo (a scene constant) fills the padding too. Intermediates (when a dict is
    given) stay at the padded size."""
    m = model.size_multiple()
    height, width = guide.shape[2], guide.shape[3]
    pad = (0, (-width) % m, 0, (-height) % m)
    padded = F.pad(guide, pad)
    if model.config.get("albedo_input"):
        k = model.config["guide_channels"]
        padded[:, k:k + 1] = F.pad(guide[:, k:k + 1], pad, mode="replicate")
    return model(padded, intermediates)[:, :, :height, :width]


def srgb_to_linear(x):
    return torch.where(x <= 0.04045, x / 12.92, ((x.clamp(min=0.04045) + 0.055) / 1.055) ** 2.4)


def decode_output(raw, config):
    """The 8 raw channels in the network's encoding -> linear, clamped at 0 (radiance and alpha are >= 0)."""
    channels = []
    for k, encoding in enumerate(output_encodings(config)):
        x = raw[:, k:k + 1]
        channels.append((srgb_to_linear(x) if encoding == "srgb" else x).clamp(min=0))
    return torch.cat(channels, dim=1)


def pack_lightmaps(decoded):
    """8 linear channels in adapter order -> (A, B), each (N, 4, H, W), Unity packing."""
    pick = lambda names: torch.cat([decoded[:, OUTPUT_CHANNELS.index(n):OUTPUT_CHANNELS.index(n) + 1]
                                    for n in names], dim=1)
    return pick(PACKING["A"]), pick(PACKING["B"])


def export_safetensors(model, path, extra_metadata=None):
    """Writes the weights (F32) and the graph + config metadata; `extra_metadata` adds string entries
    (e.g. sixway.training, sixway.metrics from the training issue)."""
    tensors = {name: t.detach().cpu().float().numpy() for name, t in model.named_tensors().items()}
    metadata = {"sixway.graph": json.dumps(model.graph()), "sixway.config": json.dumps(model.config)}
    for key, value in (extra_metadata or {}).items():
        metadata[key] = value if isinstance(value, str) else json.dumps(value)
    write_safetensors(path, tensors, metadata)


def load_safetensors(path):
    """A SixwayNet rebuilt from the file's sixway.config, with its weights; also returns the metadata."""
    tensors, metadata = read_safetensors(path)
    model = SixwayNet(json.loads(metadata["sixway.config"]))
    names = model.named_tensors()
    missing = [n for n in names if n not in tensors]
    if missing:
        raise ValueError(f"{path}: missing tensor '{missing[0]}'")
    state = {}
    for key in model.state_dict():
        module, _, param = key[len("blocks."):].partition(".")
        state[key] = torch.from_numpy(tensors[module.replace("/", ".") + "." + param].astype(np.float32))
    model.load_state_dict(state)
    return model, metadata


def randomize(model, seed, scale=1.0):
    """Deterministic random weights from numpy's PCG64 (stable across torch versions), with every NAFBlock's
    beta and gamma and every LayerNorm's affine nonzero, so no branch of the network is an identity.
    Conv weights are uniform in +-sqrt(3/fan_in)*scale (unit-variance activations)."""
    rng = np.random.default_rng(seed)
    uniform = lambda low, high, t: torch.from_numpy(rng.uniform(low, high, tuple(t.shape)).astype(np.float32))
    with torch.no_grad():
        for module in model.modules():
            if isinstance(module, FixedSelection):
                continue
            if isinstance(module, (nn.Conv2d, nn.ConvTranspose2d)):
                transposed = isinstance(module, nn.ConvTranspose2d)
                fan_in = module.weight.shape[0] if transposed else module.weight[0].numel()
                bound = math.sqrt(3.0 / fan_in) * scale
                module.weight.copy_(uniform(-bound, bound, module.weight))
                module.bias.copy_(uniform(-0.1, 0.1, module.bias))
            elif isinstance(module, LayerNorm2d):
                module.weight.copy_(uniform(0.5, 1.5, module.weight))
                module.bias.copy_(uniform(-0.2, 0.2, module.bias))
            elif isinstance(module, NAFBlock):
                for p in (module.beta, module.gamma):
                    sign = torch.from_numpy(rng.choice([-1.0, 1.0], tuple(p.shape)).astype(np.float32))
                    p.copy_(uniform(0.2, 0.6, p) * sign)
    return model
