"""The training loss: MSE in sRGB space, a perceptual term and a temporal term.

Everything is compared in the "loss space": the six lightmaps and emissive sRGB-encoded (as the paper's MSE
in sRGB), alpha linear. Channels are in the network's output order (sixway_net.ADAPTERS; alpha is channel 6).

- `mse`: mean squared error in loss space; `channel_weights` may weigh a channel's error up or down (e.g. the
  emissive channel, whose scattered glow is a small share of the mean map but a large one of an emissive
  scene's image), `sample_weights` a sample's (`area_weights`).
- `area_weights`: a mean over all pixels weighs a sample by the smoke's area, so a young puff of a hundred
  pixels counts 40x less than a developed plume in the same batch, where the metrics (masked PSNR per sample or
  set) weigh it alike. Weights (area fraction)^-p, p in [0, 1], normalised to mean 1 over the batch, undo that:
  p = 1 makes every sample's masked MSE count alike, p = 0 is the plain mean.
- `ssim`: 1 - SSIM (Wang et al. 2004; 11x11 Gaussian window, sigma 1.5) per channel, and `gradient`: L1 between
  the images' finite differences. No pretrained network (VGG, LPIPS) can be downloaded here; SSIM compares
  local mean, contrast and structure, and the gradient term penalises blurred edges, which MSE alone lets
  through (a blurred edge costs MSE only along the edge).
- `temporal`: the previous frame's prediction warped along the simulation's screen-space motion should equal
  the current prediction, where the reference itself is coherent along that motion:
  w = exp(-k |target_t - warp(target_t-1)|),  loss = mean(w * valid * (pred_t - warp(pred_t-1))^2).
  Smoke that appears, disappears or changes its lighting has a large reference difference and a small weight,
  so real changes are not punished; pixels whose source lies outside the image (valid = 0) are left out.
- `shaded`: MSE of the billboard images that the maps shade (docs/conventions.md, "Shading"), linear, under a
  fixed set of lightings: what `sixway eval` compares with the path tracer. The per-map terms weigh every map
  and every pixel alike in sRGB; the image weighs each map by the light's squared direction, sums the errors of
  the lights and the ambient (correlated errors add up) and, being linear, weighs bright smoke most.
"""
import torch
import torch.nn.functional as F

from metrics import ALPHA_MASK_THRESHOLD
from sixway_net import OUTPUT_CHANNELS, srgb_to_linear

ALPHA_CHANNEL = 6
SSIM_C1 = 0.01 ** 2  # (K1 L)^2 with the data range L = 1 of sRGB values
SSIM_C2 = 0.03 ** 2
# The shaded term's lightings: fixed (a resumed run and the held-out curve see the same ones), drawn once.
SHADED_LIGHTINGS = 32
SHADED_SEED = 20


def srgb_encode(x):
    """The sRGB transfer function (linear -> encoded); linear below 0.0031308, negative values included."""
    return torch.where(x <= 0.0031308, 12.92 * x, 1.055 * x.clamp(min=0.0031308) ** (1 / 2.4) - 0.055)


def light_channels_mask(channels, device=None):
    """(1, C, 1, 1): True for the channels that are sRGB-encoded in loss space (all but alpha)."""
    mask = torch.ones(1, channels, 1, 1, dtype=torch.bool, device=device)
    mask[:, ALPHA_CHANNEL] = False
    return mask


def target_to_loss_space(target):
    """Linear targets (N, 8, H, W) -> loss space: light channels sRGB-encoded (clamped at 0 first), alpha linear."""
    encoded = srgb_encode(target.clamp(min=0))
    return torch.where(light_channels_mask(target.shape[1], target.device), encoded, target)


def prediction_to_loss_space(raw, encodings):
    """The network's raw outputs -> loss space; `encodings` is each channel's ("srgb" or "linear",
    sixway_net.output_encodings). sRGB outputs already are sRGB values and are used as they are (a negative value
    is an error the loss should see); linear light channels are encoded here."""
    linear = torch.tensor([e == "linear" for e in encodings], device=raw.device).view(1, -1, 1, 1)
    return torch.where(linear & light_channels_mask(raw.shape[1], raw.device), srgb_encode(raw), raw)


def mse(pred, target, channel_weights=None, sample_weights=None):
    """Mean squared error; `channel_weights` (C factors, or None for all 1) weighs each channel's error,
    `sample_weights` (N factors, or None) each sample's."""
    error = (pred - target) ** 2
    if channel_weights is not None:
        error = error * channel_weights.view(1, -1, 1, 1)
    if sample_weights is not None:
        error = error * sample_weights.view(-1, 1, 1, 1)
    return error.mean()


def area_weights(target_alpha, power):
    """(N,) weights (mask area fraction)^-power, mean 1, of linear reference alphas (N, H, W); the mask is the
    metrics' (alpha > 0.01), its area at least one pixel. None when power is 0."""
    if not power:
        return None
    area = (target_alpha > ALPHA_MASK_THRESHOLD).float().mean((1, 2)).clamp(min=1.0 / target_alpha[0].numel())
    weights = area ** -power
    return weights / weights.mean()


def channel_weight_vector(factors, device=None):
    """`loss.channel_weights` ({output channel name: factor}, the others 1) -> (8,) tensor in the network's
    output order, or None when no channel is weighted."""
    if not factors:
        return None
    weights = torch.ones(len(OUTPUT_CHANNELS), device=device)
    for name, factor in factors.items():
        weights[OUTPUT_CHANNELS.index(name)] = factor
    return weights


def lighting_weights(directions, energies, ambient, background):
    """(L, 8) weights, in the network's output order, of L lightings of K directional lights each: unit
    `directions` (L, K, 3) toward the lights in the six-way frame (x right, y up, z away from the camera),
    `energies` (L, K) = E/pi, a constant `ambient` L0 (L,) and `background` (L,). A lighting's image is linear in
    the maps: image = w . maps + background, with w_i = sum_k E_k d_i^2 on right/top/back where d_i >= 0, on
    left/bottom/front where d_i < 0, (2/3) L0 more on all six, 1 on the emissive and -background on alpha
    (premultiplied over)."""
    energies = energies.unsqueeze(-1)
    positive = (energies * directions.square() * (directions >= 0)).sum(1)  # (L, 3): right, top, back
    negative = (energies * directions.square() * (directions < 0)).sum(1)  # left, bottom, front
    column = {name: k for k, name in enumerate(OUTPUT_CHANNELS)}
    weights = torch.zeros(directions.shape[0], len(OUTPUT_CHANNELS))
    for axis, (plus, minus) in enumerate([("right", "left"), ("top", "bottom"), ("back", "front")]):
        weights[:, column[plus]] = positive[:, axis] + 2 / 3 * ambient
        weights[:, column[minus]] = negative[:, axis] + 2 / 3 * ambient
    weights[:, column["emissive"]] = 1
    weights[:, column["alpha"]] = -background
    return weights


def shading_lightings(count=SHADED_LIGHTINGS, seed=SHADED_SEED):
    """The shaded term's lightings, (weights (count, 8), backgrounds (count,)): a key light (E/pi in [0.5, 1.5])
    and a fill light (in [0, 0.6]) from directions uniform on the sphere, an ambient L0 in [0, 0.15] and a
    background in [0, 0.6] (the shipped scenes' lights lie in these ranges)."""
    g = torch.Generator().manual_seed(seed)
    uniform = lambda lo, hi, *shape: lo + (hi - lo) * torch.rand(*shape, generator=g)
    directions = F.normalize(torch.randn(count, 2, 3, generator=g), dim=-1)
    energies = torch.stack([uniform(0.5, 1.5, count), uniform(0.0, 0.6, count)], dim=1)
    ambient, background = uniform(0.0, 0.15, count), uniform(0.0, 0.6, count)
    return lighting_weights(directions, energies, ambient, background), background


SHADING_WEIGHTS, SHADING_BACKGROUNDS = shading_lightings()


def prediction_to_linear(raw, encodings):
    """The network's raw outputs -> linear values, not clamped (a negative value is an error the loss sees)."""
    srgb = torch.tensor([e == "srgb" for e in encodings], device=raw.device).view(1, -1, 1, 1)
    return torch.where(srgb, srgb_to_linear(raw), raw)


def shaded_loss(pred_linear, target_linear, weights, backgrounds, sample_weights=None):
    """Mean over the lightings (`weights` (L, 8), `backgrounds` (L,)) and the pixels of the squared difference of
    the shaded images, each clipped to [0, 1] as `sixway eval` clips them (an emissive core brighter than white
    is no error where both are); `sample_weights` (N factors, or None) weighs each sample's."""
    shade = lambda maps: (torch.einsum("lc,nchw->nlhw", weights.to(maps.device), maps) +
                          backgrounds.to(maps.device).view(1, -1, 1, 1)).clamp(0, 1)
    error = (shade(pred_linear) - shade(target_linear)).square()
    if sample_weights is not None:
        error = error * sample_weights.view(-1, 1, 1, 1)
    return error.mean()


def _gaussian_window(size, sigma, channels, device):
    x = torch.arange(size, dtype=torch.float32, device=device) - (size - 1) / 2
    g = torch.exp(-x * x / (2 * sigma * sigma))
    g = g / g.sum()
    return (g[:, None] * g[None, :]).expand(channels, 1, size, size).contiguous()


def ssim(x, y, window=11, sigma=1.5):
    """Mean SSIM over the channels and the valid (unpadded) window positions; window shrinks to the image."""
    size = min(window, x.shape[2], x.shape[3])
    w = _gaussian_window(size, sigma, x.shape[1], x.device)
    blur = lambda t: F.conv2d(t, w, groups=x.shape[1])
    mx, my = blur(x), blur(y)
    vx = blur(x * x) - mx * mx
    vy = blur(y * y) - my * my
    cxy = blur(x * y) - mx * my
    s = ((2 * mx * my + SSIM_C1) * (2 * cxy + SSIM_C2)) / ((mx * mx + my * my + SSIM_C1) * (vx + vy + SSIM_C2))
    return s.mean()


def gradient_loss(x, y):
    """L1 distance between the horizontal and vertical finite differences of x and of y."""
    dx = lambda t: t[:, :, :, 1:] - t[:, :, :, :-1]
    dy = lambda t: t[:, :, 1:, :] - t[:, :, :-1, :]
    return (dx(x) - dx(y)).abs().mean() + (dy(x) - dy(y)).abs().mean()


def warp(image, motion):
    """Backward warp: out(p) = image(p - motion(p)), bilinear; motion (N, 2, H, W) in pixels (x right, y down).
    Returns (warped, valid) with valid (N, 1, H, W) = 1 where p - motion(p) lies inside the image."""
    n, _, h, w = image.shape
    ys, xs = torch.meshgrid(torch.arange(h, dtype=image.dtype, device=image.device),
                            torch.arange(w, dtype=image.dtype, device=image.device), indexing="ij")
    sx = xs - motion[:, 0]
    sy = ys - motion[:, 1]
    # grid_sample with align_corners=False: pixel centre x sits at (2x + 1) / W - 1.
    grid = torch.stack([(2 * sx + 1) / w - 1, (2 * sy + 1) / h - 1], dim=-1)
    warped = F.grid_sample(image, grid, mode="bilinear", padding_mode="zeros", align_corners=False)
    valid = ((sx >= 0) & (sx <= w - 1) & (sy >= 0) & (sy <= h - 1)).to(image.dtype).unsqueeze(1)
    return warped, valid


def temporal_loss(pred, pred_previous, target, target_previous, motion, k):
    """The warped-previous-prediction term (module docstring); all images in loss space."""
    warped_pred, valid = warp(pred_previous, motion)
    warped_target, _ = warp(target_previous, motion)
    coherence = torch.exp(-k * (target - warped_target).abs().mean(1, keepdim=True))
    weight = coherence * valid
    return (weight * (pred - warped_pred) ** 2).mean()


def training_loss(raw, raw_previous, target, target_previous, motion, encodings, weights):
    """Total loss and its terms (a dict of floats) for a batch of temporal pairs.
    raw/raw_previous: network outputs of the current and previous frames, `encodings` theirs per channel
    (sixway_net.output_encodings); targets linear; `weights` maps
    mse, ssim, gradient, temporal, shaded to their factors, temporal_k to k (terms with factor 0 are skipped),
    channel_weights to the MSE's per-channel factors ({name: factor}, e.g. {"emissive": 4}) and area_power to
    the power p of the per-sample weights of the MSE and shaded terms (area_weights; 0 or absent: none)."""
    targets = torch.cat([target, target_previous])
    pred = prediction_to_loss_space(torch.cat([raw, raw_previous]), encodings)
    ref = target_to_loss_space(targets)
    n = raw.shape[0]
    samples = area_weights(targets[:, ALPHA_CHANNEL], weights.get("area_power", 0))
    terms = {"mse": mse(pred, ref, channel_weight_vector(weights.get("channel_weights"), pred.device), samples)}
    if weights.get("ssim", 0):
        terms["ssim"] = 1 - ssim(pred, ref)
    if weights.get("gradient", 0):
        terms["gradient"] = gradient_loss(pred, ref)
    if weights.get("temporal", 0):
        terms["temporal"] = temporal_loss(pred[:n], pred[n:], ref[:n], ref[n:], motion, weights["temporal_k"])
    if weights.get("shaded", 0):
        terms["shaded"] = shaded_loss(prediction_to_linear(torch.cat([raw, raw_previous]), encodings),
                                      targets, SHADING_WEIGHTS, SHADING_BACKGROUNDS, samples)
    total = sum(weights[name] * value for name, value in terms.items())
    return total, {name: float(value) for name, value in terms.items()}
