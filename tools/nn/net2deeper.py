"""A trained UNet's function in a UNet of one more level (Net2DeeperNet: Chen, Goodfellow and Shlens 2016,
"Net2Net: Accelerating Learning via Knowledge Transfer", section 2.2, applied to a UNet's bottom).

The old bottleneck ("mid") becomes the new network's deepest encoder level, whose output is the skip that the new
decoder level reads beside the upsampled new bottleneck. That decoder level starts as the identity on the skip: its
first conv passes the skip's channels through (a 1 at each kernel's centre tap) and reads the upsampled channels
with zero weights, each conv after it is an identity too. The skip is a ReLU's output, so it is not negative and
the ReLUs after those convs pass it unchanged: the deeper network computes the old function. The new bottleneck,
its downsampling and its upsampling keep their random initialisation; the zero weights that read them get nonzero
gradients from the first step on, so training opens the new level (as with a zero-initialised residual branch).

Only a UNet of conv units with ReLU activations deepens, and the widths it had stay as they are.
"""
import torch


def deeper_state(old_net, new_net, old_state):
    """The state dict of `new_net` (`old_net`'s config with one more width appended) that computes `old_net` with
    weights `old_state` (module names as in SixwayNet.state_dict()); the new level's other weights are
    `new_net`'s own."""
    old, new = old_net.config, new_net.config
    levels = len(old["widths"]) - 1
    if new["block"] != "conv" or new["activation"] != "relu":
        raise ValueError("net2deeper: only a UNet of conv units with ReLU activations deepens")
    if new["widths"][:-1] != old["widths"] or len(new["widths"]) != len(old["widths"]) + 1:
        raise ValueError(f"net2deeper: widths {new['widths']} are not {old['widths']} and one more level")
    state = {key: value.detach().cpu().clone() for key, value in new_net.state_dict().items()}
    renamed = lambda key: key.replace("blocks.mid/", f"blocks.enc/{levels}/", 1)
    for key, value in old_state.items():
        target = renamed(key)
        if target not in state or state[target].shape != value.shape:
            raise ValueError(f"net2deeper: {key} has no place in the deeper network")
        state[target] = value.detach().cpu().clone()
    width = old["widths"][-1]
    for unit in range(new["depth"]):
        prefix = f"blocks.dec/{levels}/{unit}"
        weight = torch.zeros_like(state[prefix + ".weight"])
        # The first unit reads [upsampled bottleneck, skip]: the skip's channels come second.
        offset = width if unit == 0 else 0
        centre = weight.shape[-1] // 2
        weight[torch.arange(width), offset + torch.arange(width), centre, centre] = 1.0
        state[prefix + ".weight"] = weight
        state[prefix + ".bias"] = torch.zeros_like(state[prefix + ".bias"])
    return state
