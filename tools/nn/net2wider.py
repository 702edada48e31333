"""A trained network's function in a wider network of the same graph (Net2WiderNet: Chen, Goodfellow and Shlens
2016, "Net2Net: Accelerating Learning via Knowledge Transfer", section 2.1).

Each conv whose output widens copies its old units into the new ones (new unit j is old unit j mod old width),
and every consumer of those units divides the weight it reads from a copied unit by the number of copies, so the
consumer's sum is unchanged. Each activation acts per unit, so the wider network computes the old
function. The copies get a little noise in their incoming weights; without it, two copies receive the same
gradient and stay equal forever. An adapter projection the old network did not have (its adapters read the
decoder's output directly) starts as the sum over each old unit's copies.

Only the widths widen: the adapters keep their width (their LayerNorms would see copied channels otherwise),
the input and output stay as they are, and a UNet of NAFBlocks is not handled.
"""
import numpy as np
import torch


def _copies(old_width, new_width):
    """The old unit each new unit copies, and how many copies each old unit has."""
    source = np.arange(new_width) % old_width
    return source, np.bincount(source, minlength=old_width)


def _input_columns(parts, units):
    """For the concatenation of producer nodes `parts`: each new input column's old column and its divisor."""
    columns, divisors, offset = [], [], 0
    for part in parts:
        source, count = units[part]
        columns.append(offset + source)
        divisors.append(count[source])
        offset += len(count)
    return np.concatenate(columns), np.concatenate(divisors).astype(np.float32)


def wider_state(old_net, new_net, old_state, noise, seed):
    """The state dict of `new_net` (wider widths, else `old_net`'s config) that computes `old_net` with weights
    `old_state` (module names as in SixwayNet.state_dict()). `noise`: the standard deviation, relative to each
    layer's weight spread, of the noise added to the copies' incoming weights (0: exactly the old function)."""
    if new_net.config["block"] != "conv":
        raise ValueError("net2wider: only a UNet of conv units widens (block: conv)")
    rng = np.random.default_rng(seed)
    old_nodes = {node["name"]: node for node in old_net.nodes}
    dropped = sorted(set(old_nodes) - {node["name"] for node in new_net.nodes})
    if dropped:  # e.g. an adapter projection the wider network no longer needs: its weights would be lost
        raise ValueError(f"net2wider: node {dropped[0]} is not in the wider network")
    state = {key: value.detach().cpu().clone() for key, value in new_net.state_dict().items()}
    units = {}  # node name -> (old unit of each new unit, copies of each old unit)
    for node in new_net.nodes:
        name, op = node["name"], node["op"]
        key = "blocks." + name.replace(".", "/")
        old = old_nodes.get(name)
        if op in ("input", "naf_block", "output") or name.endswith("_from_guide"):
            if old is not None and old.get("out_channels") != node.get("out_channels"):
                raise ValueError(f"net2wider: node {name} changes width")
            width = node.get("out_channels", 0)
            units[name] = _copies(width, width)
            if op == "naf_block":
                for param in old_state:
                    if param.startswith(key + "."):
                        state[param] = old_state[param].clone()
            continue
        if op == "upsample_bilinear":
            units[name] = units[node["inputs"][0]]
            continue
        columns, divisors = _input_columns(node["inputs"], units)
        if old is None:  # an adapter projection the old network lacked: the old decoder output, summed back
            if not name.endswith(".proj"):
                raise ValueError(f"net2wider: node {name} is new")
            weight = torch.zeros_like(state[key + ".weight"])
            weight[columns, np.arange(len(columns)), 0, 0] = torch.from_numpy(1.0 / divisors)
            state[key + ".weight"] = weight
            state[key + ".bias"] = torch.zeros_like(state[key + ".bias"])
            units[name] = _copies(node["out_channels"], node["out_channels"])
            continue
        weight, bias = old_state[key + ".weight"], old_state[key + ".bias"]
        transposed = op == "conv_transpose2d"
        if transposed:  # (in, out, k, k) -> (out, in, k, k) while widening
            weight = weight.transpose(0, 1)
        source, count = _copies(weight.shape[0], node["out_channels"])
        weight = weight[:, columns] / torch.from_numpy(divisors).view(1, -1, 1, 1)
        weight, bias = weight[source].clone(), bias[source].clone()
        copied = source != np.arange(len(source))
        if noise > 0 and copied.any():
            spread = float(weight.std())
            jitter = rng.normal(0.0, noise * spread, tuple(weight[copied].shape)).astype(np.float32)
            weight[copied] += torch.from_numpy(jitter)
        state[key + ".weight"] = weight.transpose(0, 1).contiguous() if transposed else weight
        state[key + ".bias"] = bias
        units[name] = (source, count)
    return state
