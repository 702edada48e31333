"""The loss plot of a training log (tools/train.py's log.jsonl) as a PNG: the training loss and its terms and
the held-out loss against the step (log scale), and the held-out masked PSNR beside it.

Usage: /usr/bin/python3 tools/nn/plot.py LOG.jsonl OUT.png
"""
import json
import sys

from atomic_file import atomic_path


def read_log(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def plot_log(log_path, png_path, title="training"):
    """Writes the plot; needs python3-matplotlib (tools/deps.sh)."""
    import matplotlib
    matplotlib.use("Agg")  # no display
    import matplotlib.pyplot as plt

    rows = read_log(log_path)
    train = [r for r in rows if r["kind"] == "train"]
    heldout = [r for r in rows if r["kind"] == "heldout"]
    fig, (ax_loss, ax_psnr) = plt.subplots(1, 2, figsize=(12, 4.5))
    steps = [r["step"] for r in train]
    ax_loss.plot(steps, [r["loss"] for r in train], label="train loss", color="C0")
    for i, term in enumerate(("mse", "ssim", "gradient", "temporal")):
        if train and term in train[0]:
            ax_loss.plot(steps, [r[term] for r in train], label=f"train {term}", color=f"C{i + 2}", lw=0.8,
                         alpha=0.7)
    if heldout:
        ax_loss.plot([r["step"] for r in heldout], [r["loss"] for r in heldout], "o-", label="held-out loss",
                     color="C1")
        ax_psnr.plot([r["step"] for r in heldout], [r["psnr_masked"] for r in heldout], "o-", color="C1",
                     label="held-out, masked")
        ax_psnr.plot([r["step"] for r in heldout], [r["psnr_full"] for r in heldout], "s--", color="C1",
                     alpha=0.6, label="held-out, full frame")
    ax_loss.set_yscale("log")
    ax_loss.set_xlabel("step")
    ax_loss.set_ylabel("loss (sRGB space)")
    ax_loss.grid(True, which="both", alpha=0.3)
    ax_loss.legend(fontsize=8)
    ax_psnr.set_xlabel("step")
    ax_psnr.set_ylabel("PSNR (dB, linear, clipped to [0, 1])")
    ax_psnr.grid(True, alpha=0.3)
    ax_psnr.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    with atomic_path(png_path) as temporary:
        fig.savefig(temporary, dpi=100, format="png")
    plt.close(fig)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    plot_log(sys.argv[1], sys.argv[2])
